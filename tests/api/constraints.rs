//! The third release's edit fields over HTTP: `constraints` and `fixed_control_points` on
//! solve and membership, the `weights` method, any degree for the control-point and weight
//! methods, `excluded`, regions with `keep_domain`, `methods` and weight regions, and every
//! 422 of a malformed constraint set. Answers are re-evaluated by the test's own de Boor
//! (`reference.rs`), derivatives by finite differences of it.

use serde_json::{Value, json};

use crate::helpers::{assert_problem, numbers, points, spawn_app};
use crate::reference::{ReferenceCurve, cubic_2d, distance};

/// `s^(order)(u)` of the reference curve by finite differences (central inside the domain,
/// one-sided at its ends); accurate to about `1e-6` of the curve's scale.
pub(crate) fn derivative(curve: &ReferenceCurve, u: f64, order: usize) -> Vec<f64> {
    let (lo, hi) = curve.domain();
    let h = 1e-4 * (hi - lo);
    let at = |v: f64| curve.point(v);
    let combine = |terms: &[(f64, f64)], scale: f64| -> Vec<f64> {
        let dims = curve.points[0].len();
        (0..dims)
            .map(|c| terms.iter().map(|(w, v)| w * at(*v)[c]).sum::<f64>() / scale)
            .collect()
    };
    match order {
        0 => at(u),
        1 if u - h < lo => combine(&[(-3.0, u), (4.0, u + h), (-1.0, u + 2.0 * h)], 2.0 * h),
        1 if u + h > hi => combine(&[(3.0, u), (-4.0, u - h), (1.0, u - 2.0 * h)], 2.0 * h),
        1 => combine(&[(1.0, u + h), (-1.0, u - h)], 2.0 * h),
        _ if u - h < lo => combine(
            &[
                (2.0, u),
                (-5.0, u + h),
                (4.0, u + 2.0 * h),
                (-1.0, u + 3.0 * h),
            ],
            h * h,
        ),
        _ if u + h > hi => combine(
            &[
                (2.0, u),
                (-5.0, u - h),
                (4.0, u - 2.0 * h),
                (-1.0, u - 3.0 * h),
            ],
            h * h,
        ),
        _ => combine(&[(1.0, u + h), (-2.0, u), (1.0, u - h)], h * h),
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The new curve of a solution: knots, control points or weights replaced.
pub(crate) fn solution_curve(curve: &ReferenceCurve, solution: &Value) -> ReferenceCurve {
    let mut new = curve.clone();
    match solution["method"].as_str().unwrap() {
        "knots" => {
            new = ReferenceCurve::from_json(&json!({
                "degree": curve.degree, "control_points": curve.points,
                "knots": solution["knots"], "weights": curve.weights}));
        }
        "control_points" => new.points = points(&solution["control_points"]),
        "weights" => new.weights = Some(numbers(&solution["weights"])),
        other => panic!("method {other}"),
    }
    new
}

/// A quintic in 3D with weights: a curve the knot pairs do not take.
fn quintic() -> ReferenceCurve {
    ReferenceCurve {
        degree: 5,
        points: vec![
            vec![0.0, 0.0, 0.0],
            vec![1.0, 2.0, 1.0],
            vec![3.0, 3.0, 0.0],
            vec![4.0, 1.0, 2.0],
            vec![6.0, 0.0, 1.0],
            vec![7.0, 2.0, 3.0],
            vec![9.0, 3.0, 1.0],
            vec![10.0, 1.0, 0.0],
        ],
        knots: vec![
            0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0,
        ],
        weights: Some(vec![1.0, 0.8, 1.5, 1.0, 1.2, 0.7, 1.0, 1.0]),
    }
}

#[tokio::test]
async fn a_quintic_moves_by_poles_and_weights_and_keeps_every_constraint() {
    let app = spawn_app().await;
    let curve = quintic();
    let t = 0.45;
    let mut target = curve.point(t);
    target[0] += 0.15;
    target[1] += 0.1;
    let tangent_at_end = derivative(&curve, 1.0, 1);
    let request = json!({
        "curve": curve.to_json(true), "parameter": t, "target": target,
        "methods": ["control_points", "weights"],
        "constraints": [
            {"parameter": 0.0, "order": 0},
            {"parameter": 0.0, "order": 1, "value": [2.0, 4.0, 2.0]},
            {"parameter": 1.0, "order": 1, "direction_only": true},
            {"parameter": 0.8, "order": 2},
        ],
        "fixed_control_points": [7],
    });
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        body["candidates"],
        json!([]),
        "no knot candidates without `knots`"
    );
    let solutions = body["solutions"].as_array().unwrap();
    assert!(!solutions.is_empty(), "{body}");
    let deviations: Vec<f64> = solutions
        .iter()
        .map(|s| s["max_deviation"].as_f64().unwrap())
        .collect();
    assert!(
        deviations.windows(2).all(|w| w[0] <= w[1]),
        "{deviations:?}"
    );
    for solution in solutions {
        let new = solution_curve(&curve, solution);
        assert!(distance(&new.point(t), &target) < 1e-9, "{solution}");
        assert!(distance(&new.point(0.0), &curve.point(0.0)) < 1e-9);
        let start = derivative(&new, 0.0, 1);
        assert!(distance(&start, &[2.0, 4.0, 2.0]) < 1e-4, "{start:?}");
        let end = derivative(&new, 1.0, 1);
        let along: f64 = end.iter().zip(&tangent_at_end).map(|(a, b)| a * b).sum();
        let across = norm(
            &end.iter()
                .zip(&tangent_at_end)
                .map(|(a, b)| a - along / norm(&tangent_at_end).powi(2) * b)
                .collect::<Vec<_>>(),
        );
        assert!(along > 0.0 && across < 1e-5 * norm(&end), "{solution}");
        assert!(distance(&derivative(&new, 0.8, 2), &derivative(&curve, 0.8, 2)) < 1e-3);
        assert_eq!(new.points[7], curve.points[7], "the fixed pole stays");
        assert_eq!(new.weights.as_ref().unwrap()[7], 1.0);
        // Trimmed knots in, trimmed knots out (the weight solutions keep the knots).
        assert!(solution.get("knots").is_none());
    }
    // A pole move comes back; its changed poles exclude the fixed and the pinned start.
    let poles = solutions
        .iter()
        .find(|s| s["method"] == "control_points")
        .expect("a control-point move");
    let changed: Vec<u64> = poles["changed_control_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert!(
        !changed.contains(&7) && !changed.contains(&0),
        "{changed:?}"
    );
}

#[tokio::test]
async fn a_weight_solution_is_rational_and_lands_and_membership_agrees() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let t = 0.42;
    let target = [5.0, 3.3];
    let request = json!({"curve": curve.to_json(false), "parameter": t, "target": target,
                         "methods": ["weights"], "svg_paths": true});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    let solutions = body["solutions"].as_array().unwrap();
    assert!(solutions.len() >= 2, "{body}");
    let mut reached = Vec::new();
    for solution in solutions {
        assert_eq!(solution["method"], "weights");
        let weights = numbers(&solution["weights"]);
        let poles: Vec<usize> = numbers(&solution["poles"])
            .iter()
            .map(|&v| v as usize)
            .collect();
        assert_eq!(weights.len(), 8);
        for (i, w) in weights.iter().enumerate() {
            if poles.contains(&i) {
                assert!((0.01..=100.0).contains(w), "{w}");
            } else {
                assert_eq!(*w, 1.0, "a curve without weights gets ones");
            }
        }
        let new = solution_curve(&curve, solution);
        assert!(distance(&new.point(t), &target) < 1e-9);
        assert!(
            solution.get("svg_path").is_none(),
            "a rational curve has no SVG path"
        );
        reached.push(poles);
    }
    let (status, membership) = app.post_json("/v1/shape/membership", &request).await;
    assert_eq!(status, 200, "{membership}");
    assert_eq!(membership["reachable"], true);
    let pairs = membership["weights"]["pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), 6, "a cubic has six pairs at t");
    for pair in pairs {
        let poles: Vec<usize> = numbers(&pair["poles"])
            .iter()
            .map(|&v| v as usize)
            .collect();
        assert_eq!(pair["contains"] == true, reached.contains(&poles), "{pair}");
    }
    // An unreachable target: the nearest point of the quadrilaterals, reached by its solutions.
    let far = json!({"curve": curve.to_json(false), "parameter": t, "target": [0.0, 9.0],
                     "methods": ["weights"], "nearest": true});
    let (status, body) = app.post_json("/v1/shape/solve", &far).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["reachable"], false);
    let nearest = &body["nearest"];
    let point = numbers(&nearest["point"]);
    assert!((nearest["distance"].as_f64().unwrap() - distance(&point, &[0.0, 9.0])).abs() < 1e-12);
    for solution in nearest["solutions"].as_array().unwrap() {
        let new = solution_curve(&curve, solution);
        assert!(distance(&new.point(t), &point) < 1e-9, "{solution}");
    }
}

