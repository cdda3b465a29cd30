//! `/v1/curves/bezier` and evaluate's `tolerance` over HTTP, checked against a de Casteljau
//! and a point-to-edge distance written here; every new 422 (of these and of insert-knots)
//! and the limits that bound them.

use serde_json::json;

use crate::helpers::{assert_problem, numbers, points, spawn_app, spawn_app_with};
use crate::insert_knots::{SAME_CURVE_TOL, bezier_curve};
use crate::reference::{cubic_2d, distance, rational_3d};

/// De Casteljau on `(w B, w)`, projected.
fn de_casteljau(points: &[Vec<f64>], weights: Option<&[f64]>, s: f64) -> Vec<f64> {
    let dimension = points[0].len();
    let mut work: Vec<Vec<f64>> = points
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let w = weights.map_or(1.0, |w| w[i]);
            let mut h: Vec<f64> = b.iter().map(|v| w * v).collect();
            h.push(w);
            h
        })
        .collect();
    for level in 1..work.len() {
        for i in 0..work.len() - level {
            let next = work[i + 1].clone();
            for (value, later) in work[i].iter_mut().zip(next) {
                *value = (1.0 - s) * *value + s * later;
            }
        }
    }
    (0..dimension)
        .map(|c| work[0][c] / work[0][dimension])
        .collect()
}

/// The SVG path read back: the points after each command letter, as `(letter, points)`.
fn parse_svg_path(path: &str) -> Vec<(char, Vec<Vec<f64>>)> {
    let mut commands: Vec<(char, Vec<f64>)> = Vec::new();
    for token in path.split_whitespace() {
        match token {
            "M" | "L" | "Q" | "C" => commands.push((token.chars().next().unwrap(), Vec::new())),
            number => commands
                .last_mut()
                .expect("a command before numbers")
                .1
                .push(number.parse().expect("a number")),
        }
    }
    commands
        .into_iter()
        .map(|(letter, values)| {
            assert_eq!(values.len() % 2, 0, "{path}");
            (letter, values.chunks(2).map(<[f64]>::to_vec).collect())
        })
        .collect()
}

#[tokio::test]
async fn bezier_segments_are_the_curve_and_the_svg_path_reads_back() {
    let app = spawn_app().await;
    for curve in [cubic_2d(), rational_3d(), bezier_curve()] {
        let (status, body) = app
            .post_json("/v1/curves/bezier", &json!({"curve": curve.to_json(false)}))
            .await;
        assert_eq!(status, 200, "{body}");
        let segments = body["segments"].as_array().unwrap();
        let mut breaks = curve.knots.clone();
        breaks.dedup();
        assert_eq!(segments.len(), breaks.len() - 1);
        for (segment, span) in segments.iter().zip(breaks.windows(2)) {
            assert_eq!(numbers(&segment["domain"]), span);
            let control = points(&segment["control_points"]);
            assert_eq!(control.len(), curve.degree + 1);
            let weights = segment.get("weights").map(numbers);
            assert_eq!(weights.is_some(), curve.weights.is_some());
            for k in 0..=10 {
                let s = k as f64 / 10.0;
                let u = if k == 10 {
                    span[1]
                } else {
                    span[0] + s * (span[1] - span[0])
                };
                let found = de_casteljau(&control, weights.as_deref(), s);
                let expected = curve.point(u);
                assert!(distance(&found, &expected) < SAME_CURVE_TOL, "u = {u}");
            }
        }
        let planar = curve.points[0].len() == 2 && curve.weights.is_none();
        assert_eq!(body["svg_path"].is_string(), planar, "{body}");
        if planar {
            let path = parse_svg_path(body["svg_path"].as_str().unwrap());
            assert_eq!(path[0].0, 'M');
            assert_eq!(
                path[0].1,
                vec![points(&segments[0]["control_points"])[0].clone()]
            );
            assert_eq!(path.len(), segments.len() + 1);
            for (command, segment) in path[1..].iter().zip(segments) {
                assert_eq!(command.0, 'C');
                // Bit for bit: the numbers are written as their shortest round-trip text.
                assert_eq!(command.1, points(&segment["control_points"])[1..]);
            }
        }
    }
}

#[tokio::test]
async fn svg_paths_use_l_and_q_for_low_degrees_and_m_after_a_jump() {
    let app = spawn_app().await;
    let polyline = json!({"degree": 1, "control_points": [[0, 0], [1, -0.0], [2.5, 1e-7]], "knots": [0, 0, 1, 2, 2]});
    let (status, body) = app
        .post_json("/v1/curves/bezier", &json!({"curve": polyline}))
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["svg_path"], "M 0 0 L 1 0 L 2.5 1e-7");
    // A triple interior knot (degree + 1): the curve jumps from (2, 0) to (3, 2) at 1.
    let quadratic = json!({"degree": 2, "control_points": [[0, 0], [1, 2], [2, 0], [3, 2], [4, 0], [5, 2]],
        "knots": [0, 0, 0, 1, 1, 1, 2, 2, 2]});
    let (status, body) = app
        .post_json("/v1/curves/bezier", &json!({"curve": quadratic}))
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        body["svg_path"], "M 0 0 Q 1 2 2 0 M 3 2 Q 4 0 5 2",
        "{body}"
    );
}

