//! `GET /` and `GET /editor/...`: the page's files with their content types, the strict
//! Content-Security-Policy, `nosniff`, revalidation by `ETag`; no API key needed.

use crate::helpers::spawn_app_with;

const FILES: [(&str, &str); 11] = [
    ("/editor/", "text/html; charset=utf-8"),
    ("/editor/editor.css", "text/css; charset=utf-8"),
    ("/editor/js/errors.js", "text/javascript; charset=utf-8"),
    ("/editor/js/main.js", "text/javascript; charset=utf-8"),
    ("/editor/js/api.js", "text/javascript; charset=utf-8"),
    ("/editor/js/state.js", "text/javascript; charset=utf-8"),
    ("/editor/js/view.js", "text/javascript; charset=utf-8"),
    (
        "/editor/js/interaction.js",
        "text/javascript; charset=utf-8",
    ),
    ("/editor/js/geometry.js", "text/javascript; charset=utf-8"),
    ("/editor/js/sample.js", "text/javascript; charset=utf-8"),
    ("/editor/js/drawing.js", "text/javascript; charset=utf-8"),
];

#[tokio::test]
async fn the_files_are_served_with_strict_headers_even_with_an_api_key() {
    let app = spawn_app_with(|config| config.api_key = Some("s3cret".parse().unwrap())).await;
    let root = app
        .client
        .get(format!("{}/", app.address))
        .send()
        .await
        .unwrap();
    // reqwest follows the redirect to the page.
    assert_eq!(root.status().as_u16(), 200);
    assert_eq!(root.url().path(), "/editor/");
    for (path, content_type) in FILES {
        let response = app.get(path).await;
        assert_eq!(response.status().as_u16(), 200, "{path}");
        let headers = response.headers().clone();
        assert_eq!(headers["content-type"], content_type, "{path}");
        assert_eq!(headers["x-content-type-options"], "nosniff", "{path}");
        let policy = headers["content-security-policy"].to_str().unwrap();
        assert!(policy.starts_with("default-src 'self';"), "{policy}");
        assert!(
            !policy.contains("unsafe-inline") && !policy.contains("http"),
            "{policy}"
        );
        assert_eq!(headers["cache-control"], "no-cache", "{path}");
        let tag = headers["etag"].to_str().unwrap().to_owned();
        let body = response.text().await.unwrap();
        assert!(!body.is_empty());
        // Every module the page imports is served.
        for import in body.lines().filter_map(|line| line.strip_prefix("import ")) {
            let module = import.split('"').nth(1).unwrap();
            let module = module.trim_start_matches("./");
            assert!(
                FILES.iter().any(|(p, _)| p.ends_with(module)),
                "{path} imports {module}, not served"
            );
        }
        let again = app
            .client
            .get(format!("{}{path}", app.address))
            .header("if-none-match", &tag)
            .send()
            .await
            .unwrap();
        assert_eq!(again.status().as_u16(), 304, "{path}");
    }
    assert_eq!(
        app.get("/editor/js/missing.js").await.status().as_u16(),
        404
    );
    // The page's API calls still need the key.
    let (status, _) = app
        .post_json("/v1/curves/bezier", &serde_json::json!({}))
        .await;
    assert_eq!(status, 401);
}
