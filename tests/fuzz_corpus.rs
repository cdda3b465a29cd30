//! Replays the committed fuzz corpus (`fuzz/corpus/post_bodies/`, seeds and the fuzzer's
//! findings) through the fuzz target's own check (`knotshape::fuzzing`), on stable, so that
//! every finding fixed stays fixed.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use knotshape::fuzzing::Target;

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

/// The structured check (`knotshape::fuzzing::structured`) on the committed corpus and on
/// 3,000 pseudo-random byte strings, on stable: random valid curves through every core
/// operation, each answer checked another way.
#[test]
fn structured_cases_pass_the_fuzz_check() {
    use knotshape::fuzzing::structured::{Case, check};
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

/// The file readers' check (`knotshape::fuzzing::files`) on the committed corpora of the
/// `step_import` and `dxf_import` targets (seeds and the fuzzers' inputs), and on the real STEP
/// files of tests/data/interop: no panic, and what is read writes and reads back unchanged.
#[test]
fn file_corpora_pass_the_fuzz_check() {
    use knotshape::fuzzing::files::{check_dxf, check_step};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    type Check = fn(&[u8]) -> Result<(), String>;
    let targets: [(&str, Check, usize); 2] =
        [("step_import", check_step, 3), ("dxf_import", check_dxf, 2)];
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
        if target == "step_import" {
            files.push(root.join("tests/data/interop/splinecage.stp"));
            files.push(root.join("tests/data/interop/screw.step"));
        }
        for file in &files {
            let input = std::fs::read(file).unwrap();
            if let Err(finding) = check(&input) {
                panic!("{}: {finding}", file.display());
            }
        }
    }
}
