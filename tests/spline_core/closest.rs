//! The closest-point search against brute force: dense sampling with the reference evaluator
//! plus golden-section refinement around every sampled local minimum; and adversarial queries
//! with known answers (curve ends, corners, points on the curve, far away, ties, circles).

use knotshape::spline::{CLOSEST_POINT_TOLERANCE, ClosestPointSearch, Curve, CurveLimits};
use proptest::prelude::*;

use super::generators::{CaseOptions, curve_case};
use super::reference::{P3, Reference};

/// Uniform samples of the brute force (plus every knot in the range).
const SAMPLES: usize = 600;

/// Golden-section steps per sampled local minimum (the bracket shrinks to 0.618^80).
const GOLDEN_STEPS: usize = 80;

fn dist(a: P3, b: P3) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

/// The least distance from `q` to the reference curve on `[lo, hi]`, by sampling and
/// refinement; independent of the Bézier search.
fn brute_force(reference: &Reference, q: P3, lo: f64, hi: f64) -> f64 {
    let mut parameters: Vec<f64> = (0..=SAMPLES)
        .map(|i| (lo + (hi - lo) * i as f64 / SAMPLES as f64).min(hi))
        .collect();
    parameters.extend(
        reference
            .knots
            .iter()
            .copied()
            .filter(|&u| lo < u && u < hi),
    );
    parameters.sort_by(f64::total_cmp);
    parameters.dedup();
    let gap = |u: f64| dist(reference.point(u), q);
    let values: Vec<f64> = parameters.iter().map(|&u| gap(u)).collect();
    let mut best = values.iter().copied().fold(f64::INFINITY, f64::min);
    for i in 0..parameters.len() {
        let left = if i > 0 { values[i - 1] } else { f64::INFINITY };
        let right = values.get(i + 1).copied().unwrap_or(f64::INFINITY);
        if values[i] > left || values[i] > right {
            continue;
        }
        let mut a = parameters[i.saturating_sub(1)];
        let mut b = parameters[(i + 1).min(parameters.len() - 1)];
        for _ in 0..GOLDEN_STEPS {
            let x = b - 0.618_033_988_749_895 * (b - a);
            let y = a + 0.618_033_988_749_895 * (b - a);
            if gap(x) < gap(y) { b = y } else { a = x }
        }
        best = best.min(gap(0.5 * (a + b)));
    }
    best
}

fn curve(degree: usize, points: &[&[f64]], knots: &[f64], weights: Option<&[f64]>) -> Curve {
    let points: Vec<Vec<f64>> = points.iter().map(|p| p.to_vec()).collect();
    Curve::new(degree, &points, knots, weights, &CurveLimits::default()).unwrap()
}

/// The closest point's parameter and distance for `q` over `range`.
fn closest(curve: &Curve, q: P3, range: Option<(f64, f64)>) -> (f64, f64) {
    let found = ClosestPointSearch::new(curve, range).unwrap().closest(q);
    (found.parameter, found.distance)
}

