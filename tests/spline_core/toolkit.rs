//! Knot insertion, Bézier pieces and the certified polyline of `knotshape::spline`, checked
//! against the reference evaluator (Cox–de Boor on the full vector), a de Casteljau written
//! here, and dense sampling.

use knotshape::spline::{Curve, CurveLimits, InsertError, KnotConvention, TessellationError};
use proptest::collection::vec;
use proptest::prelude::*;

use super::config;
use super::generators::{CaseOptions, CurveCase, curve_case};
use super::reference::{P3, Reference};

/// Refined curve against the original, relative to the largest control-point coordinate.
const REFINED_TOL: f64 = 1e-12;
/// A Bézier piece by de Casteljau against the reference, relative likewise.
const PIECE_TOL: f64 = 1e-12;
/// Curve points sampled per polyline edge in the tessellation check.
const SAMPLES_PER_EDGE: usize = 24;

fn max_gap(a: P3, b: P3) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max)
}

/// The reference of a core curve, from its data alone (full knots, control points, weights).
fn reference_of(curve: &Curve) -> Reference {
    Reference {
        degree: curve.degree(),
        knots: curve.knots().to_vec(),
        points: curve.control_points().to_vec(),
        weights: curve.weights().map(<[f64]>::to_vec),
    }
}

/// How often `value` occurs in `knots`.
fn multiplicity(knots: &[f64], value: f64) -> usize {
    knots.iter().filter(|&&u| u == value).count()
}

/// Candidate values to insert: random ones in the domain, the knots there (raising their
/// multiplicity, up to corners) and the domain's ends.
fn candidates(case: &CurveCase, fractions: &[f64]) -> Vec<f64> {
    let (lo, hi) = case.reference.domain();
    let mut values: Vec<f64> = fractions.iter().map(|f| lo + f * (hi - lo)).collect();
    for (i, &u) in case.reference.knots.iter().enumerate() {
        if lo <= u && u <= hi && i % 2 == 0 {
            values.push(u);
            values.push(u);
        }
    }
    values.extend([lo, hi, lo]);
    values
}

/// De Casteljau on the homogeneous points `(w B, w)` of a piece, projected.
fn de_casteljau(points: &[P3], weights: Option<&[f64]>, s: f64) -> P3 {
    let mut work: Vec<[f64; 4]> = points
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let w = weights.map_or(1.0, |w| w[i]);
            [w * b[0], w * b[1], w * b[2], w]
        })
        .collect();
    for level in 1..work.len() {
        for i in 0..work.len() - level {
            let next = work[i + 1];
            for (value, later) in work[i].iter_mut().zip(next) {
                *value = (1.0 - s) * *value + s * later;
            }
        }
    }
    let [x, y, z, w] = work[0];
    [x / w, y / w, z / w]
}

