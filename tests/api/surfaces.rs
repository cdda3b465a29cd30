//! `POST /v1/surfaces/evaluate` over HTTP: known surfaces (a hyperbolic paraboloid, the
//! sphere's octant with its collapsed pole row, a periodic form), the grid order, and nulls
//! exactly where the surface has no normal.

use serde_json::{Value, json};

use crate::helpers::{numbers, points, spawn_app};

/// The bilinear patch `z = x y` over the unit square (degree 1 × 1).
pub fn saddle() -> Value {
    json!({
        "degree_u": 1, "degree_v": 1,
        "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
        "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]
    })
}

/// The octant `x, y, z >= 0` of the unit sphere: the quarter meridian (rows, along `u`, from
/// the equator to the pole) swept around `z` (along `v`); the last row collapses into the
/// pole.
pub fn octant() -> Value {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let meridian = [([1.0, 0.0], 1.0), ([1.0, 1.0], w), ([0.0, 1.0], 1.0)];
    let circle = [([1.0, 0.0], 1.0), ([1.0, 1.0], w), ([0.0, 1.0], 1.0)];
    let points: Vec<Vec<[f64; 3]>> = meridian
        .iter()
        .map(|(xz, _)| {
            circle
                .iter()
                .map(|(xy, _)| [xz[0] * xy[0], xz[0] * xy[1], xz[1]])
                .collect()
        })
        .collect();
    let weights: Vec<Vec<f64>> = meridian
        .iter()
        .map(|(_, a)| circle.iter().map(|(_, b)| a * b).collect())
        .collect();
    json!({
        "degree_u": 2, "degree_v": 2,
        "control_points": points,
        "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1],
        "weights": weights
    })
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[tokio::test]
async fn the_saddle_has_its_known_points_partials_and_curvature() {
    let app = spawn_app().await;
    let request = json!({
        "surface": saddle(),
        "parameters": [[0.5, 0.5], [0.25, 0.75], [1, 1]],
        "derivatives": 2, "normals": true, "curvature": true
    });
    let (status, body) = app.post_json("/v1/surfaces/evaluate", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["domain"], json!([[0.0, 1.0], [0.0, 1.0]]));
    let found = points(&body["points"]);
    for (point, [u, v]) in found.iter().zip([[0.5, 0.5], [0.25, 0.75], [1.0, 1.0]]) {
        assert_eq!(point, &vec![u, v, u * v]);
    }
    // S_u = (1, 0, v), S_v = (0, 1, u), S_uv = (0, 0, 1), S_uu = S_vv = 0.
    let du = points(&body["du"]);
    let dv = points(&body["dv"]);
    assert_eq!(du[1], vec![1.0, 0.0, 0.75]);
    assert_eq!(dv[1], vec![0.0, 1.0, 0.25]);
    assert_eq!(points(&body["duv"])[0], vec![0.0, 0.0, 1.0]);
    assert_eq!(points(&body["duu"])[0], vec![0.0; 3]);
    assert_eq!(points(&body["dvv"])[2], vec![0.0; 3]);
    // At the centre: n = (-1/2, -1/2, 1) / √(3/2); K = -1 / (1 + 1/4 + 1/4)² and H = uv
    // terms: for z = xy, K = -1 / (1 + x² + y²)², H = -xy / (1 + x² + y²)^(3/2).
    let normal = numbers(&body["normals"][0]);
    let expected = [-0.5, -0.5, 1.0].map(|c: f64| c / 1.5f64.sqrt());
    for (n, e) in normal.iter().zip(expected) {
        assert!((n - e).abs() < 1e-15, "{normal:?}");
    }
    let curvature = &body["curvature"][0];
    let gaussian = curvature["gaussian"].as_f64().unwrap();
    assert!(
        (gaussian + 1.0 / 1.5f64.powi(2)).abs() < 1e-14,
        "{gaussian}"
    );
    let mean = curvature["mean"].as_f64().unwrap();
    assert!((mean + 0.25 / 1.5f64.powf(1.5)).abs() < 1e-14, "{mean}");
    let principal = numbers(&curvature["principal"]);
    assert!(principal[0] >= principal[1]);
    assert!((principal[0] * principal[1] - gaussian).abs() < 1e-14);
    let directions = points(&curvature["directions"]);
    assert!((norm(&directions[0]) - 1.0).abs() < 1e-14);
    assert!(body.get("limit_normals").is_none());
}

#[tokio::test]
async fn a_grid_is_answered_row_by_row_with_both_ends() {
    let app = spawn_app().await;
    let request = json!({"surface": saddle(), "samples": [3, 2]});
    let (status, body) = app.post_json("/v1/surfaces/evaluate", &request).await;
    assert_eq!(status, 200, "{body}");
    let parameters = points(&body["parameters"]);
    assert_eq!(
        parameters,
        vec![
            vec![0.0, 0.0],
            vec![0.0, 1.0],
            vec![0.5, 0.0],
            vec![0.5, 1.0],
            vec![1.0, 0.0],
            vec![1.0, 1.0]
        ]
    );
    assert_eq!(points(&body["points"])[3], vec![0.5, 1.0, 0.5]);
    assert!(body.get("du").is_none() && body.get("normals").is_none());
}

#[tokio::test]
async fn the_pole_of_the_sphere_has_its_limit_normal_and_no_curvature() {
    let app = spawn_app().await;
    let request = json!({
        "surface": octant(),
        "parameters": [[0.5, 0.5], [1, 0], [1, 0.5], [1, 1]],
        "normals": true, "curvature": true
    });
    let (status, body) = app.post_json("/v1/surfaces/evaluate", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["limit_normals"], json!([1, 2, 3]));
    for (index, point) in points(&body["points"]).iter().enumerate() {
        assert!((norm(point) - 1.0).abs() < 1e-15);
        let normal = numbers(&body["normals"][index]);
        // u runs up the meridian, v around z: du × dv points to the centre.
        for (n, p) in normal.iter().zip(point) {
            assert!((n + p).abs() < 1e-12, "{index}: {normal:?} at {point:?}");
        }
    }
    let curvature = body["curvature"].as_array().unwrap();
    assert!((curvature[0]["gaussian"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    assert!((curvature[0]["mean"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    assert!(curvature[1..].iter().all(Value::is_null), "{body}");
}

#[tokio::test]
async fn a_surface_without_a_normal_gets_null() {
    let app = spawn_app().await;
    // Every control point on one line: du and dv are parallel everywhere.
    let line = json!({
        "degree_u": 1, "degree_v": 1,
        "control_points": [[[0, 0, 0], [1, 1, 1]], [[1, 1, 1], [2, 2, 2]]],
        "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]
    });
    let request =
        json!({"surface": line, "parameters": [[0.5, 0.5]], "normals": true, "curvature": true});
    let (status, body) = app.post_json("/v1/surfaces/evaluate", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["normals"], json!([null]));
    assert_eq!(body["curvature"], json!([null]));
}

#[tokio::test]
async fn the_periodic_form_and_the_flat_form_give_the_same_points() {
    let app = spawn_app().await;
    // A closed cylinder-like band: periodic cubic in u over 4 rows, linear in v.
    let rows = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    let periodic_points: Vec<Vec<[f64; 3]>> = rows
        .iter()
        .map(|xy| vec![[xy[0], xy[1], 0.0], [xy[0], xy[1], 1.0]])
        .collect();
    let periodic = json!({
        "degree_u": 3, "degree_v": 1,
        "control_points": periodic_points,
        "knots_u": [0, 1, 2, 3, 4], "multiplicities_u": [1, 1, 1, 1, 1], "periodic_u": true,
        "knots_v": [0, 0, 1, 1]
    });
    // The same surface cut open: rows 0 1 2 3 0 1 2, uniform knots -3 .. 7.
    let mut flat_points = periodic_points.clone();
    flat_points.extend_from_slice(&periodic_points[..3]);
    let flat = json!({
        "degree_u": 3, "degree_v": 1,
        "control_points": flat_points,
        "knots_u": [-3, -2, -1, 0, 1, 2, 3, 4, 5, 6, 7],
        "knots_v": [0, 0, 1, 1]
    });
    let parameters = json!([[0, 0], [0.5, 0.25], [3.9, 1], [2, 0.5]]);
    let (status, a) = app
        .post_json(
            "/v1/surfaces/evaluate",
            &json!({"surface": periodic, "parameters": parameters, "derivatives": 1}),
        )
        .await;
    assert_eq!(status, 200, "{a}");
    let (status, b) = app
        .post_json(
            "/v1/surfaces/evaluate",
            &json!({"surface": flat, "parameters": parameters, "derivatives": 1}),
        )
        .await;
    assert_eq!(status, 200, "{b}");
    assert_eq!(a["domain"], json!([[0.0, 4.0], [0.0, 1.0]]));
    for key in ["points", "du", "dv"] {
        for (p, q) in points(&a[key]).iter().zip(points(&b[key])) {
            for (x, y) in p.iter().zip(&q) {
                assert!((x - y).abs() < 1e-14, "{key}: {p:?} vs {q:?}");
            }
        }
    }
    // A periodic direction takes any finite parameter, reduced into the period.
    let (status, c) = app
        .post_json(
            "/v1/surfaces/evaluate",
            &json!({"surface": periodic, "parameters": [[4.5, 0.5], [-3.5, 0.5]]}),
        )
        .await;
    assert_eq!(status, 200, "{c}");
    assert_eq!(
        points(&c["parameters"]),
        vec![vec![0.5, 0.5], vec![0.5, 0.5]]
    );
}
