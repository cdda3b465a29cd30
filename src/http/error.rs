//! The one API error type: every failure is answered as an RFC 9457 problem document
//! (`application/problem+json`) with `type`, `title`, `status`, `detail` and, for rule
//! violations, `errors`: JSON pointers (RFC 6901) into the request body.

use axum::extract::rejection::{BytesRejection, FailedToBufferBody, JsonRejection};
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::pointer::{JsonPointer, pointer_from_serde_path};

/// Media type of every error body.
pub const PROBLEM_JSON: &str = "application/problem+json";

/// One offending element of a request body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"pointer": "/curve/knots/4", "detail": "knots must be non-decreasing: knot 4 is smaller than knot 3"}))]
pub struct FieldError {
    /// JSON Pointer (RFC 6901) to the offending element of the request body.
    pub pointer: String,
    /// What is wrong with it.
    pub detail: String,
}

impl FieldError {
    /// A field error at `pointer`.
    pub fn new(pointer: impl Into<JsonPointer>, detail: impl Into<String>) -> Self {
        FieldError {
            pointer: pointer.into().to_string(),
            detail: detail.into(),
        }
    }
}

/// An RFC 9457 problem document.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({
    "type": "urn:knotshape:problem:invalid-request",
    "title": "The request breaks a rule",
    "status": 422,
    "detail": "knots must be non-decreasing: knot 4 is smaller than knot 3",
    "errors": [{"pointer": "/curve/knots/4", "detail": "knots must be non-decreasing: knot 4 is smaller than knot 3"}]
}))]
pub struct Problem {
    /// URI naming the kind of problem (`about:blank` for plain HTTP errors).
    #[serde(rename = "type")]
    pub problem_type: String,
    /// Short summary of the kind of problem.
    pub title: String,
    /// The HTTP status code.
    pub status: u16,
    /// What went wrong with this request.
    pub detail: String,
    /// The offending elements of the request body (rule violations and malformed JSON).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<FieldError>,
}

impl Problem {
    /// A problem for a plain HTTP status: `type` `about:blank`, the status's reason as title.
    pub fn for_status(status: StatusCode, detail: impl Into<String>) -> Self {
        Problem {
            problem_type: "about:blank".to_owned(),
            title: status.canonical_reason().unwrap_or("Error").to_owned(),
            status: status.as_u16(),
            detail: detail.into(),
            errors: Vec::new(),
        }
    }

    /// The response: this document with `Content-Type: application/problem+json`.
    pub fn into_response_with_retry_after(self, retry_after_secs: Option<u64>) -> Response {
        let status = StatusCode::from_u16(self.status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
        let body = serde_json::to_vec(&self).unwrap_or_else(|_| b"{}".to_vec());
        let mut response = (status, body).into_response();
        let headers = response.headers_mut();
        headers.insert(header::CONTENT_TYPE, HeaderValue::from_static(PROBLEM_JSON));
        if let Some(seconds) = retry_after_secs {
            headers.insert(header::RETRY_AFTER, HeaderValue::from(seconds));
        }
        response
    }
}

/// Every way a request can fail; handlers return it with `?`, extractors reject with it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ApiError {
    /// The body is not valid JSON, or has wrong types, missing or unknown fields (400).
    #[error("{detail}")]
    MalformedBody {
        /// What the parser reported.
        detail: String,
        /// Where, when known.
        errors: Vec<FieldError>,
    },
    /// The body is not sent as `application/json` (415).
    #[error("the request body must be JSON sent with `Content-Type: application/json`")]
    UnsupportedMediaType,
    /// The body exceeds the configured size limit (413).
    #[error("the request body exceeds the configured limit{}", limit.map(|l| format!(" of {l} bytes")).unwrap_or_default())]
    PayloadTooLarge {
        /// The limit, when known where the error arises.
        limit: Option<usize>,
    },
    /// A well-formed request that breaks a rule (422); at least one field error.
    #[error("{}", .0.first().map_or("the request breaks a rule", |e| e.detail.as_str()))]
    Invalid(Vec<FieldError>),
    /// An API key is configured and the request lacks it or has a wrong one (401).
    #[error("this route needs the header `Authorization: Bearer <API key>` with a valid key")]
    Unauthorized,
    /// No route has this path (404).
    #[error("no resource at {path}")]
    NotFound {
        /// The request path.
        path: String,
    },
    /// The route exists but not for this method (405).
    #[error("method {method} is not allowed here")]
    MethodNotAllowed {
        /// The request method.
        method: String,
    },
    /// The concurrency limit is reached (503 + `Retry-After`).
    #[error("the service is at its concurrency limit; retry later")]
    Overloaded {
        /// Seconds for `Retry-After`.
        retry_after_secs: u64,
    },
    /// The service is shutting down (503 + `Retry-After`).
    #[error("the service is shutting down; retry on another instance or later")]
    ShuttingDown {
        /// Seconds for `Retry-After`.
        retry_after_secs: u64,
    },
    /// An internal failure (a caught panic): 500. No input is meant to reach this.
    #[error("internal error: {0}")]
    Internal(String),
}

