//! Global interpolation (`knotshape::spline::interpolate`), checked against independent
//! computations: a dense linear solve of the collocation system written here (basis
//! functions from the reference's Cox–de Boor recursion), SciPy's `make_interp_spline` on the
//! same parameters and knots (answers copied into `tests/data/scipy_interpolation.json`),
//! the published values of The NURBS Book's Example 9.1, and evaluation by the reference:
//! the curve passes through every point, has the given end derivatives, and a closed curve
//! is `C^{p−1}` across its seam (derivatives from both sides).

use knotshape::spline::{
    CurveLimits, InterpolationError, InterpolationSpec, ParameterChoice, Parametrization, PointSet,
    PointsError, interpolate,
};
use proptest::prelude::*;
use serde_json::Value;

use super::config;
use super::dense;
use super::point_sets::{PointCase, point_case};
use super::reference::{P3, Reference};

/// Distance of the curve from a point at its parameter, relative to the points' size.
const THROUGH_POINT_TOL: f64 = 1e-9;
/// The banded answer against the dense solve, relative to the control points' magnitude.
/// Clustered points (chords five orders of magnitude apart) give ill-conditioned systems
/// (condition numbers near 1e9); both solves are backward stable (elimination without
/// pivoting is, on totally positive matrices), so they differ by about the condition number
/// times the rounding. The sharp check is that the curve passes through the points.
const DENSE_TOL: f64 = 1e-6;
/// Against SciPy's control points (well-conditioned cases), relative likewise.
const SCIPY_TOL: f64 = 1e-12;
/// Derivatives across the seam, relative to the derivative's scale.
const SEAM_TOL: f64 = 1e-8;

fn distance(a: P3, b: P3) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

fn magnitude(points: &[P3]) -> f64 {
    points.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()))
}

/// The test's own parameters: chord length, centripetal or uniform on `[0, 1]`, with the
/// closing chord when `closed` (then one more value, 1).
fn own_parameters(points: &[P3], kind: Parametrization, closed: bool) -> Vec<f64> {
    let mut chain = points.to_vec();
    if closed {
        chain.push(points[0]);
    }
    let steps: Vec<f64> = chain
        .windows(2)
        .map(|w| {
            let chord = distance(w[0], w[1]);
            match kind {
                Parametrization::ChordLength => chord,
                Parametrization::Centripetal => chord.sqrt(),
                Parametrization::Uniform => 1.0,
            }
        })
        .collect();
    let total: f64 = steps.iter().sum();
    let mut t = vec![0.0];
    let mut sum = 0.0;
    for s in steps {
        sum += s;
        t.push(sum / total);
    }
    *t.last_mut().unwrap() = 1.0;
    t
}

/// The test's own averaged knots (The NURBS Book eq. 9.8; the windows widen by the first or
/// last with an end tangent).
fn own_knots(t: &[f64], p: usize, tangents: [bool; 2]) -> Vec<f64> {
    let m = t.len();
    let count = m + tangents.iter().filter(|&&b| b).count();
    let mut knots = vec![t[0]; p + 1];
    let interior = count - p - 1;
    let first = if tangents[0] { 0 } else { 1 };
    for j in first..first + interior {
        knots.push(t[j..j + p].iter().sum::<f64>() / p as f64);
    }
    knots.extend(std::iter::repeat_n(t[m - 1], p + 1));
    knots
}

/// A reference curve of degree `p` on `knots` with zero control points (for its basis).
fn basis_reference(p: usize, knots: &[f64]) -> Reference {
    Reference {
        degree: p,
        knots: knots.to_vec(),
        points: vec![[0.0; 3]; knots.len() - p - 1],
        weights: None,
    }
}

/// `N'_{j,p}(t)` for every `j` (The NURBS Book eq. 2.7, from the degree `p − 1` basis).
fn basis_derivatives(reference: &Reference, t: f64) -> Vec<f64> {
    let p = reference.degree;
    let u = &reference.knots;
    let lower = reference.basis(p - 1, t);
    let ratio = |a: f64, b: f64| if b == 0.0 { 0.0 } else { a / b };
    (0..u.len() - p - 1)
        .map(|j| {
            p as f64
                * (ratio(lower[j], u[j + p] - u[j]) - ratio(lower[j + 1], u[j + p + 1] - u[j + 1]))
        })
        .collect()
}

