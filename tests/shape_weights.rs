//! The weight method against independent computations: every solution re-evaluated as a NURBS
//! curve by the test's own evaluator (`tests/common/nurbs.rs`); which targets each pair
//! reaches against a brute-force grid of weights (a target made by weights inside the bounds
//! is reached by that pair with those weights, one made by weights outside is not, and the
//! drawn quadrilateral holds exactly the former); the nearest reachable point against the best
//! point of a dense grid. Random curves of degrees 1–7, 2D and 3D, rational or not.
#![allow(clippy::unwrap_used)]

mod common;

use common::SplitMix64;
use common::nurbs::Nurbs;
use knotshape::shape::{
    CONSTRAINT_TOLERANCE, ConstraintSet, EditContext, EditOptions, EditOutcome, ExclusionReason,
    FixedPoles, MethodKind, PoleVariables, PolygonOptions, ShapeQuery, SolutionDetail, edit,
    reachable_regions,
};
use knotshape::spline::vector::{Point, cross, distance, dot, norm, sub};
use knotshape::spline::{Curve, CurveLimits};
use proptest::prelude::*;

/// The weight bounds as the docs state them: `[min(0.01, w/100), max(100, 100 w)]`.
fn bounds(w: f64) -> (f64, f64) {
    ((0.01f64).min(w / 100.0), (100.0f64).max(100.0 * w))
}

fn random_curve(rng: &mut SplitMix64, degree: usize, three_d: bool, rational: bool) -> Curve {
    let dims = if three_d { 3 } else { 2 };
    loop {
        let count = degree + 1 + rng.below(6);
        let points: Vec<Vec<f64>> = (0..count)
            .map(|_| (0..dims).map(|_| rng.range(-5.0, 5.0)).collect())
            .collect();
        let weights: Option<Vec<f64>> = rational.then(|| {
            (0..count)
                .map(|_| (rng.range(-1.0, 1.0) * 3f64.ln()).exp())
                .collect()
        });
        let len = count + degree + 1;
        let clamped = rng.chance(0.5);
        let mut value = 0.0;
        let knots: Vec<f64> = (0..len)
            .map(|i| {
                if i > 0 && !(clamped && (i <= degree || i >= count)) {
                    value += rng.range(0.3, 1.0);
                }
                value
            })
            .collect();
        if let Ok(curve) = Curve::new(
            degree,
            &points,
            &knots,
            weights.as_deref(),
            &CurveLimits::default(),
        ) {
            return curve;
        }
    }
}

/// The poles whose basis is positive at `t`, by the reference (unit-pole curves).
fn active_poles(reference: &Nurbs, t: f64) -> Vec<usize> {
    (0..reference.points.len())
        .filter(|&i| {
            let mut unit = reference.clone();
            unit.points.iter_mut().for_each(|p| *p = [0.0; 3]);
            unit.points[i] = [1.0, 0.0, 0.0];
            unit.point(t)[0] > 0.0
        })
        .collect()
}

/// The reference curve with the weights of `k, l` set to `a, b`.
fn with_weights(reference: &Nurbs, [k, l]: [usize; 2], [a, b]: [f64; 2]) -> Nurbs {
    let mut moved = reference.clone();
    moved.weights[k] = a;
    moved.weights[l] = b;
    moved
}

fn size_of(reference: &Nurbs) -> f64 {
    let mut low = [f64::INFINITY; 3];
    let mut high = [f64::NEG_INFINITY; 3];
    let mut magnitude: f64 = 0.0;
    for p in &reference.points {
        for c in 0..3 {
            low[c] = low[c].min(p[c]);
            high[c] = high[c].max(p[c]);
            magnitude = magnitude.max(p[c].abs());
        }
    }
    norm(sub(high, low)).max(magnitude)
}

fn run(curve: &Curve, t: f64, target: Point, fixed: &[usize], nearest: bool) -> EditOutcome {
    let constraints = ConstraintSet::none();
    let fixed = FixedPoles::new(curve.control_points().len(), fixed).unwrap();
    let variables = PoleVariables::free_poles(&fixed);
    let context = EditContext {
        query: ShapeQuery::new(curve, t),
        constraints: &constraints,
        fixed: &fixed,
        variables: &variables,
    };
    let options = EditOptions {
        measure_deviation: true,
        nearest,
    };
    let dims = curve.dimension().count();
    edit(&context, &[MethodKind::Weights], &target[..dims], options).unwrap()
}

