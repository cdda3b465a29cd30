//! knotshape-fuzzing: the checks the fuzz targets (`fuzz/`, cargo-fuzz on nightly) run on each
//! input, and that the corpus replay test (`tests/fuzz_corpus.rs`) runs on stable. Outside the
//! service on purpose: a crate of the workspace that only knotshape's tests depend on, so the
//! library's API, the binary and its docs carry none of it (nor `arbitrary`).
//!
//! * [`Target`] (here, target `post_bodies`): raw bytes as the body of a POST endpoint,
//!   through the real router in-process, must give no server error, and every client error
//!   must be a problem document that says why. The endpoints are the POST operations of
//!   [`knotshape::openapi`], so new ones are fuzzed as soon as they are documented. The
//!   input's first byte picks the endpoint (modulo their number), the rest is the body.
//! * [`structured`] (target `structured`): bytes to a valid random curve through the core's
//!   operations, each answer checked another way.
//! * [`files`] (targets `step_import`, `dxf_import`): bytes as a file through the readers and
//!   writers.
#![cfg_attr(test, allow(clippy::unwrap_used))]

pub mod files;
pub mod structured;

use axum::Router;
use axum::body::{Body, to_bytes};
use axum::http::{Request, header};
use serde_json::Value;
use tower::ServiceExt;

use knotshape::config::Config;

/// The content types of exported files (`/v1/curves/export`).
const FILE_TYPES: [&str; 2] = ["model/step", "image/vnd.dxf"];

/// Largest answer read back (the default limits keep answers far below it).
const MAX_ANSWER_BYTES: usize = 64 * 1024 * 1024;

/// The router and the endpoints to fuzz.
#[derive(Debug, Clone)]
pub struct Target {
    router: Router,
    post_paths: Vec<String>,
}

impl Default for Target {
    fn default() -> Self {
        Self::new()
    }
}

impl Target {
    /// The router with the default configuration, and every documented POST path (sorted).
    pub fn new() -> Target {
        let post_paths = knotshape::openapi()
            .paths
            .paths
            .iter()
            .filter(|(_, item)| item.post.is_some())
            .map(|(path, _)| path.clone())
            .collect();
        Target {
            router: knotshape::app(&Config::default()),
            post_paths,
        }
    }

    /// The POST paths fuzzed.
    pub fn post_paths(&self) -> &[String] {
        &self.post_paths
    }

    /// Sends `input` (first byte: endpoint, rest: body) and checks the answer; `Err` says
    /// what is wrong with it.
    pub async fn check(&self, input: &[u8]) -> Result<(), String> {
        let Some((selector, body)) = input.split_first() else {
            return Ok(());
        };
        if self.post_paths.is_empty() {
            return Err("the document lists no POST operation".to_owned());
        }
        let path = &self.post_paths[usize::from(*selector) % self.post_paths.len()];
        let request = Request::post(path.as_str())
            .header(header::CONTENT_TYPE, "application/json")
            .body(Body::from(body.to_vec()))
            .map_err(|error| format!("cannot build the request: {error}"))?;
        let Ok(response) = self.router.clone().oneshot(request).await;
        let status = response.status();
        let content_type = response
            .headers()
            .get(header::CONTENT_TYPE)
            .and_then(|value| value.to_str().ok())
            .unwrap_or_default()
            .to_owned();
        let bytes = to_bytes(response.into_body(), MAX_ANSWER_BYTES)
            .await
            .map_err(|error| format!("{path}: cannot read the answer: {error}"))?;
        let text = String::from_utf8_lossy(&bytes);
        if status.is_server_error() {
            return Err(format!("{path}: server error {status}: {text}"));
        }
        // A file written by `/v1/curves/export` is the one answer that is not JSON: it must
        // be text of its own type, read back elsewhere (the `step_import` and `dxf_import`
        // targets, scripts/interop-roundtrip).
        if status.is_success() && FILE_TYPES.iter().any(|t| content_type.starts_with(t)) {
            return if std::str::from_utf8(&bytes).is_ok_and(|file| !file.trim().is_empty()) {
                Ok(())
            } else {
                Err(format!(
                    "{path}: {status}: an empty or non-UTF-8 {content_type} file"
                ))
            };
        }
        let answer: Value = serde_json::from_slice(&bytes).map_err(|error| {
            format!("{path}: {status} with a body that is not JSON ({error}): {text}")
        })?;
        if status.is_client_error() {
            check_problem(status.as_u16(), &content_type, &answer)
                .map_err(|why| format!("{path}: {status}: {why}: {text}"))?;
        }
        Ok(())
    }
}

/// A client error must be `application/problem+json` with its status, a title, and a detail
/// that says why; listed field errors each name a JSON pointer and say why.
fn check_problem(status: u16, content_type: &str, problem: &Value) -> Result<(), String> {
    if content_type != knotshape::http::error::PROBLEM_JSON {
        return Err(format!(
            "content type {content_type:?}, not a problem document"
        ));
    }
    if problem["status"].as_u64() != Some(u64::from(status)) {
        return Err("the problem's status differs from the answer's".to_owned());
    }
    let non_empty = |field: &Value| field.as_str().is_some_and(|text| !text.trim().is_empty());
    if !non_empty(&problem["title"]) || !non_empty(&problem["detail"]) {
        return Err("no title or no detail".to_owned());
    }
    if let Some(errors) = problem.get("errors") {
        let errors = errors.as_array().ok_or("`errors` is not a list")?;
        for error in errors {
            let pointer = error["pointer"]
                .as_str()
                .ok_or("a field error without pointer")?;
            if !(pointer.is_empty() || pointer.starts_with('/')) {
                return Err(format!("{pointer:?} is not a JSON pointer"));
            }
            if !non_empty(&error["detail"]) {
                return Err(format!("the error at {pointer:?} does not say why"));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn every_post_endpoint_is_a_target_and_good_and_bad_bodies_pass_the_check() {
        let target = Target::new();
        assert!(target.post_paths().iter().any(|p| p == "/v1/shape/solve"));
        assert!(target.post_paths().iter().all(|p| p.starts_with("/v1/")));
        for index in 0..target.post_paths().len() {
            let selector = u8::try_from(index).unwrap();
            for body in [&b"{"[..], b"null", b"[]", b"{\"curve\": 1}", b"\xff\xfe"] {
                let input = [&[selector][..], body].concat();
                target.check(&input).await.unwrap();
            }
        }
    }

    #[test]
    fn the_problem_check_refuses_what_it_should() {
        let good = serde_json::json!({"status": 422, "title": "Unprocessable Entity",
            "detail": "bad", "errors": [{"pointer": "/curve", "detail": "missing"}]});
        let json = knotshape::http::error::PROBLEM_JSON;
        assert!(check_problem(422, json, &good).is_ok());
        assert!(check_problem(422, "application/json", &good).is_err());
        assert!(check_problem(400, json, &good).is_err());
        let mut no_why = good.clone();
        no_why["errors"][0]["detail"] = Value::from(" ");
        assert!(check_problem(422, json, &no_why).is_err());
        let mut no_pointer = good;
        no_pointer["errors"][0]["pointer"] = Value::from("curve");
        assert!(check_problem(422, json, &no_pointer).is_err());
    }
}
