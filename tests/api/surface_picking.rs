//! `POST /v1/surfaces/closest-point` over HTTP: picking on known surfaces (inside, beyond an
//! edge, restricted to a range), and its 4xx rules named by pointer.

use serde_json::json;

use crate::helpers::{expect_problem, numbers, spawn_app};
use crate::surfaces::{octant, saddle};

#[tokio::test]
async fn picking_finds_interior_edge_and_range_points() {
    let app = spawn_app().await;
    // z = x y: from (0.5, 0.5, 0.25) + t (-0.5, -0.5, 1) (along the normal) the foot is the
    // centre; beyond the edge x = 1 the edge point; from a sphere's centre the first corner.
    let request = json!({
        "surface": saddle(),
        "points": [[0.25, 0.25, 0.75], [3.0, 0.5, 0.5]],
    });
    let (status, body) = app.post_json("/v1/surfaces/closest-point", &request).await;
    assert_eq!(status, 200, "{body}");
    let results = body["results"].as_array().unwrap();
    assert!(
        (results[0]["u"].as_f64().unwrap() - 0.5).abs() < 1e-12,
        "{body}"
    );
    assert!(
        (results[0]["v"].as_f64().unwrap() - 0.5).abs() < 1e-12,
        "{body}"
    );
    assert!(
        (results[0]["distance"].as_f64().unwrap() - 0.5f64.powi(2) * 6f64.sqrt()).abs() < 1e-12
    );
    assert_eq!(results[1]["u"], 1.0);
    let point = numbers(&results[1]["point"]);
    assert_eq!(point[0], 1.0);
    let request = json!({"surface": octant(), "points": [[0, 0, 0]]});
    let (status, body) = app.post_json("/v1/surfaces/closest-point", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["results"][0]["u"], 0.0);
    assert_eq!(body["results"][0]["v"], 0.0);
    // A range: the part v in [0, 0.25] of the saddle; the query above (0.5, 0.5) finds its
    // edge v = 0.25.
    let request = json!({
        "surface": saddle(),
        "points": [[0.5, 0.5, 0.25]],
        "range": [[0, 1], [0, 0.25]]
    });
    let (status, body) = app.post_json("/v1/surfaces/closest-point", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["results"][0]["v"], 0.25);
}

#[tokio::test]
async fn picking_rules_name_their_field() {
    let app = spawn_app().await;
    let cases = [
        (json!({"surface": saddle(), "points": []}), "/points"),
        (
            json!({"surface": saddle(), "points": [[0, 0, 0], [1, 2]]}),
            "/points/1",
        ),
        (
            json!({"surface": saddle(), "points": [[0, 0, 0]], "range": [[0, 2], [0, 1]]}),
            "/range/0/1",
        ),
        (
            json!({"surface": saddle(), "points": [[0, 0, 0]], "range": [[0, 1], [0.8, 0.2]]}),
            "/range/1/0",
        ),
    ];
    for (request, pointer) in cases {
        let response = app.post("/v1/surfaces/closest-point", &request).await;
        expect_problem(response, 422, Some(pointer)).await;
    }
    let mut ragged = saddle();
    ragged["control_points"][1].as_array_mut().unwrap().pop();
    let response = app
        .post(
            "/v1/surfaces/closest-point",
            &json!({"surface": ragged, "points": [[0, 0, 0]]}),
        )
        .await;
    expect_problem(response, 422, Some("/surface/control_points/1")).await;
}
