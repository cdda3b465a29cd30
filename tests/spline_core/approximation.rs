//! Approximation to a tolerance (`knotshape::spline::approximate`), checked by brute force:
//! every point's distance to the answer, found by dense sampling of the reference evaluator
//! and a golden-section refinement, is within the tolerance and never below the distance
//! the answer reports at its closest parameter (which claims the global minimum); the ends
//! are exact when asked; points on a polynomial of the degree need one Bézier piece.

use knotshape::spline::{
    ApproximationError, ApproximationSpec, Curve, CurveLimits, Parametrization, PointSet,
    PointsError, approximate,
};
use proptest::prelude::*;
use proptest::test_runner::Config;

use super::config;
use super::point_sets::{PointCase, point_case};
use super::reference::{P3, Reference};

/// Samples per knot span of the brute-force search.
const SAMPLES_PER_SPAN: usize = 200;
/// Golden-section steps refining the best sample.
const GOLDEN_STEPS: usize = 80;
/// Slack of the comparisons, relative to the points' size.
const DISTANCE_TOL: f64 = 1e-9;

fn distance(a: P3, b: P3) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

fn reference_of(curve: &Curve) -> Reference {
    Reference {
        degree: curve.degree(),
        knots: curve.knots().to_vec(),
        points: curve.control_points().to_vec(),
        weights: curve.weights().map(<[f64]>::to_vec),
    }
}

