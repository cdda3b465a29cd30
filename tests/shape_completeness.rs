//! Completeness of the closed-form knot-pair solver against an independent bounded search of
//! each pair's parameter domain (spline evaluation only), on random cubic curves.
//!
//! Cases (seeded, `tests/common`): 2D/3D, rational or not, clamped or not, coincident knots
//! and log-uniform spacing, 5–10 control points, random `t`; half the targets made by moving a
//! random pair's knots (hitting the domain's edges `a = L`, `a = b`, `c = e`, `e = R` on
//! purpose) and evaluating the curve with the spline core, half random in/near the control
//! triangle; a quarter with `keep_domain`, which the search applies too. For every side and
//! pair (`common::compare`): the search reaches the target (frame residual <= `FOUND`) exactly
//! where `membership` says `contains`; the two find the same solutions (within a radius that
//! widens where the target pins the knots down only loosely); every closed-form solution is
//! monotone, changes only its pair's knots and `u_{j+1} := t`, and lands on the target when
//! re-evaluated by `Curve::point` and by a de Boor written in the test.
//!
//! Not asserted, but counted and printed: targets within `ABSENT` (frame units) of a region's
//! boundary (search residual between `FOUND` and `ABSENT`); disagreements where the solution
//! lies within floating-point reach of the domain's edge and the target pins the knots down
//! only to `ILL_CONDITIONED` or worse; and targets at an edge that the keep-domain rule
//! forbids (approached by the search, never reached). Each has its own cap.
//!
//! More cases: `KNOTSHAPE_CASES=20000 cargo test --release --test shape_completeness --
//! --nocapture` (`KNOTSHAPE_FIRST_CASE`, `KNOTSHAPE_GRID`, `KNOTSHAPE_ALL_FAILURES=1` to list
//! everything).
#![allow(clippy::unwrap_used)]

mod common;

use common::compare::{Tally, compare_with_search};
use common::{RandomCase, SearchOptions, random_case};

/// Random cases run in `cargo test` (override with `KNOTSHAPE_CASES`).
const DEFAULT_CASES: usize = 1000;

/// Seed of case `i` is `SEED + i`.
const SEED: u64 = 0x005E_ED0F_C0DE;

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn run_case(case: usize, tally: &mut Tally, options: SearchOptions) {
    let seed = SEED + case as u64;
    let Some(RandomCase {
        curve,
        t,
        keep_domain,
        target,
        reachable,
        ..
    }) = random_case(seed)
    else {
        return;
    };
    tally.cases += 1;
    let knots = curve.knots();
    let n = curve.control_points().len() - 1;
    tally.three_d += usize::from(curve.dimension() == knotshape::spline::Dimension::Three);
    tally.rational += usize::from(curve.is_rational());
    tally.clamped += usize::from(knots[0] == knots[3] && knots[n + 1] == knots[n + 4]);
    tally.coincident_interior += usize::from(knots[4..=n].windows(2).any(|w| w[0] == w[1]));
    tally.reachable_cases += usize::from(reachable);
    tally.keep_domain_cases += usize::from(keep_domain);
    let context = format!(
        "case {case} (seed {seed:#x}): t = {t:?}, target = {target:?}, keep_domain = {keep_domain}, curve = {curve:?}"
    );
    compare_with_search(&curve, t, target, keep_domain, options, &context, tally);
}

#[test]
fn closed_forms_find_exactly_what_the_search_finds() {
    let cases = env_usize("KNOTSHAPE_CASES", DEFAULT_CASES);
    let options = SearchOptions {
        grid: env_usize("KNOTSHAPE_GRID", SearchOptions::default().grid),
        ..SearchOptions::default()
    };
    let started = std::time::Instant::now();
    let mut tally = Tally::default();
    let first = env_usize("KNOTSHAPE_FIRST_CASE", 0);
    for case in first..first + cases {
        run_case(case, &mut tally, options);
    }
    let failures = std::mem::take(&mut tally.failures);
    let excused = std::mem::take(&mut tally.excused_on_edge);
    let open_end = std::mem::take(&mut tally.open_end);
    let show_all = std::env::var_os("KNOTSHAPE_ALL_FAILURES").is_some();
    println!("{tally:#?}\nelapsed {:?}", started.elapsed());
    for (what, list) in [
        ("excused on an edge", &excused),
        ("at an open keep-domain end", &open_end),
    ] {
        println!("{what}: {}", list.len());
        for why in list.iter().take(if show_all { usize::MAX } else { 3 }) {
            let head: String = why.chars().take(120).collect();
            let tail: String = why
                .split("}: ")
                .last()
                .unwrap_or("")
                .chars()
                .take(160)
                .collect();
            println!("  {head} … {tail}");
        }
    }
    for failure in failures.iter().take(8) {
        println!("FAIL {failure}\n");
    }
    if show_all {
        for failure in &failures {
            println!("FAILURE {failure}");
        }
    }
    assert!(failures.is_empty(), "{} failures", failures.len());
    assert!(tally.cases >= cases * 9 / 10, "too few usable cases");
    assert!(
        tally.excluded * 100 <= tally.pair_checks,
        "more than 1% of the pair checks were near a boundary"
    );
    assert!(
        excused.len() * 1000 <= tally.pair_checks,
        "more than 0.1% of the pair checks were excused as on an edge"
    );
    assert!(
        open_end.len() * 200 <= tally.pair_checks,
        "more than 0.5% of the pair checks were at an open keep-domain end"
    );
    assert!(tally.found > tally.pair_checks / 10 && tally.absent > tally.pair_checks / 10);
}
