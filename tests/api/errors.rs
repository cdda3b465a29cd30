//! Every status code of API.md's error table, produced by a real request; each body a valid
//! problem document with the right pointer.

use serde_json::{Value, json};

use crate::helpers::{expect_problem, spawn_app};
use crate::reference::{Lcg, cubic_2d};

fn curve() -> Value {
    cubic_2d().to_json(false)
}

#[tokio::test]
async fn malformed_json_wrong_types_and_unknown_fields_are_400() {
    let app = spawn_app().await;
    let url = format!("{}/v1/curves/evaluate", app.address);
    let send = |body: String| {
        app.client
            .post(&url)
            .header("content-type", "application/json")
            .body(body)
            .send()
    };
    expect_problem(
        send("{\"curve\": ".to_owned()).await.unwrap(),
        400,
        Some("/curve"),
    )
    .await;
    expect_problem(send("[1, 2".to_owned()).await.unwrap(), 400, None).await;
    let wrong_type = json!({"curve": curve(), "parameters": [0.1, "half"]}).to_string();
    expect_problem(send(wrong_type).await.unwrap(), 400, Some("/parameters/1")).await;
    let float_degree =
        json!({"curve": {"degree": 2.5, "control_points": [], "knots": []}, "samples": 3})
            .to_string();
    expect_problem(
        send(float_degree).await.unwrap(),
        400,
        Some("/curve/degree"),
    )
    .await;
    let unknown = json!({"curve": curve(), "samples": 3, "colour": "red"}).to_string();
    expect_problem(send(unknown).await.unwrap(), 400, Some("/colour")).await;
    let mut nested_unknown = json!({"curve": curve(), "samples": 3});
    nested_unknown["curve"]["closed"] = json!(true);
    expect_problem(
        send(nested_unknown.to_string()).await.unwrap(),
        400,
        Some("/curve/closed"),
    )
    .await;
    let missing = json!({"curve": {"degree": 3, "knots": []}, "samples": 3}).to_string();
    expect_problem(
        send(missing).await.unwrap(),
        400,
        Some("/curve/control_points"),
    )
    .await;
    expect_problem(send("{} trailing".to_owned()).await.unwrap(), 400, None).await;
}

#[tokio::test]
async fn a_body_that_is_not_json_is_415() {
    let app = spawn_app().await;
    let url = format!("{}/v1/curves/evaluate", app.address);
    let body = json!({"curve": curve(), "samples": 3}).to_string();
    let missing = app
        .client
        .post(&url)
        .body(body.clone())
        .send()
        .await
        .unwrap();
    expect_problem(missing, 415, None).await;
    let text = app
        .client
        .post(&url)
        .header("content-type", "text/plain")
        .body(body)
        .send()
        .await
        .unwrap();
    expect_problem(text, 415, None).await;
}

#[tokio::test]
async fn json_media_types_with_parameters_or_suffix_are_accepted() {
    let app = spawn_app().await;
    let url = format!("{}/v1/curves/evaluate", app.address);
    let body = json!({"curve": curve(), "samples": 3}).to_string();
    for content_type in [
        "application/json",
        "Application/JSON",
        "application/json; charset=utf-8",
        "application/vnd.knotshape+json",
    ] {
        let response = post_as(&app, &url, content_type, &body).await;
        assert_eq!(response.status(), 200, "content type {content_type}");
        let answer: Value = response.json().await.unwrap();
        assert_eq!(answer["points"].as_array().map(Vec::len), Some(3));
    }
    // The same pointer for a wrong type, whichever way the media type is written.
    let wrong_type = json!({"curve": curve(), "parameters": [0.1, "half"]}).to_string();
    for content_type in ["application/json", "application/json; charset=utf-8"] {
        let response = post_as(&app, &url, content_type, &wrong_type).await;
        expect_problem(response, 400, Some("/parameters/1")).await;
    }
}

/// Posts `body` to `url` with the given `Content-Type`.
async fn post_as(
    app: &crate::helpers::TestApp,
    url: &str,
    content_type: &str,
    body: &str,
) -> reqwest::Response {
    app.client
        .post(url)
        .header("content-type", content_type)
        .body(body.to_owned())
        .send()
        .await
        .unwrap()
}

