//! Answers written straight to JSON text, for the hot `/v1/shape/solve` path.
//!
//! On a small answer `serde_json` spends most of its time escaping keys that are constants.
//! [`JsonOut`] copies such keys and punctuation as they are and formats numbers as
//! `serde_json` does (`zmij` for `f64`, `itoa` for integers; a non-finite `f64` becomes `null`
//! and is remembered). The answer types keep their `Serialize` derive, which the OpenAPI
//! document and the tests use: a test checks that both give the same bytes.

use axum::http::header::CONTENT_TYPE;
use axum::response::{IntoResponse, Response};

use super::error::ApiError;

/// A JSON text being written; punctuation and keys come from the caller, verbatim.
pub struct JsonOut {
    bytes: Vec<u8>,
    non_finite: bool,
}

impl JsonOut {
    /// An empty text with room for `capacity` bytes.
    pub fn with_capacity(capacity: usize) -> Self {
        JsonOut {
            bytes: Vec::with_capacity(capacity),
            non_finite: false,
        }
    }

    /// Appends `text` as it is: punctuation and keys that need no escaping (`"{\"key\":"`).
    pub fn raw(&mut self, text: &str) {
        self.bytes.extend_from_slice(text.as_bytes());
    }

    /// A string value, escaped as JSON requires.
    pub fn string(&mut self, text: &str) {
        // Writing a `&str` to a `Vec` cannot fail.
        let _ = serde_json::to_writer(&mut self.bytes, text);
    }

    /// `true` or `false`.
    pub fn bool(&mut self, value: bool) {
        self.raw(if value { "true" } else { "false" });
    }

    /// An unsigned integer.
    pub fn usize(&mut self, value: usize) {
        self.raw(itoa::Buffer::new().format(value));
    }

    /// A number: the shortest text that reads back as `value`; `null` (and remembered, see
    /// [`JsonOut::into_response`]) when it is not finite.
    pub fn f64(&mut self, value: f64) {
        if value.is_finite() {
            self.raw(zmij::Buffer::new().format_finite(value));
        } else {
            self.non_finite = true;
            self.raw("null");
        }
    }

    /// An array of numbers.
    pub fn f64s(&mut self, values: &[f64]) {
        self.array(values, |out, &value| out.f64(value));
    }

    /// An array of unsigned integers.
    pub fn usizes(&mut self, values: &[usize]) {
        self.array(values, |out, &value| out.usize(value));
    }

    /// An array with one element per item, each written by `element`.
    pub fn array<T>(&mut self, items: &[T], mut element: impl FnMut(&mut Self, &T)) {
        self.raw("[");
        for (index, item) in items.iter().enumerate() {
            if index > 0 {
                self.raw(",");
            }
            element(self, item);
        }
        self.raw("]");
    }

    /// The text written so far.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes
    }
}

/// As a response, the rules of [`super::extract::ApiJson`]: `application/json`, unless a
/// number was not finite (then a 422 that names the curve).
impl IntoResponse for JsonOut {
    fn into_response(self) -> Response {
        if self.non_finite {
            return ApiError::non_finite_result().into_response();
        }
        ([(CONTENT_TYPE, "application/json")], self.bytes).into_response()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_strings_read_as_serde_json_writes_them() {
        let mut out = JsonOut::with_capacity(0);
        let values = [0.0, -0.0, 1.0, 0.1, 1e300, 5e-324, -2.5e-8, 123456789.125];
        out.f64s(&values);
        out.raw(",");
        out.usizes(&[0, 7, usize::MAX]);
        out.raw(",");
        out.string("a \"quoted\"\n\\ text");
        out.raw(",");
        out.bool(true);
        let expected = format!(
            "{},{},{},true",
            serde_json::to_string(&values).unwrap(),
            serde_json::to_string(&[0, 7, usize::MAX]).unwrap(),
            serde_json::to_string("a \"quoted\"\n\\ text").unwrap(),
        );
        assert_eq!(std::str::from_utf8(out.as_bytes()).unwrap(), expected);
        assert!(!out.non_finite);
    }

    #[test]
    fn a_non_finite_number_is_null_and_turns_the_answer_into_a_422() {
        let mut out = JsonOut::with_capacity(0);
        out.f64s(&[1.0, f64::INFINITY]);
        assert_eq!(out.as_bytes(), b"[1.0,null]");
        let response = out.into_response();
        assert_eq!(
            response.status(),
            axum::http::StatusCode::UNPROCESSABLE_ENTITY
        );
    }
}
