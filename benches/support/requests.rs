//! The two requests the request benchmarks send through the router, in-process:
//! `GET /healthz`, and `POST /v1/shape/solve` with the load test's body.

use axum::Router;
use axum::body::{Body, Bytes};
use axum::http::Request;
use knotshape::config::Config;
use tower::ServiceExt;

/// Which request to send.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `GET /healthz`.
    Healthz,
    /// `POST /v1/shape/solve` with `benches/load/solve.json`.
    Solve,
}

/// The router with default configuration, a single-threaded runtime to drive it, and the
/// solve body.
pub struct Bench {
    runtime: tokio::runtime::Runtime,
    app: Router,
    solve_body: Bytes,
}

impl Bench {
    /// Reads the solve body (run from the project's root, as cargo does).
    pub fn new() -> Self {
        Bench {
            runtime: tokio::runtime::Builder::new_current_thread()
                .enable_all()
                .build()
                .expect("a tokio runtime"),
            app: knotshape::app(&Config::default()),
            solve_body: std::fs::read("benches/load/solve.json")
                .expect("benches/load/solve.json")
                .into(),
        }
    }

    /// Sends one request of `kind` and reads the whole answer, which must be a success.
    pub fn send(&self, kind: Kind) -> Bytes {
        let request = match kind {
            Kind::Healthz => Request::get("/healthz").body(Body::empty()),
            Kind::Solve => Request::post("/v1/shape/solve")
                .header("content-type", "application/json")
                .body(Body::from(self.solve_body.clone())),
        }
        .expect("a valid request");
        self.runtime.block_on(async {
            let response = self.app.clone().oneshot(request).await.expect("infallible");
            assert!(
                response.status().is_success(),
                "{kind:?}: {}",
                response.status()
            );
            axum::body::to_bytes(response.into_body(), usize::MAX)
                .await
                .expect("the whole body")
        })
    }
}
