//! `/v1/curves/evaluate` and `/v1/curves/envelope`, checked against the test's own de Boor.

use serde_json::json;

use crate::helpers::{numbers, points, spawn_app};
use crate::reference::{ReferenceCurve, cubic_2d, distance, rational_3d};

/// Agreement between the service and the reference evaluator (coordinates ~10).
const EVALUATION_TOLERANCE: f64 = 1e-11;

#[tokio::test]
async fn evaluate_matches_an_independent_de_boor_evaluation() {
    let app = spawn_app().await;
    for (curve, trimmed) in [
        (cubic_2d(), false),
        (rational_3d(), false),
        (rational_3d(), true),
    ] {
        let (lo, hi) = curve.domain();
        // Ends, knots (including the double knot) and points in between, in no order.
        let parameters = vec![
            hi,
            lo,
            0.25,
            0.5,
            0.1,
            0.333,
            0.75,
            0.9999,
            0.5 - 1e-12,
            0.62,
        ];
        let (status, body) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": curve.to_json(trimmed), "parameters": parameters}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(numbers(&body["domain"]), vec![lo, hi]);
        assert_eq!(numbers(&body["parameters"]), parameters);
        assert!(
            body.get("derivatives").is_none(),
            "no derivatives asked for"
        );
        let got = points(&body["points"]);
        assert_eq!(got.len(), parameters.len());
        for (t, point) in parameters.iter().zip(&got) {
            let expected = curve.point(*t);
            assert_eq!(point.len(), curve.points[0].len(), "dimension kept");
            assert!(
                distance(point, &expected) < EVALUATION_TOLERANCE,
                "t = {t}: {point:?} vs {expected:?}"
            );
        }
    }
}

#[tokio::test]
async fn samples_cover_the_domain_and_clamped_ends_are_the_end_control_points() {
    let app = spawn_app().await;
    let curve = rational_3d();
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve.to_json(true), "samples": 5}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        numbers(&body["parameters"]),
        vec![0.0, 0.25, 0.5, 0.75, 1.0]
    );
    let got = points(&body["points"]);
    assert_eq!(got[0], curve.points[0]);
    assert!(distance(&got[4], curve.points.last().unwrap()) < 1e-14);
    for (t, point) in [0.25, 0.5, 0.75].iter().zip(&got[1..4]) {
        assert!(distance(point, &curve.point(*t)) < EVALUATION_TOLERANCE);
    }
}

#[tokio::test]
async fn derivatives_match_finite_differences_of_the_reference() {
    let app = spawn_app().await;
    for curve in [cubic_2d(), rational_3d()] {
        let parameters = [0.05, 0.3, 0.45, 0.6, 0.9];
        let (status, body) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": curve.to_json(false), "parameters": parameters, "derivatives": 2}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let derivatives = body["derivatives"].as_array().unwrap();
        assert_eq!(derivatives.len(), 2, "orders 1 and 2");
        let first = points(&derivatives[0]);
        let second = points(&derivatives[1]);
        let h = 1e-5;
        for (i, &t) in parameters.iter().enumerate() {
            let (minus, centre, plus) = (curve.point(t - h), curve.point(t), curve.point(t + h));
            let scale = 1.0 + first[i].iter().map(|v| v.abs()).fold(0.0, f64::max);
            for c in 0..minus.len() {
                let fd1 = (plus[c] - minus[c]) / (2.0 * h);
                let fd2 = (plus[c] - 2.0 * centre[c] + minus[c]) / (h * h);
                assert!((first[i][c] - fd1).abs() < 1e-5 * scale, "s'({t})[{c}]");
                assert!(
                    (second[i][c] - fd2).abs() < 1e-2 * (1.0 + fd2.abs()),
                    "s''({t})[{c}]: {} vs {fd2}",
                    second[i][c]
                );
            }
        }
    }
}

#[tokio::test]
async fn the_clamped_end_derivative_is_the_end_leg_of_the_control_polygon() {
    // s'(u_p) = p (d_1 - d_0) / (u_{p+1} - u_1) for a clamped curve.
    let app = spawn_app().await;
    let curve = cubic_2d();
    let (_, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve.to_json(false), "parameters": [0.0], "derivatives": 1}),
        )
        .await;
    let tangent = points(&body["derivatives"][0])[0].clone();
    assert!(distance(&tangent, &[3.0 * 1.0 / 0.2, 3.0 * 3.0 / 0.2]) < 1e-12);
}

#[tokio::test]
async fn the_envelope_touches_the_moved_curve_at_the_moved_knot() {
    let app = spawn_app().await;
    for trimmed in [false, true] {
        let curve = cubic_2d();
        // Full index 5 (value 0.35); trimmed index 4.
        let knot_index = if trimmed { 4 } else { 5 };
        let (status, body) = app
            .post_json(
                "/v1/curves/envelope",
                &json!({"curve": curve.to_json(trimmed), "knot_index": knot_index}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(body["multiplicity"], 1);
        assert_eq!(numbers(&body["range"]), vec![0.2, 0.5]);
        assert_eq!(body["moved_knots"], json!([knot_index]));
        let envelope = &body["envelope"];
        assert_eq!(envelope["degree"], 2);
        assert_eq!(points(&envelope["control_points"]), curve.points);
        let mut expected_knots = curve.knots.clone();
        expected_knots.remove(5);
        if trimmed {
            expected_knots = expected_knots[1..expected_knots.len() - 1].to_vec();
        }
        assert_eq!(
            numbers(&envelope["knots"]),
            expected_knots,
            "caller's convention"
        );

        // s(τ; τ) = h(τ), with s(·; τ) built here and h evaluated by the service. The full
        // vector of a clamped envelope holds p' + 2 equal end values, which the validation of
        // input curves refuses (at most p' + 1); the trimmed form of the same curve is accepted.
        let reference_envelope = ReferenceCurve::from_json(envelope);
        let envelope = &reference_envelope.to_json(true);
        for tau in [0.2, 0.27, 0.35, 0.41, 0.5] {
            let mut moved = curve.knots.clone();
            moved[5] = tau;
            let family_member = curve.with_knots(moved);
            let (status, evaluated) = app
                .post_json(
                    "/v1/curves/evaluate",
                    &json!({"curve": envelope, "parameters": [tau]}),
                )
                .await;
            assert_eq!(status, 200, "{evaluated}");
            let on_envelope = points(&evaluated["points"])[0].clone();
            assert!(
                distance(&family_member.point(tau), &on_envelope) < 1e-12,
                "τ = {tau}"
            );
            assert!(distance(&reference_envelope.point(tau), &on_envelope) < 1e-12);
        }
    }
}

#[tokio::test]
async fn a_double_knot_moves_as_a_run() {
    let app = spawn_app().await;
    let curve = rational_3d();
    let (status, body) = app
        .post_json(
            "/v1/curves/envelope",
            &json!({"curve": curve.to_json(false), "knot_index": 6}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["multiplicity"], 2);
    assert_eq!(body["moved_knots"], json!([5, 6]));
    assert_eq!(numbers(&body["range"]), vec![0.25, 1.0]);
    assert_eq!(body["envelope"]["degree"], 1);
    assert_eq!(
        numbers(&body["envelope"]["weights"]),
        curve.weights.clone().unwrap()
    );
}
