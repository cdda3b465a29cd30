//! Solve's second-release fields: `methods` (the control-point move beside the knot pairs),
//! `nearest`, and membership with `methods`. Checked with the test's own de Boor and a
//! finite-difference least-squares solution.

use serde_json::{Value, json};

use crate::helpers::{expect_problem, numbers, points, spawn_app};
use crate::reference::{ReferenceCurve, cubic_2d, distance, rational_3d};

/// The minimum-norm pole change that moves `s(t)` to `target`, from finite differences:
/// column `i` of `A = ∂s(t)/∂d_i` is found by moving pole `i` by `h` in each coordinate
/// (exact for a curve that is linear in its poles), then `Δd_i = a_i (target - s(t)) / Σ a²`.
fn least_squares_by_differences(curve: &ReferenceCurve, t: f64, target: &[f64]) -> Vec<Vec<f64>> {
    let h = 1e-3;
    let base = curve.point(t);
    let sensitivity: Vec<f64> = (0..curve.points.len())
        .map(|i| {
            let mut moved = curve.clone();
            moved.points[i][0] += h;
            (moved.point(t)[0] - base[0]) / h
        })
        .collect();
    let squares: f64 = sensitivity.iter().map(|a| a * a).sum();
    let gap: Vec<f64> = target.iter().zip(&base).map(|(p, s)| p - s).collect();
    curve
        .points
        .iter()
        .zip(&sensitivity)
        .map(|(point, a)| {
            point
                .iter()
                .zip(&gap)
                .map(|(x, g)| x + a * g / squares)
                .collect()
        })
        .collect()
}

fn solution_of<'a>(body: &'a Value, method: &str) -> Option<&'a Value> {
    body["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["method"] == method)
}

#[tokio::test]
async fn both_methods_answer_in_one_sorted_list_and_the_pole_move_is_least_squares() {
    let app = spawn_app().await;
    for (curve, t, offset) in [(cubic_2d(), 0.42, 0.3), (rational_3d(), 0.55, 0.2)] {
        let dimension = curve.points[0].len();
        let mut target = curve.point(t);
        target[0] += offset;
        target[1] -= offset;
        let request = json!({"curve": curve.to_json(false), "parameter": t, "target": target,
                             "methods": ["knots", "control_points"]});
        let (status, body) = app.post_json("/v1/shape/solve", &request).await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(body["reachable"], true);
        let deviations: Vec<f64> = body["solutions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["max_deviation"].as_f64().unwrap())
            .collect();
        assert!(
            deviations.windows(2).all(|w| w[0] <= w[1]),
            "{deviations:?}"
        );
        let poles = solution_of(&body, "control_points").expect("a control-point solution");
        assert!(poles.get("knots").is_none() && poles.get("region").is_none());
        let moved = points(&poles["control_points"]);
        let expected = least_squares_by_differences(&curve, t, &target);
        for (got, want) in moved.iter().zip(&expected) {
            assert_eq!(got.len(), dimension);
            assert!(distance(got, want) < 1e-8, "{got:?} vs {want:?}");
        }
        // The new poles, evaluated by the reference, put s(t) on the target.
        let new_curve = ReferenceCurve {
            points: moved.clone(),
            ..curve.clone()
        };
        assert!(distance(&new_curve.point(t), &target) < 1e-10);
        assert!(distance(&numbers(&poles["point"]), &target) < 1e-10);
        let changed: Vec<u64> = poles["changed_control_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap())
            .collect();
        for (i, (old, new)) in curve.points.iter().zip(&moved).enumerate() {
            assert_eq!(old != new, changed.contains(&(i as u64)), "pole {i}");
        }
        // The deviation is at least the move at t, and no sample beats it.
        let deviation = poles["max_deviation"].as_f64().unwrap();
        let (lo, hi) = curve.domain();
        let sampled = (0..=2000)
            .map(|k| lo + (hi - lo) * k as f64 / 2000.0)
            .map(|u| distance(&curve.point(u), &new_curve.point(u)))
            .fold(0.0f64, f64::max);
        assert!(deviation >= sampled - 1e-12 && deviation <= sampled * 1.01 + 1e-12);
        if let Some(knots) = solution_of(&body, "knots") {
            assert!(knots["knots"].is_array() && knots["region"].is_string());
        }
    }
}

#[tokio::test]
async fn control_points_alone_reach_a_target_no_region_holds() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let far = [40.0, -30.0];
    let request = json!({"curve": curve.to_json(true), "parameter": 0.3, "target": far,
                         "methods": ["control_points"]});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["reachable"], true);
    assert_eq!(body["solutions"].as_array().unwrap().len(), 1);
    assert!(body.get("nearest").is_none());
    let (status, body) = app.post_json("/v1/shape/membership", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["reachable"], true);
    assert_eq!(body["control_points"]["contains"], true);
    let knots_only = json!({"curve": curve.to_json(true), "parameter": 0.3, "target": far});
    let (_, body) = app.post_json("/v1/shape/membership", &knots_only).await;
    assert_eq!(body["reachable"], false);
    assert!(body.get("control_points").is_none());
}