/// The distance from `q` to the segment `[a, b]` (written here, not the core's).
fn to_segment(q: P3, a: P3, b: P3) -> f64 {
    let d: Vec<f64> = (0..3).map(|c| b[c] - a[c]).collect();
    let length_squared: f64 = d.iter().map(|v| v * v).sum();
    let along = if length_squared == 0.0 {
        0.0
    } else {
        ((0..3).map(|c| (q[c] - a[c]) * d[c]).sum::<f64>() / length_squared).clamp(0.0, 1.0)
    };
    (0..3)
        .map(|c| (q[c] - a[c] - along * d[c]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Whether an interior knot value has multiplicity `p + 1` or more (the curve may jump).
fn has_jump(case: &CurveCase) -> bool {
    let (lo, hi) = case.reference.domain();
    let knots = &case.reference.knots;
    knots
        .iter()
        .any(|&u| lo < u && u < hi && multiplicity(knots, u) > case.degree)
}

/// Checks that `parameters` make a polyline within `tolerance` of the reference curve:
/// increasing, both ends, every knot of the domain, and each of [`SAMPLES_PER_EDGE`] curve
/// points inside an edge's parameter interval within `tolerance` of that edge (so of the
/// polyline).
fn assert_polyline_within(reference: &Reference, parameters: &[f64], tolerance: f64) {
    let (lo, hi) = reference.domain();
    assert_eq!(parameters.first(), Some(&lo));
    assert_eq!(parameters.last(), Some(&hi));
    assert!(parameters.windows(2).all(|w| w[0] < w[1]), "{parameters:?}");
    for &u in &reference.knots {
        if lo <= u && u <= hi {
            assert!(
                parameters.contains(&u),
                "knot {u} missing from {parameters:?}"
            );
        }
    }
    let vertices: Vec<P3> = parameters.iter().map(|&t| reference.point(t)).collect();
    for (edge, pair) in parameters.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        for k in 0..=SAMPLES_PER_EDGE {
            let u = a + (b - a) * k as f64 / SAMPLES_PER_EDGE as f64;
            let u = u.min(b);
            let distance = to_segment(reference.point(u), vertices[edge], vertices[edge + 1]);
            assert!(
                distance <= tolerance,
                "u = {u} on edge [{a}, {b}]: {distance} > {tolerance}"
            );
        }
    }
}

/// Control points on a line with tiny offsets: nearly straight pieces.
fn nearly_straight(case: &mut CurveCase, offset: f64) {
    let count = case.control_points.len();
    for (i, point) in case.control_points.iter_mut().enumerate() {
        let s = i as f64 / count as f64;
        let wobble = offset * if i % 2 == 0 { 1.0 } else { -1.0 };
        point[0] = -5.0 + 10.0 * s;
        point[1] = 2.0 + 3.0 * s + wobble;
        if point.len() == 3 {
            point[2] = 1.0 - s;
        }
        let three = [point[0], point[1], point.get(2).copied().unwrap_or(0.0)];
        case.reference.points[i] = three;
    }
}

proptest! {
    #![proptest_config(config())]

    /// The refined curve (any degree, rational or not, either convention) is the original:
    /// its own data evaluated by the reference agree with the original's reference at
    /// random parameters, at every old and new knot and at both ends; the knot vector is the
    /// old one with the values merged in, in the caller's convention.
    #[test]
    fn inserted_knots_keep_the_curve(case in curve_case(CaseOptions::default()), fractions in vec(0.0..=1.0f64, 0..10), probes in vec(0.0..=1.0f64, 0..16)) {
        let curve = case.curve();
        let p = case.degree;
        // Accept candidates while the multiplicity stays at most p (the rule, counted here).
        let mut accepted: Vec<f64> = Vec::new();
        let mut refused: Option<f64> = None;
        for value in candidates(&case, &fractions) {
            let count = multiplicity(curve.knots(), value) + multiplicity(&accepted, value);
            if count < p {
                accepted.push(value);
            } else if refused.is_none() {
                refused = Some(value);
            }
        }
        let refined = curve.insert_knots(&accepted, usize::MAX).unwrap();
        prop_assert_eq!(refined.convention(), curve.convention());
        prop_assert_eq!(refined.control_points().len(), curve.control_points().len() + accepted.len());
        let mut merged = curve.knots().to_vec();
        merged.extend_from_slice(&accepted);
        merged.sort_by(f64::total_cmp);
        prop_assert_eq!(refined.knots(), &merged[..]);
        let expected_convention_len = match curve.convention() {
            KnotConvention::Full | KnotConvention::Multiplicities => merged.len(),
            KnotConvention::Trimmed => merged.len() - 2,
        };
        prop_assert_eq!(refined.knots_in_convention().len(), expected_convention_len);
        prop_assert_eq!(refined.is_rational(), curve.is_rational());
        if let Some(weights) = refined.weights() {
            prop_assert!(weights.iter().all(|&w| w > 0.0));
        }
        let refined_reference = reference_of(&refined);
        let scale = case.reference.point_scale();
        let mut parameters = case.parameters(&probes);
        parameters.extend_from_slice(&accepted);
        for t in parameters {
            let expected = case.reference.point(t);
            let found = refined_reference.point(t);
            prop_assert!(max_gap(found, expected) <= REFINED_TOL * scale, "t = {}: {:?} vs {:?}", t, found, expected);
        }
        // One more of a value already at multiplicity p (or a clamped end) is refused, naming it.
        if let Some(value) = refused {
            let mut values = accepted.clone();
            values.push(value);
            let error = curve.insert_knots(&values, usize::MAX).unwrap_err();
            let is_multiplicity_error = matches!(error, InsertError::MultiplicityTooHigh { .. });
            prop_assert!(is_multiplicity_error, "{:?}", error);
            prop_assert_eq!(error.index(), Some(values.len() - 1));
        }
    }

    /// Each Bézier piece, evaluated by de Casteljau, is the curve on its span; the pieces
    /// are the non-empty spans of the domain, in order.
    #[test]
    fn bezier_pieces_are_the_curve_span_by_span(case in curve_case(CaseOptions::default())) {
        let curve = case.curve();
        let reference = &case.reference;
        let (lo, hi) = reference.domain();
        let mut breaks: Vec<f64> = reference.knots.iter().copied().filter(|&u| lo <= u && u <= hi).collect();
        breaks.dedup();
        let pieces: Vec<_> = curve.bezier_pieces().collect();
        prop_assert_eq!(pieces.len(), breaks.len() - 1);
        let scale = reference.point_scale();
        for (piece, span) in pieces.iter().zip(breaks.windows(2)) {
            prop_assert_eq!(piece.domain, (span[0], span[1]));
            prop_assert_eq!(piece.degree(), case.degree);
            let points: Vec<P3> = piece.control_points().collect();
            let weights: Vec<f64> = piece.weights().collect();
            let weights = curve.is_rational().then_some(&weights[..]);
            let jumps_at_end = span[1] < hi && multiplicity(&reference.knots, span[1]) > case.degree;
            for k in 0..=16 {
                if k == 16 && jumps_at_end {
                    continue; // the curve at the knot is the next piece's start
                }
                let u = if k == 16 { span[1] } else { span[0] + k as f64 / 16.0 * (span[1] - span[0]) };
                // The local parameter of the rounded `u` (on a short span the curve moves
                // fast, and `k / 16` itself would be off by `u`'s rounding times the speed).
                let s = (u - span[0]) / (span[1] - span[0]);
                let expected = reference.point(u);
                let found = de_casteljau(&points, weights, s);
                prop_assert!(max_gap(found, expected) <= PIECE_TOL * scale, "u = {}: {:?} vs {:?}", u, found, expected);
            }
        }
    }

    /// The certified polyline is within the tolerance of the curve everywhere (dense
    /// sampling), on curves of degree 1 to 5 with corners (knots of multiplicity p).
    #[test]
    fn the_polyline_stays_within_the_tolerance(case in curve_case(CaseOptions { min_degree: 1, max_degree: 5, clamped: None }), exponent in -4.0..-1.0f64) {
        let curve = case.curve();
        let tolerance = 10f64.powf(exponent) * case.reference.point_scale();
        if has_jump(&case) {
            let refused = matches!(curve.tessellate(tolerance, 10_000), Err(TessellationError::Discontinuous { .. }));
            prop_assert!(refused);
        } else {
            let parameters = curve.tessellate(tolerance, 100_000).unwrap();
            assert_polyline_within(&case.reference, &parameters, tolerance);
        }
    }

    /// Nearly straight control polygons: few points, still within the tolerance.
    #[test]
    fn nearly_straight_curves_need_few_points(mut case in curve_case(CaseOptions { min_degree: 2, max_degree: 5, clamped: None }), offset in 0.0..1e-3f64) {
        prop_assume!(!has_jump(&case));
        nearly_straight(&mut case, offset);
        let curve = case.curve();
        let tolerance = 1e-3 * case.reference.point_scale();
        let parameters = curve.tessellate(tolerance, 100_000).unwrap();
        let (lo, hi) = case.reference.domain();
        let mut knots: Vec<f64> = case.reference.knots.iter().copied().filter(|&u| lo <= u && u <= hi).collect();
        knots.dedup();
        // Every control point is within the tolerance of the chord through the line: the
        // knots alone suffice (the unclamped ends may make more necessary; allow a few).
        prop_assert!(parameters.len() <= 4 * knots.len(), "{} points for {} knots", parameters.len(), knots.len());
        assert_polyline_within(&case.reference, &parameters, tolerance);
    }
}

#[test]
fn a_tessellation_refuses_a_tolerance_too_fine_for_the_budget() {
    let points = [[0.0, 0.0], [1.0, 3.0], [2.0, -3.0], [3.0, 0.0]];
    let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let curve = Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap();
    let error = curve.tessellate(1e-8, 1000).unwrap_err();
    assert_eq!(
        error,
        TessellationError::TooManyPoints {
            tolerance: 1e-8,
            max: 1000
        }
    );
    // The same request with a budget that holds it is answered, and more points than for a
    // coarser tolerance.
    let fine = curve.tessellate(1e-6, 10_000).unwrap();
    let coarse = curve.tessellate(1e-3, 10_000).unwrap();
    assert!(fine.len() > coarse.len());
    assert_polyline_within(&reference_of(&curve), &fine, 1e-6);
}
