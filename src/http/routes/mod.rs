//! Request handlers, one module per resource group.

pub mod closest;
pub mod curves;
pub mod editor;
pub mod files;
pub mod ops;
pub mod shape;
pub mod toolkit;
// The curve toolkit of the third release.
pub mod from_points;
pub mod length;
pub mod reshape;
// Surfaces (fourth release).
pub mod surface_closest;
pub mod surface_edit;
pub mod surface_mesh;
pub mod surface_toolkit;
pub mod surfaces;

use axum::Extension;

use super::error::ApiError;
use super::middleware::AdmissionPermit;

/// Requests whose estimated work is at most this many point evaluations (well under a
/// millisecond) are computed inline on the runtime: a hand-off to the blocking pool would
/// cost more than the work itself.
pub const INLINE_WORK_LIMIT: usize = 20_000;

/// Runs request work: inline when `estimated_work` (point evaluations, roughly) is at most
/// [`INLINE_WORK_LIMIT`], else on the blocking pool, so a large request never stalls the
/// runtime and the request timeout can answer while it runs. The request's admission permit
/// moves along, so work that outlives a timed-out request still counts against the
/// concurrency limit. A panic in `work` is resumed here, where the panic-catching layer
/// answers it as a 500 problem and logs it.
pub async fn compute<T, F>(
    admission: Option<Extension<AdmissionPermit>>,
    estimated_work: usize,
    work: F,
) -> Result<T, ApiError>
where
    T: Send + 'static,
    F: FnOnce() -> Result<T, ApiError> + Send + 'static,
{
    if estimated_work <= INLINE_WORK_LIMIT {
        let _admission = admission;
        return work();
    }
    let computation = move || {
        let _admission = admission;
        work()
    };
    match tokio::task::spawn_blocking(computation).await {
        Ok(result) => result,
        Err(join_error) => match join_error.try_into_panic() {
            Ok(payload) => std::panic::resume_unwind(payload),
            Err(_) => Err(ApiError::Internal(
                "the computation was cancelled".to_owned(),
            )),
        },
    }
}
