//! Shared state of the HTTP edge: limits, the API key, the load-shedding semaphore, readiness
//! and metrics.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use tokio::sync::Semaphore;

use super::metrics::Metrics;
use crate::config::{ApiKey, Config, Limits};
use crate::spline::{CurveLimits, MAX_DEGREE};
use crate::surface::SurfaceLimits;

/// Whether the service takes new work; turns false once shutdown begins. Cheap to clone;
/// clones share the flag.
#[derive(Debug, Clone)]
pub struct Readiness {
    ready: Arc<AtomicBool>,
}

impl Default for Readiness {
    fn default() -> Self {
        Self::new()
    }
}

impl Readiness {
    /// A ready flag.
    pub fn new() -> Self {
        Readiness {
            ready: Arc::new(AtomicBool::new(true)),
        }
    }

    /// Whether the service is ready (not draining).
    pub fn is_ready(&self) -> bool {
        self.ready.load(Ordering::SeqCst)
    }

    /// Starts draining: `/readyz` answers 503 and new `/v1` requests are refused with 503.
    pub fn start_draining(&self) {
        self.ready.store(false, Ordering::SeqCst);
    }
}

/// What every handler and middleware can reach: a shared handle (one atomic increment to
/// clone, which every layer and extractor does per request) to [`SharedState`].
#[derive(Debug, Clone)]
pub struct AppState(Arc<SharedState>);

impl std::ops::Deref for AppState {
    type Target = SharedState;

    fn deref(&self) -> &SharedState {
        &self.0
    }
}

/// The service's shared, read-mostly state.
#[derive(Debug)]
pub struct SharedState {
    /// Request size limits.
    pub limits: Limits,
    /// The limits the spline core applies while validating curves.
    pub curve_limits: CurveLimits,
    /// The limits the surface core applies while validating surfaces.
    pub surface_limits: SurfaceLimits,
    /// When set, `/v1` routes need `Authorization: Bearer <key>`.
    pub api_key: Option<Arc<ApiKey>>,
    /// Permits for `/v1` requests served at once.
    pub admission: Arc<Semaphore>,
    /// Seconds sent with `Retry-After`.
    pub retry_after_secs: u64,
    /// Readiness (false while draining).
    pub readiness: Readiness,
    /// Request metrics.
    pub metrics: Metrics,
    /// The OpenAPI document served at `/openapi.json`.
    pub openapi_json: Arc<str>,
}

impl AppState {
    /// The state for `config`, sharing `readiness` with whoever drives shutdown.
    pub fn new(config: &Config, readiness: Readiness, openapi_json: Arc<str>) -> Self {
        let limits = config.limits();
        AppState(Arc::new(SharedState {
            limits,
            curve_limits: CurveLimits {
                max_degree: MAX_DEGREE,
                max_control_points: limits.max_control_points,
            },
            surface_limits: SurfaceLimits {
                max_degree: MAX_DEGREE,
                max_control_points: limits.max_surface_control_points,
            },
            api_key: config.api_key.clone().map(Arc::new),
            admission: Arc::new(Semaphore::new(
                config.concurrency_limit.clamp(1, Semaphore::MAX_PERMITS),
            )),
            retry_after_secs: config.retry_after_secs,
            readiness,
            metrics: Metrics::new(),
            openapi_json,
        }))
    }
}
