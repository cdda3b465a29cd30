//! Configured limits: body size (413), load shedding (503 + Retry-After), request timeout
//! (503), and output bounded by the parameter limit.

use serde_json::json;

use crate::helpers::{assert_problem, expect_problem, spawn_app_with};
use crate::reference::cubic_2d;

#[tokio::test]
async fn a_body_over_the_limit_is_413() {
    let app = spawn_app_with(|config| config.max_body_bytes = 2_000).await;
    let small = json!({"curve": cubic_2d().to_json(false), "samples": 3});
    assert_eq!(app.post("/v1/curves/evaluate", &small).await.status(), 200);
    let big = json!({"curve": cubic_2d().to_json(false), "parameters": vec![0.5; 1_000]});
    assert!(big.to_string().len() > 2_000);
    let response = app.post("/v1/curves/evaluate", &big).await;
    expect_problem(response, 413, None).await;
    // Also when no Content-Length announces the size (chunked upload).
    let text = big.to_string();
    let mut request = format!(
        "POST /v1/curves/evaluate HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\nConnection: close\r\n\r\n",
        app.socket
    );
    for chunk in text.as_bytes().chunks(500) {
        request.push_str(&format!(
            "{:x}\r\n{}\r\n",
            chunk.len(),
            std::str::from_utf8(chunk).unwrap()
        ));
    }
    request.push_str("0\r\n\r\n");
    let chunked = app.raw_exchange(request.as_bytes()).await;
    assert_eq!(chunked.status, 413);
    assert_problem(413, &chunked.body, None);
}

#[tokio::test]
async fn excess_load_is_shed_with_503_and_retry_after() {
    let app = spawn_app_with(|config| {
        config.concurrency_limit = 1;
        config.retry_after_secs = 7;
    })
    .await;
    let body = json!({"curve": cubic_2d().to_json(false), "parameters": [0.0, 0.5, 1.0]});
    // Holds the only permit: its body is half sent.
    let slow = app.start_slow_post("/v1/curves/evaluate", &body).await;
    app.wait_for_in_flight(1).await;
    let shed = app.post("/v1/curves/evaluate", &body).await;
    assert_eq!(shed.headers()["retry-after"], "7");
    let problem = expect_problem(shed, 503, None).await;
    assert!(problem["detail"].as_str().unwrap().contains("concurrency"));
    // Probes are never shed.
    assert_eq!(app.get("/healthz").await.status(), 200);
    // The held request completes normally, and then there is room again.
    let finished = slow.finish().await;
    assert_eq!(finished.status, 200, "{}", finished.body);
    assert_eq!(finished.body["points"].as_array().unwrap().len(), 3);
    assert_eq!(app.post("/v1/curves/evaluate", &body).await.status(), 200);
}

#[tokio::test]
async fn a_request_over_the_time_limit_is_503() {
    let app = spawn_app_with(|config| config.request_timeout_ms = 200).await;
    let body = json!({"curve": cubic_2d().to_json(false), "samples": 3});
    // The body never completes, so the handler cannot finish within 200 ms.
    let slow = app.start_slow_post("/v1/curves/evaluate", &body).await;
    let response = slow.response().await;
    assert_eq!(response.status, 503);
    assert_eq!(
        response.header("content-type"),
        Some("application/problem+json")
    );
    assert!(response.header("retry-after").is_some());
    assert_problem(503, &response.body, None);
}

#[tokio::test]
async fn output_size_is_bounded_by_the_parameter_and_derivative_limits() {
    let app = spawn_app_with(|config| {
        config.max_parameters = 50;
        config.max_derivative_order = 2;
    })
    .await;
    let curve = cubic_2d().to_json(false);
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "samples": 50, "derivatives": 2}),
        )
        .await;
    assert_eq!(status, 200);
    assert_eq!(body["points"].as_array().unwrap().len(), 50);
    assert_eq!(body["derivatives"].as_array().unwrap().len(), 2);
    let (status, _) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "samples": 51}),
        )
        .await;
    assert_eq!(status, 422);
    let (status, _) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "samples": 2, "derivatives": 3}),
        )
        .await;
    assert_eq!(status, 422);
}
