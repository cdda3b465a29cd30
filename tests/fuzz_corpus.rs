//! Replays the committed fuzz corpus (`fuzz/corpus/post_bodies/`, seeds and the fuzzer's
//! findings) through the fuzz target's own check (`knotshape_fuzzing`), on stable, so that
//! every finding fixed stays fixed.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use knotshape_fuzzing::Target;

#[tokio::test]
async fn the_post_body_corpus_passes_the_fuzz_check() {
    let directory = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/post_bodies");
    let mut files: Vec<_> = std::fs::read_dir(&directory)
        .expect("the committed corpus")
        .map(|entry| entry.unwrap().path())
        .collect();
    files.sort();
    assert!(files.len() >= 50, "only {} corpus files", files.len());
    let target = Target::new();
    let mut findings = Vec::new();
    for file in &files {
        let input = std::fs::read(file).unwrap();
        if let Err(finding) = target.check(&input).await {
            findings.push(format!("{}: {finding}", file.display()));
        }
    }
    assert!(findings.is_empty(), "{}", findings.join("\n"));
}

/// The structured check (`knotshape_fuzzing::structured`) on the committed corpus and on
/// 3,000 pseudo-random byte strings, on stable: random valid curves through every core
/// operation, each answer checked another way.
#[test]
fn structured_cases_pass_the_fuzz_check() {
    use knotshape_fuzzing::structured::{Case, check};
    let directory = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/structured");
    let mut inputs: Vec<(String, Vec<u8>)> = std::fs::read_dir(&directory)
        .map(|entries| {
            entries
                .map(|entry| entry.unwrap().path())
                .map(|path| (path.display().to_string(), std::fs::read(&path).unwrap()))
                .collect()
        })
        .unwrap_or_default();
    // SplitMix64 byte strings of 40 to 400 bytes.
    let mut state = 0x5EED_u64;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    for case in 0..3_000 {
        let len = 40 + (next() % 360) as usize;
        let bytes: Vec<u8> = (0..len).map(|_| next() as u8).collect();
        inputs.push((format!("generated case {case}"), bytes));
    }
    let drawn = inputs
        .iter()
        .filter(|(_, bytes)| Case::draw(bytes).is_some())
        .count();
    assert!(drawn >= 1_000, "only {drawn} inputs made a curve");
    let findings: Vec<String> = inputs
        .iter()
        .filter_map(|(name, bytes)| {
            check(bytes)
                .err()
                .map(|finding| format!("{name}: {finding}"))
        })
        .collect();
    assert!(findings.is_empty(), "{}", findings.join("\n"));
}

/// The file readers' checks (`knotshape_fuzzing::files`) on the committed corpora of the
/// `step_import`, `step_surfaces` and `dxf_import` targets (seeds and the fuzzers' inputs), and
/// on the real STEP files of tests/data/interop: no panic, and what is read (curves, surfaces)
/// writes and reads back unchanged.
#[test]
fn file_corpora_pass_the_fuzz_check() {
    use knotshape_fuzzing::files::{check_dxf, check_step, check_step_surfaces};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    type Check = fn(&[u8]) -> Result<(), String>;
    let targets: [(&str, Check, usize); 3] = [
        ("step_import", check_step, 3),
        ("step_surfaces", check_step_surfaces, 8),
        ("dxf_import", check_dxf, 2),
    ];
    for (target, check, at_least) in targets {
        let mut files: Vec<_> = std::fs::read_dir(root.join("fuzz/corpus").join(target))
            .expect("the committed corpus")
            .map(|entry| entry.unwrap().path())
            .collect();
        files.sort();
        assert!(
            files.len() >= at_least,
            "{target}: only {} corpus files",
            files.len()
        );
        if target.starts_with("step") {
            files.push(root.join("tests/data/interop/splinecage.stp"));
            files.push(root.join("tests/data/interop/screw.step"));
            files.push(root.join("tests/data/interop/as1-oc-214.stp"));
        }
        for file in &files {
            let input = std::fs::read(file).unwrap();
            if let Err(finding) = check(&input) {
                panic!("{}: {finding}", file.display());
            }
        }
    }
}

/// The names of the dependencies in the section `[header]` of a Cargo manifest: the keys of
/// the lines up to the next section (a plain reading; the manifest is this repository's).
fn section_keys(manifest: &str, header: &str) -> Vec<String> {
    manifest
        .lines()
        .map(str::trim)
        .skip_while(|line| *line != header)
        .skip(1)
        .take_while(|line| !line.starts_with('['))
        .filter(|line| !line.is_empty() && !line.starts_with('#'))
        .filter_map(|line| line.split('=').next())
        .map(|key| key.trim().to_owned())
        .collect()
}

/// The harness lives outside the product: knotshape's normal dependencies hold neither
/// `arbitrary` nor the fuzzing crate (only its dev-dependencies hold the latter), and no
/// source file of the library or the binary declares a fuzzing module or uses `arbitrary`.
#[test]
fn the_service_carries_no_fuzz_harness() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let normal = section_keys(&manifest, "[dependencies]");
    assert!(normal.iter().any(|name| name == "axum"), "{normal:?}");
    for harness in ["arbitrary", "libfuzzer-sys", "knotshape-fuzzing"] {
        assert!(
            !normal.iter().any(|name| name == harness),
            "{harness} is a dependency of the service"
        );
    }
    let dev = section_keys(&manifest, "[dev-dependencies]");
    assert!(
        dev.iter().any(|name| name == "knotshape-fuzzing"),
        "{dev:?}"
    );
    let mut pending = vec![root.join("src")];
    let mut sources = 0;
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                sources += 1;
                let text = std::fs::read_to_string(&path).unwrap();
                for line in text.lines().map(str::trim) {
                    assert!(
                        !(line.contains("mod fuzzing") || line.contains("arbitrary::")),
                        "{}: {line}",
                        path.display()
                    );
                }
            }
        }
    }
    assert!(sources > 50, "only {sources} source files");
}
