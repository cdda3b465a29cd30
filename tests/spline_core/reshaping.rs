//! Degree elevation, knot removal and splitting (`Curve::elevate_degree`,
//! `Curve::remove_knots`, `Curve::split_at`), checked by dense two-way comparison with the
//! reference evaluator: the answer's and the input's points (and derivatives) at the knots
//! of both curves and a dense grid, on random curves of degrees 1–6, rational or not, 2D or
//! 3D, clamped or not, in both knot conventions.

use knotshape::spline::{Curve, CurveLimits, EXACT_REMOVAL_ALLOWANCE, KnotConvention};
use proptest::collection::vec;
use proptest::prelude::*;

use super::config;
use super::corpus::split_mix;
use super::generators::{CaseOptions, CurveCase, curve_case};
use super::reference::{P3, Reference};

/// Same-curve comparisons, relative to the control points' magnitude.
const SAME_TOL: f64 = 1e-10;
/// Grid points per span of the dense comparison.
const GRID_PER_SPAN: usize = 16;

fn reference_of(curve: &Curve) -> Reference {
    Reference {
        degree: curve.degree(),
        knots: curve.knots().to_vec(),
        points: curve.control_points().to_vec(),
        weights: curve.weights().map(<[f64]>::to_vec),
    }
}

fn gap(a: P3, b: P3) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

/// The parameters of a two-way comparison on `[lo, hi]`: the knots of both curves there and
/// a grid between consecutive ones.
fn comparison_parameters(first: &Reference, second: &Reference, lo: f64, hi: f64) -> Vec<f64> {
    let mut breaks: Vec<f64> = first
        .knots
        .iter()
        .chain(&second.knots)
        .copied()
        .filter(|&u| lo <= u && u <= hi)
        .chain([lo, hi])
        .collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut out = Vec::new();
    for w in breaks.windows(2) {
        for i in 0..GRID_PER_SPAN {
            out.push(w[0] + (w[1] - w[0]) * i as f64 / GRID_PER_SPAN as f64);
        }
    }
    out.push(hi);
    out
}

/// The largest distance between the two curves at the comparison parameters on `[lo, hi]`
/// (each curve evaluated from the left at the end, as the domain's end is).
fn largest_gap(first: &Reference, second: &Reference, lo: f64, hi: f64) -> f64 {
    comparison_parameters(first, second, lo, hi)
        .into_iter()
        .map(|t| {
            if t == hi && t != first.domain().1 {
                gap(
                    first.derivatives_from_left(t, 0)[0],
                    second.derivatives_from_left(t, 0)[0],
                )
            } else {
                gap(first.point(t), second.point(t))
            }
        })
        .fold(0.0, f64::max)
}

fn multiplicity(knots: &[f64], value: f64) -> usize {
    knots.iter().filter(|&&u| u == value).count()
}

fn convention(case: &CurveCase) -> KnotConvention {
    if case.trimmed {
        KnotConvention::Trimmed
    } else {
        KnotConvention::Full
    }
}

