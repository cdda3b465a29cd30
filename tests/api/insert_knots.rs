//! `/v1/curves/insert-knots` over HTTP, checked against the test's own de Boor: the refined
//! curve is the original in both conventions, `editable_at` makes a Bézier piece solvable,
//! and parameters just outside the domain are its ends on every endpoint that takes them.

use serde_json::{Value, json};

use crate::helpers::{assert_problem, numbers, points, spawn_app};
use crate::reference::{ReferenceCurve, cubic_2d, distance, rational_3d};

/// The refined curve against the original (coordinates ~10).
pub const SAME_CURVE_TOL: f64 = 1e-11;

/// Parameters across the domain `[0, 1]`, knots and ends included.
fn probes() -> Vec<f64> {
    let mut t: Vec<f64> = (0..=40).map(|i| i as f64 / 40.0).collect();
    t.extend([0.2, 0.35, 0.5, 0.75, 0.123, 0.999]);
    t
}

/// A single cubic Bézier piece on `[0, 1]`.
pub fn bezier_curve() -> ReferenceCurve {
    ReferenceCurve {
        degree: 3,
        points: vec![
            vec![0.0, 0.0],
            vec![1.0, 2.0],
            vec![3.0, 2.0],
            vec![4.0, 0.0],
        ],
        knots: vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        weights: None,
    }
}

/// An unclamped uniform cubic: domain `[3, 8]`.
fn unclamped() -> ReferenceCurve {
    ReferenceCurve {
        degree: 3,
        points: (0..8)
            .map(|i| vec![i as f64, ((i * 5) % 3) as f64])
            .collect(),
        knots: (0..12).map(f64::from).collect(),
        weights: None,
    }
}

#[tokio::test]
async fn inserted_knots_keep_the_curve_in_the_callers_convention() {
    let app = spawn_app().await;
    for (curve, trimmed) in [
        (cubic_2d(), false),
        (cubic_2d(), true),
        (rational_3d(), false),
        (rational_3d(), true),
    ] {
        let knots = [0.9, 0.1, 0.5, 0.1, 0.2, 1e-9];
        let (status, body) = app
            .post_json(
                "/v1/curves/insert-knots",
                &json!({"curve": curve.to_json(trimmed), "knots": knots}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let mut sorted = knots.to_vec();
        sorted.sort_by(f64::total_cmp);
        assert_eq!(numbers(&body["inserted"]), sorted);
        let sent_knots = curve.to_json(trimmed)["knots"].as_array().unwrap().len();
        assert_eq!(
            body["curve"]["knots"].as_array().unwrap().len(),
            sent_knots + knots.len()
        );
        assert_eq!(body["curve"]["weights"].is_array(), curve.weights.is_some());
        let refined = ReferenceCurve::from_json(&body["curve"]);
        assert_eq!(refined.points.len(), curve.points.len() + knots.len());
        for t in probes().into_iter().chain(knots) {
            let (expected, found) = (curve.point(t), refined.point(t));
            assert!(
                distance(&expected, &found) < SAME_CURVE_TOL,
                "t = {t}: {found:?} vs {expected:?}"
            );
        }
    }
}

#[tokio::test]
async fn editable_at_makes_a_bezier_piece_solvable_in_one_request() {
    let app = spawn_app().await;
    let curve = bezier_curve();
    let t = 0.5;
    let center = curve.point(t);
    let center = [center[0], center[1]];
    let targets: Vec<[f64; 2]> = [0.02, 0.05, 0.1, 0.2, 0.3]
        .into_iter()
        .flat_map(|radius| {
            (0..16).map(move |k| {
                let angle = std::f64::consts::TAU * k as f64 / 16.0;
                [
                    center[0] + radius * angle.cos(),
                    center[1] + radius * angle.sin(),
                ]
            })
        })
        .collect();
    let reachable = |body: &Value| body["reachable"] == true;
    for target in &targets {
        let (status, body) = app
            .post_json(
                "/v1/shape/solve",
                &json!({"curve": curve.to_json(false), "parameter": t, "target": target}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        assert!(!reachable(&body), "the Bézier piece alone has no pair");
    }
    let (status, body) = app
        .post_json(
            "/v1/curves/insert-knots",
            &json!({"curve": curve.to_json(false), "editable_at": {"parameter": t}}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        numbers(&body["inserted"]),
        vec![0.125, 0.25, 0.375, 0.625, 0.75, 0.875]
    );
    let mut reached = 0;
    for target in &targets {
        let (status, solved) = app
            .post_json(
                "/v1/shape/solve",
                &json!({"curve": body["curve"], "parameter": t, "target": target}),
            )
            .await;
        assert_eq!(status, 200, "{solved}");
        reached += usize::from(reachable(&solved));
    }
    assert!(reached > 0, "no target around s(t) became reachable");
}

#[tokio::test]
async fn parameters_just_outside_the_domain_are_its_ends_on_every_endpoint() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let body_of = |path: &str, parameter: f64| {
        let mut body = json!({"curve": curve.to_json(false), "parameter": parameter});
        if path != "/v1/shape/regions" {
            body["target"] = json!([4.0, 3.0]);
        }
        body
    };
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve.to_json(false), "parameters": [-1e-13, 0.5, 1.0 + 1e-13]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(numbers(&body["parameters"]), vec![0.0, 0.5, 1.0]);
    assert_eq!(points(&body["points"])[2], curve.point(1.0));
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve.to_json(false), "parameters": [0.5, 1.0 + 1e-9]}),
        )
        .await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/parameters/1"));
    let closest = |range: [f64; 2]| json!({"curve": curve.to_json(false), "points": [[4.0, 3.0]], "range": range});
    let (status, body) = app
        .post_json("/v1/curves/closest-point", &closest([-1e-13, 1.0 + 1e-13]))
        .await;
    assert_eq!(status, 200, "{body}");
    let (status, body) = app
        .post_json("/v1/curves/closest-point", &closest([0.0, 1.0 + 1e-9]))
        .await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/range/1"));
    for path in [
        "/v1/shape/membership",
        "/v1/shape/regions",
        "/v1/shape/solve",
    ] {
        for near_end in [-1e-13, 1.0 + 1e-13] {
            let (status, body) = app.post_json(path, &body_of(path, near_end)).await;
            assert_eq!(status, 200, "{path} at {near_end}: {body}");
        }
        let (status, body) = app.post_json(path, &body_of(path, 1.0 + 1e-9)).await;
        assert_eq!(status, 422, "{path}: {body}");
        assert_problem(422, &body, Some("/parameter"));
    }
    // Insertion: just past the end of an unclamped curve is its end, a knot it can take.
    let unclamped = unclamped();
    let (status, body) = app
        .post_json(
            "/v1/curves/insert-knots",
            &json!({"curve": unclamped.to_json(false), "knots": [8.0 + 1e-12, 3.0 - 1e-12]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(numbers(&body["inserted"]), vec![3.0, 8.0]);
    let refined = ReferenceCurve::from_json(&body["curve"]);
    for t in [3.0, 3.5, 5.0, 7.9, 8.0] {
        assert!(
            distance(&refined.point(t), &unclamped.point(t)) < SAME_CURVE_TOL,
            "t = {t}"
        );
    }
    let (status, body) = app
        .post_json(
            "/v1/curves/insert-knots",
            &json!({"curve": unclamped.to_json(false), "knots": [8.0 + 1e-6]}),
        )
        .await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/knots/0"));
    let (status, body) = app
        .post_json(
            "/v1/curves/insert-knots",
            &json!({"curve": curve.to_json(false), "editable_at": {"parameter": 0.5 + 1e-13}}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
}
