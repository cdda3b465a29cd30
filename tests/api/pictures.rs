//! The pictures of `docs/`, drawn by the service itself (`POST /v1/shape/regions` with
//! `Accept: image/svg+xml`): a test fails when a committed picture differs from what the
//! service draws now. Set `UPDATE_PICTURES=1` to redraw them.

use serde_json::{Value, json};

use crate::helpers::spawn_app;

/// `(file under docs/pictures/, request)`.
fn pictures() -> Vec<(&'static str, Value)> {
    let example: Value =
        serde_json::from_str(include_str!("../../examples/shape-solve.json")).unwrap();
    vec![
        (
            // Both sides' regions of the first worked example's pick that solve reaches with
            // the domain kept (the default), and its target.
            "regions-worked-example.svg",
            json!({"curve": example["curve"], "parameter": example["parameter"],
                   "target": example["target"]}),
        ),
        (
            // The left side only, the consecutive pair Ω2 and the non-consecutive Ω4, whole
            // (without `keep_domain` Ω4 may move the domain's start).
            "regions-omega2-omega4.svg",
            json!({"curve": example["curve"], "parameter": example["parameter"],
                   "side": "left", "regions": ["omega2", "omega4"], "keep_domain": false}),
        ),
        (
            // The weight pairs' quadrilaterals of the same pick, and the target.
            "regions-weights.svg",
            json!({"curve": example["curve"], "parameter": example["parameter"],
                   "target": example["target"], "methods": ["weights"]}),
        ),
    ]
}

#[tokio::test]
async fn the_docs_pictures_are_what_the_service_draws() {
    let app = spawn_app().await;
    let directory = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/pictures");
    let update = std::env::var_os("UPDATE_PICTURES").is_some();
    let mut stale = Vec::new();
    for (name, request) in pictures() {
        let response = app
            .client
            .post(format!("{}/v1/shape/regions", app.address))
            .header("accept", "image/svg+xml")
            .json(&request)
            .send()
            .await
            .unwrap();
        assert_eq!(response.status(), 200, "{name}");
        let drawn = response.text().await.unwrap();
        assert!(
            drawn.starts_with("<svg") || drawn.starts_with("<?xml"),
            "{name}"
        );
        let path = directory.join(name);
        if update {
            std::fs::write(&path, &drawn).unwrap();
        } else if std::fs::read_to_string(&path).ok().as_deref() != Some(drawn.as_str()) {
            stale.push(name);
        }
    }
    assert!(
        stale.is_empty(),
        "docs/pictures {stale:?} differ from what the service draws: run \
         `UPDATE_PICTURES=1 cargo test --test api the_docs_pictures`"
    );
}