/// Every weight solution, re-evaluated as a NURBS curve, lands on the target; only its pair's
/// weights changed, to positive values within the bounds.
fn check_solutions(curve: &Curve, t: f64, target: Point, outcome: &EditOutcome, context: &str) {
    let reference = Nurbs::of(curve);
    let size = size_of(&reference).max(norm(target));
    for solution in &outcome.solutions {
        let SolutionDetail::Weights {
            poles,
            changed_weights,
        } = &solution.detail
        else {
            panic!("{context}: not a weight solution");
        };
        let new = Nurbs::of(&solution.curve);
        assert_eq!(new.points, reference.points, "{context}: poles kept");
        assert_eq!(new.knots, reference.knots, "{context}: knots kept");
        for i in 0..reference.points.len() {
            if poles.contains(&i) {
                let (lo, hi) = bounds(reference.weights[i]);
                assert!(
                    new.weights[i] >= lo && new.weights[i] <= hi,
                    "{context}: weight {i} = {} outside [{lo}, {hi}]",
                    new.weights[i]
                );
                assert_eq!(
                    changed_weights.contains(&i),
                    new.weights[i] != reference.weights[i]
                );
            } else {
                assert_eq!(
                    new.weights[i], reference.weights[i],
                    "{context}: weight {i}"
                );
            }
        }
        let landed = distance(new.point(t), target);
        assert!(
            landed <= CONSTRAINT_TOLERANCE * size,
            "{context}: pair {poles:?} lands {landed} away"
        );
    }
}

/// A target made by weights inside the bounds is reached by that pair, with those weights
/// (the map from weights to the point is one to one); one made by weights outside them is not
/// reached by that pair.
fn check_grid_case(seed: u64) {
    let mut rng = SplitMix64::new(seed);
    let degree = 1 + rng.below(7);
    let (three_d, rational) = (rng.chance(0.4), rng.chance(0.5));
    let curve = random_curve(&mut rng, degree, three_d, rational);
    let reference = Nurbs::of(&curve);
    let (lo, hi) = curve.domain();
    let t = rng.range(lo, hi);
    let active = active_poles(&reference, t);
    if active.len() < 2 {
        return;
    }
    let first = rng.below(active.len() - 1);
    let second = first + 1 + rng.below(active.len() - first - 1);
    let pair = [active[first], active[second]];
    let only_pair = active.len() == 2;
    let (a_lo, a_hi) = bounds(reference.weights[pair[0]]);
    let (b_lo, b_hi) = bounds(reference.weights[pair[1]]);
    // Log-uniform over a range four times wider than the bounds on either side.
    let pick = |rng: &mut SplitMix64, lo: f64, hi: f64| {
        (rng.range((lo / 4.0).ln(), (hi * 4.0).ln())).exp()
    };
    let weights = [pick(&mut rng, a_lo, a_hi), pick(&mut rng, b_lo, b_hi)];
    let inside = |w: f64, lo: f64, hi: f64| w >= lo && w <= hi;
    let margin = |w: f64, lo: f64, hi: f64| ((w / lo).ln().abs()).min((w / hi).ln().abs());
    // Near a bound rounding decides: skip those.
    if margin(weights[0], a_lo, a_hi) < 1e-6 || margin(weights[1], b_lo, b_hi) < 1e-6 {
        return;
    }
    let reachable = inside(weights[0], a_lo, a_hi) && inside(weights[1], b_lo, b_hi);
    let target = with_weights(&reference, pair, weights).point(t);
    let outcome = run(&curve, t, target, &[], false);
    let context =
        format!("seed {seed}: degree {degree}, t {t}, pair {pair:?}, weights {weights:?}");
    check_solutions(&curve, t, target, &outcome, &context);
    let found = outcome
        .solutions
        .iter()
        .find(|s| matches!(&s.detail, SolutionDetail::Weights { poles, .. } if *poles == pair));
    let membership = outcome
        .weight_pairs
        .as_ref()
        .unwrap()
        .iter()
        .find(|m| m.poles == pair)
        .map(|m| m.contains);
    if only_pair {
        // Only the ratio a N_k : b N_l matters: some other weights within the bounds may
        // reach it; when found, it lands (checked above).
        return;
    }
    assert_eq!(
        found.is_some(),
        reachable,
        "{context}: {:?}",
        outcome.weight_pairs
    );
    assert_eq!(membership.unwrap_or(false), reachable, "{context}");
    if let Some(solution) = found {
        // The same weights, up to how well the point determines them: a relative change `h`
        // of a weight moves the point by about `h` times its sensitivity.
        let new = Nurbs::of(&solution.curve);
        let size = size_of(&reference);
        for (slot, &pole) in pair.iter().enumerate() {
            let h = 1e-4;
            let mut bumped = weights;
            bumped[slot] *= 1.0 + h;
            let sensitivity = distance(with_weights(&reference, pair, bumped).point(t), target) / h;
            let allowed = (1e-8 * size / sensitivity).max(1e-6);
            let relative = (new.weights[pole] / weights[slot] - 1.0).abs();
            assert!(
                relative < allowed,
                "{context}: weight {pole} {} vs {} (allowed {allowed})",
                new.weights[pole],
                weights[slot]
            );
        }
    }
    // The drawn quadrilateral holds the target exactly when the pair reaches it.
    let regions = {
        let constraints = ConstraintSet::none();
        let fixed = FixedPoles::none(curve.control_points().len());
        let variables = PoleVariables::free_poles(&fixed);
        let context = EditContext {
            query: ShapeQuery::new(&curve, t),
            constraints: &constraints,
            fixed: &fixed,
            variables: &variables,
        };
        reachable_regions(
            &context,
            &[MethodKind::Weights],
            PolygonOptions {
                tolerance: None,
                max_vertices: 512,
            },
        )
        .unwrap()
    };
    let region = regions
        .weight_regions
        .iter()
        .find(|r| r.pair.poles == pair)
        .unwrap();
    assert_eq!(
        inside_polygon(&region.polygon, target),
        reachable,
        "{context}: polygon {:?}",
        region.polygon
    );
}

