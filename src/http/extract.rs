//! The JSON body extractor whose rejections (wrong content type, bad JSON, oversize body) are
//! [`ApiError`]s, so they are answered as problem documents like every other failure.

use axum::extract::FromRequest;
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use serde_json::Value;

use super::error::ApiError;

/// `axum::Json` with [`ApiError`] as its rejection; also usable as a JSON response.
#[derive(Debug, Clone, FromRequest)]
#[from_request(via(axum::Json), rejection(ApiError))]
pub struct ApiJson<T>(pub T);

/// As a response: JSON, unless a number in it is not finite (JSON has no NaN or infinity,
/// and serde would write `null`). That only happens for inputs of extreme magnitude (say
/// coordinates near 1e300 or weights near 1e-300) whose results overflow; they get a 422
/// instead of a body with `null` where a number belongs.
impl<T: Serialize> IntoResponse for ApiJson<T> {
    fn into_response(self) -> Response {
        match serde_json::to_value(&self.0) {
            Ok(value) if !holds_null(&value) => axum::Json(value).into_response(),
            Ok(_) => ApiError::invalid(
                "/curve",
                "the result is not finite: the curve's coordinates or weights are too extreme \
                 for double precision",
            )
            .into_response(),
            Err(error) => {
                ApiError::Internal(format!("response serialization: {error}")).into_response()
            }
        }
    }
}

/// Whether `value` holds a `null` anywhere (the service's responses never use `null`, so one
/// marks a non-finite number).
fn holds_null(value: &Value) -> bool {
    match value {
        Value::Null => true,
        Value::Array(items) => items.iter().any(holds_null),
        Value::Object(fields) => fields.values().any(holds_null),
        Value::Bool(_) | Value::Number(_) | Value::String(_) => false,
    }
}