/// The dense solve of the open system: rows for the points and the end derivatives.
fn dense_open(
    points: &[P3],
    t: &[f64],
    knots: &[f64],
    p: usize,
    tangents: [Option<P3>; 2],
) -> Vec<P3> {
    let reference = basis_reference(p, knots);
    let mut rows = Vec::new();
    let mut rhs = Vec::new();
    let m = points.len();
    for k in 0..m {
        if k == m - 1 {
            if let Some(d) = tangents[1] {
                rows.push(basis_derivatives(&reference, t[m - 1]));
                rhs.push(d.to_vec());
            }
        }
        rows.push(reference.basis(p, t[k]));
        rhs.push(points[k].to_vec());
        if k == 0 {
            if let Some(d) = tangents[0] {
                rows.push(basis_derivatives(&reference, t[0]));
                rhs.push(d.to_vec());
            }
        }
    }
    dense::solve(rows, rhs)
        .expect("the dense system is regular")
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect()
}

fn parametrization(index: usize) -> Parametrization {
    [
        Parametrization::ChordLength,
        Parametrization::Centripetal,
        Parametrization::Uniform,
    ][index % 3]
}

fn set_of(case: &PointCase) -> PointSet {
    PointSet::new(&case.points, 100_000).unwrap()
}

proptest! {
    #![proptest_config(config())]

    /// Open curves: our parameters and averaged knots equal the test's; the control points
    /// equal the dense solve; the curve passes through every point and has the end
    /// derivatives asked for. Degrees 1–5, 2D/3D, clustered, collinear and zig-zag points.
    #[test]
    fn open_interpolants_match_a_dense_solve(
        case in point_case(2, 24),
        degree in 1usize..=5,
        kind in 0usize..3,
        tangents in (any::<bool>(), any::<bool>()),
        scales in (-1.0..1.0f64, 0.3..3.0f64),
    ) {
        let points = case.points_3d();
        let p = degree;
        let m = points.len();
        let kind = parametrization(kind);
        let t = own_parameters(&points, kind, false);
        // End tangents: along the first and last chords, scaled.
        let first = [0, 1, 2].map(|c| (points[1][c] - points[0][c]) / (t[1] - t[0]) * scales.1);
        let last = [0, 1, 2].map(|c| (points[m - 1][c] - points[m - 2][c]) / (t[m - 1] - t[m - 2]) * (2.0 - scales.1 / 2.0));
        let mut wanted = [tangents.0.then_some(first), tangents.1.then_some(last)];
        if p < 2 {
            wanted = [None, None];
        }
        let given = wanted.iter().flatten().count();
        let spec = InterpolationSpec {
            degree: p,
            parameters: ParameterChoice::By(kind),
            knots: None,
            end_tangents: wanted,
            closed: false,
        };
        let result = interpolate(&set_of(&case), &spec, &CurveLimits::default());
        if m + given < p + 1 {
            let too_few = matches!(result, Err(InterpolationError::Points(PointsError::TooFewPoints { .. })));
            prop_assert!(too_few, "{:?}", result);
            return Ok(());
        }
        let interpolation = result.unwrap();
        let curve = interpolation.curve;
        for (ours, own) in interpolation.parameters.iter().zip(&t) {
            prop_assert!((ours - own).abs() <= 1e-14, "parameter {ours} vs {own}");
        }
        let knots = own_knots(&t, p, [wanted[0].is_some(), wanted[1].is_some()]);
        prop_assert_eq!(curve.knots().len(), knots.len());
        for (ours, own) in curve.knots().iter().zip(&knots) {
            prop_assert!((ours - own).abs() <= 1e-14, "knot {ours} vs {own}");
        }
        let dense = dense_open(&points, &t, &knots, p, wanted);
        let scale = magnitude(&dense);
        for (ours, theirs) in curve.control_points().iter().zip(&dense) {
            prop_assert!(distance(*ours, *theirs) <= DENSE_TOL * scale, "{ours:?} vs {theirs:?} ({:?})", case.shape);
        }
        let reference = Reference {
            degree: p,
            knots: curve.knots().to_vec(),
            points: curve.control_points().to_vec(),
            weights: None,
        };
        for (k, q) in points.iter().enumerate() {
            let at = reference.point(interpolation.parameters[k]);
            prop_assert!(distance(at, *q) <= THROUGH_POINT_TOL * case.size().max(scale), "point {k}: {at:?} vs {q:?}");
        }
        for (end, at) in [(0, 0.0), (1, 1.0)] {
            if let Some(d) = wanted[end] {
                let derivative = if end == 0 {
                    reference.derivatives(at, 1)[1]
                } else {
                    reference.derivatives_from_left(at, 1)[1]
                };
                let scale = d.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                prop_assert!(distance(derivative, d) <= 1e-8 * scale, "end {end}: {derivative:?} vs {d:?}");
            }
        }
    }

    /// Closed curves: the knots follow the periodic rule, the control points equal the dense
    /// solve of the cyclic system (columns folded modulo the point count), the curve passes
    /// through every point, and its derivatives up to order `p − 1` agree across the seam.
    #[test]
    fn closed_interpolants_match_a_dense_cyclic_solve(
        case in point_case(2, 24),
        degree in 1usize..=5,
        kind in 0usize..3,
    ) {
        let points = case.points_3d();
        let p = degree;
        let m = points.len();
        let kind = parametrization(kind);
        let spec = InterpolationSpec {
            degree: p,
            parameters: ParameterChoice::By(kind),
            knots: None,
            end_tangents: [None, None],
            closed: true,
        };
        let set = set_of(&case);
        let result = interpolate(&set, &spec, &CurveLimits::default());
        if m < p + 1 {
            let too_few = matches!(result, Err(InterpolationError::Points(PointsError::TooFewPoints { .. })));
            prop_assert!(too_few, "{:?}", result);
            return Ok(());
        }
        let closing = distance(points[0], points[m - 1]) <= 1e-12 * case.size();
        if closing {
            prop_assert!(result.is_err());
            return Ok(());
        }
        let interpolation = result.unwrap();
        let curve = interpolation.curve;
        let t = own_parameters(&points, kind, true);
        prop_assert_eq!(curve.control_points().len(), m + p);
        // Knots in the domain: the parameters (odd p) or midpoints (even p); spacing periodic.
        let knots = curve.knots();
        prop_assert_eq!(knots.len(), m + 2 * p + 1);
        for i in 0..=m {
            let expected = if p % 2 == 1 || i == 0 || i == m { t[i] } else { 0.5 * (t[i - 1] + t[i]) };
            prop_assert!((knots[p + i] - expected).abs() <= 1e-14);
        }
        for j in 0..knots.len() - m - 1 {
            let a = knots[j + m + 1] - knots[j + m];
            let b = knots[j + 1] - knots[j];
            prop_assert!((a - b).abs() <= 1e-12, "spacing {j}: {a} vs {b}");
        }
        // The dense cyclic solve.
        let reference = basis_reference(p, knots);
        let rows: Vec<Vec<f64>> = (0..m)
            .map(|k| {
                let basis = reference.basis(p, t[k]);
                let mut row = vec![0.0; m];
                for (j, value) in basis.iter().enumerate() {
                    row[j % m] += value;
                }
                row
            })
            .collect();
        let rhs: Vec<Vec<f64>> = points.iter().map(|q| q.to_vec()).collect();
        let dense = dense::solve(rows, rhs).expect("the cyclic system is regular");
        let scale = dense.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
        for (j, pole) in curve.control_points().iter().enumerate() {
            let theirs = &dense[j % m];
            prop_assert!(distance(*pole, [theirs[0], theirs[1], theirs[2]]) <= DENSE_TOL * scale, "pole {j}");
        }
        let reference = Reference {
            degree: p,
            knots: knots.to_vec(),
            points: curve.control_points().to_vec(),
            weights: None,
        };
        for (k, q) in points.iter().enumerate() {
            prop_assert!(distance(reference.point(t[k]), *q) <= THROUGH_POINT_TOL * case.size().max(scale));
        }
        let (lo, hi) = reference.domain();
        let start = reference.derivatives(lo, p - 1);
        let end = reference.derivatives_from_left(hi, p - 1);
        for order in 0..p {
            let size = reference.derivative_scale(lo, order).max(reference.derivative_scale(hi - 1e-12, order));
            prop_assert!(distance(start[order], end[order]) <= SEAM_TOL * size, "order {order}: {:?} vs {:?}", start[order], end[order]);
        }
    }
}