proptest! {
    #![proptest_config(proptest::test_runner::Config {
        cases: 1024,
        ..super::config()
    })]

    /// ≥ 1000 random curves (degrees 1–5, 2D/3D, rational or not, clamped or not, both knot
    /// conventions): near, random and far queries, the whole domain or a sub-range. The answer
    /// is a true curve point at its parameter, and no sampled-and-refined point is closer.
    #[test]
    fn closest_point_is_the_global_minimum(
        case in curve_case(CaseOptions { min_degree: 1, max_degree: 5, clamped: None }),
        at in 0.0..1.0f64,
        offset in prop::array::uniform3(-3.0..3.0f64),
        scale in prop_oneof![Just(0.01), Just(1.0), Just(30.0)],
        range_ends in (0.0..1.0f64, 0.0..1.0f64),
        sub_range in any::<bool>(),
    ) {
        let curve = case.curve();
        let reference = &case.reference;
        let (lo, hi) = reference.domain();
        let (lo, hi) = if sub_range {
            let (f, g) = (range_ends.0.min(range_ends.1), range_ends.0.max(range_ends.1));
            (lo + f * (hi - lo), lo + g * (hi - lo))
        } else {
            (lo, hi)
        };
        let base = reference.point(lo + at * (hi - lo));
        let planar = case.control_points[0].len() == 2;
        let q: P3 = std::array::from_fn(|c| {
            if planar && c == 2 { 0.0 } else { base[c] + scale * offset[c] }
        });
        let search = ClosestPointSearch::new(&curve, Some((lo, hi))).unwrap();
        let found = search.closest(q);
        let size = reference.point_scale();
        prop_assert!(lo <= found.parameter && found.parameter <= hi);
        // The answer is the curve's point at its parameter, measured honestly.
        let truth = reference.point(found.parameter);
        prop_assert!(dist(truth, found.point) <= 1e-10 * size, "{:?} vs {:?}", truth, found.point);
        prop_assert!((dist(truth, q) - found.distance).abs() <= 1e-10 * (size + found.distance));
        let brute = brute_force(reference, q, lo, hi);
        prop_assert!(
            found.distance <= brute + 1e-9 * (size + brute),
            "search {} at {} > brute force {} for q {:?} on [{}, {}]: degree {}, points {:?}, weights {:?}, knots {:?}",
            found.distance, found.parameter, brute, q, lo, hi, case.degree, case.control_points, case.weights, case.knots
        );
    }

    /// Queries very near the curve, `10^-13` to `10^-5` of its size off a curve point (at a
    /// random parameter, an end, just inside an end or just beside a knot), on curves that are half the time closed (the last control
    /// point moved onto the first, so both ends meet at a seam): the answer is never farther
    /// than that curve point, however small the distance.
    #[test]
    fn queries_very_near_the_curve_and_its_seam(
        mut case in curve_case(CaseOptions { min_degree: 1, max_degree: 5, clamped: Some(true) }),
        at in prop_oneof![Just(0.0), Just(1.0), Just(1e-9), Just(1.0 - 1e-9), 0.0..1.0f64],
        next_to_knot in prop_oneof![Just(None), (0usize..64, -1e-7..1e-7f64).prop_map(Some)],
        offset in prop::array::uniform3(-1.0..1.0f64),
        exponent in -13i32..=-5,
        closed in any::<bool>(),
    ) {
        if closed {
            let first = case.control_points[0].clone();
            *case.control_points.last_mut().unwrap() = first;
            let first = case.reference.points[0];
            *case.reference.points.last_mut().unwrap() = first;
        }
        let curve = case.curve();
        let reference = &case.reference;
        let (lo, hi) = reference.domain();
        // A parameter just inside an end, or just beside a knot (which the search measures
        // first, as piece ends), is where a near tie used to hide the nearer point.
        let knots: Vec<f64> = reference.knots.iter().copied().filter(|&u| lo <= u && u <= hi).collect();
        let t = match next_to_knot {
            Some((pick, shift)) => (knots[pick % knots.len()] + shift * (hi - lo)).clamp(lo, hi),
            None => lo + at * (hi - lo),
        };
        let base = reference.point(t);
        let size = reference.point_scale();
        let planar = case.control_points[0].len() == 2;
        let q: P3 = std::array::from_fn(|c| {
            if planar && c == 2 { 0.0 } else { base[c] + 10f64.powi(exponent) * size * offset[c] }
        });
        let found = ClosestPointSearch::new(&curve, None).unwrap().closest(q);
        let near = dist(base, q);
        // Ties as the search defines them (within the tolerance of the control points'
        // bounding-box diagonal), and the two evaluators' rounding (a few units in the last
        // place of the coordinates: a closed curve of two equal control points is one point).
        let diagonal = {
            let (mut min, mut max) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for d in &reference.points {
                for c in 0..3 {
                    min[c] = min[c].min(d[c]);
                    max[c] = max[c].max(d[c]);
                }
            }
            dist(min, max)
        };
        let rounding = 4.0 * (case.degree + 1) as f64 * f64::EPSILON * size;
        prop_assert!(
            found.distance <= near + CLOSEST_POINT_TOLERANCE * (diagonal + near) + rounding,
            "found {:e} at {} but s({}) is {:e} away (closed: {})",
            found.distance, found.parameter, t, near, closed
        );
    }
}

