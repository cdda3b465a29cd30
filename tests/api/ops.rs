//! Probes, metrics, the OpenAPI document (served, printed and committed) and CORS.

use serde_json::{Value, json};

use crate::helpers::{spawn_app, spawn_app_with};
use crate::reference::cubic_2d;

#[tokio::test]
async fn health_and_readiness_answer_200() {
    let app = spawn_app().await;
    let health = app.get("/healthz").await;
    assert_eq!(health.status(), 200);
    assert_eq!(
        health.json::<Value>().await.unwrap(),
        json!({"status": "ok"})
    );
    let ready = app.get("/readyz").await;
    assert_eq!(ready.status(), 200);
    assert_eq!(
        ready.json::<Value>().await.unwrap(),
        json!({"status": "ready"})
    );
}

#[tokio::test]
async fn metrics_count_requests_by_matched_route_method_and_status() {
    let app = spawn_app().await;
    let body = json!({"curve": cubic_2d().to_json(false), "samples": 3});
    for _ in 0..3 {
        assert_eq!(app.post("/v1/curves/evaluate", &body).await.status(), 200);
    }
    assert_eq!(
        app.post("/v1/curves/evaluate", &json!({})).await.status(),
        400
    );
    assert_eq!(app.get("/no/such/path/12345").await.status(), 404);
    let response = app.get("/metrics").await;
    assert_eq!(response.status(), 200);
    let content_type = response.headers()["content-type"]
        .to_str()
        .unwrap()
        .to_owned();
    assert!(
        content_type.starts_with("application/openmetrics-text"),
        "{content_type}"
    );
    let text = response.text().await.unwrap();
    assert!(text.contains(
        r#"knotshape_http_requests_total{method="POST",route="/v1/curves/evaluate",status="200"} 3"#
    ), "{text}");
    assert!(text.contains(
        r#"knotshape_http_requests_total{method="POST",route="/v1/curves/evaluate",status="400"} 1"#
    ));
    // Unmatched paths share one label: no cardinality from client-chosen paths.
    assert!(text.contains(
        r#"knotshape_http_requests_total{method="GET",route="unmatched",status="404"} 1"#
    ));
    assert!(!text.contains("12345"));
    assert!(text.contains(
        r#"knotshape_http_request_duration_seconds_count{method="POST",route="/v1/curves/evaluate"} 4"#
    ));
    assert!(text.contains("knotshape_http_request_duration_seconds_bucket{le="));
    assert!(text.trim_end().ends_with("# EOF"));
}

#[tokio::test]
async fn the_served_document_is_the_generated_one() {
    let app = spawn_app().await;
    let response = app.get("/openapi.json").await;
    assert_eq!(response.status(), 200);
    let served: Value = response.json().await.unwrap();
    let generated: Value = serde_json::from_str(&knotshape::openapi_json()).unwrap();
    assert_eq!(served, generated);
    for path in [
        "/v1/curves/evaluate",
        "/v1/curves/envelope",
        "/v1/curves/closest-point",
        "/v1/shape/membership",
        "/v1/shape/regions",
        "/v1/shape/solve",
        "/healthz",
        "/readyz",
        "/metrics",
        "/openapi.json",
    ] {
        assert!(served["paths"][path].is_object(), "{path} documented");
    }
    // Every schema carries a description and an example.
    for (name, schema) in served["components"]["schemas"].as_object().unwrap() {
        assert!(
            schema["description"].is_string(),
            "{name} has a description"
        );
        assert!(!schema["example"].is_null(), "{name} has an example");
    }
    assert_eq!(
        served["components"]["securitySchemes"]["api_key"]["scheme"],
        "bearer"
    );
    // The key is optional, document-wide: no /v1 operation carries a requirement of its own
    // (a generated client would then demand an authenticated client for every call), and
    // the operations outside /v1 are open.
    assert_eq!(served["security"], json!([{}, {"api_key": []}]));
    for (path, item) in served["paths"].as_object().unwrap() {
        for (method, operation) in item.as_object().unwrap() {
            if path.starts_with("/v1/") {
                assert!(
                    operation.get("security").is_none(),
                    "{method} {path} has its own security"
                );
            } else {
                assert_eq!(operation["security"], json!([]), "{method} {path} is open");
            }
        }
    }
}

