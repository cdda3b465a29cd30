//! Criterion benchmark of whole requests through the real router, in-process (no sockets):
//! `GET /healthz` against `POST /v1/shape/solve` with the load test's body. Their ratio is the
//! service's own share of the load test's solve/healthz ratio (the kernel's TCP work is not in
//! it).
#![allow(clippy::unwrap_used)]

use axum::body::Body;
use axum::http::Request;
use criterion::{Criterion, criterion_group, criterion_main};
use knotshape::config::Config;
use tower::ServiceExt;

fn bench_requests(c: &mut Criterion) {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    let app = knotshape::app(&Config::default());
    let body = std::fs::read("benches/load/solve.json").unwrap();
    let mut group = c.benchmark_group("request");
    group.bench_function("healthz", |b| {
        b.iter(|| {
            runtime.block_on(async {
                let request = Request::get("/healthz").body(Body::empty()).unwrap();
                let response = app.clone().oneshot(request).await.unwrap();
                axum::body::to_bytes(response.into_body(), usize::MAX)
                    .await
                    .unwrap()
            })
        })
    });
    group.bench_function("solve", |b| {
        b.iter(|| {
            runtime.block_on(async {
                let request = Request::post("/v1/shape/solve")
                    .header("content-type", "application/json")
                    .body(Body::from(body.clone()))
                    .unwrap();
                let response = app.clone().oneshot(request).await.unwrap();
                assert!(response.status().is_success());
                axum::body::to_bytes(response.into_body(), usize::MAX)
                    .await
                    .unwrap()
            })
        })
    });
    group.finish();
}

criterion_group!(benches, bench_requests);
criterion_main!(benches);