#[tokio::test]
async fn knot_solutions_that_break_a_pin_are_excluded_and_membership_follows() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let example: Value =
        serde_json::from_str(include_str!("../../examples/shape-solve.json")).unwrap();
    let free = json!({"curve": example["curve"], "parameter": 0.42, "target": example["target"],
                      "methods": ["knots", "control_points"]});
    let (_, unconstrained) = app.post_json("/v1/shape/solve", &free).await;
    let knot_count = unconstrained["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["method"] == "knots")
        .count();
    assert!(knot_count >= 1, "{unconstrained}");
    assert_eq!(unconstrained["excluded"], json!([]));
    // Pin the tangent at u = 0.5, inside every knot solution's affected domain.
    let mut pinned = free.clone();
    pinned["constraints"] = json!([{"parameter": 0.5, "order": 1}]);
    let (status, body) = app.post_json("/v1/shape/solve", &pinned).await;
    assert_eq!(status, 200, "{body}");
    let excluded = body["excluded"].as_array().unwrap();
    let dropped: u64 = excluded
        .iter()
        .filter(|e| e["method"] == "knots")
        .map(|e| e["count"].as_u64().unwrap())
        .sum();
    let kept = body["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["method"] == "knots")
        .count();
    assert_eq!(dropped as usize + kept, knot_count, "{body}");
    assert!(dropped > 0);
    for exclusion in excluded {
        assert_eq!(exclusion["constraint"], 0);
        assert!(
            exclusion["reason"].as_str().unwrap().contains("u = 0.5"),
            "{exclusion}"
        );
    }
    let tangent = derivative(&curve, 0.5, 1);
    for solution in body["solutions"].as_array().unwrap() {
        let new = solution_curve(&curve, solution);
        assert!(
            distance(&derivative(&new, 0.5, 1), &tangent) < 1e-5,
            "{solution}"
        );
    }
    // Membership with the same request agrees region by region.
    let (status, membership) = app.post_json("/v1/shape/membership", &pinned).await;
    assert_eq!(status, 200, "{membership}");
    for candidate in membership["candidates"].as_array().unwrap() {
        for region in candidate["regions"].as_array().unwrap() {
            let solved = body["solutions"].as_array().unwrap().iter().any(|s| {
                s["method"] == "knots"
                    && s["side"] == candidate["side"]
                    && s["region"] == region["region"]
            });
            assert_eq!(region["contains"] == true, solved, "{region}");
        }
    }
    assert_eq!(membership["excluded"], body["excluded"]);
}

#[tokio::test]
async fn contradictory_constraints_and_impossible_ones_are_answers_not_errors() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let request = |constraints: Value, fixed: Value| {
        json!({"curve": curve.to_json(false), "parameter": 0.42, "target": [4.8, 3.4],
               "methods": ["knots", "control_points", "weights"],
               "constraints": constraints, "fixed_control_points": fixed})
    };
    let (status, body) = app
        .post_json(
            "/v1/shape/solve",
            &request(
                json!([{"parameter": 0.7, "order": 1},
                       {"parameter": 0.7, "order": 1, "value": [1.0, 2.0]}]),
                json!([]),
            ),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["reachable"], false);
    let excluded = body["excluded"].as_array().unwrap();
    assert!(excluded.iter().any(|e| e["method"] == "control_points"));
    for exclusion in excluded {
        assert!(
            exclusion["reason"].as_str().unwrap().contains("contradict"),
            "{exclusion}"
        );
    }
    // Every pole fixed: only the knot pairs (which move no pole) may answer.
    let all: Vec<usize> = (0..8).collect();
    let (status, body) = app
        .post_json("/v1/shape/solve", &request(json!([]), json!(all)))
        .await;
    assert_eq!(status, 200, "{body}");
    assert!(
        body["solutions"]
            .as_array()
            .unwrap()
            .iter()
            .all(|s| s["method"] == "knots"),
        "{body}"
    );
    assert!(
        body["excluded"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|e| e["method"] == "weights")
            .all(|e| e["fixed_control_point"].is_u64()),
        "{body}"
    );
    assert!(
        body["excluded"]
            .as_array()
            .unwrap()
            .iter()
            .any(|e| e["method"] == "control_points"
                && e["reason"] == "the constraints leave no free control point"),
        "{body}"
    );
}

