//! Points and derivatives of `Curve` and `BatchEvaluator` against the reference evaluator.

use approx::assert_relative_eq;
use knotshape::spline::{BatchEvaluator, Curve, CurveLimits, KnotConvention, Point};
use proptest::collection::vec;
use proptest::prelude::*;

use super::config;
use super::generators::{CaseOptions, CurveCase, curve_case};
use super::reference::{P3, Reference, central_difference};

/// Point agreement with the reference, relative to the largest control-point coordinate.
const POINT_TOL: f64 = 1e-11;
/// Exact derivatives (both sides analytic) relative to the derivative's natural scale.
const DERIVATIVE_TOL: f64 = 1e-9;
/// First central difference (one Richardson step) of the reference's derivative of order
/// `k - 1` against the analytic derivative of order `k`, relative to the natural scale.
const FIRST_DIFFERENCE_TOL: f64 = 1e-7;
/// Its step, as a fraction of the span's length scale (see the test).
const FIRST_DIFFERENCE_STEP: f64 = 0.02;
/// Highest order also checked by a `k`-th central difference of the reference's points alone.
const DIRECT_DIFFERENCE_MAX_ORDER: usize = 4;
/// Tolerances of those `k`-th differences, by order: cancellation costs digits as `k` grows.
const DIRECT_DIFFERENCE_TOL: [f64; DIRECT_DIFFERENCE_MAX_ORDER + 1] = [0.0, 1e-5, 1e-4, 1e-3, 1e-3];
/// Their step, as a fraction of the span's length scale (longer: rounding dominates).
const DIRECT_DIFFERENCE_STEP: f64 = 0.2;

/// Asserts `actual ≈ expected` coordinate-wise within `tol · scale`.
fn assert_close(actual: Point, expected: P3, tol: f64, scale: f64, what: &str) {
    let ok = (0..3).all(|c| (actual[c] - expected[c]).abs() <= tol * scale);
    assert!(
        ok,
        "{what}: {actual:?} != {expected:?} (tol {tol} × scale {scale})"
    );
    assert_relative_eq!(
        actual[..],
        expected[..],
        epsilon = tol * scale,
        max_relative = tol
    );
}

/// The largest coordinate magnitude of `v`.
fn max_abs(v: P3) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The reference's derivatives `0..=order` at `t` and their natural scales.
fn reference_derivatives(reference: &Reference, t: f64, order: usize) -> (Vec<P3>, Vec<f64>) {
    let values = reference.derivatives(t, order);
    let scales = values
        .iter()
        .enumerate()
        .map(|(k, v)| reference.derivative_scale(t, k).max(max_abs(*v)))
        .collect();
    (values, scales)
}

