//! The optional API key: `/v1` routes need it when configured; probes never do.

use serde_json::json;

use crate::helpers::{expect_problem, spawn_app, spawn_app_with};
use crate::reference::cubic_2d;

#[tokio::test]
async fn without_a_configured_key_v1_is_open() {
    let app = spawn_app().await;
    let body = json!({"curve": cubic_2d().to_json(false), "samples": 2});
    assert_eq!(app.post("/v1/curves/evaluate", &body).await.status(), 200);
}

#[tokio::test]
async fn with_a_configured_key_every_v1_route_needs_it() {
    let app = spawn_app_with(|config| config.api_key = Some("s3cret-key".parse().unwrap())).await;
    let evaluate = json!({"curve": cubic_2d().to_json(false), "samples": 2});
    let solve =
        json!({"curve": cubic_2d().to_json(false), "parameter": 0.42, "target": [4.7, 3.3]});
    for (path, body) in [
        ("/v1/curves/evaluate", &evaluate),
        (
            "/v1/curves/envelope",
            &json!({"curve": cubic_2d().to_json(false), "knot_index": 5}),
        ),
        ("/v1/shape/solve", &solve),
        ("/v1/shape/membership", &solve),
        (
            "/v1/shape/regions",
            &json!({"curve": cubic_2d().to_json(false), "parameter": 0.42}),
        ),
    ] {
        let url = format!("{}{path}", app.address);
        let missing = app.client.post(&url).json(body).send().await.unwrap();
        assert_eq!(missing.headers()["www-authenticate"], "Bearer");
        expect_problem(missing, 401, None).await;
        let wrong = app
            .client
            .post(&url)
            .bearer_auth("s3cret-kez")
            .json(body)
            .send()
            .await
            .unwrap();
        expect_problem(wrong, 401, None).await;
        let prefix = app
            .client
            .post(&url)
            .bearer_auth("s3cret")
            .json(body)
            .send()
            .await
            .unwrap();
        expect_problem(prefix, 401, None).await;
        let basic = app
            .client
            .post(&url)
            .header("authorization", "Basic s3cret-key")
            .json(body)
            .send()
            .await
            .unwrap();
        expect_problem(basic, 401, None).await;
        let right = app
            .client
            .post(&url)
            .bearer_auth("s3cret-key")
            .json(body)
            .send()
            .await
            .unwrap();
        assert_eq!(right.status(), 200, "{path}");
    }
    for probe in ["/healthz", "/readyz", "/metrics", "/openapi.json"] {
        assert_eq!(app.get(probe).await.status(), 200, "{probe} stays open");
    }
}
