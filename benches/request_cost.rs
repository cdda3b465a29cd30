//! Driver for `benches/instructions.sh`: sends `COUNT` requests of one kind (`healthz` or
//! `solve`, the load test's body) through the real router, in-process, one after the other.
//! Run under callgrind it gives instructions per request, a measure that, unlike time, does
//! not change with the machine's load.
//!
//! Usage: `request_cost healthz|solve COUNT`.
#![allow(clippy::unwrap_used)]

use axum::body::Body;
use axum::http::Request;
use knotshape::config::Config;
use tower::ServiceExt;

fn main() {
    let mut args = std::env::args().skip(1);
    let kind = args.next().unwrap_or_default();
    let count: usize = args.next().map_or(1000, |n| n.parse().unwrap());
    assert!(
        kind == "healthz" || kind == "solve",
        "usage: request_cost healthz|solve COUNT"
    );
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    let app = knotshape::app(&Config::default());
    let body = std::fs::read("benches/load/solve.json").unwrap();
    for _ in 0..count {
        runtime.block_on(async {
            let request = if kind == "solve" {
                Request::post("/v1/shape/solve")
                    .header("content-type", "application/json")
                    .body(Body::from(body.clone()))
                    .unwrap()
            } else {
                Request::get("/healthz").body(Body::empty()).unwrap()
            };
            let response = app.clone().oneshot(request).await.unwrap();
            assert!(response.status().is_success());
            axum::body::to_bytes(response.into_body(), usize::MAX)
                .await
                .unwrap()
        });
    }
}