#[tokio::test]
async fn unknown_paths_are_404_and_wrong_methods_405() {
    let app = spawn_app().await;
    expect_problem(app.get("/v2/curves/evaluate").await, 404, None).await;
    let post = app.post("/v1/curves/nothing", &json!({})).await;
    expect_problem(post, 404, None).await;
    let wrong = app.get("/v1/shape/solve").await;
    assert_eq!(wrong.headers()["allow"], "POST");
    expect_problem(wrong, 405, None).await;
    let delete = app
        .client
        .delete(format!("{}/healthz", app.address))
        .send()
        .await
        .unwrap();
    expect_problem(delete, 405, None).await;
}

/// Posts `body` to `path` and expects a 422 naming `pointer`.
async fn expect_422(
    app: &crate::helpers::TestApp,
    path: &str,
    body: Value,
    pointer: &str,
) -> Value {
    expect_problem(app.post(path, &body).await, 422, Some(pointer)).await
}

/// Posts `body` with the string `"HUGE"` replaced by the raw number `huge`, expecting a 422.
async fn expect_422_raw(
    app: &crate::helpers::TestApp,
    path: &str,
    body: &Value,
    huge: &str,
    pointer: &str,
) {
    let raw = body.to_string().replace("\"HUGE\"", huge);
    let response = app
        .client
        .post(format!("{}{path}", app.address))
        .header("content-type", "application/json")
        .body(raw)
        .send()
        .await
        .unwrap();
    expect_problem(response, 422, Some(pointer)).await;
}

#[tokio::test]
async fn broken_rules_are_422_with_pointers() {
    let app = spawn_app_limited().await;
    let evaluate = "/v1/curves/evaluate";
    let mut decreasing = curve();
    decreasing["knots"][4] = json!(-0.5);
    let body = expect_422(
        &app,
        evaluate,
        json!({"curve": decreasing, "samples": 3}),
        "/curve/knots/4",
    )
    .await;
    assert!(body["detail"].as_str().unwrap().contains("non-decreasing"));
    let mut short = curve();
    short["knots"].as_array_mut().unwrap().pop();
    short["knots"].as_array_mut().unwrap().pop();
    short["knots"].as_array_mut().unwrap().pop();
    expect_422(
        &app,
        evaluate,
        json!({"curve": short, "samples": 3}),
        "/curve/knots",
    )
    .await;
    expect_422(
        &app,
        evaluate,
        json!({"curve": curve(), "parameters": [0.0, 0.5, 1.0, 1.5]}),
        "/parameters/3",
    )
    .await;
    // JSON cannot carry infinities, but a huge exponent would parse to one.
    let huge_parameter = json!({"curve": curve(), "parameters": [0.5, "HUGE"]});
    expect_422_raw(&app, evaluate, &huge_parameter, "1e999", "/parameters/1").await;
    let mut infinite_point = json!({"curve": curve(), "samples": 3});
    infinite_point["curve"]["control_points"][2][1] = json!("HUGE");
    expect_422_raw(
        &app,
        evaluate,
        &infinite_point,
        "-1e999",
        "/curve/control_points/2/1",
    )
    .await;
    expect_422(
        &app,
        evaluate,
        json!({"curve": curve(), "parameters": [0.5], "samples": 3}),
        "/samples",
    )
    .await;
    expect_422(&app, evaluate, json!({"curve": curve()}), "").await;
    expect_422(
        &app,
        evaluate,
        json!({"curve": curve(), "samples": 1}),
        "/samples",
    )
    .await;
    expect_422(
        &app,
        evaluate,
        json!({"curve": curve(), "samples": 101}),
        "/samples",
    )
    .await;
    expect_422(
        &app,
        evaluate,
        json!({"curve": curve(), "parameters": vec![0.5; 101]}),
        "/parameters",
    )
    .await;
    expect_422(
        &app,
        evaluate,
        json!({"curve": curve(), "samples": 3, "derivatives": 9}),
        "/derivatives",
    )
    .await;
    let mut weights = curve();
    weights["weights"] = json!([1, 1, 1, 0, 1, 1, 1, 1]);
    expect_422(
        &app,
        evaluate,
        json!({"curve": weights, "samples": 3}),
        "/curve/weights/3",
    )
    .await;
    let mut mixed = curve();
    mixed["control_points"][5] = json!([1, 2, 3]);
    expect_422(
        &app,
        evaluate,
        json!({"curve": mixed, "samples": 3}),
        "/curve/control_points/5",
    )
    .await;
    let many = json!({
        "degree": 1,
        "control_points": vec![[0.0, 0.0]; 21],
        "knots": (0..23).map(f64::from).collect::<Vec<_>>(),
    });
    expect_422(
        &app,
        evaluate,
        json!({"curve": many, "samples": 3}),
        "/curve/control_points",
    )
    .await;

    let envelope = "/v1/curves/envelope";
    expect_422(
        &app,
        envelope,
        json!({"curve": curve(), "knot_index": 3}),
        "/knot_index",
    )
    .await;
    expect_422(
        &app,
        envelope,
        json!({"curve": curve(), "knot_index": 99}),
        "/knot_index",
    )
    .await;

    let target = json!([4.7, 3.3]);
    for path in ["/v1/shape/solve", "/v1/shape/membership"] {
        // Knots do not move a degree-1 curve (the polyline of its control points).
        let polyline = json!({"degree": 1, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0]],
                              "knots": [0, 0, 0.3, 0.7, 1, 1]});
        expect_422(
            &app,
            path,
            json!({"curve": polyline, "parameter": 0.4, "target": target}),
            "/curve/degree",
        )
        .await;
        expect_422(
            &app,
            path,
            json!({"curve": curve(), "parameter": 1.5, "target": target}),
            "/parameter",
        )
        .await;
        expect_422(
            &app,
            path,
            json!({"curve": curve(), "parameter": 0.4, "target": [1.0, 2.0, 3.0]}),
            "/target",
        )
        .await;
        let huge_target = json!({"curve": curve(), "parameter": 0.4, "target": [1.0, "HUGE"]});
        expect_422_raw(&app, path, &huge_target, "1e999", "/target/1").await;
        expect_422(&app, path, json!({"curve": curve(), "parameter": 0.4, "target": target, "regions": ["omega1", "omega9"]}), "/regions/1").await;
        expect_422(&app, path, json!({"curve": curve(), "parameter": 0.4, "target": target, "regions": ["omega2", "omega2"]}), "/regions/1").await;
        expect_422(
            &app,
            path,
            json!({"curve": curve(), "parameter": 0.4, "target": target, "regions": []}),
            "/regions",
        )
        .await;
        expect_422(
            &app,
            path,
            json!({"curve": curve(), "parameter": 0.4, "target": target, "side": "up"}),
            "/side",
        )
        .await;
    }
    let regions = "/v1/shape/regions";
    expect_422(
        &app,
        regions,
        json!({"curve": curve(), "parameter": 0.4, "tolerance": 0.0}),
        "/tolerance",
    )
    .await;
    expect_422(
        &app,
        regions,
        json!({"curve": curve(), "parameter": -0.1}),
        "/parameter",
    )
    .await;
}