/// Every operation has its own `operationId` (OpenAPI requires it; a generated TypeScript
/// client declares one member per id, and a repeated one does not compile).
#[test]
fn operation_ids_are_unique() {
    let document: Value = serde_json::from_str(&knotshape::openapi_json()).unwrap();
    let mut seen = std::collections::BTreeMap::new();
    for (path, item) in document["paths"].as_object().unwrap() {
        for operation in item.as_object().unwrap().values() {
            let id = operation["operationId"].as_str().unwrap().to_owned();
            if let Some(first) = seen.insert(id.clone(), path.clone()) {
                panic!("operationId {id} on both {first} and {path}");
            }
        }
    }
}

/// Set `UPDATE_OPENAPI=1` to rewrite the committed document after an API change.
#[test]
fn generated_openapi_json_is_up_to_date() {
    let generated = knotshape::openapi_json();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("openapi/openapi.json");
    if std::env::var_os("UPDATE_OPENAPI").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "openapi/openapi.json is stale: run `UPDATE_OPENAPI=1 cargo test --test api generated_openapi` \
         or `cargo run -- openapi > openapi/openapi.json`"
    );
}

#[tokio::test]
async fn cors_is_off_by_default_and_follows_the_allowlist() {
    let closed = spawn_app().await;
    let response = closed
        .client
        .get(format!("{}/healthz", closed.address))
        .header("origin", "https://cad.example.com")
        .send()
        .await
        .unwrap();
    assert!(
        response
            .headers()
            .get("access-control-allow-origin")
            .is_none()
    );

    let open = spawn_app_with(|config| {
        config.cors_allow_origins = vec!["https://cad.example.com".to_owned()];
        config.api_key = Some("k3y".parse().unwrap());
    })
    .await;
    // A preflight needs no API key.
    let preflight = open
        .client
        .request(
            reqwest::Method::OPTIONS,
            format!("{}/v1/shape/solve", open.address),
        )
        .header("origin", "https://cad.example.com")
        .header("access-control-request-method", "POST")
        .header(
            "access-control-request-headers",
            "content-type, authorization",
        )
        .send()
        .await
        .unwrap();
    assert!(preflight.status().is_success(), "{}", preflight.status());
    assert_eq!(
        preflight.headers()["access-control-allow-origin"],
        "https://cad.example.com"
    );
    let allowed_methods = preflight.headers()["access-control-allow-methods"]
        .to_str()
        .unwrap()
        .to_owned();
    assert!(allowed_methods.contains("POST"), "{allowed_methods}");
    let other = open
        .client
        .get(format!("{}/healthz", open.address))
        .header("origin", "https://evil.example.com")
        .send()
        .await
        .unwrap();
    assert!(other.headers().get("access-control-allow-origin").is_none());
}

/// Runs the compiled binary with `args` and `KNOTSHAPE_LISTEN`, returning exit success and stdout.
async fn run_binary(args: &'static [&'static str], listen: String) -> (bool, String) {
    tokio::task::spawn_blocking(move || {
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_knotshape"))
            .args(args)
            .env("KNOTSHAPE_LISTEN", listen)
            .output()
            .expect("run the knotshape binary");
        (
            output.status.success(),
            String::from_utf8_lossy(&output.stdout).into_owned(),
        )
    })
    .await
    .unwrap()
}

#[tokio::test]
async fn the_binary_probes_health_and_prints_the_document() {
    let app = spawn_app().await;
    let port = app.socket.port();
    let (healthy, _) = run_binary(&["healthcheck"], format!("127.0.0.1:{port}")).await;
    assert!(healthy, "healthcheck against a running server exits 0");
    let (healthy, _) = run_binary(&["healthcheck"], format!("0.0.0.0:{port}")).await;
    assert!(healthy, "0.0.0.0 is probed on 127.0.0.1");
    let closed = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let closed_port = closed.local_addr().unwrap().port();
    drop(closed);
    let (healthy, _) = run_binary(&["healthcheck"], format!("127.0.0.1:{closed_port}")).await;
    assert!(!healthy, "healthcheck with nothing listening exits 1");
    let (printed, document) = run_binary(&["openapi"], "127.0.0.1:0".to_owned()).await;
    assert!(printed);
    assert_eq!(document, knotshape::openapi_json());
}
