//! The JSON body extractor whose rejections (wrong content type, bad JSON, oversize body) are
//! [`ApiError`]s, so they are answered as problem documents like every other failure.

use axum::body::Bytes;
use axum::extract::rejection::JsonRejection;
use axum::extract::{FromRequest, Request};
use axum::http::HeaderMap;
use axum::http::header::CONTENT_TYPE;
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;

use super::error::ApiError;

/// `axum::Json` with [`ApiError`] as its rejection; also usable as a JSON response.
#[derive(Debug, Clone)]
pub struct ApiJson<T>(pub T);

/// As an extractor: what `axum::Json` accepts, with its rejections as [`ApiError`]s. The
/// common case (`Content-Type: application/json`, a valid body) is parsed by plain
/// `serde_json`; only a body that fails is parsed again by `axum::Json`, whose path tracking
/// gives the error's JSON pointer. Other content types go to `axum::Json` as a whole.
impl<T, S> FromRequest<S> for ApiJson<T>
where
    T: DeserializeOwned,
    S: Send + Sync,
{
    type Rejection = ApiError;

    async fn from_request(request: Request, state: &S) -> Result<Self, ApiError> {
        if !is_plain_json(request.headers()) {
            let axum::Json(value) = axum::Json::<T>::from_request(request, state).await?;
            return Ok(ApiJson(value));
        }
        let bytes = Bytes::from_request(request, state)
            .await
            .map_err(|rejection| ApiError::from(JsonRejection::from(rejection)))?;
        match serde_json::from_slice(&bytes) {
            Ok(value) => Ok(ApiJson(value)),
            Err(_) => {
                let axum::Json(value) = axum::Json::<T>::from_bytes(&bytes)?;
                Ok(ApiJson(value))
            }
        }
    }
}

/// Whether the content type is exactly `application/json` (any letter case, no parameters).
fn is_plain_json(headers: &HeaderMap) -> bool {
    headers
        .get(CONTENT_TYPE)
        .is_some_and(|value| value.as_bytes().eq_ignore_ascii_case(b"application/json"))
}

/// As a response: JSON, unless a number in it is not finite (JSON has no NaN or infinity,
/// and serde would write `null`). That only happens for inputs of extreme magnitude (say
/// coordinates near 1e300 or weights near 1e-300) whose results overflow; they get a 422
/// instead of a body with `null` where a number belongs.
impl<T: Serialize> IntoResponse for ApiJson<T> {
    fn into_response(self) -> Response {
        // One serialization; only a body with a `null` token (rare) is parsed again to look
        // for a non-finite number exactly.
        // Most answers are a few hundred bytes to a few kilobytes: start with room for those.
        let mut bytes = Vec::with_capacity(RESPONSE_CAPACITY);
        match serde_json::to_writer(&mut bytes, &self.0).map(|()| bytes) {
            Ok(bytes) if !has_non_finite(&bytes) => {
                ([(CONTENT_TYPE, "application/json")], bytes).into_response()
            }
            Ok(_) => ApiError::non_finite_result().into_response(),
            Err(error) => {
                ApiError::Internal(format!("response serialization: {error}")).into_response()
            }
        }
    }
}

/// A JSON answer that holds `null` on purpose (a surface's normal where it has none). The
/// handler checks that every number in it is finite before it builds one (and answers the
/// 422 of an overflow itself), so no `null` stands for an overflow and the body is not
/// scanned for one, as [`ApiJson`] scans.
#[derive(Debug, Clone)]
pub struct JsonWithNulls<T>(pub T);

impl<T: Serialize> IntoResponse for JsonWithNulls<T> {
    fn into_response(self) -> Response {
        let mut bytes = Vec::with_capacity(RESPONSE_CAPACITY);
        match serde_json::to_writer(&mut bytes, &self.0) {
            Ok(()) => ([(CONTENT_TYPE, "application/json")], bytes).into_response(),
            Err(error) => {
                ApiError::Internal(format!("response serialization: {error}")).into_response()
            }
        }
    }
}

/// Initial capacity of a response body buffer, in bytes.
pub const RESPONSE_CAPACITY: usize = 2048;

/// Whether serialized JSON holds a `null` value (serde writes non-finite numbers as `null`;
/// the service's responses never use `null` otherwise). A byte scan first; a `null` inside a
/// string is told apart by parsing.
fn has_non_finite(json: &[u8]) -> bool {
    memchr::memmem::find(json, b"null").is_some()
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
