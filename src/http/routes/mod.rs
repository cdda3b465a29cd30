//! Request handlers, one module per resource group.

pub mod curves;
pub mod ops;
pub mod shape;

use super::error::ApiError;

/// Runs CPU-bound request work on the blocking pool, so a slow request never stalls the
/// runtime and the request timeout can answer while it runs. A panic in `work` is resumed
/// here, where the panic-catching layer answers it as a 500 problem and logs it.
pub async fn compute<T, F>(work: F) -> Result<T, ApiError>
where
    T: Send + 'static,
    F: FnOnce() -> Result<T, ApiError> + Send + 'static,
{
    match tokio::task::spawn_blocking(work).await {
        Ok(result) => result,
        Err(join_error) => match join_error.try_into_panic() {
            Ok(payload) => std::panic::resume_unwind(payload),
            Err(_) => Err(ApiError::Internal(
                "the computation was cancelled".to_owned(),
            )),
        },
    }
}