/// The distance from `q` to the curve by brute force: dense samples, then a golden-section
/// search on both sample intervals beside every sample nearer than its neighbours (each
/// interval inside one knot span, where the distance is smooth); the least value found.
fn brute_force_distance(reference: &Reference, samples: &[(f64, P3)], q: P3) -> f64 {
    let distances: Vec<f64> = samples.iter().map(|s| distance(s.1, q)).collect();
    let f = |t: f64| distance(reference.point(t), q);
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let golden = |mut lo: f64, mut hi: f64| {
        for _ in 0..GOLDEN_STEPS {
            let a = hi - ratio * (hi - lo);
            let b = lo + ratio * (hi - lo);
            if f(a) < f(b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        f(0.5 * (lo + hi))
    };
    let last = samples.len() - 1;
    let mut best = distances.iter().copied().fold(f64::INFINITY, f64::min);
    for i in 0..=last {
        let before = if i > 0 {
            distances[i - 1]
        } else {
            f64::INFINITY
        };
        let after = if i < last {
            distances[i + 1]
        } else {
            f64::INFINITY
        };
        if distances[i] <= before && distances[i] <= after {
            if i > 0 {
                best = best.min(golden(samples[i - 1].0, samples[i].0));
            }
            if i < last {
                best = best.min(golden(samples[i].0, samples[i + 1].0));
            }
        }
    }
    best
}

fn samples(reference: &Reference) -> Vec<(f64, P3)> {
    let (lo, hi) = reference.domain();
    let mut breaks: Vec<f64> = reference
        .knots
        .iter()
        .copied()
        .filter(|&u| lo <= u && u <= hi)
        .collect();
    breaks.dedup();
    let mut out = Vec::new();
    for w in breaks.windows(2) {
        for i in 0..SAMPLES_PER_SPAN {
            let t = w[0] + (w[1] - w[0]) * i as f64 / SAMPLES_PER_SPAN as f64;
            out.push((t, reference.point(t)));
        }
    }
    out.push((hi, reference.point(hi)));
    out
}

/// Checks an answer by brute force (module docs); returns the largest brute-force distance.
fn check(
    case: &PointCase,
    spec: &ApproximationSpec,
    curve: &Curve,
    max_error: f64,
    parameters: &[f64],
) -> Result<f64, TestCaseError> {
    let points = case.points_3d();
    let size = case.size();
    let reference = reference_of(curve);
    let dense = samples(&reference);
    let mut largest = 0.0f64;
    let mut reported = 0.0f64;
    for (k, q) in points.iter().enumerate() {
        let brute = brute_force_distance(&reference, &dense, *q);
        let ours = distance(reference.point(parameters[k]), *q);
        prop_assert!(
            ours <= brute + DISTANCE_TOL * size,
            "point {k}: the reported closest point ({ours}) is farther than brute force ({brute})"
        );
        largest = largest.max(brute);
        reported = reported.max(ours);
    }
    prop_assert!(
        largest <= spec.tolerance * (1.0 + 1e-12),
        "{largest} > {}",
        spec.tolerance
    );
    prop_assert!(
        (reported - max_error).abs() <= DISTANCE_TOL * size,
        "{reported} vs {max_error}"
    );
    if spec.end_points_exact {
        let (lo, hi) = reference.domain();
        let ends = [
            distance(reference.point(lo), points[0]),
            distance(reference.point(hi), points[points.len() - 1]),
        ];
        prop_assert!(
            ends[0] <= 1e-12 * size.max(1.0) && ends[1] <= 1e-12 * size.max(1.0),
            "ends {ends:?}"
        );
    }
    Ok(largest)
}

fn fewer_cases() -> Config {
    Config {
        cases: 48,
        ..config()
    }
}

proptest! {
    #![proptest_config(fewer_cases())]

    /// Random point sets (clustered, nearly collinear, zig-zag, scattered), degrees 1–5,
    /// 2D/3D, tolerances from 1e-1 to 1e-4 of the size, ends exact or not.
    #[test]
    fn every_point_is_within_the_tolerance_by_brute_force(
        case in point_case(2, 40),
        degree in 1usize..=5,
        exponent in 1.0..4.0f64,
        kind in 0usize..3,
        ends_exact in any::<bool>(),
    ) {
        let set = PointSet::new(&case.points, 10_000).unwrap();
        let spec = ApproximationSpec {
            degree,
            tolerance: 10f64.powf(-exponent) * case.size(),
            parametrization: [Parametrization::ChordLength, Parametrization::Centripetal, Parametrization::Uniform][kind],
            end_points_exact: ends_exact,
        };
        let result = approximate(&set, &spec, &CurveLimits::default());
        if case.points.len() < degree + 1 {
            let too_few = matches!(result, Err(ApproximationError::Points(PointsError::TooFewPoints { .. })));
            prop_assert!(too_few, "{:?}", result);
            return Ok(());
        }
        let answer = result.unwrap();
        prop_assert_eq!(answer.curve.degree(), degree);
        prop_assert!(answer.curve.control_points().len() <= case.points.len().max(degree + 1));
        check(&case, &spec, &answer.curve, answer.max_error, &answer.parameters)?;
    }
}

#[test]
fn points_on_a_polynomial_of_the_degree_need_one_piece() {
    // x uniform: the uniform parametrization is the polynomial's own, so the first least
    // squares fit is exact; chord length needs the Gauss–Newton parameter correction.
    for degree in 1..=5usize {
        let points: Vec<[f64; 3]> = (0..=60)
            .map(|i| {
                let x = i as f64 / 60.0;
                [x, x.powi(degree as i32) - 0.5 * x, 0.3 * x]
            })
            .collect();
        let set = PointSet::new(&points, 1000).unwrap();
        let uniform = ApproximationSpec {
            degree,
            tolerance: 1e-9,
            parametrization: Parametrization::Uniform,
            end_points_exact: true,
        };
        let answer = approximate(&set, &uniform, &CurveLimits::default()).unwrap();
        assert_eq!(
            answer.curve.control_points().len(),
            degree + 1,
            "degree {degree}"
        );
        assert!(answer.max_error <= 1e-9);
        if degree <= 3 {
            let chord = ApproximationSpec {
                tolerance: 1e-5,
                parametrization: Parametrization::ChordLength,
                ..uniform
            };
            let answer = approximate(&set, &chord, &CurveLimits::default()).unwrap();
            assert_eq!(
                answer.curve.control_points().len(),
                degree + 1,
                "degree {degree}"
            );
        }
    }
}

#[test]
fn a_dense_sampling_of_a_smooth_curve_needs_far_fewer_poles_than_points() {
    // 500 points on two turns of a spiral; at 1e-3 of the size a few dozen poles do.
    let points: Vec<[f64; 2]> = (0..500)
        .map(|i| {
            let a = i as f64 / 499.0 * 4.0 * std::f64::consts::PI;
            [a.cos() * (1.0 + a), a.sin() * (1.0 + a)]
        })
        .collect();
    let case = PointCase {
        shape: super::point_sets::Shape::Scattered,
        points: points.iter().map(|p| p.to_vec()).collect(),
    };
    let set = PointSet::new(&points, 1000).unwrap();
    let spec = ApproximationSpec {
        degree: 3,
        tolerance: 1e-3 * case.size(),
        parametrization: Parametrization::ChordLength,
        end_points_exact: true,
    };
    let answer = approximate(&set, &spec, &CurveLimits::default()).unwrap();
    let poles = answer.curve.control_points().len();
    assert!(poles <= 40, "{poles} poles");
    check(
        &case,
        &spec,
        &answer.curve,
        answer.max_error,
        &answer.parameters,
    )
    .unwrap();
}

#[test]
fn bad_requests_are_refused() {
    let set = PointSet::new(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]], 10).unwrap();
    let spec = ApproximationSpec {
        degree: 3,
        tolerance: 0.1,
        parametrization: Parametrization::ChordLength,
        end_points_exact: true,
    };
    let limits = CurveLimits::default();
    assert!(matches!(
        approximate(&set, &spec, &limits),
        Err(ApproximationError::Points(PointsError::TooFewPoints {
            needed: 4,
            ..
        }))
    ));
    for tolerance in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let spec = ApproximationSpec {
            degree: 2,
            tolerance,
            ..spec
        };
        assert!(matches!(
            approximate(&set, &spec, &limits),
            Err(ApproximationError::InvalidTolerance)
        ));
    }
    let tiny = ApproximationSpec {
        degree: 2,
        tolerance: 1e-12,
        ..spec
    };
    assert!(matches!(
        approximate(&set, &tiny, &limits),
        Err(ApproximationError::ToleranceBelowFloor { .. })
    ));
    let same = PointSet::new(&[[1.0, 1.0]; 5], 10).unwrap();
    assert!(matches!(
        approximate(&same, &ApproximationSpec { degree: 2, ..spec }, &limits),
        Err(ApproximationError::Points(PointsError::AllPointsCoincide))
    ));
}

