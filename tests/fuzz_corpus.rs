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