proptest! {
    #![proptest_config(config())]

    /// The elevated curve is the same curve (points and first derivatives), clamped over
    /// the domain, each interior knot's multiplicity raised by the degree difference (a
    /// jump keeps `q + 1`), in the caller's convention.
    #[test]
    fn elevation_keeps_the_curve(case in curve_case(CaseOptions::default()), raise in 1usize..=3) {
        let curve = case.curve();
        let p = curve.degree();
        let q = p + raise;
        let elevated = curve.elevate_degree(q, 15, 100_000).unwrap();
        prop_assert_eq!(elevated.degree(), q);
        prop_assert_eq!(elevated.convention(), convention(&case));
        prop_assert_eq!(elevated.is_rational(), curve.is_rational());
        prop_assert_eq!(elevated.dimension(), curve.dimension());
        prop_assert_eq!(elevated.domain(), curve.domain());
        let (lo, hi) = curve.domain();
        let knots = elevated.knots();
        prop_assert!(knots[..=q].iter().all(|&u| u == lo));
        prop_assert!(knots[knots.len() - q - 1..].iter().all(|&u| u == hi));
        let mut values: Vec<f64> = curve.knots().iter().copied().filter(|&u| lo < u && u < hi).collect();
        values.dedup();
        for u in values {
            let before = multiplicity(curve.knots(), u).min(p + 1);
            let expected = if before > p { q + 1 } else { before + raise };
            prop_assert_eq!(multiplicity(knots, u), expected, "knot {}", u);
        }
        let (a, b) = (reference_of(&curve), reference_of(&elevated));
        let scale = a.point_scale();
        prop_assert!(largest_gap(&a, &b, lo, hi) <= SAME_TOL * scale);
        for t in comparison_parameters(&a, &b, lo, hi) {
            if t == hi || curve.knots().contains(&t) {
                continue;
            }
            let (da, db) = (a.derivatives(t, 1)[1], b.derivatives(t, 1)[1]);
            prop_assert!(gap(da, db) <= 1e-8 * a.derivative_scale(t, 1), "derivative at {}", t);
        }
    }

    /// Knots inserted into a curve, some of them repeatedly, are removed again with tolerance
    /// 0, each as often as it was inserted, giving back the knot vector and the curve, with a
    /// certified deviation within the allowance of tolerance 0: whether the inserted values
    /// are listed once each (as a client lists the values it wants out), as inserted, or not
    /// at all (every interior knot tried). Degrees 1–7, weights spread up to `25³` apart.
    #[test]
    fn inserted_knots_are_exactly_removable(
        case in curve_case(CaseOptions { max_degree: 7, ..CaseOptions::default() }),
        insertions in vec((0.01..0.99f64, 1usize..=7), 1..5),
        spread in 1.0..3.0f64,
    ) {
        let curve = case.curve();
        let curve = match curve.weights() {
            Some(weights) => {
                let spread: Vec<f64> = weights.iter().map(|w| w.powf(spread)).collect();
                Curve::new(case.degree, &case.control_points, &case.knots, Some(&spread), &CurveLimits::default()).unwrap()
            }
            None => curve,
        };
        let (lo, hi) = curve.domain();
        let p = curve.degree();
        let mut inserted = Vec::new();
        for (f, times) in insertions {
            let u = lo + f * (hi - lo);
            let existing = multiplicity(curve.knots(), u) + multiplicity(&inserted, u);
            for _ in 0..times.min(p.saturating_sub(existing)) {
                inserted.push(u);
            }
        }
        prop_assume!(!inserted.is_empty());
        inserted.sort_by(f64::total_cmp);
        let mut distinct = inserted.clone();
        distinct.dedup();
        let refined = curve.insert_knots(&inserted, 100_000).unwrap();
        let allowance = refined.removal_allowance();
        prop_assert!(allowance > 0.0);
        let (a, scale) = (reference_of(&curve), reference_of(&curve).point_scale());
        for listed in [Some(&distinct[..]), Some(&inserted[..]), None] {
            let removal = refined.remove_knots(0.0, listed).unwrap();
            prop_assert_eq!(&removal.removed, &inserted, "listed {:?}", listed);
            prop_assert!(removal.max_deviation <= allowance, "{} > {allowance}", removal.max_deviation);
            prop_assert_eq!(removal.curve.knots(), curve.knots());
            prop_assert_eq!(removal.curve.convention(), convention(&case));
            let b = reference_of(&removal.curve);
            prop_assert!(largest_gap(&a, &b, lo, hi) <= SAME_TOL * scale);
            for (q, original) in removal.curve.control_points().iter().zip(curve.control_points()) {
                prop_assert!(gap(*q, *original) <= SAME_TOL * scale, "{:?} against {:?}", q, original);
            }
            if let (Some(after), Some(before)) = (removal.curve.weights(), curve.weights()) {
                for (w, v) in after.iter().zip(before) {
                    prop_assert!((w - v).abs() <= SAME_TOL * v, "weight {} against {}", w, v);
                }
            }
        }
    }

    /// Removal within a tolerance: the reported deviation is a bound of the true one (dense
    /// comparison) and within the tolerance (plus the rounding allowance); the removed values
    /// were interior knots and the rest of the curve's data is kept.
    #[test]
    fn removal_within_a_tolerance_is_certified(
        case in curve_case(CaseOptions::default()),
        fraction in 0.0..0.3f64,
    ) {
        let curve = case.curve();
        let reference = reference_of(&curve);
        let scale = reference.point_scale();
        let tolerance = fraction * scale;
        let removal = curve.remove_knots(tolerance, None).unwrap();
        let allowance = curve.removal_allowance();
        prop_assert!(removal.max_deviation <= tolerance + allowance * 1.0001, "{} > {tolerance}", removal.max_deviation);
        let (lo, hi) = curve.domain();
        let after = reference_of(&removal.curve);
        let measured = largest_gap(&reference, &after, lo, hi);
        prop_assert!(measured <= removal.max_deviation * (1.0 + 1e-9) + 1e-12 * scale,
            "measured {measured} above the bound {}", removal.max_deviation);
        prop_assert_eq!(removal.curve.domain(), curve.domain());
        prop_assert_eq!(removal.curve.convention(), convention(&case));
        prop_assert_eq!(removal.curve.is_rational(), curve.is_rational());
        prop_assert_eq!(
            removal.curve.control_points().len() + removal.removed.len(),
            curve.control_points().len()
        );
        for u in &removal.removed {
            prop_assert!(lo < *u && *u < hi);
        }
    }

    /// Split pieces: clamped, consecutive domains covering the domain, each the curve there.
    #[test]
    fn split_pieces_are_the_curve(
        case in curve_case(CaseOptions::default()),
        fractions in vec(0.0..1.0f64, 1..5),
        at_knots in any::<bool>(),
    ) {
        let curve = case.curve();
        let (lo, hi) = curve.domain();
        let mut parameters: Vec<f64> = fractions.iter().map(|f| lo + f * (hi - lo)).collect();
        if at_knots {
            parameters.extend(curve.knots().iter().copied().filter(|&u| lo < u && u < hi));
        }
        parameters.retain(|&u| lo < u && u < hi);
        prop_assume!(!parameters.is_empty());
        let pieces = curve.split_at(&parameters, 1000).unwrap();
        let mut cuts = parameters.clone();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        prop_assert_eq!(pieces.len(), cuts.len() + 1);
        let reference = reference_of(&curve);
        let scale = reference.point_scale();
        let mut start = lo;
        for (i, piece) in pieces.iter().enumerate() {
            let end = cuts.get(i).copied().unwrap_or(hi);
            prop_assert_eq!(piece.domain(), (start, end));
            let p = piece.degree();
            let knots = piece.knots();
            prop_assert!(knots[..=p].iter().all(|&u| u == start));
            prop_assert!(knots[knots.len() - p - 1..].iter().all(|&u| u == end));
            prop_assert_eq!(piece.convention(), convention(&case));
            let other = reference_of(piece);
            prop_assert!(largest_gap(&reference, &other, start, end) <= SAME_TOL * scale, "piece {}", i);
            start = end;
        }
    }
}