impl ApiError {
    /// A 422 with one field error.
    pub fn invalid(pointer: impl Into<JsonPointer>, detail: impl Into<String>) -> Self {
        ApiError::Invalid(vec![FieldError::new(pointer, detail)])
    }

    /// The 422 for an answer with a non-finite number (JSON has none): only inputs of extreme
    /// magnitude (coordinates near 1e300, weights near 1e-300) overflow so.
    pub fn non_finite_result() -> Self {
        ApiError::invalid(
            "/curve",
            "the result is not finite: the curve's coordinates or weights are too extreme for \
             double precision",
        )
    }

    /// The HTTP status code.
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::MalformedBody { .. } => StatusCode::BAD_REQUEST,
            ApiError::UnsupportedMediaType => StatusCode::UNSUPPORTED_MEDIA_TYPE,
            ApiError::PayloadTooLarge { .. } => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::Invalid(_) => StatusCode::UNPROCESSABLE_ENTITY,
            ApiError::Unauthorized => StatusCode::UNAUTHORIZED,
            ApiError::NotFound { .. } => StatusCode::NOT_FOUND,
            ApiError::MethodNotAllowed { .. } => StatusCode::METHOD_NOT_ALLOWED,
            ApiError::Overloaded { .. } | ApiError::ShuttingDown { .. } => {
                StatusCode::SERVICE_UNAVAILABLE
            }
            ApiError::Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
        }
    }

    /// `(type, title)` of the problem document.
    fn kind(&self) -> (&'static str, &'static str) {
        match self {
            ApiError::MalformedBody { .. } => (
                "urn:knotshape:problem:malformed-body",
                "The request body is not valid for this endpoint",
            ),
            ApiError::UnsupportedMediaType => (
                "urn:knotshape:problem:unsupported-media-type",
                "Unsupported media type",
            ),
            ApiError::PayloadTooLarge { .. } => (
                "urn:knotshape:problem:payload-too-large",
                "Request body too large",
            ),
            ApiError::Invalid(_) => (
                "urn:knotshape:problem:invalid-request",
                "The request breaks a rule",
            ),
            ApiError::Unauthorized => ("urn:knotshape:problem:unauthorized", "Unauthorized"),
            ApiError::NotFound { .. } => ("about:blank", "Not Found"),
            ApiError::MethodNotAllowed { .. } => ("about:blank", "Method Not Allowed"),
            ApiError::Overloaded { .. } => ("urn:knotshape:problem:overloaded", "Overloaded"),
            ApiError::ShuttingDown { .. } => {
                ("urn:knotshape:problem:shutting-down", "Shutting down")
            }
            ApiError::Internal(_) => ("urn:knotshape:problem:internal", "Internal error"),
        }
    }

    /// The problem document describing this error.
    pub fn problem(&self) -> Problem {
        let (problem_type, title) = self.kind();
        let detail = match self {
            // Never leak internals (panic messages) to clients.
            ApiError::Internal(_) => {
                "the request could not be completed; it has been logged".to_owned()
            }
            other => other.to_string(),
        };
        let errors = match self {
            ApiError::Invalid(errors) | ApiError::MalformedBody { errors, .. } => errors.clone(),
            _ => Vec::new(),
        };
        Problem {
            problem_type: problem_type.to_owned(),
            title: title.to_owned(),
            status: self.status().as_u16(),
            detail,
            errors,
        }
    }

    fn retry_after_secs(&self) -> Option<u64> {
        match self {
            ApiError::Overloaded { retry_after_secs }
            | ApiError::ShuttingDown { retry_after_secs } => Some(*retry_after_secs),
            _ => None,
        }
    }
}

