//! `POST /v1/surfaces/shape/solve` and `/regions` over HTTP: every bad input is a 4xx problem
//! document naming the field (parameter outside the domain, a target that is not 3D, fixed
//! indices out of range or repeated, malformed constraints, unknown methods), the answers'
//! shape (the knot method excluded, contradictions excluded, fixed poles kept, the nearest
//! point), and the deviation and displacement of a move checked by hand.

use serde_json::{Value, json};

use crate::helpers::{expect_problem, numbers, spawn_app};

/// A biquadratic 4 × 4 net (one interior knot each way).
fn surface() -> Value {
    let points: Vec<Vec<[f64; 3]>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| [f64::from(i), f64::from(j), f64::from((i + j) % 2) * 0.5])
                .collect()
        })
        .collect();
    json!({
        "degree_u": 2, "degree_v": 2,
        "control_points": points,
        "knots_u": [0, 0, 0, 0.5, 1, 1, 1],
        "knots_v": [0, 0, 0, 0.5, 1, 1, 1]
    })
}

fn request() -> Value {
    json!({"surface": surface(), "parameter": [0.3, 0.6], "target": [1.0, 1.8, 1.0]})
}

async fn refused(request: Value, status: u16, pointer: &str) -> Value {
    let app = spawn_app().await;
    let response = app.post("/v1/surfaces/shape/solve", &request).await;
    expect_problem(response, status, Some(pointer)).await
}

#[tokio::test]
async fn every_bad_field_is_named() {
    let mut outside = request();
    outside["parameter"] = json!([0.3, 1.5]);
    refused(outside, 422, "/parameter/1").await;

    let mut planar = request();
    planar["target"] = json!([1.0, 2.0]);
    refused(planar, 422, "/target").await;

    let mut fixed = request();
    fixed["fixed_control_points"] = json!([[1, 1], [4, 0]]);
    refused(fixed, 422, "/fixed_control_points/1").await;

    let mut repeated = request();
    repeated["fixed_control_points"] = json!([[1, 1], [1, 1]]);
    refused(repeated, 422, "/fixed_control_points/1").await;

    let mut order = request();
    order["constraints"] = json!([{"parameter": [0.1, 0.1], "order": 2}]);
    refused(order, 422, "/constraints/0/order").await;

    let mut shape = request();
    shape["constraints"] = json!([{"parameter": [0.1, 0.1], "order": 1, "value": [1, 2, 3]}]);
    refused(shape, 422, "/constraints/0/value").await;

    let mut vector = request();
    vector["constraints"] =
        json!([{"parameter": [0.1, 0.1], "order": 1, "value": [[1, 0, 0], [0, 1]]}]);
    refused(vector, 422, "/constraints/0/value/1").await;

    let mut value = request();
    value["constraints"] = json!([{"parameter": [0.1, 0.1], "order": 0, "value": [1, 2]}]);
    refused(value, 422, "/constraints/0/value").await;

    let mut place = request();
    place["constraints"] = json!([{"parameter": [-0.5, 0.1], "order": 0}]);
    refused(place, 422, "/constraints/0/parameter/0").await;

    let mut picked = request();
    picked["constraints"] = json!([{"parameter": [0.3, 0.6], "order": 0}]);
    refused(picked, 422, "/constraints/0/parameter/0").await;

    let mut method = request();
    method["methods"] = json!(["weights", "splines"]);
    refused(method, 422, "/methods/1").await;

    let mut twice = request();
    twice["methods"] = json!(["weights", "weights"]);
    refused(twice, 422, "/methods/1").await;

    let mut broken = request();
    broken["surface"]["knots_u"] = json!([0, 0, 0, 1, 1, 1]);
    refused(broken, 422, "/surface/knots_u").await;

    let app = spawn_app().await;
    let mut unknown = request();
    unknown["colour"] = json!("red");
    let response = app.post("/v1/surfaces/shape/solve", &unknown).await;
    expect_problem(response, 400, None).await;
    let mut regions = json!({"surface": surface(), "parameter": [2.0, 0.5]});
    regions["methods"] = json!(["weights"]);
    let response = app.post("/v1/surfaces/shape/regions", &regions).await;
    expect_problem(response, 422, Some("/parameter/0")).await;
}

/// The unconstrained control-point move by hand: `Δd = R / Σ R² · (p − S)`, so the point
/// moves by exactly `|p − S|`, the displacement norm is `|p − S| / sqrt(Σ R²)`, and the
/// deviation (certified) is at least `|p − S|`.
#[tokio::test]
async fn the_control_point_move_is_the_closed_form() {
    let app = spawn_app().await;
    let mut body = request();
    body["methods"] = json!(["control_points"]);
    let (status, answer) = app.post_json("/v1/surfaces/shape/solve", &body).await;
    assert_eq!(status, 200, "{answer}");
    let solution = &answer["solutions"][0];
    // N(0.3) on knots 0,0,0,.5,1,1,1: the span [0, .5) with t = 0.6 local.
    let basis_u = [0.16, 0.66, 0.18, 0.0];
    let basis_v = [0.0, 0.32, 0.64, 0.04];
    let squares: f64 = basis_u
        .iter()
        .flat_map(|a| basis_v.iter().map(move |b| (a * b) * (a * b)))
        .sum();
    let before = {
        let (status, evaluated) = app
            .post_json(
                "/v1/surfaces/evaluate",
                &json!({"surface": surface(), "parameters": [[0.3, 0.6]]}),
            )
            .await;
        assert_eq!(status, 200);
        numbers(&evaluated["points"][0])
    };
    let target = [1.0, 1.8, 1.0];
    let gap = (0..3)
        .map(|c| (target[c] - before[c]).powi(2))
        .sum::<f64>()
        .sqrt();
    let norm = solution["displacement_norm"].as_f64().unwrap();
    assert!(
        (norm - gap / squares.sqrt()).abs() < 1e-12,
        "{norm} vs {gap}"
    );
    let deviation = solution["max_deviation"].as_f64().unwrap();
    assert!(deviation >= gap * (1.0 - 1e-12) && deviation < 2.0 * gap);
    assert_eq!(
        solution["changed_control_points"].as_array().unwrap().len(),
        9
    );
}