/// A server with small limits, so limit violations are cheap to send.
async fn spawn_app_limited() -> crate::helpers::TestApp {
    crate::helpers::spawn_app_with(|config| {
        config.max_parameters = 100;
        config.max_control_points = 20;
        config.max_derivative_order = 8;
    })
    .await
}

/// A number for the robustness test: mostly ordinary, sometimes extreme.
fn rough_number(rng: &mut Lcg) -> f64 {
    const EXTREMES: [f64; 7] = [1e300, -1e300, 1e-300, 0.0, 1e308, -1e308, 5e-324];
    if rng.unit() < 0.05 {
        EXTREMES[(rng.unit() * 7.0) as usize % 7]
    } else {
        rng.between(-10.0, 10.0)
    }
}

/// A random, often degenerate, curve object: coincident or collinear points, repeated or
/// unclamped knots, extreme weights, either knot convention.
fn rough_curve(rng: &mut Lcg) -> Value {
    let degree = [3, 3, 3, 1, 2, 4][(rng.unit() * 6.0) as usize % 6];
    let count = degree + 1 + (rng.unit() * 6.0) as usize;
    let dimension = if rng.unit() < 0.3 { 3 } else { 2 };
    let mut control_points: Vec<Vec<f64>> = (0..count)
        .map(|_| (0..dimension).map(|_| rough_number(rng)).collect())
        .collect();
    if rng.unit() < 0.2 {
        control_points = vec![control_points[0].clone(); count];
    } else if rng.unit() < 0.2 {
        control_points = (0..count)
            .map(|i| (1..=dimension).map(|c| (i * c) as f64).collect())
            .collect();
    }
    let mut knots: Vec<f64> = vec![0.0; degree + 1];
    let mut inner: Vec<f64> = (0..count - degree - 1)
        .map(|_| [0.0, 0.25, 0.5, 0.5, 0.75, rng.unit()][(rng.unit() * 6.0) as usize % 6])
        .collect();
    inner.sort_by(f64::total_cmp);
    knots.extend(inner);
    knots.extend(vec![1.0; degree + 1]);
    if rng.unit() < 0.3 {
        knots = (0..count + degree + 1)
            .map(|_| rng.between(-1.0, 2.0))
            .collect();
        knots.sort_by(f64::total_cmp);
    }
    if rng.unit() < 0.3 {
        knots = knots[1..knots.len() - 1].to_vec();
    }
    let mut curve = json!({"degree": degree, "control_points": control_points, "knots": knots});
    if rng.unit() < 0.3 {
        let weights: Vec<f64> = (0..count)
            .map(|_| [rng.between(0.01, 5.0), 1e-300, 1e300][(rng.unit() * 3.0) as usize % 3])
            .collect();
        curve["weights"] = json!(weights);
    }
    curve
}