impl IntoResponse for Problem {
    fn into_response(self) -> Response {
        self.into_response_with_retry_after(None)
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let retry_after = self.retry_after_secs();
        let mut response = self.problem().into_response_with_retry_after(retry_after);
        if matches!(self, ApiError::Unauthorized) {
            response
                .headers_mut()
                .insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
        }
        response
    }
}

impl From<JsonRejection> for ApiError {
    fn from(rejection: JsonRejection) -> Self {
        match rejection {
            JsonRejection::MissingJsonContentType(_) => ApiError::UnsupportedMediaType,
            JsonRejection::BytesRejection(BytesRejection::FailedToBufferBody(
                FailedToBufferBody::LengthLimitError(_),
            )) => ApiError::PayloadTooLarge { limit: None },
            JsonRejection::JsonDataError(ref error) => from_serde_error(error, &rejection),
            JsonRejection::JsonSyntaxError(ref error) => from_serde_error(error, &rejection),
            other => ApiError::MalformedBody {
                detail: other.body_text(),
                errors: Vec::new(),
            },
        }
    }
}

/// serde's message for a number with a fraction or exponent where a count or an index is
/// read (`3.0` for `degree`, as Python's `json.dumps(3.0)` writes it) names a Rust type;
/// this one says what to send. Such numbers are refused, never rounded.
fn plain_integer_message(message: String) -> String {
    let expected_integer = [
        "expected usize",
        "expected u32",
        "expected u64",
        "expected u8",
    ]
    .iter()
    .any(|expected| message.contains(expected));
    if message.starts_with("invalid type: floating point") && expected_integer {
        let found = message
            .split('`')
            .nth(1)
            .map_or_else(String::new, |number| format!(" (got {number})"));
        return format!(
            "expected an integer written without a fraction or exponent, such as 3, not 3.0{found}"
        );
    }
    message
}

/// Maps a JSON parse failure to a 400 with the pointer where it happened; a number too large
/// for a double (`1e999`, which would be infinite) is a 422 like any other non-finite number.
fn from_serde_error(
    error: &(dyn std::error::Error + 'static),
    rejection: &JsonRejection,
) -> ApiError {
    let mut source: Option<&(dyn std::error::Error + 'static)> = Some(error);
    while let Some(current) = source {
        if let Some(located) =
            current.downcast_ref::<serde_path_to_error::Error<serde_json::Error>>()
        {
            let pointer = pointer_from_serde_path(located.path(), &located.inner().to_string());
            let message = located.inner().to_string();
            if message.starts_with("number out of range") {
                return ApiError::invalid(
                    pointer,
                    "numbers must be finite: this one is too large for a double",
                );
            }
            if message.starts_with("unknown variant") {
                // A string of the right type that names no allowed value breaks a rule.
                return ApiError::invalid(pointer, message);
            }
            let message = plain_integer_message(message);
            return ApiError::MalformedBody {
                detail: message.clone(),
                errors: vec![FieldError {
                    pointer: pointer.to_string(),
                    detail: message,
                }],
            };
        }
        source = current.source();
    }
    ApiError::MalformedBody {
        detail: rejection.body_text(),
        errors: Vec::new(),
    }
}
