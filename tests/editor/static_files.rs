//! `GET /` and `GET /editor/...`: the page and every file it refers to (found by following
//! its `src`/`href` attributes and the modules' `import` lines, three.js's included) are served with their content
//! types, the strict Content-Security-Policy, `nosniff`, and revalidation by `ETag`; no API
//! key needed. `/favicon.ico` is served too.

use std::collections::BTreeSet;

use crate::helpers::spawn_app_with;

/// The content type a file's name calls for.
fn content_type(path: &str) -> &'static str {
    if path.ends_with('/') || path.ends_with(".html") {
        "text/html; charset=utf-8"
    } else if path.ends_with(".css") {
        "text/css; charset=utf-8"
    } else if path.ends_with(".js") {
        "text/javascript; charset=utf-8"
    } else if path.ends_with(".svg") || path.ends_with(".ico") {
        "image/svg+xml"
    } else if path.ends_with("/LICENSE") || path.ends_with("/VERSION") {
        "text/plain; charset=utf-8"
    } else {
        panic!("unexpected file {path}")
    }
}

/// The site paths `body` (served at `path`) refers to.
fn references(path: &str, body: &str) -> Vec<String> {
    let directory = &path[..=path.rfind('/').unwrap()];
    let mut found = Vec::new();
    for attribute in ["src=\"", "href=\""] {
        for piece in body.split(attribute).skip(1) {
            let target = piece.split('"').next().unwrap();
            if target.starts_with('/') {
                found.push(target.to_owned());
            }
        }
    }
    for line in body.lines() {
        // `import … from "./m.js";`, `} from '../m.js';` (a multi-line import, three.js's
        // quotes), `import "./m.js";`.
        let line = line.trim_start();
        if !(line.starts_with("import ") || line.starts_with("} from ")) {
            continue;
        }
        let Some(module) = quoted_module(line) else {
            continue;
        };
        found.push(resolve(directory, module));
    }
    found
}

/// The module named in quotes (either kind) after `from`, or after `import` alone.
fn quoted_module(line: &str) -> Option<&str> {
    let rest = line.rsplit_once(" from ").map_or(line, |(_, rest)| rest);
    let quote = rest.find(['"', '\''])?;
    let mark = &rest[quote..=quote];
    let inner = &rest[quote + 1..];
    let module = &inner[..inner.find(mark)?];
    assert!(
        module.starts_with("./") || module.starts_with("../"),
        "relative imports only: {module}"
    );
    Some(module)
}

/// `module` (relative, with `./` and `../` steps) from the site directory `directory`.
fn resolve(directory: &str, module: &str) -> String {
    let mut parts: Vec<&str> = directory.trim_end_matches('/').split('/').collect();
    for step in module.split('/') {
        match step {
            "." => {}
            ".." => {
                parts.pop();
            }
            name => parts.push(name),
        }
    }
    parts.join("/")
}

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

    let mut pending = vec!["/editor/".to_owned(), "/favicon.ico".to_owned()];
    let mut seen = BTreeSet::new();
    while let Some(path) = pending.pop() {
        if !seen.insert(path.clone()) {
            continue;
        }
        let response = app.get(&path).await;
        assert_eq!(response.status().as_u16(), 200, "{path}");
        let headers = response.headers().clone();
        assert_eq!(headers["content-type"], content_type(&path), "{path}");
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
        assert!(!body.is_empty(), "{path}");
        pending.extend(references(&path, &body));
        let again = app
            .client
            .get(format!("{}{path}", app.address))
            .header("if-none-match", &tag)
            .send()
            .await
            .unwrap();
        assert_eq!(again.status().as_u16(), 304, "{path}");
    }
    // The page, its style, its icon and its modules.
    assert!(seen.len() > 20, "{seen:?}");
    assert!(seen.contains("/editor/js/main.js") && seen.contains("/editor/favicon.svg"));
    // The 3D view's modules and the vendored three.js they import.
    for module in [
        "/editor/js/space/main.js",
        "/editor/vendor/three/three.module.js",
        "/editor/vendor/three/three.core.js",
        "/editor/vendor/three/OrbitControls.js",
    ] {
        assert!(seen.contains(module), "{module} not reached: {seen:?}");
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
