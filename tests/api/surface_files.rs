//! Surfaces in STEP over HTTP: `/v1/curves/import` answers the 28 rational complex surfaces of
//! a real AP214 file (tests/data/interop/as1-oc-214.stp) beside its curves, `/v1/curves/export`
//! writes surfaces (a periodic one clamped over its period) that import back to the same
//! numbers and points, and the rules of an export with surfaces are 422s naming the field.

use serde_json::{Value, json};

use crate::helpers::{expect_problem, points, spawn_app};
use crate::surfaces::{octant, saddle};

fn evaluate_body(surface: &Value) -> Value {
    let mut surface = surface.clone();
    surface.as_object_mut().unwrap().remove("source");
    json!({"surface": surface, "samples": [5, 5]})
}

#[tokio::test]
async fn real_step_surfaces_import_and_surfaces_export_and_import_back() {
    let app = spawn_app().await;
    let data = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/interop/as1-oc-214.stp"
    ))
    .unwrap();
    let (status, body) = app
        .post_json(
            "/v1/curves/import",
            &json!({"format": "step", "data": data}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let surfaces = body["surfaces"].as_array().unwrap();
    assert_eq!(surfaces.len(), 28);
    for surface in surfaces {
        assert!(surface["source"].as_str().unwrap().starts_with('#'));
        assert!(surface["weights"].is_array(), "rational complex entities");
        assert!(surface["multiplicities_u"].is_array());
    }

    // Export: an imported surface, the saddle, the octant, and a surface periodic in v.
    let periodic = json!({
        "degree_u": 1, "degree_v": 2,
        "control_points": [[[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]],
                           [[1, 0, 1], [0, 1, 1], [-1, 0, 1], [0, -1, 1]]],
        "knots_u": [0, 0, 1, 1],
        "knots_v": [0, 1, 2, 3, 4], "multiplicities_v": [1, 1, 1, 1, 1], "periodic_v": true
    });
    let mut first = surfaces[0].clone();
    first.as_object_mut().unwrap().remove("source");
    let sent = vec![first, saddle(), octant(), periodic];
    let response = app
        .post(
            "/v1/curves/export",
            &json!({"format": "step", "surfaces": sent}),
        )
        .await;
    assert_eq!(response.status().as_u16(), 200);
    assert_eq!(response.headers()["content-type"], "model/step");
    let text = response.text().await.unwrap();
    assert!(text.contains("GEOMETRIC_SET"));
    let (status, back) = app
        .post_json(
            "/v1/curves/import",
            &json!({"format": "step", "data": text}),
        )
        .await;
    assert_eq!(status, 200, "{back}");
    assert_eq!(back["skipped"], 0);
    assert_eq!(back["curves"], json!([]));
    let back = back["surfaces"].as_array().unwrap();
    assert_eq!(back.len(), sent.len());
    assert_eq!(back[0]["control_points"], sent[0]["control_points"]);
    assert_eq!(back[0]["weights"], sent[0]["weights"]);
    assert_eq!(back[2]["weights"], sent[2]["weights"]);
    // The same points on a grid of the domain (the periodic one over its period, clamped).
    for (ours, again) in sent.iter().zip(back) {
        let (_, a) = app
            .post_json("/v1/surfaces/evaluate", &evaluate_body(ours))
            .await;
        let (_, b) = app
            .post_json("/v1/surfaces/evaluate", &evaluate_body(again))
            .await;
        for (p, q) in points(&a["points"]).iter().zip(points(&b["points"])) {
            let gap: f64 = p.iter().zip(&q).map(|(x, y)| (x - y).powi(2)).sum::<f64>();
            assert!(gap.sqrt() <= 1e-14, "{p:?} {q:?}");
        }
    }
}

#[tokio::test]
async fn export_rules_with_surfaces_name_their_field() {
    let app = spawn_app().await;
    let mut ragged = saddle();
    ragged["control_points"][1] = json!([[1, 0, 0]]);
    let cases = [
        (json!({"format": "step"}), "/curves"),
        (
            json!({"format": "dxf", "surfaces": [saddle()]}),
            "/surfaces",
        ),
        (
            json!({"format": "step", "surfaces": [saddle(), ragged]}),
            "/surfaces/1/control_points/1",
        ),
    ];
    for (request, pointer) in cases {
        let response = app.post("/v1/curves/export", &request).await;
        expect_problem(response, 422, Some(pointer)).await;
    }
}