#[test]
fn scipy_make_interp_spline_builds_the_same_curves() {
    let text = include_str!("../data/scipy_interpolation.json");
    let document: Value = serde_json::from_str(text).unwrap();
    for case in document["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let points: Vec<Vec<f64>> = serde_json::from_value(case["points"].clone()).unwrap();
        let degree = case["degree"].as_u64().unwrap() as usize;
        let kind = match case["parametrization"].as_str().unwrap() {
            "chord_length" => Parametrization::ChordLength,
            _ => Parametrization::Centripetal,
        };
        let tangents: Vec<Option<Vec<f64>>> =
            serde_json::from_value(case["end_tangents"].clone()).unwrap();
        let tangent = |i: usize| {
            tangents[i]
                .as_ref()
                .map(|v| [v[0], v[1], v.get(2).copied().unwrap_or(0.0)])
        };
        let spec = InterpolationSpec {
            degree,
            parameters: ParameterChoice::By(kind),
            knots: None,
            end_tangents: [tangent(0), tangent(1)],
            closed: case["closed"].as_bool().unwrap(),
        };
        let set = PointSet::new(&points, 1000).unwrap();
        let interpolation = interpolate(&set, &spec, &CurveLimits::default()).unwrap();
        let numbers = |v: &Value| -> Vec<f64> { serde_json::from_value(v.clone()).unwrap() };
        for (ours, theirs) in interpolation
            .parameters
            .iter()
            .zip(numbers(&case["parameters"]))
        {
            assert!((ours - theirs).abs() < 1e-15, "{name}: parameter");
        }
        let knots = numbers(&case["knots"]);
        assert_eq!(interpolation.curve.knots().len(), knots.len(), "{name}");
        for (ours, theirs) in interpolation.curve.knots().iter().zip(&knots) {
            assert!(
                (ours - theirs).abs() < 1e-14,
                "{name}: knot {ours} vs {theirs}"
            );
        }
        let theirs: Vec<Vec<f64>> = serde_json::from_value(case["control_points"].clone()).unwrap();
        let scale = theirs.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
        assert_eq!(
            interpolation.curve.control_points().len(),
            theirs.len(),
            "{name}"
        );
        for (ours, theirs) in interpolation.curve.control_points().iter().zip(&theirs) {
            for (c, value) in theirs.iter().enumerate() {
                assert!(
                    (ours[c] - value).abs() <= SCIPY_TOL * scale,
                    "{name}: {ours:?} vs {theirs:?}"
                );
            }
        }
    }
}