#[test]
fn beyond_an_end_the_end_is_closest() {
    // A clamped cubic; queries past either end along the end tangents.
    let c = curve(
        3,
        &[
            &[0.0, 0.0],
            &[1.0, 2.0],
            &[3.0, 2.0],
            &[4.0, 0.0],
            &[6.0, 1.0],
        ],
        &[0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        None,
    );
    let (u, d) = closest(&c, [-1.0, -2.0, 0.0], None);
    assert_eq!(u, 0.0);
    assert!((d - 5f64.sqrt()).abs() < 1e-12);
    let (u, d) = closest(&c, [8.0, 2.0, 0.0], None);
    assert_eq!(u, 1.0);
    assert!((d - 5f64.sqrt()).abs() < 1e-12);
}

#[test]
fn outside_a_corner_the_corner_is_closest() {
    // Two quadratic arcs meeting at a C0 corner (1, 1) (knot 0.5 of multiplicity 2 = degree).
    let c = curve(
        2,
        &[
            &[0.0, 0.0],
            &[0.5, 1.0],
            &[1.0, 1.0],
            &[1.5, 1.0],
            &[2.0, 0.0],
        ],
        &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        None,
    );
    let (u, d) = closest(&c, [1.0, 3.0, 0.0], None);
    assert_eq!(u, 0.5);
    assert!((d - 2.0).abs() < 1e-12);
}

#[test]
fn a_point_on_the_curve_is_found_at_distance_zero() {
    let c = curve(
        3,
        &[
            &[0.0, 0.0, 0.0],
            &[1.0, 2.0, 1.0],
            &[3.0, 2.0, -1.0],
            &[4.0, 0.0, 2.0],
            &[6.0, 1.0, 0.0],
        ],
        &[0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
        Some(&[1.0, 2.0, 0.5, 1.0, 3.0]),
    );
    for t in [0.0, 0.1, 0.4, 0.77, 1.0] {
        let q = c.point(t).unwrap();
        let (u, d) = closest(&c, q, None);
        assert!(d < 1e-12, "t = {t}: distance {d}");
        assert!((u - t).abs() < 1e-6, "t = {t}: parameter {u}");
    }
}

#[test]
fn far_away_queries_still_find_the_global_minimum() {
    let c = curve(
        3,
        &[
            &[0.0, 0.0],
            &[1.0, 2.0],
            &[3.0, 2.0],
            &[4.0, 0.0],
            &[6.0, 1.0],
        ],
        &[0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        None,
    );
    let reference = Reference {
        degree: 3,
        knots: c.knots().to_vec(),
        points: c.control_points().to_vec(),
        weights: None,
    };
    for q in [[1e6, 3e5, 0.0], [-4e7, -1e7, 0.0], [3.0, -1e9, 0.0]] {
        let (_, d) = closest(&c, q, None);
        let brute = brute_force(&reference, q, 0.0, 1.0);
        assert!(d <= brute * (1.0 + 1e-12), "{q:?}: {d} > {brute}");
    }
}

#[test]
fn equidistant_arcs_tie_to_the_smaller_parameter() {
    // A cubic symmetric about x = 2 (mirror control points, symmetric knots): its two humps
    // are equally close to a point on the axis above them.
    let c = curve(
        3,
        &[
            &[0.0, 0.0],
            &[0.5, 2.0],
            &[1.5, 2.0],
            &[2.0, 0.0],
            &[2.5, 2.0],
            &[3.5, 2.0],
            &[4.0, 0.0],
        ],
        &[0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0],
        None,
    );
    let (u, _) = closest(&c, [2.0, 5.0, 0.0], None);
    assert!(u < 0.5, "the left hump comes first: {u}");
    // The mirror image of the answer is just as close: a true tie.
    let left = c.point(u).unwrap();
    let right = c.point(1.0 - u).unwrap();
    assert!((left[1] - right[1]).abs() < 1e-12 && (left[0] + right[0] - 4.0).abs() < 1e-12);
}

#[test]
fn near_the_centre_of_a_circle_the_radial_point_is_closest() {
    // A rational quadratic quarter circle of radius 2 about the origin.
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = curve(
        2,
        &[&[2.0, 0.0], &[2.0, 2.0], &[0.0, 2.0]],
        &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        Some(&[1.0, w, 1.0]),
    );
    for q in [[1e-3, 2e-3, 0.0], [0.3, 0.1, 0.0], [1e-9, 1e-9, 0.0]] {
        let found = ClosestPointSearch::new(&arc, None).unwrap().closest(q);
        let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
        assert!(
            (found.distance - (2.0 - r)).abs() < 1e-12,
            "{q:?}: {}",
            found.distance
        );
        let expected = [2.0 * q[0] / r, 2.0 * q[1] / r];
        assert!(
            (found.point[0] - expected[0]).abs() < 1e-6,
            "{q:?}: {:?}",
            found.point
        );
        assert!(
            (found.point[1] - expected[1]).abs() < 1e-6,
            "{q:?}: {:?}",
            found.point
        );
    }
    // Exactly at the centre every point ties: the smallest parameter.
    let (u, d) = closest(&arc, [0.0, 0.0, 0.0], None);
    assert_eq!(u, 0.0);
    assert!((d - 2.0).abs() < 1e-14 * 2.0 + CLOSEST_POINT_TOLERANCE);
}

#[test]
fn a_range_restricts_the_search() {
    let c = curve(
        3,
        &[
            &[0.0, 0.0],
            &[1.0, 2.0],
            &[3.0, 2.0],
            &[4.0, 0.0],
            &[6.0, 1.0],
        ],
        &[0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        None,
    );
    // Near the start point, but the range starts at 0.6: its start is the closest.
    let (u, _) = closest(&c, [0.0, 0.0, 0.0], Some((0.6, 0.9)));
    assert_eq!(u, 0.6);
    let (u, _) = closest(&c, [6.0, 1.0, 0.0], Some((0.2, 0.7)));
    assert_eq!(u, 0.7);
    // A single-point range.
    let (u, _) = closest(&c, [6.0, 1.0, 0.0], Some((0.3, 0.3)));
    assert_eq!(u, 0.3);
    assert!(ClosestPointSearch::new(&c, Some((0.5, 0.4))).is_err());
    assert!(ClosestPointSearch::new(&c, Some((-0.5, 0.4))).is_err());
    assert!(ClosestPointSearch::new(&c, Some((0.1, f64::NAN))).is_err());
}

/// Issue 20's case: a closed cubic (first control point = last) and a query 9.27e-9 from the
/// seam. The point at `u = 0.999999999914` is 2.98e-9 away, nearer than the seam itself; the
/// Bernstein search alone cannot tell them apart (both are within its rounding noise), the
/// polished candidates can.
#[test]
fn a_query_next_to_a_closed_curves_seam_finds_the_nearer_side() {
    let points: [&[f64]; 11] = [
        &[-1.5089046792388427, -0.31344828797400304, 4.592269136048317],
        &[-3.550727542619967, 2.603869469707911, 4.641558531000271],
        &[-4.2313642544501455, 4.800192177425679, 0.5099725533290709],
        &[-0.8221294587351471, -3.170521055180673, -1.8928805606468782],
        &[0.7369232588458896, -3.702311200854612, 0.7676050707760709],
        &[-1.519620002350007, 1.590196259224177, -4.759968481226602],
        &[3.344906864914716, 3.9026070492770213, 0.9173961043047782],
        &[-2.2260637921172033, -4.910353229829091, -0.5284357605307672],
        &[2.3575136812998707, -3.7794648033544878, 4.416596080576024],
        &[-2.444843159710801, -2.3727167399762985, -2.9897975824993495],
        &[-1.5089046792388427, -0.31344828797400304, 4.592269136048317],
    ];
    let knots = [
        0.0,
        0.0,
        0.0,
        0.0,
        0.039410670198165465,
        0.12763490421325163,
        0.20394160510478776,
        0.20394160510478776,
        0.20394160510478776,
        0.7603316025080157,
        0.7670126857239229,
        1.0,
        1.0,
        1.0,
        1.0,
    ];
    let q = [-1.5089046799191852, -0.3134482874135482, 4.592269126820995];
    let closed = curve(3, &points, &knots, None);
    let reference = Reference {
        degree: 3,
        knots: knots.to_vec(),
        points: points.iter().map(|p| [p[0], p[1], p[2]]).collect(),
        weights: None,
    };
    let (u, d) = closest(&closed, q, None);
    // The numbers: the seam is 9.27e-9 away, the nearer side 2.98e-9.
    assert!((dist(reference.point(0.0), q) - 9.27e-9).abs() < 1e-11);
    assert!((dist(reference.point(0.999999999914), q) - 2.98e-9).abs() < 1e-11);
    assert!(u > 0.99999999, "u = {u}, at distance {d:e}");
    assert!(d <= 2.99e-9, "distance {d:e}");
    assert!((dist(reference.point(u), q) - d).abs() < 1e-15);
}
