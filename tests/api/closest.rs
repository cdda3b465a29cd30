//! `/v1/curves/closest-point`: answers checked against the test's own de Boor evaluator and
//! dense sampling; every new 422.

use serde_json::json;

use crate::helpers::{expect_problem, numbers, spawn_app, spawn_app_with};
use crate::reference::{cubic_2d, distance, rational_3d};

#[tokio::test]
async fn closest_points_are_curve_points_no_sample_beats() {
    let app = spawn_app().await;
    for (curve, trimmed) in [(cubic_2d(), false), (rational_3d(), true)] {
        let dimension = curve.points[0].len();
        let queries: Vec<Vec<f64>> = [[2.0, 3.0, 1.0], [-4.0, 0.5, -2.0], [9.0, -1.0, 0.5]]
            .iter()
            .map(|q| q[..dimension].to_vec())
            .collect();
        let (status, body) = app
            .post_json(
                "/v1/curves/closest-point",
                &json!({"curve": curve.to_json(trimmed), "points": queries}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let results = body["results"].as_array().unwrap();
        assert_eq!(results.len(), queries.len());
        let (lo, hi) = curve.domain();
        for (q, result) in queries.iter().zip(results) {
            let u = result["parameter"].as_f64().unwrap();
            let point = numbers(&result["point"]);
            assert_eq!(point.len(), dimension);
            assert!(distance(&point, &curve.point(u)) < 1e-11, "{result}");
            let d = result["distance"].as_f64().unwrap();
            assert!((d - distance(&point, q)).abs() < 1e-11);
            let sampled = (0..=4000)
                .map(|i| distance(&curve.point(lo + (hi - lo) * i as f64 / 4000.0), q))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= sampled + 1e-12, "{d} > sampled {sampled}");
        }
    }
}

#[tokio::test]
async fn a_range_restricts_the_search_to_it() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let start = curve.point(0.0);
    let (status, body) = app
        .post_json(
            "/v1/curves/closest-point",
            &json!({"curve": curve.to_json(false), "points": [start], "range": [0.6, 0.9]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["results"][0]["parameter"], 0.6);
}

#[tokio::test]
async fn every_rule_of_a_closest_point_request_names_its_field() {
    let app = spawn_app_with(|config| config.max_parameters = 10).await;
    let curve = cubic_2d().to_json(false);
    let cases = [
        (json!({"curve": curve, "points": []}), "/points"),
        (
            json!({"curve": curve, "points": vec![[1.0, 1.0]; 11]}),
            "/points",
        ),
        (
            json!({"curve": curve, "points": [[1.0, 1.0], [1.0, 2.0, 3.0]]}),
            "/points/1",
        ),
        (json!({"curve": curve, "points": [[1.0]]}), "/points/0"),
        (
            json!({"curve": curve, "points": [[1.0, 1.0]], "range": [0.5, 2.0]}),
            "/range/1",
        ),
        (
            json!({"curve": curve, "points": [[1.0, 1.0]], "range": [-1.0, 0.5]}),
            "/range/0",
        ),
        (
            json!({"curve": curve, "points": [[1.0, 1.0]], "range": [0.7, 0.5]}),
            "/range/0",
        ),
    ];
    for (body, pointer) in cases {
        let response = app.post("/v1/curves/closest-point", &body).await;
        expect_problem(response, 422, Some(pointer)).await;
    }
    let unknown = json!({"curve": curve, "points": [[1.0, 1.0]], "nearest": true});
    let response = app.post("/v1/curves/closest-point", &unknown).await;
    expect_problem(response, 400, None).await;
}