proptest! {
    #![proptest_config(config())]

    /// `Curve::point` equals the Cox–de Boor reference at random parameters, at every knot in
    /// the domain and at both ends (right end: limit from the left).
    #[test]
    fn point_matches_reference(case in curve_case(CaseOptions::default()), fractions in vec(0.0..=1.0f64, 0..12)) {
        let curve = case.curve();
        let convention = if case.trimmed { KnotConvention::Trimmed } else { KnotConvention::Full };
        prop_assert_eq!(curve.convention(), convention);
        prop_assert_eq!(curve.knots_in_convention(), &case.knots[..]);
        let scale = case.reference.point_scale();
        for t in case.parameters(&fractions) {
            let actual = curve.point(t).unwrap();
            assert_close(actual, case.reference.point(t), POINT_TOL, scale, &format!("point({t})"));
        }
    }

    /// `points_into` (unsorted and sorted parameters) equals `Curve::point` and the reference.
    #[test]
    fn batch_points_match_single_and_reference(case in curve_case(CaseOptions::default()), fractions in vec(0.0..=1.0f64, 0..24)) {
        let curve = case.curve();
        let batch = BatchEvaluator::new(&curve);
        let scale = case.reference.point_scale();
        let unsorted = case.parameters(&fractions);
        let mut sorted = unsorted.clone();
        sorted.sort_by(f64::total_cmp);
        for parameters in [unsorted, sorted] {
            let mut out = vec![[f64::NAN; 3]; parameters.len()];
            batch.points_into(&parameters, &mut out).unwrap();
            for (&t, &p) in parameters.iter().zip(&out) {
                assert_close(p, curve.point(t).unwrap(), POINT_TOL, scale, &format!("batch vs single at {t}"));
                assert_close(p, case.reference.point(t), POINT_TOL, scale, &format!("batch vs reference at {t}"));
            }
        }
    }

    /// `uniform_points_into` gives the reference's points at `lo + (hi - lo) i / (count - 1)`,
    /// with both ends exact.
    #[test]
    fn uniform_points_match_reference(case in curve_case(CaseOptions::default()), count in 2usize..300) {
        let curve = case.curve();
        let batch = BatchEvaluator::new(&curve);
        let mut out = vec![[f64::NAN; 3]; count];
        batch.uniform_points_into(&mut out);
        let (lo, hi) = case.reference.domain();
        let scale = case.reference.point_scale();
        for (i, &p) in out.iter().enumerate() {
            let t = if i + 1 == count { hi } else { lo + (hi - lo) * i as f64 / (count - 1) as f64 };
            assert_close(p, case.reference.point(t), POINT_TOL, scale, &format!("uniform point {i} at {t}"));
        }
        let parameters: Vec<f64> = curve.uniform_parameters(count).collect();
        prop_assert_eq!(parameters[0], lo);
        prop_assert_eq!(parameters[count - 1], hi);
    }

    /// `Curve::derivatives` and `BatchEvaluator::derivatives_into` (unsorted and sorted
    /// parameters), orders `0..=p+1` (rational too), equal the reference's hodograph
    /// derivatives, at knots (span on the right), at both ends (limit from the left) and at
    /// random parameters.
    #[test]
    fn derivatives_match_reference(case in curve_case(CaseOptions::default()), fractions in vec(0.0..=1.0f64, 0..8)) {
        let curve = case.curve();
        let batch = BatchEvaluator::new(&curve);
        let order = case.degree + 1;
        let unsorted = case.parameters(&fractions);
        let mut sorted = unsorted.clone();
        sorted.sort_by(f64::total_cmp);
        for parameters in [unsorted, sorted] {
            let mut batch_out = vec![[f64::NAN; 3]; (order + 1) * parameters.len()];
            batch.derivatives_into(&parameters, order, &mut batch_out).unwrap();
            for (index, &t) in parameters.iter().enumerate() {
                let (expected, scales) = reference_derivatives(&case.reference, t, order);
                let mut single = vec![[f64::NAN; 3]; order + 1];
                curve.derivatives(t, &mut single).unwrap();
                for k in 0..=order {
                    let what = format!("derivative {k} at {t}");
                    assert_close(single[k], expected[k], DERIVATIVE_TOL, scales[k], &what);
                    let b = batch_out[k * parameters.len() + index];
                    assert_close(b, expected[k], DERIVATIVE_TOL, scales[k], &format!("batch {what}"));
                }
            }
        }
    }

    /// Derivatives of orders `1..=p+1` against central differences of the reference, inside a
    /// span (the curve is smooth there): every order `k` against the first difference of the
    /// reference's order `k - 1` (order 0: its Cox–de Boor points), and orders up to
    /// [`DIRECT_DIFFERENCE_MAX_ORDER`] also against `k`-th differences of the points alone.
    /// Steps follow the span's length scale `w / p`, shortened by the weight ratio of the span's
    /// control points (a rational curve's denominator can have a pole close by).
    #[test]
    fn derivatives_match_finite_differences(
        case in curve_case(CaseOptions::default()),
        span_pick in 0usize..1000,
        position in 0.3..0.7f64,
    ) {
        let curve = case.curve();
        let reference = &case.reference;
        let p = case.degree;
        let spans: Vec<usize> = (p..case.control_points.len())
            .filter(|&m| reference.knots[m] < reference.knots[m + 1])
            .collect();
        let m = spans[span_pick % spans.len()];
        let (a, b) = (reference.knots[m], reference.knots[m + 1]);
        let t = a + position * (b - a);
        let weights: Vec<f64> = (m - p..=m).map(|i| reference.weight(i)).collect();
        let ratio = weights.iter().fold(0.0f64, |x, &w| x.max(w)) / weights.iter().fold(f64::INFINITY, |x, &w| x.min(w));
        let length = (b - a) / (p as f64 * ratio);
        let order = p + 1;
        let mut analytic = vec![[0.0; 3]; order + 1];
        curve.derivatives(t, &mut analytic).unwrap();
        let points = |x: f64| reference.point(x);
        for (k, &value) in analytic.iter().enumerate().skip(1) {
            let lower = |x: f64| if k == 1 { reference.point(x) } else { reference.derivatives(x, k - 1)[k - 1] };
            let fd = central_difference(&lower, t, 1, FIRST_DIFFERENCE_STEP * length);
            let scale = reference.derivative_scale(t, k).max(max_abs(fd));
            assert_close(value, fd, FIRST_DIFFERENCE_TOL, scale, &format!("derivative {k} at {t} vs first difference"));
            if k <= DIRECT_DIFFERENCE_MAX_ORDER {
                let fd = central_difference(&points, t, k, DIRECT_DIFFERENCE_STEP * length);
                let scale = reference.derivative_scale(t, k).max(max_abs(fd));
                assert_close(value, fd, DIRECT_DIFFERENCE_TOL[k], scale, &format!("derivative {k} at {t} vs {k}-th difference"));
            }
        }
    }

    /// A clamped curve starts at `d_0` and ends at `d_n`, single point and batch.
    #[test]
    fn clamped_ends_are_end_control_points(case in curve_case(CaseOptions { clamped: Some(true), ..CaseOptions::default() })) {
        prop_assert!(case.clamped);
        let curve = case.curve();
        let (lo, hi) = curve.domain();
        let first = case.reference.points[0];
        let last = case.reference.points[case.reference.points.len() - 1];
        let scale = case.reference.point_scale();
        assert_close(curve.point(lo).unwrap(), first, POINT_TOL, scale, "start");
        assert_close(curve.point(hi).unwrap(), last, POINT_TOL, scale, "end");
        let mut out = [[f64::NAN; 3]; 2];
        BatchEvaluator::new(&curve).points_into(&[hi, lo], &mut out).unwrap();
        assert_close(out[0], last, POINT_TOL, scale, "batch end");
        assert_close(out[1], first, POINT_TOL, scale, "batch start");
    }

    /// Partition of unity: with every control point equal to `c` (any weights), the curve is `c`
    /// everywhere; and the reference's own basis sums to 1 on the domain.
    #[test]
    fn partition_of_unity(case in curve_case(CaseOptions::default()), fractions in vec(0.0..=1.0f64, 0..8), c in (-10.0..10.0f64, -10.0..10.0f64)) {
        let constant: Vec<Vec<f64>> = case.control_points.iter().map(|d| {
            let mut v = vec![c.0, c.1];
            v.extend(d.get(2).map(|_| 0.5));
            v
        }).collect();
        let expected = [c.0, c.1, if case.control_points[0].len() == 3 { 0.5 } else { 0.0 }];
        let curve = Curve::new(case.degree, &constant, &case.knots, case.weights.as_deref(), &CurveLimits::default()).unwrap();
        let parameters = case.parameters(&fractions);
        let mut out = vec![[0.0; 3]; parameters.len()];
        BatchEvaluator::new(&curve).points_into(&parameters, &mut out).unwrap();
        for (&t, &p) in parameters.iter().zip(&out) {
            assert_close(curve.point(t).unwrap(), expected, POINT_TOL, 10.0, &format!("constant curve at {t}"));
            assert_close(p, expected, POINT_TOL, 10.0, &format!("constant batch at {t}"));
            let sum: f64 = case.reference.basis(case.degree, t).iter().take(case.control_points.len()).sum();
            assert_relative_eq!(sum, 1.0, epsilon = POINT_TOL);
        }
    }
}

