//! `/v1/curves/elevate-degree`, `/remove-knots`, `/split`, `/length` and evaluate's
//! `curvature` over HTTP, on a planar cubic and a rational 3D curve in both knot conventions:
//! answers compared with the test's own de Boor, the caller's convention kept, and the rules
//! refused with 422s that name the field.

use serde_json::{Value, json};

use crate::helpers::{assert_problem, numbers, spawn_app};
use crate::reference::{Lcg, ReferenceCurve, cubic_2d, distance, rational_3d};

/// Same-curve comparisons (coordinates ~10).
const SAME_TOL: f64 = 1e-11;

fn grid(curve: &ReferenceCurve) -> Vec<f64> {
    let (lo, hi) = curve.domain();
    (0..=64).map(|i| lo + (hi - lo) * i as f64 / 64.0).collect()
}

fn largest_gap(a: &ReferenceCurve, b: &ReferenceCurve, parameters: &[f64]) -> f64 {
    parameters
        .iter()
        .map(|&t| distance(&a.point(t), &b.point(t)))
        .fold(0.0, f64::max)
}

/// Whether the answer's knots are in the trimmed convention (`n + p − 1` values).
fn is_trimmed(curve: &Value) -> bool {
    let n = curve["control_points"].as_array().unwrap().len();
    let p = curve["degree"].as_u64().unwrap() as usize;
    curve["knots"].as_array().unwrap().len() == n + p - 1
}

/// The values of issue 30's report: inserted into a degree-4 curve, each comes out as often
/// as it went in with tolerance 0, whether the removal lists the distinct values once, the
/// inserted list, or nothing.
const REPORTED_INSERTIONS: [f64; 7] = [
    0.179589, 0.179589, 0.289034, 0.289034, 0.378234, 0.801368, 0.801368,
];

/// A random curve of degree `degree` with `count` control points on `[0, 1]`: clamped or
/// not, 2D or 3D, rational or not.
fn random_curve(
    random: &mut Lcg,
    degree: usize,
    count: usize,
    clamped: bool,
    dimension: usize,
    rational: bool,
) -> ReferenceCurve {
    let points: Vec<Vec<f64>> = (0..count)
        .map(|_| {
            (0..dimension)
                .map(|_| random.between(-10.0, 10.0))
                .collect()
        })
        .collect();
    let mut knots: Vec<f64> = if clamped {
        let mut interior: Vec<f64> = (0..count - degree - 1).map(|_| random.unit()).collect();
        interior.sort_by(f64::total_cmp);
        [vec![0.0; degree + 1], interior, vec![1.0; degree + 1]].concat()
    } else {
        // The domain [u_p, u_n] is [0, 1]; the knots outside it spread below and above.
        let mut inside: Vec<f64> = (0..count - degree - 1).map(|_| random.unit()).collect();
        inside.sort_by(f64::total_cmp);
        let below: Vec<f64> = (0..degree).map(|k| -0.1 * (degree - k) as f64).collect();
        let above: Vec<f64> = (1..=degree).map(|k| 1.0 + 0.1 * k as f64).collect();
        [below, vec![0.0], inside, vec![1.0], above].concat()
    };
    knots.sort_by(f64::total_cmp);
    let weights = rational.then(|| (0..count).map(|_| random.between(0.3, 3.0)).collect());
    ReferenceCurve {
        degree,
        points,
        knots,
        weights,
    }
}

