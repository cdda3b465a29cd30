//! The JSON body extractor whose rejections (wrong content type, bad JSON, oversize body) are
//! [`ApiError`]s, so they are answered as problem documents like every other failure.

use axum::extract::FromRequest;
use axum::response::{IntoResponse, Response};
use serde::Serialize;

use super::error::ApiError;

/// `axum::Json` with [`ApiError`] as its rejection; also usable as a JSON response.
#[derive(Debug, Clone, FromRequest)]
#[from_request(via(axum::Json), rejection(ApiError))]
pub struct ApiJson<T>(pub T);

impl<T: Serialize> IntoResponse for ApiJson<T> {
    fn into_response(self) -> Response {
        axum::Json(self.0).into_response()
    }
}
