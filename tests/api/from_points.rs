//! `/v1/curves/interpolate` and `/v1/curves/approximate` over HTTP: answers checked with the
//! test's own de Boor (the curve passes through the points, the tolerance holds at the
//! reported closest parameters), and every rule refused with a 422 that names the field.

use serde_json::{Value, json};

use crate::helpers::{assert_problem, expect_problem, numbers, spawn_app, spawn_app_with};
use crate::reference::{ReferenceCurve, distance};

fn zigzag(count: usize) -> Vec<Vec<f64>> {
    (0..count)
        .map(|i| vec![i as f64, if i % 2 == 0 { 0.0 } else { 1.5 }])
        .collect()
}

#[tokio::test]
async fn interpolants_pass_through_every_point_in_both_forms() {
    let app = spawn_app().await;
    let points = vec![
        vec![0.0, 0.0, 0.0],
        vec![3.0, 4.0, 1.0],
        vec![-1.0, 4.0, 2.0],
        vec![-4.0, 0.0, 1.0],
        vec![-4.0, -3.0, 0.0],
        vec![0.0, -4.0, -1.0],
    ];
    for (closed, parametrization) in [
        (false, "chord_length"),
        (false, "centripetal"),
        (false, "uniform"),
        (true, "chord_length"),
        (true, "centripetal"),
    ] {
        let (status, body) = app
            .post_json(
                "/v1/curves/interpolate",
                &json!({"points": points, "parametrization": parametrization, "closed": closed}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let curve = ReferenceCurve::from_json(&body["curve"]);
        let parameters = numbers(&body["parameters"]);
        assert_eq!(parameters.len(), points.len());
        for (point, t) in points.iter().zip(&parameters) {
            assert!(
                distance(&curve.point(*t), point) < 1e-12,
                "{closed} {parametrization}"
            );
        }
        let control_points = body["curve"]["control_points"].as_array().unwrap().len();
        if closed {
            // The first `degree` poles repeat at the end, the seam is at points[0].
            assert_eq!(control_points, points.len() + 3);
            let (lo, hi) = curve.domain();
            assert!(distance(&curve.point(lo), &curve.point(hi)) < 1e-12);
            assert_eq!(parameters[0], lo);
        } else {
            assert_eq!(control_points, points.len());
        }
    }
}

#[tokio::test]
async fn end_tangents_and_given_knots_are_honoured() {
    let app = spawn_app().await;
    let points = zigzag(6);
    let (status, body) = app
        .post_json(
            "/v1/curves/interpolate",
            &json!({"points": points, "degree": 3, "end_tangents": [[2.0, 0.0], null]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let curve = ReferenceCurve::from_json(&body["curve"]);
    assert_eq!(curve.points.len(), 7);
    // s'(0) = p / (u_{p+1} − u_1) (P_1 − P_0) for a clamped curve.
    let slope = 3.0 / (curve.knots[4] - curve.knots[1]);
    for c in 0..2 {
        let derivative = slope * (curve.points[1][c] - curve.points[0][c]);
        assert!((derivative - [2.0, 0.0][c]).abs() < 1e-9, "{derivative}");
    }
    // Given parameters and trimmed knots: the answer keeps the trimmed convention.
    let parameters = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    let knots = [0.0, 0.0, 0.0, 2.0, 3.0, 5.0, 5.0, 5.0];
    let (status, body) = app
        .post_json(
            "/v1/curves/interpolate",
            &json!({"points": points, "parameters": parameters, "knots": knots}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(numbers(&body["curve"]["knots"]), knots.to_vec());
    let curve = ReferenceCurve::from_json(&body["curve"]);
    for (point, t) in points.iter().zip(parameters) {
        assert!(distance(&curve.point(t), point) < 1e-12);
    }
}

#[tokio::test]
async fn interpolation_rules_are_422s_with_pointers() {
    let app = spawn_app_with(|config| config.max_fit_points = 50).await;
    let cases: Vec<(Value, &str)> = vec![
        (json!({"points": zigzag(3), "degree": 3}), "/points"),
        (
            json!({"points": [[0, 0], [1, 1], [1, 1], [2, 0], [3, 1]]}),
            "/points/2",
        ),
        (
            json!({"points": [[0, 0], [1, 1], [2, 0], [0, 0]], "degree": 2, "closed": true}),
            "/points/3",
        ),
        (
            json!({"points": zigzag(5), "parameters": [0, 1, 1, 2, 3]}),
            "/parameters/2",
        ),
        (
            json!({"points": zigzag(5), "parameters": [0, 1, 2]}),
            "/parameters",
        ),
        (
            json!({"points": zigzag(5), "parameters": [0, 1, 2, 3, 4], "parametrization": "uniform"}),
            "/parameters",
        ),
        (json!({"points": [[0, 0], [1, 1, 1], [2, 0]]}), "/points/1"),
        (json!({"points": [[0, 0], [1], [2, 0]]}), "/points/1"),
        (json!({"points": [[0, 0, 0, 0], [1, 1, 1, 1]]}), "/points/0"),
        (
            json!({"points": [[0, 0], [1, 1e308], [2, -1e308]]}),
            "/points",
        ),
        (json!({"points": zigzag(51), "degree": 1}), "/points"),
        (json!({"points": zigzag(5), "degree": 0}), "/degree"),
        (json!({"points": zigzag(5), "degree": 16}), "/degree"),
        (
            json!({"points": zigzag(5), "degree": 1, "end_tangents": [[1, 0], null]}),
            "/end_tangents",
        ),
        (
            json!({"points": zigzag(5), "end_tangents": [[1, 0]]}),
            "/end_tangents",
        ),
        (
            json!({"points": zigzag(5), "end_tangents": [[1, 0, 0], null]}),
            "/end_tangents/0",
        ),
        (
            json!({"points": zigzag(5), "closed": true, "end_tangents": [[1, 0], null]}),
            "/end_tangents",
        ),
        (
            json!({"points": zigzag(5), "closed": true, "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]}),
            "/knots",
        ),
        (
            json!({"points": zigzag(5), "knots": [0, 0, 1, 1]}),
            "/knots",
        ),
        (
            json!({"points": zigzag(5), "knots": [0, 0, 0, 0, 0.6, 0.5, 1, 1, 1]}),
            "/knots/5",
        ),
        (
            json!({"points": zigzag(6), "parameters": [0, 1, 2, 3, 4, 5], "knots": [0, 0, 0, 0.2, 0.5, 5, 5, 5]}),
            "/knots",
        ),
        (
            json!({"points": zigzag(5), "parameters": [0, 1, 2, 3, 9], "knots": [0, 0, 0, 2, 4, 4, 4]}),
            "/parameters/4",
        ),
    ];
    for (request, pointer) in cases {
        let (status, body) = app.post_json("/v1/curves/interpolate", &request).await;
        assert_eq!(status, 422, "{request} -> {body}");
        assert_problem(422, &body, Some(pointer));
    }
    // JSON cannot carry infinities, but a huge exponent parses to one.
    for (request, pointer) in [
        (
            json!({"points": [[0, 0], [1, "HUGE"], [2, 0]]}),
            "/points/1/1",
        ),
        (
            json!({"points": zigzag(4), "parameters": [0, 1, "HUGE", 3]}),
            "/parameters/2",
        ),
        (
            json!({"points": zigzag(4), "end_tangents": [null, [1, "HUGE"]]}),
            "/end_tangents/1/1",
        ),
    ] {
        let raw = request.to_string().replace("\"HUGE\"", "1e999");
        let response = app
            .client
            .post(format!("{}/v1/curves/interpolate", app.address))
            .header("content-type", "application/json")
            .body(raw)
            .send()
            .await
            .unwrap();
        expect_problem(response, 422, Some(pointer)).await;
    }
}

#[tokio::test]
async fn approximations_stay_within_the_tolerance_at_their_closest_parameters() {
    let app = spawn_app().await;
    let points: Vec<Vec<f64>> = (0..200)
        .map(|i| {
            let t = i as f64 / 199.0 * 6.0;
            vec![t, t.sin() + 0.01 * ((i * 7919) % 13) as f64 / 13.0, 0.1 * t]
        })
        .collect();
    for (tolerance, ends) in [(0.05, true), (0.005, true), (0.02, false)] {
        let (status, body) = app
            .post_json(
                "/v1/curves/approximate",
                &json!({"points": points, "tolerance": tolerance, "end_points_exact": ends}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let curve = ReferenceCurve::from_json(&body["curve"]);
        let parameters = numbers(&body["parameters"]);
        let max_error = body["max_error"].as_f64().unwrap();
        assert!(max_error <= tolerance);
        let mut largest = 0.0f64;
        for (point, t) in points.iter().zip(&parameters) {
            largest = largest.max(distance(&curve.point(*t), point));
        }
        assert!(
            (largest - max_error).abs() < 1e-12,
            "{largest} vs {max_error}"
        );
        assert!(
            curve.points.len() < points.len() / 4,
            "{} poles",
            curve.points.len()
        );
        if ends {
            let (lo, hi) = curve.domain();
            assert!(distance(&curve.point(lo), &points[0]) < 1e-12);
            assert!(distance(&curve.point(hi), &points[199]) < 1e-12);
        }
    }
}

#[tokio::test]
async fn approximation_rules_are_422s_with_pointers() {
    let app = spawn_app_with(|config| config.max_fit_points = 50).await;
    let cases: Vec<(Value, &str)> = vec![
        (json!({"points": zigzag(3), "tolerance": 0.1}), "/points"),
        (json!({"points": zigzag(5), "tolerance": 0}), "/tolerance"),
        (json!({"points": zigzag(5), "tolerance": -1}), "/tolerance"),
        (
            json!({"points": zigzag(5), "tolerance": 1e-15}),
            "/tolerance",
        ),
        (json!({"points": zigzag(51), "tolerance": 0.1}), "/points"),
        (
            json!({"points": zigzag(5), "tolerance": 0.1, "degree": 0}),
            "/degree",
        ),
        (
            json!({"points": [[1, 1], [1, 1], [1, 1], [1, 1]], "tolerance": 0.1}),
            "/points",
        ),
        (
            json!({"points": [[0, 0], [1, 1], [2, "x"]], "tolerance": 0.1}),
            "/points/2/1",
        ),
    ];
    for (request, pointer) in cases {
        let (status, body) = app.post_json("/v1/curves/approximate", &request).await;
        if pointer == "/points/2/1" {
            // A wrong JSON type is a 400 that points at the value.
            assert_eq!(status, 400, "{body}");
            assert_problem(400, &body, Some(pointer));
            continue;
        }
        assert_eq!(status, 422, "{request} -> {body}");
        assert_problem(422, &body, Some(pointer));
    }
}

/// The end-tangent rule (degree 2 or more, open curves) is in the OpenAPI document, where a
/// client reads it before calling, and the server keeps to what it says: a tangent with
/// degree 1 is a 422 at `/end_tangents`, no tangent (`[null, null]`) at degree 1 and a
/// tangent at degree 2 are not.
#[tokio::test]
async fn the_end_tangent_rule_is_stated_in_the_schema() {
    let document: Value = serde_json::from_str(&knotshape::openapi_json()).unwrap();
    let properties = &document["components"]["schemas"]["InterpolateRequest"]["properties"];
    let tangents = properties["end_tangents"]["description"].as_str().unwrap();
    for needed in [
        "`degree` ≥ 2",
        "`degree: 1`",
        "`closed: true`",
        "422 at `/end_tangents`",
    ] {
        assert!(tangents.contains(needed), "{needed:?} not in {tangents:?}");
    }
    let degree = properties["degree"]["description"].as_str().unwrap();
    assert!(
        degree.contains("at least 2 when an end tangent is given"),
        "{degree}"
    );
    let app = spawn_app().await;
    let post = |degree: usize, tangents: Value| json!({"points": zigzag(5), "degree": degree, "end_tangents": tangents});
    let (status, body) = app
        .post_json("/v1/curves/interpolate", &post(1, json!([null, [0, 1]])))
        .await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/end_tangents"));
    for (degree, tangents) in [(1, json!([null, null])), (2, json!([[1, 0], null]))] {
        let (status, body) = app
            .post_json("/v1/curves/interpolate", &post(degree, tangents))
            .await;
        assert_eq!(status, 200, "{body}");
    }
}