/// A zig-zag of 21 points that a random run of the property above found (degree 1, chord
/// length, ends exact, tolerance 10^-1.3018 of the size): the start must be exact too.
#[test]
fn a_degree_1_zig_zag_keeps_both_ends_exact() {
    let points: Vec<Vec<f64>> = vec![
        vec![0.0, 0.5506365822551728],
        vec![1.0, -0.6909199412562784],
        vec![2.0, 0.5],
        vec![3.0, -0.5],
        vec![4.0, 0.7053968849529083],
        vec![5.125600233132254, -1.1821151646734522],
        vec![6.125476862537245, 0.5],
        vec![7.0, -0.9058495348394895],
        vec![8.118718576098612, 1.3163802585204067],
        vec![9.09908891703313, -0.6408690644273349],
        vec![10.0, 0.8465243594077874],
        vec![11.103707113293938, -0.7408475487105379],
        vec![12.0, 0.9049036065459004],
        vec![13.144708137893236, -1.3449438487993084],
        vec![14.0, 0.5],
        vec![15.0, -1.4272567922600365],
        vec![16.09384503507483, 1.1472027181288618],
        vec![17.130127625518643, -0.6196689796851234],
        vec![18.174580829909786, 0.5],
        vec![19.0, -0.5],
        vec![20.10350116163413, 1.28758022956938],
    ];
    let case = PointCase {
        shape: super::point_sets::Shape::ZigZag,
        points,
    };
    let set = PointSet::new(&case.points, 10_000).unwrap();
    let spec = ApproximationSpec {
        degree: 1,
        tolerance: 10f64.powf(-1.3018006183793578) * case.size(),
        parametrization: Parametrization::ChordLength,
        end_points_exact: true,
    };
    let answer = approximate(&set, &spec, &CurveLimits::default()).unwrap();
    check(
        &case,
        &spec,
        &answer.curve,
        answer.max_error,
        &answer.parameters,
    )
    .unwrap();
}