#[tokio::test]
async fn nearest_follows_a_target_outside_every_region() {
    let app = spawn_app().await;
    for (curve, t) in [(cubic_2d(), 0.42), (rational_3d(), 0.55)] {
        let mut target = curve.point(t);
        target[0] += 20.0;
        let request = json!({"curve": curve.to_json(false), "parameter": t, "target": target,
                             "nearest": true});
        let (status, body) = app.post_json("/v1/shape/solve", &request).await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(body["reachable"], false);
        let nearest = &body["nearest"];
        let point = numbers(&nearest["point"]);
        let d = nearest["distance"].as_f64().unwrap();
        assert!((distance(&point, &target) - d).abs() < 1e-12);
        assert!(d > 1.0 && d < 20.0, "{d}");
        let solutions = nearest["solutions"].as_array().unwrap();
        assert!(!solutions.is_empty());
        for solution in solutions {
            let knots = numbers(&solution["knots"]);
            let reached = curve.with_knots(knots).point(t);
            assert!(
                distance(&reached, &point) < 1e-9,
                "{reached:?} vs {point:?}"
            );
        }
        // Without the flag, no `nearest`.
        let plain = json!({"curve": curve.to_json(false), "parameter": t, "target": target});
        let (_, body) = app.post_json("/v1/shape/solve", &plain).await;
        assert!(body.get("nearest").is_none());
    }
}

#[tokio::test]
async fn bad_methods_are_422s_that_point_at_them() {
    let app = spawn_app().await;
    let curve = cubic_2d().to_json(false);
    for (methods, pointer) in [
        (json!(["knots", "poles"]), "/methods/1"),
        (json!([]), "/methods"),
        (json!(["control_points", "control_points"]), "/methods/1"),
    ] {
        for path in ["/v1/shape/solve", "/v1/shape/membership"] {
            let request = json!({"curve": curve, "parameter": 0.4, "target": [1, 1],
                                 "methods": methods});
            let response = app.post(path, &request).await;
            expect_problem(response, 422, Some(pointer)).await;
        }
    }
}

#[tokio::test]
async fn svg_paths_are_the_new_curves_as_bezier_draws_them() {
    let app = spawn_app().await;
    // The first worked example: a target that knot pairs reach too.
    let example: Value =
        serde_json::from_str(include_str!("../../examples/shape-solve.json")).unwrap();
    let curve = ReferenceCurve::from_json(&example["curve"]);
    let target = numbers(&example["target"]);
    let request = json!({"curve": curve.to_json(false), "parameter": example["parameter"],
                         "target": target, "methods": ["knots", "control_points"],
                         "svg_paths": true});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    let solutions = body["solutions"].as_array().unwrap();
    assert!(solutions.len() >= 2, "{body}");
    for solution in solutions {
        let mut moved = curve.to_json(false);
        if let Some(knots) = solution.get("knots") {
            moved["knots"] = knots.clone();
        } else {
            moved["control_points"] = solution["control_points"].clone();
        }
        let (status, pieces) = app
            .post_json("/v1/curves/bezier", &json!({"curve": moved}))
            .await;
        assert_eq!(status, 200, "{pieces}");
        assert_eq!(solution["svg_path"], pieces["svg_path"], "{solution}");
    }
    // Without the flag, no paths.
    let plain = json!({"curve": curve.to_json(false), "parameter": example["parameter"],
                       "target": target});
    let (_, body) = app.post_json("/v1/shape/solve", &plain).await;
    assert!(body["solutions"][0].get("svg_path").is_none(), "{body}");
}
