//! The JSON body extractor whose rejections (wrong content type, bad JSON, oversize body) are
//! [`ApiError`]s, so they are answered as problem documents like every other failure.

use axum::extract::FromRequest;
use axum::http::header::CONTENT_TYPE;
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
        // One serialization; only a body with a `null` token (rare) is parsed again to look
        // for a non-finite number exactly.
        match serde_json::to_vec(&self.0) {
            Ok(bytes) if !has_non_finite(&bytes) => {
                ([(CONTENT_TYPE, "application/json")], bytes).into_response()
            }
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

/// Whether serialized JSON holds a `null` value (serde writes non-finite numbers as `null`;
/// the service's responses never use `null` otherwise). A byte scan first; a `null` inside a
/// string is told apart by parsing.
fn has_non_finite(json: &[u8]) -> bool {
    json.windows(4)
        .any(|w| w[0] == b'n' && w[1] == b'u' && w[2] == b'l' && w[3] == b'l')
        && serde_json::from_slice::<Value>(json).is_ok_and(|value| holds_null(&value))
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