#[tokio::test]
async fn a_tolerance_gives_a_polyline_within_it() {
    let app = spawn_app().await;
    for (curve, tolerance) in [
        (cubic_2d(), 0.01),
        (rational_3d(), 0.001),
        (bezier_curve(), 0.1),
    ] {
        let (status, body) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": curve.to_json(false), "tolerance": tolerance}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let parameters = numbers(&body["parameters"]);
        let vertices = points(&body["points"]);
        assert_eq!(parameters.first(), Some(&0.0));
        assert_eq!(parameters.last(), Some(&1.0));
        assert!(parameters.windows(2).all(|w| w[0] < w[1]));
        for (edge, pair) in parameters.windows(2).enumerate() {
            for k in 0..=20 {
                let u = pair[0] + (pair[1] - pair[0]) * k as f64 / 20.0;
                let q = curve.point(u);
                let (a, b) = (&vertices[edge], &vertices[edge + 1]);
                let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| y - x).collect();
                let len2: f64 = d.iter().map(|v| v * v).sum();
                let along = (q
                    .iter()
                    .zip(a)
                    .zip(&d)
                    .map(|((q, a), d)| (q - a) * d)
                    .sum::<f64>()
                    / len2)
                    .clamp(0.0, 1.0);
                let foot: Vec<f64> = a.iter().zip(&d).map(|(a, d)| a + along * d).collect();
                assert!(distance(&q, &foot) <= tolerance, "u = {u}");
            }
        }
    }
}

#[tokio::test]
async fn every_new_rule_is_a_422_naming_the_field() {
    let app = spawn_app().await;
    let curve = cubic_2d().to_json(false);
    let cases = [
        (
            "/v1/curves/insert-knots",
            json!({"curve": curve, "knots": [0.5, 1.5]}),
            "/knots/1",
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": curve, "knots": [0.3, 0.5, 0.5, 0.5]}),
            "/knots/3",
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": curve, "knots": [1.0]}),
            "/knots/0",
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": curve, "knots": [-1e-9]}),
            "/knots/0",
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": curve, "editable_at": {"parameter": 0.0}}),
            "/editable_at/parameter",
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": curve, "editable_at": {"parameter": 2.0}}),
            "/editable_at/parameter",
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": curve, "editable_at": {"parameter": 0.5, "spacing": 0}}),
            "/editable_at/spacing",
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": {"degree": 3, "control_points": [[0, 0]], "knots": []}, "knots": [0.5]}),
            "/curve/control_points",
        ),
        (
            "/v1/curves/bezier",
            json!({"curve": {"degree": 0, "control_points": [[0, 0]], "knots": [0, 1]}}),
            "/curve/degree",
        ),
        (
            "/v1/curves/evaluate",
            json!({"curve": curve, "tolerance": 0.1, "samples": 3}),
            "/tolerance",
        ),
        (
            "/v1/curves/evaluate",
            json!({"curve": curve, "tolerance": 0.1, "parameters": [0.5]}),
            "/tolerance",
        ),
        (
            "/v1/curves/evaluate",
            json!({"curve": curve, "tolerance": 0}),
            "/tolerance",
        ),
        (
            "/v1/curves/evaluate",
            json!({"curve": curve, "tolerance": -1}),
            "/tolerance",
        ),
        (
            "/v1/curves/evaluate",
            json!({"curve": curve, "tolerance": 1e-12}),
            "/tolerance",
        ),
        (
            "/v1/curves/evaluate",
            json!({"curve": {"degree": 1, "control_points": [[0, 0], [1, 1], [2, 0], [3, 1]],
            "knots": [0, 0, 0.5, 0.5, 1, 1]}, "tolerance": 0.1}),
            "/tolerance",
        ),
    ];
    for (path, request, pointer) in cases {
        let (status, body) = app.post_json(path, &request).await;
        assert_eq!(status, 422, "{path} {request}: {body}");
        assert_problem(422, &body, Some(pointer));
    }
    // The messages say what is wrong.
    let (_, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "tolerance": 1e-12}),
        )
        .await;
    assert!(
        body["detail"]
            .as_str()
            .unwrap()
            .contains("double precision"),
        "{body}"
    );
    let (_, body) = app
        .post_json(
            "/v1/curves/insert-knots",
            &json!({"curve": curve, "knots": [0.3, 0.5, 0.5, 0.5]}),
        )
        .await;
    assert!(
        body["detail"].as_str().unwrap().contains("multiplicity 4"),
        "{body}"
    );
}

#[tokio::test]
async fn limits_bound_the_polyline_and_the_refined_curve() {
    let app = spawn_app_with(|config| {
        config.max_parameters = 50;
        config.max_control_points = 10;
    })
    .await;
    let curve = cubic_2d().to_json(false);
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "tolerance": 1e-6}),
        )
        .await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/tolerance"));
    assert!(
        body["detail"]
            .as_str()
            .unwrap()
            .contains("more than 50 points"),
        "{body}"
    );
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "tolerance": 0.5}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let (status, body) = app
        .post_json(
            "/v1/curves/insert-knots",
            &json!({"curve": curve, "knots": [0.1, 0.3, 0.6]}),
        )
        .await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/knots"));
    let (status, body) = app
        .post_json(
            "/v1/curves/insert-knots",
            &json!({"curve": curve, "knots": [0.1, 0.3], "editable_at": {"parameter": 0.9}}),
        )
        .await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/editable_at"));
}
