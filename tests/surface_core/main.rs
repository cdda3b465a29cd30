//! Surface-core conformance tests: evaluation (points, partials, normals, curvature) of
//! `knotshape::surface` on the real-surface corpus and on random surfaces, against exact
//! rational arithmetic, finite differences and independent computations.
#![allow(clippy::unwrap_used)]

#[path = "../common/mod.rs"]
mod common;
#[path = "../spline_core/exact.rs"]
#[allow(dead_code)]
mod curve_exact;
#[path = "../common/real_surfaces.rs"]
mod real_surfaces;

mod closest;
mod corpus;
mod evaluation;
mod exact;
mod generators;
mod tessellation;
mod toolkit;

use proptest::test_runner::Config;

/// Proptest cases per property (a debug build keeps the suite within seconds).
const CASES: u32 = 96;

/// The proptest configuration of every property in this suite: the seed is fixed so that CI
/// is repeatable, unless `PROPTEST_RNG_SEED` names another (for hunts); failures are not
/// persisted (a case worth keeping becomes a named test).
fn config() -> Config {
    let seed = std::env::var("PROPTEST_RNG_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x7375_7266);
    Config {
        cases: CASES,
        max_shrink_time: 20_000,
        failure_persistence: None,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        ..Config::default()
    }
}