#[tokio::test]
async fn repeated_insertions_come_out_again_at_tolerance_0() {
    let app = spawn_app().await;
    let mut random = Lcg(30);
    let mut distinct = REPORTED_INSERTIONS.to_vec();
    distinct.dedup();
    let mut cases = 0;
    for degree in 3..=5 {
        for (clamped, trimmed, dimension, rational) in [
            (true, false, 3, false),
            (false, true, 3, true),
            (true, true, 2, true),
            (false, false, 2, false),
        ] {
            let count = degree + 1 + 4;
            let curve = random_curve(&mut random, degree, count, clamped, dimension, rational);
            let wire = curve.to_json(trimmed);
            let (status, refined) = app
                .post_json(
                    "/v1/curves/insert-knots",
                    &json!({"curve": wire, "knots": REPORTED_INSERTIONS}),
                )
                .await;
            assert_eq!(status, 200, "{refined}");
            for listed in [json!(distinct), json!(REPORTED_INSERTIONS), Value::Null] {
                let mut request = json!({"curve": refined["curve"], "tolerance": 0});
                if !listed.is_null() {
                    request["knots"] = listed.clone();
                }
                let (status, body) = app.post_json("/v1/curves/remove-knots", &request).await;
                assert_eq!(status, 200, "{body}");
                let case = format!(
                    "degree {degree}, clamped {clamped}, trimmed {trimmed}, listed {listed}"
                );
                assert_eq!(numbers(&body["removed"]), REPORTED_INSERTIONS, "{case}");
                assert!(
                    body["max_deviation"].as_f64().unwrap() < 1e-12,
                    "{case}: {body}"
                );
                assert_eq!(is_trimmed(&body["curve"]), trimmed, "{case}");
                let back = ReferenceCurve::from_json(&body["curve"]);
                assert_eq!(back.to_json(trimmed)["knots"], wire["knots"], "{case}");
                assert!(
                    largest_gap(&curve, &back, &grid(&curve)) < SAME_TOL,
                    "{case}"
                );
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 3 * 4 * 3);
}

#[tokio::test]
async fn elevation_removal_and_split_keep_the_curve_and_the_convention() {
    let app = spawn_app().await;
    for (curve, trimmed) in [
        (cubic_2d(), false),
        (cubic_2d(), true),
        (rational_3d(), false),
        (rational_3d(), true),
    ] {
        let wire = curve.to_json(trimmed);
        let parameters = grid(&curve);
        // Elevation to degree 5.
        let (status, body) = app
            .post_json(
                "/v1/curves/elevate-degree",
                &json!({"curve": wire, "degree": 5}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(body["curve"]["degree"], 5);
        assert_eq!(is_trimmed(&body["curve"]), trimmed);
        assert_eq!(body["curve"]["weights"].is_array(), curve.weights.is_some());
        let elevated = ReferenceCurve::from_json(&body["curve"]);
        assert!(largest_gap(&curve, &elevated, &parameters) < SAME_TOL);
        // Removal: the knots inserted by insert-knots come out again with tolerance 0.
        let (status, refined) = app
            .post_json(
                "/v1/curves/insert-knots",
                &json!({"curve": wire, "knots": [0.3, 0.3, 0.7]}),
            )
            .await;
        assert_eq!(status, 200, "{refined}");
        let (status, body) = app
            .post_json(
                "/v1/curves/remove-knots",
                &json!({"curve": refined["curve"], "tolerance": 0, "knots": [0.3, 0.3, 0.7]}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(numbers(&body["removed"]), vec![0.3, 0.3, 0.7]);
        assert!(body["max_deviation"].as_f64().unwrap() < 1e-12);
        assert_eq!(is_trimmed(&body["curve"]), trimmed);
        let back = ReferenceCurve::from_json(&body["curve"]);
        assert_eq!(back.knots, curve.knots);
        assert!(largest_gap(&curve, &back, &parameters) < SAME_TOL);
        // Removal within a tolerance: the bound holds on a dense grid.
        let (status, body) = app
            .post_json(
                "/v1/curves/remove-knots",
                &json!({"curve": wire, "tolerance": 0.5}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let bound = body["max_deviation"].as_f64().unwrap();
        assert!(bound <= 0.5 + 1e-11, "{bound}");
        let reduced = ReferenceCurve::from_json(&body["curve"]);
        assert!(largest_gap(&curve, &reduced, &parameters) <= bound + 1e-12);
        // Split at two parameters: three clamped pieces, together the curve.
        let (status, body) = app
            .post_json(
                "/v1/curves/split",
                &json!({"curve": wire, "parameters": [0.6, 0.25, 0.6]}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let pieces = body["curves"].as_array().unwrap();
        assert_eq!(pieces.len(), 3);
        let cuts = [0.0, 0.25, 0.6, 1.0];
        for (i, piece) in pieces.iter().enumerate() {
            assert_eq!(is_trimmed(piece), trimmed);
            let piece = ReferenceCurve::from_json(piece);
            assert_eq!(piece.domain(), (cuts[i], cuts[i + 1]));
            let inside: Vec<f64> = parameters
                .iter()
                .copied()
                .filter(|&t| cuts[i] <= t && t <= cuts[i + 1])
                .collect();
            assert!(largest_gap(&curve, &piece, &inside) < SAME_TOL);
        }
    }
}

#[tokio::test]
async fn length_and_parameters_at_lengths() {
    let app = spawn_app().await;
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let quarter = json!({
        "degree": 2,
        "control_points": [[2, 0], [2, 2], [0, 2]],
        "knots": [0, 0, 0, 1, 1, 1],
        "weights": [1, w, 1]
    });
    let exact = std::f64::consts::PI;
    let (status, body) = app
        .post_json(
            "/v1/curves/length",
            &json!({"curve": quarter, "at_lengths": [0, exact / 2.0, exact]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let length = body["length"].as_f64().unwrap();
    assert!((length - exact).abs() < 1e-10 * exact, "{length}");
    let parameters = numbers(&body["parameters"]);
    assert_eq!(parameters[0], 0.0);
    assert!((parameters[1] - 0.5).abs() < 1e-10, "{parameters:?}");
    assert!((parameters[2] - 1.0).abs() < 1e-12);
    // A range: the half from 0.5 to 1 is half the length.
    let (status, body) = app
        .post_json(
            "/v1/curves/length",
            &json!({"curve": quarter, "range": [0.5, 1]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert!((body["length"].as_f64().unwrap() - exact / 2.0).abs() < 1e-10);
    assert!(body.get("parameters").is_none());
    for (request, pointer) in [
        (
            json!({"curve": quarter, "at_lengths": [1.0, 4.0]}),
            "/at_lengths/1",
        ),
        (
            json!({"curve": quarter, "at_lengths": [-0.1]}),
            "/at_lengths/0",
        ),
        (json!({"curve": quarter, "range": [0.7, 0.2]}), "/range"),
        (json!({"curve": quarter, "range": [0, 2]}), "/range/1"),
    ] {
        let (status, body) = app.post_json("/v1/curves/length", &request).await;
        assert_eq!(status, 422, "{body}");
        assert_problem(422, &body, Some(pointer));
    }
}

#[tokio::test]
async fn evaluate_answers_curvature_signed_in_the_plane() {
    let app = spawn_app().await;
    let w = std::f64::consts::FRAC_1_SQRT_2;
    for (points, sign) in [
        (json!([[2, 0], [2, 2], [0, 2]]), 1.0),
        (json!([[0, 2], [2, 2], [2, 0]]), -1.0),
    ] {
        let curve = json!({"degree": 2, "control_points": points, "knots": [0, 0, 0, 1, 1, 1], "weights": [1, w, 1]});
        let (status, body) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": curve, "samples": 5, "curvature": true}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        for value in numbers(&body["curvature"]) {
            assert!((value - sign * 0.5).abs() < 1e-12, "{value}");
        }
        assert!(body.get("curvature_undefined").is_none());
    }
    // Without the flag, no curvature; where the tangent vanishes, it is listed as undefined.
    let cusp = json!({"degree": 3, "control_points": [[0, 0], [0, 0], [1, 1], [2, 0]], "knots": [0, 0, 0, 0, 1, 1, 1, 1]});
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": cusp, "parameters": [0, 0.5]}),
        )
        .await;
    assert_eq!(status, 200);
    assert!(body.get("curvature").is_none());
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": cusp, "parameters": [0, 0.5], "curvature": true}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(numbers(&body["curvature"])[0], 0.0);
    assert_eq!(body["curvature_undefined"], json!([0]));
    // 3D: the magnitude.
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": rational_3d().to_json(false), "samples": 7, "curvature": true}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert!(numbers(&body["curvature"]).iter().all(|&k| k >= 0.0));
}

#[tokio::test]
async fn reshaping_rules_are_422s_with_pointers() {
    let app = spawn_app().await;
    let curve = cubic_2d().to_json(false);
    let cases: Vec<(&str, Value, &str)> = vec![
        (
            "/v1/curves/elevate-degree",
            json!({"curve": curve, "degree": 3}),
            "/degree",
        ),
        (
            "/v1/curves/elevate-degree",
            json!({"curve": curve, "degree": 16}),
            "/degree",
        ),
        (
            "/v1/curves/remove-knots",
            json!({"curve": curve, "tolerance": -1}),
            "/tolerance",
        ),
        (
            "/v1/curves/remove-knots",
            json!({"curve": curve, "tolerance": 0, "knots": [0.123]}),
            "/knots/0",
        ),
        (
            "/v1/curves/remove-knots",
            json!({"curve": curve, "tolerance": 0, "knots": [0.0]}),
            "/knots/0",
        ),
        (
            "/v1/curves/split",
            json!({"curve": curve, "parameters": [0.5, 1.0]}),
            "/parameters/1",
        ),
        (
            "/v1/curves/split",
            json!({"curve": curve, "parameters": [-0.5]}),
            "/parameters/0",
        ),
        (
            "/v1/curves/split",
            json!({"curve": {"degree": 3, "control_points": [[0, 0]], "knots": [0]}, "parameters": [0.5]}),
            "/curve/control_points",
        ),
    ];
    for (path, request, pointer) in cases {
        let (status, body) = app.post_json(path, &request).await;
        assert_eq!(status, 422, "{path} {request} -> {body}");
        assert_problem(422, &body, Some(pointer));
    }
}