/// A degree-1 curve is the polyline of its control points: knots cannot change it, and the
/// 422 says which methods take it; a quintic is edited by knots (every family applies).
#[tokio::test]
async fn knots_on_a_polyline_say_which_methods_take_it() {
    let app = spawn_app().await;
    let polyline = json!({"degree": 1, "control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 1], [3, 1, 1]],
                          "knots": [0, 0, 0.3, 0.6, 1, 1]});
    for (path, extra) in [
        ("/v1/shape/solve", json!({"target": [1.0, 1.0, 1.0]})),
        ("/v1/shape/membership", json!({"target": [1.0, 1.0, 1.0]})),
        ("/v1/shape/regions", json!({})),
    ] {
        let mut request = json!({"curve": polyline, "parameter": 0.5});
        for (key, value) in extra.as_object().unwrap() {
            request[key] = value.clone();
        }
        let (status, body) = app.post_json(path, &request).await;
        assert_eq!(status, 422, "{path}: {body}");
        assert_problem(422, &body, Some("/curve/degree"));
        let detail = body["errors"][0]["detail"].as_str().unwrap();
        assert!(
            detail.contains("control_points")
                && detail.contains("weights")
                && detail.contains("polyline"),
            "{detail}"
        );
        request["methods"] = json!(["weights"]);
        let (status, body) = app.post_json(path, &request).await;
        assert_eq!(status, 200, "{path} with weights: {body}");
        // The quintic takes knots: its families are answered.
        let mut quintic_request = json!({"curve": quintic().to_json(false), "parameter": 0.5});
        for (key, value) in extra.as_object().unwrap() {
            quintic_request[key] = value.clone();
        }
        let (status, body) = app.post_json(path, &quintic_request).await;
        assert_eq!(status, 200, "{path} on a quintic: {body}");
        let families: Vec<&str> = body["families"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["family"].as_str().unwrap())
            .collect();
        assert!(
            families.contains(&"envelope") && families.contains(&"direct"),
            "{path}: {families:?}"
        );
    }
}