/// The case used by the hand-written tests: the random-curve case type built from fixed data.
fn fixed_case(degree: usize, points: &[[f64; 2]], knots: &[f64]) -> (Curve, CurveCase) {
    let control_points: Vec<Vec<f64>> = points.iter().map(|p| p.to_vec()).collect();
    let curve = Curve::new(
        degree,
        &control_points,
        knots,
        None,
        &CurveLimits::default(),
    )
    .unwrap();
    let case = CurveCase {
        degree,
        control_points,
        weights: None,
        knots: knots.to_vec(),
        trimmed: false,
        clamped: false,
        reference: Reference {
            degree,
            knots: knots.to_vec(),
            points: points.iter().map(|p| [p[0], p[1], 0.0]).collect(),
            weights: None,
        },
    };
    (curve, case)
}

/// A quadratic with a double interior knot (C0 corner at 2): at the knot the curve is `d_2`, and
/// the derivative there is the one of the span on the right.
#[test]
fn interior_knot_uses_span_on_the_right() {
    let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [6.0, 1.0]];
    let knots = [0.0, 0.0, 0.0, 2.0, 2.0, 5.0, 5.0, 5.0];
    let (curve, case) = fixed_case(2, &points, &knots);
    assert_close(
        curve.point(2.0).unwrap(),
        [3.0, 2.0, 0.0],
        POINT_TOL,
        6.0,
        "corner point",
    );
    let mut d = [[0.0; 3]; 2];
    curve.derivatives(2.0, &mut d).unwrap();
    // Right span [2, 5): s'(2) = 2 (d_3 - d_2) / (u_4... ) = 2 (d_3 - d_2) / (5 - 2).
    let right = [2.0 * (4.0 - 3.0) / 3.0, 2.0 * (0.0 - 2.0) / 3.0, 0.0];
    assert_close(
        d[1],
        right,
        DERIVATIVE_TOL,
        6.0,
        "derivative from the right",
    );
    let mut batch = [[0.0; 3]; 2];
    BatchEvaluator::new(&curve)
        .derivatives_into(&[2.0], 1, &mut batch)
        .unwrap();
    assert_close(
        batch[1],
        right,
        DERIVATIVE_TOL,
        6.0,
        "batch derivative from the right",
    );
    assert_close(
        case.reference.derivatives(2.0, 1)[1],
        right,
        DERIVATIVE_TOL,
        6.0,
        "reference derivative",
    );
    // The right end: the limit from the left of the last span, s'(5) = 2 (d_4 - d_3) / 3.
    curve.derivatives(5.0, &mut d).unwrap();
    assert_close(d[0], [6.0, 1.0, 0.0], POINT_TOL, 6.0, "end point");
    assert_close(
        d[1],
        [4.0 / 3.0, 2.0 / 3.0, 0.0],
        DERIVATIVE_TOL,
        6.0,
        "end derivative",
    );
}

