//! `POST /v1/surfaces/iso-curve`, `/v1/surfaces/insert-knots` and `/v1/surfaces/split` over
//! HTTP: the iso-curve is a curve every curve endpoint takes and equal to the surface on its
//! line; insertion and split keep the surface; their rules are 422s naming the field.

use serde_json::{Value, json};

use crate::helpers::{expect_problem, numbers, points, spawn_app};
use crate::surfaces::{octant, saddle};

/// The points of `surface` at `parameters`, over HTTP.
async fn surface_points(
    app: &crate::helpers::TestApp,
    surface: &Value,
    parameters: &[[f64; 2]],
) -> Vec<Vec<f64>> {
    let (status, body) = app
        .post_json(
            "/v1/surfaces/evaluate",
            &json!({"surface": surface, "parameters": parameters}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    points(&body["points"])
}

fn close(a: &[Vec<f64>], b: &[Vec<f64>], tolerance: f64) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| p.iter().zip(q).all(|(x, y)| (x - y).abs() <= tolerance))
}

#[tokio::test]
async fn iso_curves_are_curves_every_curve_endpoint_takes() {
    let app = spawn_app().await;
    for (surface, fixed, value) in [
        (saddle(), "v", 0.3),
        (octant(), "u", 0.4),
        (octant(), "v", 1.0),
    ] {
        let (status, body) = app
            .post_json(
                "/v1/surfaces/iso-curve",
                &json!({"surface": surface, "fixed": fixed, "parameter": value}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let curve = &body["curve"];
        assert_eq!(
            curve["weights"].is_array(),
            surface["weights"].is_array(),
            "{body}"
        );
        let ts = [0.0, 0.25, 0.5, 0.9, 1.0];
        let (status, evaluated) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": curve, "parameters": ts}),
            )
            .await;
        assert_eq!(status, 200, "{evaluated}");
        let pairs: Vec<[f64; 2]> = ts
            .iter()
            .map(|&t| if fixed == "v" { [t, value] } else { [value, t] })
            .collect();
        let expected = surface_points(&app, &surface, &pairs).await;
        assert!(
            close(&points(&evaluated["points"]), &expected, 1e-15),
            "{evaluated}"
        );
        for path in ["/v1/curves/length", "/v1/curves/bezier"] {
            let (status, answer) = app.post_json(path, &json!({"curve": curve})).await;
            assert_eq!(status, 200, "{path}: {answer}");
        }
        let (status, answer) = app
            .post_json(
                "/v1/curves/split",
                &json!({"curve": curve, "parameters": [0.5]}),
            )
            .await;
        assert_eq!(status, 200, "{answer}");
    }
    let response = app
        .post(
            "/v1/surfaces/iso-curve",
            &json!({"surface": saddle(), "fixed": "u", "parameter": 1.5}),
        )
        .await;
    expect_problem(response, 422, Some("/parameter")).await;
    let response = app
        .post(
            "/v1/surfaces/iso-curve",
            &json!({"surface": saddle(), "fixed": "w", "parameter": 0.5}),
        )
        .await;
    expect_problem(response, 422, Some("/fixed")).await;
}

#[tokio::test]
async fn insertion_and_split_keep_the_surface() {
    let app = spawn_app().await;
    let grid: Vec<[f64; 2]> = (0..=4)
        .flat_map(|i| (0..=4).map(move |j| [f64::from(i) / 4.0, f64::from(j) / 4.0]))
        .collect();
    let surface = octant();
    let before = surface_points(&app, &surface, &grid).await;
    let (status, body) = app
        .post_json(
            "/v1/surfaces/insert-knots",
            &json!({"surface": surface, "knots_u": [0.5, 0.5], "knots_v": [0.3]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let refined = &body["surface"];
    assert_eq!(refined["control_points"].as_array().unwrap().len(), 5);
    assert_eq!(refined["control_points"][0].as_array().unwrap().len(), 4);
    assert_eq!(
        numbers(&refined["knots_u"]),
        [0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]
    );
    let after = surface_points(&app, refined, &grid).await;
    assert!(close(&before, &after, 1e-15));

    let (status, body) = app
        .post_json(
            "/v1/surfaces/split",
            &json!({"surface": surface, "fixed": "u", "parameters": [0.6, 0.2]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let pieces = body["surfaces"].as_array().unwrap();
    assert_eq!(pieces.len(), 3);
    for (piece, (lo, hi)) in pieces.iter().zip([(0.0, 0.2), (0.2, 0.6), (0.6, 1.0)]) {
        let knots = numbers(&piece["knots_u"]);
        assert_eq!((knots[0], knots[knots.len() - 1]), (lo, hi));
        let local: Vec<[f64; 2]> = (0..=3)
            .map(|k| [lo + (hi - lo) * f64::from(k) / 3.0, 0.7])
            .collect();
        let whole = surface_points(&app, &surface, &local).await;
        let part = surface_points(&app, piece, &local).await;
        assert!(close(&whole, &part, 1e-15));
    }
}

#[tokio::test]
async fn insertion_and_split_rules_name_their_field() {
    let app = spawn_app().await;
    let cases = [
        (
            "/v1/surfaces/insert-knots",
            json!({"surface": saddle(), "knots_u": [0.5, 1.5]}),
            "/knots_u/1",
        ),
        (
            "/v1/surfaces/insert-knots",
            json!({"surface": saddle(), "knots_v": [0.5, 0.5]}),
            "/knots_v/1",
        ),
        (
            "/v1/surfaces/split",
            json!({"surface": saddle(), "fixed": "v", "parameters": [0.5, 1]}),
            "/parameters/1",
        ),
        (
            "/v1/surfaces/split",
            json!({"surface": saddle(), "fixed": "u", "parameters": [0]}),
            "/parameters/0",
        ),
    ];
    for (path, request, pointer) in cases {
        let response = app.post(path, &request).await;
        expect_problem(response, 422, Some(pointer)).await;
    }
}
