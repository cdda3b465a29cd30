//! Graceful shutdown: readiness turns 503, new work is refused, a request in flight still
//! completes, then the server stops.

use std::time::Duration;

use serde_json::json;

use crate::helpers::{expect_problem, points, spawn_app_with};
use crate::reference::{cubic_2d, distance};

#[tokio::test]
async fn shutdown_drains_and_lets_the_request_in_flight_finish() {
    let mut app = spawn_app_with(|config| config.drain_delay_ms = 300).await;
    let curve = cubic_2d();
    let body = json!({"curve": curve.to_json(false), "parameters": [0.0, 0.42, 1.0]});
    let in_flight = app.start_slow_post("/v1/curves/evaluate", &body).await;
    app.wait_for_in_flight(1).await;

    app.trigger_shutdown();
    // During the drain delay the listener still answers: not ready, and no new /v1 work.
    let mut ready_status = 200;
    for _ in 0..100 {
        ready_status = app.get("/readyz").await.status().as_u16();
        if ready_status == 503 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    assert_eq!(ready_status, 503, "readiness turns 503 on shutdown");
    let refused = app.post("/v1/curves/evaluate", &body).await;
    assert!(refused.headers().contains_key("retry-after"));
    expect_problem(refused, 503, None).await;

    // After the drain delay the listener is closed; the request in flight still completes.
    tokio::time::sleep(Duration::from_millis(500)).await;
    assert!(
        tokio::net::TcpStream::connect(app.socket).await.is_err(),
        "the listener is closed"
    );
    let response = in_flight.finish().await;
    assert_eq!(response.status, 200, "{}", response.body);
    let got = points(&response.body["points"]);
    for (t, point) in [0.0, 0.42, 1.0].iter().zip(&got) {
        assert!(distance(point, &curve.point(*t)) < 1e-11);
    }
    app.stopped().await.expect("clean exit");
}