#[tokio::test]
async fn every_malformed_constraint_is_a_422_with_its_pointer() {
    let app = spawn_app().await;
    let quadratic = ReferenceCurve {
        degree: 2,
        points: vec![
            vec![0.0, 0.0],
            vec![1.0, 2.0],
            vec![3.0, 2.0],
            vec![4.0, 0.0],
        ],
        knots: vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        weights: None,
    };
    let cases: Vec<(Value, Value, &str)> = vec![
        (
            json!([{"parameter": 0.3, "order": 3}]),
            json!(null),
            "/constraints/0/order",
        ),
        (
            json!([{"parameter": 0.2, "order": 2}, {"parameter": 1.5, "order": 1}]),
            json!(null),
            "/constraints/1/parameter",
        ),
        (
            json!([{"parameter": 0.4, "order": 0}]),
            json!(null),
            "/constraints/0/parameter",
        ),
        (
            json!([{"parameter": 0.3, "order": 0, "value": [1.0, 2.0, 3.0]}]),
            json!(null),
            "/constraints/0/value",
        ),
        (
            json!([{"parameter": 0.3, "order": 0, "direction_only": true}]),
            json!(null),
            "/constraints/0/direction_only",
        ),
        (
            json!([{"parameter": 0.3, "order": 2, "direction_only": true}]),
            json!(null),
            "/constraints/0/direction_only",
        ),
        (
            json!([{"parameter": 0.3, "order": 1, "value": [0.0, 0.0], "direction_only": true}]),
            json!(null),
            "/constraints/0/value",
        ),
        (
            json!([{"parameter": 0.3, "order": 1}, {"parameter": 0.3, "order": 1, "direction_only": false}]),
            json!(null),
            "/constraints/1",
        ),
        (json!([]), json!([4]), "/fixed_control_points/0"),
        (json!([]), json!([1, 2, 1]), "/fixed_control_points/2"),
    ];
    for (constraints, fixed, pointer) in cases {
        let mut request = json!({"curve": quadratic.to_json(false), "parameter": 0.4,
                                 "target": [2.0, 2.0], "methods": ["control_points"],
                                 "constraints": constraints});
        if !fixed.is_null() {
            request["fixed_control_points"] = fixed;
        }
        for path in ["/v1/shape/solve", "/v1/shape/membership"] {
            let (status, body) = app.post_json(path, &request).await;
            assert_eq!(status, 422, "{path} {pointer}: {body}");
            assert_problem(422, &body, Some(pointer));
        }
    }
    // Order 3 on a quintic: not supported (orders are 0 to 2).
    let request = json!({"curve": quintic().to_json(false), "parameter": 0.4,
                         "target": [2.0, 2.0, 1.0], "methods": ["weights"],
                         "constraints": [{"parameter": 0.3, "order": 3}]});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/constraints/0/order"));
    // Too many.
    let many: Vec<Value> = (0..33)
        .map(|i| json!({"parameter": 0.01 * f64::from(i), "order": 1}))
        .collect();
    let request = json!({"curve": quadratic.to_json(false), "parameter": 0.4,
                         "target": [2.0, 2.0], "methods": ["control_points"],
                         "constraints": many});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 422, "{body}");
    assert_problem(422, &body, Some("/constraints"));
    // Unknown fields and wrong types are 400s.
    for constraint in [
        json!({"parameter": 0.3, "order": 1, "tangent": true}),
        json!({"parameter": 0.3, "order": -1}),
        json!({"parameter": "0.3", "order": 1}),
    ] {
        let request = json!({"curve": quadratic.to_json(false), "parameter": 0.4,
                             "target": [2.0, 2.0], "methods": ["control_points"],
                             "constraints": [constraint]});
        let (status, body) = app.post_json("/v1/shape/solve", &request).await;
        assert_eq!(status, 400, "{body}");
    }
    // An unknown method names the three.
    let request = json!({"curve": quadratic.to_json(false), "parameter": 0.4,
                         "target": [2.0, 2.0], "methods": ["poles"]});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 422);
    assert!(
        body["errors"][0]["detail"]
            .as_str()
            .unwrap()
            .contains("\"weights\"")
    );
}