/// The rounding that tolerance 0 allows for, measured (docs/method.md §26): random
/// insert-then-remove cases (2,000, or `REMOVAL_CASES`) of degrees 1–7, 3D, half rational with
/// weights up to `10⁶` apart, a third of them up to `10⁴` of their size away from the origin,
/// clamped or not, each value inserted up to `p` times, often next to a knot of the curve;
/// every inserted knot comes out as often as it went in and nothing else does, and the
/// certified bound stays below a fifth of the allowance (`2e-13` of the rounding scale
/// `M w_max / w_min`). `--nocapture` prints the largest ratio.
#[test]
fn exact_removals_stay_far_below_the_allowance() {
    let mut state = 0x0030_u64;
    let mut unit = || {
        state = split_mix(state);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let total: usize = std::env::var("REMOVAL_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(2_000);
    let (mut worst, mut cases) = (0.0f64, 0);
    for case in 0..total {
        let p = 1 + case % 7;
        let count = p + 1 + (unit() * 12.0) as usize;
        let size = 10f64.powf(unit() * 6.0 - 3.0);
        let offset = if case % 3 == 0 {
            size * 10f64.powf(unit() * 4.0)
        } else {
            0.0
        };
        let points: Vec<[f64; 3]> = (0..count)
            .map(|_| {
                [
                    offset + (unit() - 0.5) * size,
                    (unit() - 0.5) * size,
                    (unit() - 0.5) * size,
                ]
            })
            .collect();
        let weights: Vec<f64> = (0..count)
            .map(|_| 10f64.powf((unit() - 0.5) * 6.0))
            .collect();
        let clamped = case % 2 == 0;
        let mut knots: Vec<f64> = if clamped {
            let interior = (0..count - p - 1).map(|_| unit());
            std::iter::repeat_n(0.0, p + 1)
                .chain(interior)
                .chain(std::iter::repeat_n(1.0, p + 1))
                .collect()
        } else {
            (0..count + p + 1).map(|_| unit() * 1.6 - 0.3).collect()
        };
        knots.sort_by(f64::total_cmp);
        let rational = case % 4 < 2;
        let Ok(curve) = Curve::new(
            p,
            &points,
            &knots,
            rational.then_some(&weights[..]),
            &CurveLimits::default(),
        ) else {
            continue;
        };
        let (lo, hi) = curve.domain();
        let mut inserted = Vec::new();
        for _ in 0..1 + (unit() * 4.0) as usize {
            let u = lo + (0.1 + 0.8 * unit()) * (hi - lo);
            let times = 1 + (unit() * p as f64) as usize;
            let room = p.saturating_sub(multiplicity(curve.knots(), u));
            inserted.extend(std::iter::repeat_n(u, times.min(room)));
        }
        inserted.sort_by(f64::total_cmp);
        let refined = curve.insert_knots(&inserted, 100_000).unwrap();
        let removal = refined.remove_knots(0.0, None).unwrap();
        assert_eq!(removal.removed, inserted, "case {case}");
        // The bound in units of the rounding scale `M w_max / w_min`.
        let ratio = removal.max_deviation * EXACT_REMOVAL_ALLOWANCE / curve.removal_allowance();
        assert!(
            ratio <= EXACT_REMOVAL_ALLOWANCE / 5.0,
            "case {case}: {ratio:e}"
        );
        worst = worst.max(ratio);
        cases += 1;
    }
    assert!(cases * 20 > total * 19, "{cases} of {total}");
    println!("{cases} cases: largest certified bound / (M w_max / w_min) = {worst:.2e}");
}