#[tokio::test]
async fn the_answer_says_what_it_left_out() {
    let app = spawn_app().await;
    // The knot method beside the control points: its solutions name their family, region
    // and new knots; nothing is excluded as unavailable.
    let mut knots = request();
    knots["methods"] = json!(["knots", "control_points"]);
    let (status, answer) = app.post_json("/v1/surfaces/shape/solve", &knots).await;
    assert_eq!(status, 200, "{answer}");
    assert!(
        answer["excluded"]
            .as_array()
            .unwrap()
            .iter()
            .all(|e| !e["reason"].as_str().unwrap().contains("not available")),
        "{answer}"
    );
    let solutions = answer["solutions"].as_array().unwrap();
    assert!(solutions.iter().any(|s| s["method"] == "control_points"));
    for solution in solutions.iter().filter(|s| s["method"] == "knots") {
        assert!(solution["family"].is_string() && solution["region"].is_string());
        assert!(solution["knots_u"].is_array() || solution["knots_v"].is_array());
    }

    // Contradictory constraints: no move, one exclusion per method.
    let mut clash = request();
    clash["constraints"] = json!([
        {"parameter": [0.8, 0.2], "order": 0},
        {"parameter": [0.8, 0.2], "order": 0, "value": [9, 9, 9]}
    ]);
    let (status, answer) = app.post_json("/v1/surfaces/shape/solve", &clash).await;
    assert_eq!(status, 200, "{answer}");
    assert_eq!(answer["reachable"], false);
    assert_eq!(answer["excluded"].as_array().unwrap().len(), 3);
    assert!(
        answer["excluded"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|e| e["method"] != "knots")
            .all(|e| e["constraint"] == 0)
    );

    // Every pole fixed: the control-point move says so.
    let mut all = request();
    all["methods"] = json!(["control_points"]);
    all["fixed_control_points"] = json!([[1, 1], [1, 2], [2, 1], [2, 2]]);
    all["keep_boundary"] = json!(true);
    let (status, answer) = app.post_json("/v1/surfaces/shape/solve", &all).await;
    assert_eq!(status, 200, "{answer}");
    assert_eq!(answer["solutions"].as_array().unwrap().len(), 0);
    assert!(
        answer["excluded"][0]["reason"]
            .as_str()
            .unwrap()
            .contains("no free control point")
    );

    // A far target for the weights alone: the nearest point they reach, with its solutions.
    let far = json!({"surface": surface(), "parameter": [0.3, 0.6], "target": [1.0, 1.8, 9.0],
                     "methods": ["weights"], "nearest": true});
    let (status, answer) = app.post_json("/v1/surfaces/shape/solve", &far).await;
    assert_eq!(status, 200, "{answer}");
    assert_eq!(answer["reachable"], false);
    let nearest = &answer["nearest"];
    let point = numbers(&nearest["point"]);
    let solutions = nearest["solutions"].as_array().unwrap();
    assert!(!solutions.is_empty(), "{answer}");
    for solution in solutions {
        let reached = numbers(&solution["point"]);
        let gap: f64 = (0..3).map(|c| (reached[c] - point[c]).powi(2)).sum();
        assert!(gap.sqrt() < 1e-9);
    }
    assert!(nearest["distance"].as_f64().unwrap() < 9.0);
}

#[tokio::test]
async fn regions_list_each_methods_reach() {
    let app = spawn_app().await;
    let body = json!({"surface": surface(), "parameter": [0.3, 0.6],
                      "methods": ["control_points", "weights", "knots"],
                      "fixed_control_points": [[1, 1]]});
    let (status, answer) = app.post_json("/v1/surfaces/shape/regions", &body).await;
    assert_eq!(status, 200, "{answer}");
    let methods = answer["methods"].as_array().unwrap();
    let method = |name: &str| {
        methods
            .iter()
            .find(|m| m["method"] == name)
            .unwrap_or_else(|| panic!("no {name} in {answer}"))
    };
    assert_eq!(method("control_points")["everywhere"], true);
    let tetrahedra = method("weights")["tetrahedra"].as_array().unwrap();
    assert!(!tetrahedra.is_empty());
    // 9 poles act; the fixed [1, 1] is in none of the triples.
    assert!(tetrahedra.len() <= 56);
    assert!(
        tetrahedra
            .iter()
            .all(|t| !t["poles"].as_array().unwrap().contains(&json!([1, 1])))
    );
    // The knot families' planar regions (the mixed moves reach solids, not drawn).
    let knots = method("knots");
    assert_eq!(knots["everywhere"], false);
    for region in knots["knot_regions"].as_array().unwrap() {
        assert!(region["family"].as_str().unwrap().starts_with("iso_"));
        for ring in region["rings"].as_array().unwrap() {
            let ring = ring.as_array().unwrap();
            assert!(ring.len() >= 4 && ring[0] == ring[ring.len() - 1]);
        }
    }
}
