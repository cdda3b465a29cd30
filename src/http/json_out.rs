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
    ///
    /// Whole numbers below `2^53` in magnitude (clamped knots, grid points) take a shortcut:
    /// every such number is a double, so its shortest text is its digits, which `serde_json`
    /// writes as `{digits}.0`; `itoa` writes them without `zmij`'s table lookups.
    pub fn f64(&mut self, value: f64) {
        if let Some(whole) = exact_whole_number(value) {
            self.raw(itoa::Buffer::new().format(whole));
            self.raw(".0");
        } else if value.is_finite() {
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

/// `value` as an integer when it is a whole number with `|value| < 2^53` other than `-0.0`
/// (which must keep its sign), else `None`.
#[inline]
fn exact_whole_number(value: f64) -> Option<i64> {
    const TWO_POW_53: f64 = 9_007_199_254_740_992.0;
    // In range, the cast is exact for whole numbers and truncates the others (NaN fails the
    // range test).
    let whole = value as i64;
    (value.abs() < TWO_POW_53 && whole as f64 == value && !(whole == 0 && value.is_sign_negative()))
        .then_some(whole)
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
    fn whole_numbers_read_as_serde_json_writes_them() {
        const TWO_POW_53: f64 = 9_007_199_254_740_992.0;
        let mut values = vec![0.0, -0.0, 1.0, -1.0, 10.0, 1e15, -1e15, 1234500.0];
        values.extend([
            TWO_POW_53 - 1.0,
            -(TWO_POW_53 - 1.0),
            TWO_POW_53,
            -TWO_POW_53,
        ]);
        values.extend([
            TWO_POW_53 + 2.0,
            1e16,
            1e17,
            2.0f64.powi(63),
            -(2.0f64.powi(63)),
        ]);
        values.extend([0.5, -0.5, 1.0 - f64::EPSILON, 4503599627370495.5]);
        // A deterministic spread over every magnitude up to 2^60 (xorshift).
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let magnitude = (state >> 4) >> (state % 60);
            let sign = if state & 1 == 0 { 1.0 } else { -1.0 };
            values.push(sign * magnitude as f64);
            values.push(sign * magnitude as f64 / 8.0);
        }
        for value in values {
            let mut out = JsonOut::with_capacity(0);
            out.f64(value);
            assert_eq!(
                std::str::from_utf8(out.as_bytes()).unwrap(),
                serde_json::to_string(&value).unwrap(),
                "{value:e}"
            );
        }
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