/// Whether `point` lies inside the closed convex polygon (in its plane), by the signs of
/// the edges' cross products with the polygon's normal (Newell's method).
fn inside_polygon(polygon: &[Point], point: Point) -> bool {
    let mut normal = [0.0; 3];
    for w in polygon.windows(2) {
        normal = std::array::from_fn(|c| normal[c] + cross(w[0], w[1])[c]);
    }
    let sides: Vec<f64> = polygon
        .windows(2)
        .map(|w| dot(cross(sub(w[1], w[0]), sub(point, w[0])), normal))
        .collect();
    sides.iter().all(|&s| s >= 0.0) || sides.iter().all(|&s| s <= 0.0)
}

fn config() -> ProptestConfig {
    let env = |name: &str| std::env::var(name).ok().and_then(|v| v.parse().ok());
    ProptestConfig {
        cases: env("PROPTEST_CASES").map_or(400, |v: u64| v as u32),
        rng_seed: proptest::test_runner::RngSeed::Fixed(
            env("PROPTEST_RNG_SEED").unwrap_or(0x7765_6967),
        ),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn reachable_pairs_agree_with_a_grid_of_weights(seed in any::<u64>()) {
        check_grid_case(seed);
    }
}

/// The nearest reachable point of an unreachable target is at least as close as the best of
/// a 48 × 48 log grid of weights within the bounds, over every pair; its solutions land on it.
#[test]
fn the_nearest_point_beats_a_brute_force_grid() {
    let mut rng = SplitMix64::new(0x6e65);
    let mut compared = 0;
    for case in 0..60 {
        let degree = 1 + case % 7;
        let curve = random_curve(&mut rng, degree, case % 3 == 0, case % 2 == 0);
        let reference = Nurbs::of(&curve);
        let (lo, hi) = curve.domain();
        let t = rng.range(lo, hi);
        let dims = curve.dimension().count();
        let mut target = reference.point(t);
        for value in target.iter_mut().take(dims) {
            *value += rng.range(-8.0, 8.0);
        }
        let outcome = run(&curve, t, target, &[], true);
        if !outcome.solutions.is_empty() {
            continue;
        }
        let Some(nearest) = &outcome.nearest else {
            continue;
        };
        let active = active_poles(&reference, t);
        let mut best = f64::INFINITY;
        for (i, &k) in active.iter().enumerate() {
            for &l in &active[i + 1..] {
                let (a_lo, a_hi) = bounds(reference.weights[k]);
                let (b_lo, b_hi) = bounds(reference.weights[l]);
                for x in 0..48 {
                    for y in 0..48 {
                        let log = |lo: f64, hi: f64, s: usize| {
                            (lo.ln() + (hi / lo).ln() * s as f64 / 47.0).exp()
                        };
                        let w = [log(a_lo, a_hi, x), log(b_lo, b_hi, y)];
                        let point = with_weights(&reference, [k, l], w).point(t);
                        best = best.min(distance(point, target));
                    }
                }
            }
        }
        let found = distance(nearest.point, target);
        assert!(
            found <= best + 1e-9 * size_of(&reference),
            "case {case}: nearest {found} vs grid {best}"
        );
        assert!(!nearest.solutions.is_empty());
        check_solutions(
            &curve,
            t,
            nearest.point,
            &EditOutcome {
                solutions: nearest.solutions.clone(),
                ..outcome.clone()
            },
            &format!("case {case} (nearest)"),
        );
        compared += 1;
    }
    assert!(compared > 20, "{compared}");
}

/// A pair with a fixed pole is not returned; the answer counts it, with the pole.
#[test]
fn a_pair_with_a_fixed_pole_is_excluded() {
    let points = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 3.5],
        [6.0, 1.0],
        [8.0, 0.0],
    ];
    let knots = [0.0, 0.0, 0.0, 0.0, 0.4, 0.6, 1.0, 1.0, 1.0, 1.0];
    let curve = Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap();
    let reference = Nurbs::of(&curve);
    let t = 0.5;
    let target = with_weights(&reference, [2, 3], [1.7, 0.6]).point(t);
    let free = run(&curve, t, target, &[], false);
    assert!(
        free.solutions.iter().any(
            |s| matches!(&s.detail, SolutionDetail::Weights { poles, .. } if *poles == [2, 3])
        )
    );
    let fixed = run(&curve, t, target, &[3], false);
    assert!(fixed.solutions.iter().all(|s| !matches!(
        &s.detail,
        SolutionDetail::Weights { poles, .. } if poles.contains(&3)
    )));
    assert!(
        fixed
            .excluded
            .iter()
            .any(|e| e.reason == ExclusionReason::MovesFixedPole { index: 3 })
    );
}