/// Parameters outside the domain or not finite are refused, naming the parameter's index.
#[test]
fn out_of_domain_parameters_are_refused() {
    use knotshape::spline::EvalError;
    let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
    let (curve, _) = fixed_case(2, &points, &[0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0]);
    assert!(matches!(
        curve.point(-1e-12),
        Err(EvalError::OutsideDomain { index: 0, .. })
    ));
    assert!(matches!(
        curve.point(2.0 + 1e-12),
        Err(EvalError::OutsideDomain { .. })
    ));
    assert!(matches!(
        curve.point(f64::NAN),
        Err(EvalError::NonFiniteParameter { index: 0 })
    ));
    let batch = BatchEvaluator::new(&curve);
    let mut out = [[0.0; 3]; 3];
    let err = batch.points_into(&[0.5, 1.0, 3.0], &mut out).unwrap_err();
    assert_eq!(
        err,
        EvalError::OutsideDomain {
            index: 2,
            value: 3.0,
            domain: (0.0, 2.0)
        }
    );
    let mut ders = [[0.0; 3]; 6];
    let err = batch
        .derivatives_into(&[0.5, f64::INFINITY], 2, &mut ders)
        .unwrap_err();
    assert_eq!(err, EvalError::NonFiniteParameter { index: 1 });
}

/// Batches longer than the evaluator's internal chunks: every point equals `Curve::point`, and
/// an invalid parameter far into the batch is reported by its own index.
#[test]
fn long_batches_match_single_points() {
    use knotshape::spline::EvalError;
    let points = [
        [0.0, 0.0],
        [1.0, 2.0],
        [3.0, 2.5],
        [4.0, 0.0],
        [6.0, 1.0],
        [7.0, 3.0],
    ];
    let (curve, case) = fixed_case(
        3,
        &points,
        &[0.0, 0.0, 0.0, 0.0, 0.7, 1.1, 2.0, 2.0, 2.0, 2.0],
    );
    let batch = BatchEvaluator::new(&curve);
    let count = 10_007;
    // A scrambled order (a multiplicative permutation) over the whole domain, ends included.
    let mut parameters: Vec<f64> = (0..count)
        .map(|i| 2.0 * ((i * 3_001) % count) as f64 / (count - 1) as f64)
        .collect();
    parameters[5_000] = 2.0;
    let mut out = vec![[f64::NAN; 3]; count];
    batch.points_into(&parameters, &mut out).unwrap();
    for (&t, &p) in parameters.iter().zip(&out) {
        assert_close(
            p,
            curve.point(t).unwrap(),
            POINT_TOL,
            7.0,
            &format!("batch point at {t}"),
        );
    }
    for &i in &[0, 2_047, 2_048, 9_999] {
        let t = parameters[i];
        assert_close(
            out[i],
            case.reference.point(t),
            POINT_TOL,
            7.0,
            &format!("reference at {t}"),
        );
    }
    parameters[4_500] = f64::NAN;
    let err = batch.points_into(&parameters, &mut out).unwrap_err();
    assert_eq!(err, EvalError::NonFiniteParameter { index: 4_500 });
    parameters[4_500] = 2.5;
    let err = batch.points_into(&parameters, &mut out).unwrap_err();
    assert_eq!(
        err,
        EvalError::OutsideDomain {
            index: 4_500,
            value: 2.5,
            domain: (0.0, 2.0)
        }
    );
}