#[tokio::test]
async fn random_and_degenerate_requests_never_give_a_server_error() {
    let app = spawn_app().await;
    let mut rng = Lcg(4242);
    for _ in 0..60 {
        let curve = rough_curve(&mut rng);
        let dimension = curve["control_points"][0].as_array().unwrap().len();
        let t = [0.0, 1.0, 0.5, 0.25, rng.unit(), rng.between(-1.0, 2.0)]
            [(rng.unit() * 6.0) as usize % 6];
        let target: Vec<f64> = (0..dimension).map(|_| rough_number(&mut rng)).collect();
        let tolerance = [1e-3, 1e-9, 0.5][(rng.unit() * 3.0) as usize % 3];
        let samples = 2 + (rng.unit() * 40.0) as usize;
        let order = (rng.unit() * 8.0) as usize;
        let knot_index = (rng.unit() * 12.0) as usize;
        let keep_domain = rng.unit() < 0.7;
        let other = rng.unit();
        let requests = [
            (
                "/v1/curves/evaluate",
                json!({"curve": curve, "samples": samples, "derivatives": order}),
            ),
            (
                "/v1/curves/evaluate",
                json!({"curve": curve, "parameters": [t, other], "derivatives": 2}),
            ),
            (
                "/v1/curves/envelope",
                json!({"curve": curve, "knot_index": knot_index}),
            ),
            (
                "/v1/shape/solve",
                json!({"curve": curve, "parameter": t, "target": target, "keep_domain": keep_domain}),
            ),
            (
                "/v1/shape/membership",
                json!({"curve": curve, "parameter": t, "target": target}),
            ),
            (
                "/v1/shape/regions",
                json!({"curve": curve, "parameter": t, "tolerance": tolerance}),
            ),
        ];
        for (path, body) in &requests {
            let response = app.post(path, body).await;
            let status = response.status().as_u16();
            let text = response.text().await.unwrap();
            assert!(
                status == 200 || status == 422,
                "{status} from {path} {body}: {text}"
            );
            assert!(
                !text.contains("null"),
                "a non-finite number from {path} {body}: {text}"
            );
        }
    }
}

/// A whole-number float where an integer is expected (`"degree": 3.0`, as Python's
/// `json.dumps(3.0)` writes it) is refused with a 400 that names the field and says an integer
/// is expected: the API reads JSON integers only, as documented in docs/api.md.
#[tokio::test]
async fn whole_number_floats_for_integers_are_a_400_that_says_why() {
    let app = crate::helpers::spawn_app().await;
    let mut curve = cubic_2d().to_json(false);
    curve["degree"] = serde_json::json!(3.0);
    let body = serde_json::json!({"curve": curve, "samples": 3});
    let response = app.post("/v1/curves/evaluate", &body).await;
    let problem = crate::helpers::expect_problem(response, 400, Some("/curve/degree")).await;
    let detail = problem["errors"][0]["detail"]
        .as_str()
        .unwrap_or_default()
        .to_owned();
    assert!(
        detail.contains("integer") && detail.contains("3.0"),
        "{problem}"
    );
    assert!(!detail.contains("usize"), "{problem}");
}