#[test]
fn the_books_example_9_1_has_its_published_parameters_and_knot() {
    // The NURBS Book, Example 9.1: ū = 0, 5/17, 9/17, 14/17, 1 and the knot 28/51.
    let points = [
        [0.0, 0.0],
        [3.0, 4.0],
        [-1.0, 4.0],
        [-4.0, 0.0],
        [-4.0, -3.0],
    ];
    let set = PointSet::new(&points, 10).unwrap();
    let spec = InterpolationSpec {
        degree: 3,
        parameters: ParameterChoice::By(Parametrization::ChordLength),
        knots: None,
        end_tangents: [None, None],
        closed: false,
    };
    let interpolation = interpolate(&set, &spec, &CurveLimits::default()).unwrap();
    let published = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
    for (ours, book) in interpolation.parameters.iter().zip(published) {
        assert!((ours - book).abs() < 1e-15);
    }
    assert!((interpolation.curve.knots()[4] - 28.0 / 51.0).abs() < 1e-15);
}

#[test]
fn given_parameters_and_knots_are_used_and_checked() {
    let points = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0], [4.0, 0.0]];
    let set = PointSet::new(&points, 10).unwrap();
    let parameters = [0.0, 1.0, 2.0, 3.0, 4.0];
    // The trimmed convention: 5 + 3 − 1 = 7 values.
    let knots = [0.0, 0.0, 0.0, 2.0, 4.0, 4.0, 4.0];
    let spec = InterpolationSpec {
        degree: 3,
        parameters: ParameterChoice::Given(&parameters),
        knots: Some(&knots),
        end_tangents: [None, None],
        closed: false,
    };
    let interpolation = interpolate(&set, &spec, &CurveLimits::default()).unwrap();
    assert_eq!(interpolation.curve.knots_in_convention(), &knots);
    for (k, q) in points.iter().enumerate() {
        let at = interpolation.curve.point(parameters[k]).unwrap();
        assert!(distance(at, [q[0], q[1], 0.0]) < 1e-13);
    }
    // Knots that violate Schoenberg–Whitney: N_1 (support (0, 0.5)) vanishes at ū_1 = 1.
    let six = PointSet::new(
        &[
            [0.0, 0.0],
            [1.0, 1.0],
            [2.0, 0.0],
            [3.0, 1.0],
            [4.0, 0.0],
            [5.0, 1.0],
        ],
        10,
    )
    .unwrap();
    let six_parameters = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    let bad = [0.0, 0.0, 0.0, 0.2, 0.5, 5.0, 5.0, 5.0];
    let singular = interpolate(
        &six,
        &InterpolationSpec {
            parameters: ParameterChoice::Given(&six_parameters),
            knots: Some(&bad),
            ..spec
        },
        &CurveLimits::default(),
    );
    assert!(
        matches!(
            singular,
            Err(InterpolationError::Singular { given_knots: true })
        ),
        "{singular:?}"
    );
    let decreasing = [0.0, 1.0, 1.0, 3.0, 4.0];
    let error = interpolate(
        &set,
        &InterpolationSpec {
            parameters: ParameterChoice::Given(&decreasing),
            knots: None,
            ..spec
        },
        &CurveLimits::default(),
    )
    .unwrap_err();
    assert!(matches!(
        error,
        InterpolationError::Points(PointsError::ParametersNotIncreasing { index: 2 })
    ));
}

