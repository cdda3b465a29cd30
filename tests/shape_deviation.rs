//! Property tests of the certified deviation (`knotshape::shape::max_deviation` and
//! `max_deviation_of_moved_poles`) over random curves of degree 1 to 7 (2D and 3D, rational
//! and not, clamped and unclamped, with coincident knots): moved knots, moved poles, changed
//! weights, near-ties between two maxima and maxima at the domain's ends. The answer is
//! compared with an independent brute force: dense sampling of the spline evaluator's points
//! plus golden-section refinement of every sampled local maximum. The answer must be attained
//! (not above the brute force's maximum beyond rounding) and certified (not below it by more
//! than the documented relative tolerance).
#![allow(clippy::unwrap_used)]

use knotshape::shape::{DEVIATION_RELATIVE_TOLERANCE, max_deviation, max_deviation_of_moved_poles};
use knotshape::spline::vector::distance;
use knotshape::spline::{Curve, CurveLimits};
use proptest::prelude::*;

mod common;

use common::SplitMix64 as Rng;

/// Uniform samples of the brute force on the compared interval (knots are sampled too).
const SAMPLES: usize = 3000;

/// Golden-section steps per sampled local maximum: the bracket shrinks to `0.618^100` of two
/// sample steps, far below what the value can resolve.
const GOLDEN_STEPS: usize = 100;

/// Rounding allowed on top of the relative tolerance, relative to the control net's size
/// (distances of the two curves' evaluations).
const ROUNDING: f64 = 1e-12;

