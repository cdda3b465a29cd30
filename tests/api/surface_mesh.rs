//! `POST /v1/surfaces/tessellate` over HTTP: a mesh within the tolerance (JSON and binary
//! glTF of the same mesh), and its rules as 422s naming the field.

use serde_json::json;

use crate::helpers::{expect_problem, numbers, points, spawn_app, spawn_app_with};
use crate::surfaces::{octant, saddle};

#[tokio::test]
async fn a_mesh_meets_its_tolerance_as_json_and_as_gltf() {
    let app = spawn_app().await;
    let request = json!({"surface": octant(), "tolerance": 1e-3});
    let (status, body) = app.post_json("/v1/surfaces/tessellate", &request).await;
    assert_eq!(status, 200, "{body}");
    let max_error = body["max_error"].as_f64().unwrap();
    assert!(max_error > 0.0 && max_error <= 1e-3, "{max_error}");
    let vertices = points(&body["vertices"]);
    let triangles = body["triangles"].as_array().unwrap();
    assert!(triangles.len() >= 8, "{}", triangles.len());
    // On the unit sphere: every vertex at distance 1, every triangle's centroid within the
    // tolerance of it (inside: chords cut in). Its normals (du × dv) point inwards; the
    // triangles turn counter-clockwise seen from there.
    for vertex in &vertices {
        let r = vertex.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((r - 1.0).abs() < 1e-14);
    }
    let normals = points(&body["normals"]);
    for triangle in triangles {
        let [a, b, c] = [0, 1, 2].map(|k| vertices[triangle[k].as_u64().unwrap() as usize].clone());
        let centroid: Vec<f64> = (0..3).map(|k| (a[k] + b[k] + c[k]) / 3.0).collect();
        let r = centroid.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!(1.0 - r <= max_error + 1e-15, "{r}");
        let (e, f) = (
            (0..3).map(|k| b[k] - a[k]).collect::<Vec<_>>(),
            (0..3).map(|k| c[k] - a[k]).collect::<Vec<_>>(),
        );
        let face = [
            e[1] * f[2] - e[2] * f[1],
            e[2] * f[0] - e[0] * f[2],
            e[0] * f[1] - e[1] * f[0],
        ];
        // Triangles at the pole (two vertices of the collapsed row) have no area.
        let area = (face[0] * face[0] + face[1] * face[1] + face[2] * face[2]).sqrt();
        if area > 1e-12 {
            let n = &normals[triangle[0].as_u64().unwrap() as usize];
            assert!(face[0] * n[0] + face[1] * n[1] + face[2] * n[2] > 0.0);
        }
    }
    let response = app
        .post(
            "/v1/surfaces/tessellate",
            &json!({"surface": octant(), "tolerance": 1e-3, "format": "gltf"}),
        )
        .await;
    assert_eq!(response.status().as_u16(), 200);
    assert_eq!(response.headers()["content-type"], "model/gltf-binary");
    let glb = response.bytes().await.unwrap();
    assert_eq!(&glb[..4], b"glTF");
    let json_length = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let document: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_length]).unwrap();
    assert_eq!(
        document["accessors"][0]["count"].as_u64().unwrap() as usize,
        vertices.len()
    );
    assert_eq!(
        document["accessors"][2]["count"].as_u64().unwrap() as usize,
        3 * triangles.len()
    );
    assert_eq!(
        document["asset"]["extras"]["max_error"].as_f64().unwrap(),
        max_error
    );
    let translation = numbers(&document["nodes"][0]["translation"]);
    assert_eq!(translation.len(), 3);
}

#[tokio::test]
async fn mesh_rules_name_their_field() {
    let app = spawn_app_with(|config| config.max_triangles = 50).await;
    let jump = json!({
        "degree_u": 1, "degree_v": 1,
        "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]], [[2, 0, 1], [2, 1, 1]], [[3, 0, 1], [3, 1, 1]]],
        "knots_u": [0, 0, 1, 1, 2, 2], "knots_v": [0, 0, 1, 1]
    });
    let cases = [
        (json!({"surface": saddle(), "tolerance": 0}), "/tolerance"),
        (
            json!({"surface": saddle(), "tolerance": 1e-12}),
            "/tolerance",
        ),
        (
            json!({"surface": octant(), "tolerance": 1e-6}),
            "/tolerance",
        ),
        (
            json!({"surface": jump, "tolerance": 0.1}),
            "/surface/knots_u",
        ),
        (
            json!({"surface": saddle(), "tolerance": 0.1, "format": "obj"}),
            "/format",
        ),
    ];
    for (request, pointer) in cases {
        let response = app.post("/v1/surfaces/tessellate", &request).await;
        expect_problem(response, 422, Some(pointer)).await;
    }
    let (status, body) = app
        .post_json(
            "/v1/surfaces/tessellate",
            &json!({"surface": saddle(), "tolerance": 0.1}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
}