/// Point in polygon (even-odd rule), in x–y.
pub(crate) fn inside(polygon: &[Vec<f64>], point: [f64; 2]) -> bool {
    let mut inside = false;
    for edge in polygon.windows(2) {
        let (a, b) = (&edge[0], &edge[1]);
        if (a[1] > point[1]) != (b[1] > point[1]) {
            let x = a[0] + (point[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if point[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[tokio::test]
async fn drawn_regions_hold_only_what_solve_reaches_with_the_same_request() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    for keep_domain in [true, false] {
        let request = json!({"curve": curve.to_json(false), "parameter": 0.42,
                             "keep_domain": keep_domain, "methods": ["knots", "weights"],
                             "fixed_control_points": [5]});
        let (status, regions) = app.post_json("/v1/shape/regions", &request).await;
        assert_eq!(status, 200, "{regions}");
        let drawn: usize = regions["candidates"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["regions"].as_array().unwrap().len())
            .sum();
        // t = 0.42: right Ω3/Ω5/Ω6 and left Ω1/Ω4/Ω5 move an end of the domain.
        assert_eq!(drawn, if keep_domain { 6 } else { 12 });
        let weight_regions = regions["weight_regions"].as_array().unwrap();
        // Six pairs of poles 2..=5 act at t; pole 5 is fixed, so three are left.
        assert_eq!(weight_regions.len(), 3, "{regions}");
        assert!(
            weight_regions
                .iter()
                .all(|r| !numbers(&r["poles"]).contains(&5.0))
        );
        let mut checked = 0;
        let mut samples = 0;
        for candidate in regions["candidates"].as_array().unwrap() {
            for region in candidate["regions"].as_array().unwrap() {
                let polygon = points(&region["polygon"]);
                // Points inside the polygon: midpoints of pairs of its vertices, every
                // seventh of those that are inside.
                for i in 0..polygon.len() {
                    for j in i + 1..polygon.len() {
                        let point = [
                            0.5 * (polygon[i][0] + polygon[j][0]),
                            0.5 * (polygon[i][1] + polygon[j][1]),
                        ];
                        samples += 1;
                        if samples % 7 != 0 || !inside(&polygon, point) {
                            continue;
                        }
                        let solve = json!({"curve": curve.to_json(false), "parameter": 0.42,
                                           "target": point, "keep_domain": keep_domain,
                                           "side": candidate["side"],
                                           "regions": [region["region"]]});
                        let (status, membership) =
                            app.post_json("/v1/shape/membership", &solve).await;
                        assert_eq!(status, 200);
                        let holds = membership["candidates"][0]["regions"][0]["contains"] == true;
                        // Within the polygon's tolerance (1/1000 of the triangle) of its edge
                        // the answer may go either way; elsewhere it must hold.
                        if !holds {
                            let near_edge = polygon
                                .windows(2)
                                .any(|e| segment_distance(point, &e[0], &e[1]) < 0.01);
                            assert!(near_edge, "{point:?} in {} not reachable", region["region"]);
                        }
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 30, "{checked}");
    }
}

pub(crate) fn segment_distance(p: [f64; 2], a: &[f64], b: &[f64]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length = dx * dx + dy * dy;
    let s = if length == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length).clamp(0.0, 1.0)
    };
    ((p[0] - a[0] - s * dx).powi(2) + (p[1] - a[1] - s * dy).powi(2)).sqrt()
}
