//! Every rule of a surface request is a 4xx problem document naming the field (JSON pointer
//! into the body): ragged rows, planar control points, wrong knot counts, zero or negative
//! weights, non-finite numbers, sizes over the configured limits, parameters outside the
//! domain. Never a 500.

use serde_json::{Value, json};

use crate::helpers::{expect_problem, spawn_app, spawn_app_with};
use crate::surfaces::saddle;

/// A bicubic net of 4 × 5 points (clamped, one interior v-knot).
fn bicubic() -> Value {
    let points: Vec<Vec<[f64; 3]>> = (0..4)
        .map(|i| {
            (0..5)
                .map(|j| [f64::from(i), f64::from(j), f64::from((i * j) % 3)])
                .collect()
        })
        .collect();
    json!({
        "degree_u": 3, "degree_v": 3,
        "control_points": points,
        "knots_u": [0, 0, 0, 0, 1, 1, 1, 1],
        "knots_v": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
    })
}

/// Posts `surface` to evaluate at the centre and expects a 422 naming `pointer`.
async fn refused(app: &crate::helpers::TestApp, surface: Value, pointer: &str) -> Value {
    let request = json!({"surface": surface, "parameters": [[0.5, 0.5]]});
    let response = app.post("/v1/surfaces/evaluate", &request).await;
    expect_problem(response, 422, Some(pointer)).await
}

#[tokio::test]
async fn every_rule_of_the_surface_names_its_field() {
    let app = spawn_app().await;
    let mut ragged = bicubic();
    ragged["control_points"][2].as_array_mut().unwrap().pop();
    let problem = refused(&app, ragged, "/surface/control_points/2").await;
    assert!(
        problem["detail"].as_str().unwrap().contains("row 2"),
        "{problem}"
    );

    let mut planar = bicubic();
    planar["control_points"][1][3] = json!([1, 3]);
    let problem = refused(&app, planar, "/surface/control_points/1/3").await;
    assert!(
        problem["detail"].as_str().unwrap().contains("3D"),
        "{problem}"
    );

    let mut few_rows = bicubic();
    few_rows["control_points"].as_array_mut().unwrap().pop();
    refused(&app, few_rows, "/surface/control_points").await;

    let mut knots = bicubic();
    knots["knots_v"].as_array_mut().unwrap().pop();
    let problem = refused(&app, knots, "/surface/knots_v").await;
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .starts_with("v direction"),
        "{problem}"
    );

    let mut decreasing = bicubic();
    decreasing["knots_u"][4] = json!(-1);
    refused(&app, decreasing, "/surface/knots_u/4").await;

    let mut degree = bicubic();
    degree["degree_v"] = json!(0);
    refused(&app, degree, "/surface/degree_v").await;

    let mut high = bicubic();
    high["degree_u"] = json!(16);
    refused(&app, high, "/surface/degree_u").await;

    for (value, detail) in [(0.0, "greater than 0"), (-2.0, "greater than 0")] {
        let mut weighted = bicubic();
        let mut weights = vec![vec![1.0; 5]; 4];
        weights[2][1] = value;
        weighted["weights"] = json!(weights);
        let problem = refused(&app, weighted, "/surface/weights/2/1").await;
        assert!(
            problem["detail"].as_str().unwrap().contains(detail),
            "{problem}"
        );
    }
    let mut short = bicubic();
    short["weights"] = json!(vec![vec![1.0; 5]; 3]);
    refused(&app, short, "/surface/weights").await;
    let mut ragged_weights = bicubic();
    let mut weights = vec![vec![1.0; 5]; 4];
    weights[3].pop();
    ragged_weights["weights"] = json!(weights);
    refused(&app, ragged_weights, "/surface/weights/3").await;

    let mut periodic = bicubic();
    periodic["periodic_u"] = json!(true);
    refused(&app, periodic, "/surface/multiplicities_u").await;

    let mut sums = bicubic();
    sums["knots_u"] = json!([0, 1]);
    sums["multiplicities_u"] = json!([4, 3]);
    refused(&app, sums, "/surface/multiplicities_u").await;
}

#[tokio::test]
async fn non_finite_numbers_and_malformed_bodies_are_refused() {
    let app = spawn_app().await;
    // JSON has no NaN; a number too large for a double is its stand-in.
    let body = r#"{"surface": {"degree_u": 1, "degree_v": 1,
        "control_points": [[[0, 0, 0], [0, 1, 1e999]], [[1, 0, 0], [1, 1, 1]]],
        "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]}, "parameters": [[0.5, 0.5]]}"#;
    let response = app
        .client
        .post(format!("{}/v1/surfaces/evaluate", app.address))
        .header("content-type", "application/json")
        .body(body)
        .send()
        .await
        .unwrap();
    expect_problem(response, 422, Some("/surface/control_points/0/1/2")).await;
    let unknown = json!({"surface": saddle(), "parameters": [[0.5, 0.5]], "colour": 1});
    let response = app.post("/v1/surfaces/evaluate", &unknown).await;
    expect_problem(response, 400, None).await;
    let null_point = json!({"surface": saddle(), "parameters": [[0.5, null]]});
    let response = app.post("/v1/surfaces/evaluate", &null_point).await;
    expect_problem(response, 400, Some("/parameters/0/1")).await;
}

#[tokio::test]
async fn parameters_and_grids_are_checked() {
    let app = spawn_app_with(|config| config.max_parameters = 20).await;
    let cases = [
        (
            json!({"surface": saddle(), "parameters": [[0.5, 0.5], [0.5, 1.5]]}),
            "/parameters/1/1",
        ),
        (
            json!({"surface": saddle(), "parameters": [[-0.5, 0.5]]}),
            "/parameters/0/0",
        ),
        (
            json!({"surface": saddle(), "samples": [1, 5]}),
            "/samples/0",
        ),
        (json!({"surface": saddle(), "samples": [5, 5]}), "/samples"),
        (
            json!({"surface": saddle(), "parameters": vec![[0.5, 0.5]; 21]}),
            "/parameters",
        ),
        (
            json!({"surface": saddle(), "parameters": [[0.5, 0.5]], "samples": [2, 2]}),
            "/samples",
        ),
        (json!({"surface": saddle()}), ""),
        (
            json!({"surface": saddle(), "parameters": [[0.5, 0.5]], "derivatives": 3}),
            "/derivatives",
        ),
    ];
    for (request, pointer) in cases {
        let response = app.post("/v1/surfaces/evaluate", &request).await;
        expect_problem(response, 422, Some(pointer)).await;
    }
    // Just outside the domain (roundoff) is the end.
    let (status, body) = app
        .post_json(
            "/v1/surfaces/evaluate",
            &json!({"surface": saddle(), "parameters": [[1.0000000000000002, -1e-17]]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["parameters"], json!([[1.0, 0.0]]));
}

#[tokio::test]
async fn the_control_point_limit_is_configurable() {
    let app = spawn_app_with(|config| config.max_surface_control_points = 19).await;
    let problem = refused(&app, bicubic(), "/surface/control_points").await;
    assert!(
        problem["detail"].as_str().unwrap().contains("limit 19"),
        "{problem}"
    );
    let app = spawn_app_with(|config| config.max_surface_control_points = 20).await;
    let request = json!({"surface": bicubic(), "parameters": [[0.5, 0.5]]});
    assert_eq!(
        app.post("/v1/surfaces/evaluate", &request).await.status(),
        200
    );
}