/// Cases: `PROPTEST_CASES` when set (for long hunts), else 160; the seed is fixed (so CI is
/// repeatable) unless `PROPTEST_RNG_SEED` names another.
fn config() -> ProptestConfig {
    let env = |name: &str| std::env::var(name).ok().and_then(|v| v.parse().ok());
    ProptestConfig {
        cases: env("PROPTEST_CASES").map_or(160, |v: u64| v as u32),
        rng_seed: proptest::test_runner::RngSeed::Fixed(
            env("PROPTEST_RNG_SEED").unwrap_or(0x6465_7669),
        ),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// How the second curve differs from the first.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Change {
    /// One or two interior knots moved (the same net over new knots).
    Knots,
    /// One to three poles moved.
    Poles,
    /// Weights changed (the first curve rational or not).
    Weights,
    /// Two poles moved by the same vector, one of them by a factor `1 + 1e-9` more, on
    /// uniform knots: two maxima within a relative `1e-9` (exactly tied for polynomial
    /// curves without the factor).
    NearTie,
    /// The first or the last pole of a clamped curve moved: the largest gap at a domain end.
    EndPole,
}

/// A random curve and its changed copy (or the new knot vector).
struct Case {
    old: Curve,
    new: Curve,
    /// `Some` for [`Change::Knots`]: the vector `max_deviation` gets.
    new_knots: Option<Vec<f64>>,
    change: Change,
}

fn random_case(rng: &mut Rng) -> Case {
    let change = [
        Change::Knots,
        Change::Poles,
        Change::Weights,
        Change::NearTie,
        Change::EndPole,
    ][rng.below(5)];
    let p = 1 + rng.below(7);
    // Near-ties need two poles `p + 1` apart whose basis functions lie inside the domain.
    let count = if change == Change::NearTie {
        3 * p + 3 + rng.below(4)
    } else {
        p + 1 + rng.below(6)
    };
    let dimension = 2 + rng.below(2);
    let points: Vec<Vec<f64>> = (0..count)
        .map(|i| {
            let mut point = vec![i as f64 + rng.range(-0.5, 0.5), rng.range(-2.0, 2.0)];
            if dimension == 3 {
                point.push(rng.range(-2.0, 2.0));
            }
            point
        })
        .collect();
    let rational = rng.chance(0.5);
    let weights: Option<Vec<f64>> =
        rational.then(|| (0..count).map(|_| rng.range(0.3, 3.0)).collect());
    let clamped = change == Change::EndPole || rng.chance(0.6);
    let knots = random_knots(rng, p, count, clamped, change == Change::NearTie);
    let limits = CurveLimits::default();
    let old = Curve::new(p, &points, &knots, weights.as_deref(), &limits).unwrap();
    let mut new_points = points.clone();
    let mut new_weights = weights.clone();
    let mut new_knots = None;
    let displacement =
        |rng: &mut Rng| -> Vec<f64> { (0..dimension).map(|_| rng.range(-1.0, 1.0)).collect() };
    let mut moved = |index: usize, by: &[f64], factor: f64| {
        for (c, d) in by.iter().enumerate() {
            new_points[index][c] += factor * d;
        }
    };
    match change {
        Change::Knots => {
            let mut changed = knots.clone();
            let interior: Vec<usize> = (p + 1..count).collect();
            if interior.is_empty() {
                // No interior knot: move the pole instead.
                moved(rng.below(count), &displacement(rng), 1.0);
            } else {
                for _ in 0..1 + rng.below(2) {
                    let i = interior[rng.below(interior.len())];
                    changed[i] = rng.range(changed[i - 1], changed[i + 1]);
                }
                new_knots = Some(changed);
            }
        }
        Change::Poles => {
            for _ in 0..1 + rng.below(3) {
                moved(rng.below(count), &displacement(rng), 1.0);
            }
        }
        Change::Weights => {
            let mut changed = weights.clone().unwrap_or_else(|| vec![1.0; count]);
            for _ in 0..1 + rng.below(2) {
                changed[rng.below(count)] *= rng.range(0.4, 2.5);
            }
            new_weights = Some(changed);
        }
        Change::NearTie => {
            // Poles far enough apart that their basis functions do not overlap, both away
            // from the clamped ends (uniform knots there: the basis functions are translates).
            let by = displacement(rng);
            let first = p + rng.below(count - 3 * p - 2);
            let second = first + p + 1 + rng.below(count - p - first - p - 1);
            let factor = if rng.chance(0.5) { 1.0 } else { 1.0 + 1e-9 };
            moved(first, &by, 1.0);
            moved(second, &by, factor);
        }
        Change::EndPole => {
            let index = if rng.chance(0.5) { 0 } else { count - 1 };
            moved(index, &displacement(rng), 1.0);
        }
    }
    let new = Curve::new(
        p,
        &new_points,
        new_knots.as_deref().unwrap_or(&knots),
        new_weights.as_deref(),
        &limits,
    )
    .unwrap();
    Case {
        old,
        new,
        new_knots,
        change,
    }
}

/// A full knot vector of `count + p + 1` values: clamped on [0, 1] or unclamped, interior
/// knots random with repeats up to multiplicity `p` (or uniform for near-ties).
fn random_knots(rng: &mut Rng, p: usize, count: usize, clamped: bool, uniform: bool) -> Vec<f64> {
    let total = count + p + 1;
    if !clamped {
        return (0..total).map(|i| i as f64 / (total - 1) as f64).collect();
    }
    let inner = count - p - 1;
    let mut interior: Vec<f64> = if uniform {
        (1..=inner).map(|i| i as f64 / (inner + 1) as f64).collect()
    } else {
        let mut values: Vec<f64> = Vec::new();
        while values.len() < inner {
            let u = rng.range(0.05, 0.95);
            let repeats = (1 + rng.below(p)).min(inner - values.len());
            let repeats = if rng.chance(0.3) { repeats } else { 1 };
            values.extend(std::iter::repeat_n(u, repeats));
        }
        values
    };
    interior.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; p + 1];
    knots.extend(interior);
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    knots
}