#[test]
fn bad_requests_are_named() {
    let limits = CurveLimits::default();
    let spec = |degree| InterpolationSpec {
        degree,
        parameters: ParameterChoice::By(Parametrization::ChordLength),
        knots: None,
        end_tangents: [None, None],
        closed: false,
    };
    let three = PointSet::new(&[[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]], 10).unwrap();
    assert!(matches!(
        interpolate(&three, &spec(3), &limits),
        Err(InterpolationError::Points(PointsError::TooFewPoints {
            needed: 4,
            ..
        }))
    ));
    // One tangent makes room for the cubic.
    let with_tangent = InterpolationSpec {
        end_tangents: [Some([1.0, 0.0, 0.0]), None],
        ..spec(3)
    };
    assert!(interpolate(&three, &with_tangent, &limits).is_ok());
    let repeated = PointSet::new(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [2.0, 1.0]], 10).unwrap();
    assert!(matches!(
        interpolate(&repeated, &spec(2), &limits),
        Err(InterpolationError::Points(PointsError::CoincidentPoints {
            index: 2,
            ..
        }))
    ));
    let small = CurveLimits {
        max_control_points: 2,
        ..limits
    };
    assert!(matches!(
        interpolate(&three, &spec(1), &small),
        Err(InterpolationError::TooManyControlPoints { count: 3, max: 2 })
    ));
    let closed_with_tangent = InterpolationSpec {
        closed: true,
        ..with_tangent
    };
    assert!(matches!(
        interpolate(&three, &closed_with_tangent, &limits),
        Err(InterpolationError::ClosedWithTangents)
    ));
    let linear_with_tangent = InterpolationSpec {
        degree: 1,
        ..with_tangent
    };
    assert!(matches!(
        interpolate(&three, &linear_with_tangent, &limits),
        Err(InterpolationError::TangentsNeedDegreeTwo)
    ));
}

#[test]
fn ten_thousand_points_interpolate_in_a_banded_solve() {
    // Large enough that a dense n × n solve (10^12 operations) could not finish in a test.
    let points: Vec<[f64; 2]> = (0..10_000)
        .map(|i| {
            let a = i as f64 * 0.01;
            [a.cos() * (1.0 + 0.1 * a), a.sin() * (1.0 + 0.1 * a)]
        })
        .collect();
    let set = PointSet::new(&points, 10_000).unwrap();
    let spec = InterpolationSpec {
        degree: 3,
        parameters: ParameterChoice::By(Parametrization::ChordLength),
        knots: None,
        end_tangents: [None, None],
        closed: false,
    };
    let interpolation = interpolate(&set, &spec, &CurveLimits::default()).unwrap();
    for k in (0..10_000).step_by(997) {
        let at = interpolation
            .curve
            .point(interpolation.parameters[k])
            .unwrap();
        assert!(distance(at, [points[k][0], points[k][1], 0.0]) < 1e-10);
    }
}