/// The largest gap `|old(u) - new(u)|` on `[lo, hi]` by brute force with the spline
/// evaluator: uniform samples and every knot inside, then golden-section search in the
/// neighbourhood of every sampled local maximum.
fn brute_force(old: &Curve, new: &Curve, lo: f64, hi: f64) -> f64 {
    let gap = |u: f64| distance(old.point(u).unwrap(), new.point(u).unwrap());
    let mut samples: Vec<f64> = (0..=SAMPLES)
        .map(|i| (lo + (hi - lo) * i as f64 / SAMPLES as f64).min(hi))
        .chain(
            old.knots()
                .iter()
                .chain(new.knots())
                .copied()
                .filter(|&u| lo < u && u < hi),
        )
        .collect();
    samples.sort_by(f64::total_cmp);
    samples.dedup();
    let values: Vec<f64> = samples.iter().map(|&u| gap(u)).collect();
    let mut best = values.iter().copied().fold(0.0, f64::max);
    for i in 0..samples.len() {
        let left = if i > 0 {
            values[i - 1]
        } else {
            f64::NEG_INFINITY
        };
        let right = values.get(i + 1).copied().unwrap_or(f64::NEG_INFINITY);
        if values[i] < left || values[i] < right {
            continue;
        }
        let (mut a, mut b) = (
            samples[i.saturating_sub(1)],
            samples[(i + 1).min(samples.len() - 1)],
        );
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let (mut c, mut d) = (b - ratio * (b - a), a + ratio * (b - a));
        let (mut gc, mut gd) = (gap(c), gap(d));
        for _ in 0..GOLDEN_STEPS {
            if gc > gd {
                (b, d, gd) = (d, c, gc);
                c = b - ratio * (b - a);
                gc = gap(c);
            } else {
                (a, c, gc) = (c, d, gd);
                d = a + ratio * (b - a);
                gd = gap(d);
            }
        }
        best = best.max(gc).max(gd);
    }
    best
}

fn net_size(curve: &Curve) -> f64 {
    curve
        .control_points()
        .iter()
        .flatten()
        .fold(0.0, |size: f64, c| size.max(c.abs()))
}

fn check(case: &Case) -> Result<(), TestCaseError> {
    let (old, new) = (&case.old, &case.new);
    let (a, b) = (old.domain(), new.domain());
    let (lo, hi) = (a.0.max(b.0), a.1.min(b.1));
    prop_assume!(lo < hi);
    let found = match &case.new_knots {
        Some(knots) => max_deviation(old, knots, (lo, hi)),
        None => max_deviation_of_moved_poles(old, new, (lo, hi)),
    };
    let expected = brute_force(old, new, lo, hi);
    let rounding = ROUNDING * net_size(old).max(net_size(new));
    // Attained: a distance the curves have somewhere, so not above their maximum.
    prop_assert!(
        found <= expected * (1.0 + 1e-12) + rounding,
        "{:?}: {found} above the brute-force maximum {expected}",
        case.change
    );
    // Certified: no place exceeds it by more than the relative tolerance (on the squared
    // distance; half of it on the distance).
    prop_assert!(
        found >= expected * (1.0 - DEVIATION_RELATIVE_TOLERANCE) - rounding,
        "{:?}: {found} below the brute-force maximum {expected} (relative {:e})",
        case.change,
        (expected - found) / expected
    );
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn deviation_is_attained_and_certified(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let case = random_case(&mut rng);
        check(&case)?;
    }
}

/// The same checks on a fixed near-tie: two poles of a uniform cubic moved by the same
/// vector, the second by `1 + 1e-9` more, so the larger maximum is the second one.
#[test]
fn a_near_tie_finds_the_larger_maximum() {
    let points: Vec<Vec<f64>> = (0..12).map(|i| vec![i as f64, (i % 3) as f64]).collect();
    let knots: Vec<f64> = (0..16).map(|i| i as f64).collect();
    let limits = CurveLimits::default();
    let old = Curve::new(3, &points, &knots, None, &limits).unwrap();
    let mut moved = points.clone();
    moved[4][1] += 0.7;
    moved[9][1] += 0.7 * (1.0 + 1e-9);
    let new = Curve::new(3, &moved, &knots, None, &limits).unwrap();
    let found = max_deviation_of_moved_poles(&old, &new, old.domain());
    // The largest value of a uniform cubic B-spline basis function is 2/3, at its middle.
    let expected = 0.7 * (1.0 + 1e-9) * 2.0 / 3.0;
    assert!(
        (found - expected).abs() <= 1e-15 * 4.0 + expected * DEVIATION_RELATIVE_TOLERANCE,
        "{found} vs {expected}"
    );
    assert!(
        found > 0.7 * 2.0 / 3.0 * (1.0 + 0.5e-9),
        "{found} is the smaller maximum"
    );
}
