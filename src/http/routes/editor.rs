//! `GET /` and `GET /editor/...`: the editor, a page of static files compiled into the binary
//! (`editor/` at the repository root, with three.js vendored under `editor/vendor/three/`), and `GET /favicon.ico` (its icon, which browsers ask
//! for on any page of the service). Open like the probes (no API key): the page itself
//! sends the key, when one is configured, on its `/v1` requests.
//!
//! Every file is answered with its content type, a strict Content-Security-Policy (only this
//! origin, no inline script or style), `X-Content-Type-Options: nosniff`, and
//! `Cache-Control: no-cache` with an `ETag`, so a browser revalidates (a 304 when unchanged)
//! and never runs a stale module after the binary is upgraded.

use axum::Router;
use axum::extract::Path;
use axum::http::{HeaderMap, HeaderValue, StatusCode, Uri, header};
use axum::response::{IntoResponse, Redirect, Response};
use axum::routing::get;

use crate::http::error::ApiError;

/// The policy of every editor file: scripts, styles, images and requests from this origin
/// only; no plugins, no framing, no forms, no `<base>`.
pub const CONTENT_SECURITY_POLICY: &str = "default-src 'self'; script-src 'self'; \
    style-src 'self'; img-src 'self' data:; connect-src 'self'; font-src 'self'; \
    object-src 'none'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

/// Where the editor's page lives.
pub const EDITOR_PATH: &str = "/editor/";

/// One static file of the editor.
struct Asset {
    /// Path below `/editor/`.
    path: &'static str,
    content_type: &'static str,
    body: &'static str,
}

const HTML: &str = "text/html; charset=utf-8";
const JAVASCRIPT: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";
const SVG: &str = "image/svg+xml";
const TEXT: &str = "text/plain; charset=utf-8";

/// Declares the editor's files, read at compile time from `editor/`.
macro_rules! assets {
    ($(($path:literal, $content_type:expr)),* $(,)?) => {
        &[$(Asset {
            path: $path,
            content_type: $content_type,
            body: include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/editor/", $path)),
        }),*]
    };
}

/// Every file of the editor.
const ASSETS: &[Asset] = assets![
    ("index.html", HTML),
    ("editor.css", CSS),
    ("favicon.svg", SVG),
    ("js/errors.js", JAVASCRIPT),
    ("js/main.js", JAVASCRIPT),
    ("js/api.js", JAVASCRIPT),
    ("js/store.js", JAVASCRIPT),
    ("js/state.js", JAVASCRIPT),
    ("js/options.js", JAVASCRIPT),
    ("js/viewport.js", JAVASCRIPT),
    ("js/render.js", JAVASCRIPT),
    ("js/view.js", JAVASCRIPT),
    ("js/strip.js", JAVASCRIPT),
    ("js/panel.js", JAVASCRIPT),
    ("js/interaction.js", JAVASCRIPT),
    ("js/picking.js", JAVASCRIPT),
    ("js/dragging.js", JAVASCRIPT),
    ("js/precision.js", JAVASCRIPT),
    ("js/committing.js", JAVASCRIPT),
    ("js/connection.js", JAVASCRIPT),
    ("js/files.js", JAVASCRIPT),
    ("js/problems.js", JAVASCRIPT),
    ("js/jsonsource.js", JAVASCRIPT),
    ("js/snapping.js", JAVASCRIPT),
    ("js/geometry.js", JAVASCRIPT),
    ("js/drawing.js", JAVASCRIPT),
    ("js/sample.js", JAVASCRIPT),
    ("js/conditions.js", JAVASCRIPT),
    ("js/sketching.js", JAVASCRIPT),
    ("js/space/main.js", JAVASCRIPT),
    ("js/space/scene.js", JAVASCRIPT),
    ("js/space/editing.js", JAVASCRIPT),
    ("js/space/objects.js", JAVASCRIPT),
    ("js/space/panel.js", JAVASCRIPT),
    ("js/space/nurbs.js", JAVASCRIPT),
    // three.js, vendored at the version in vendor/three/VERSION (scripts/refresh-three).
    ("vendor/three/three.module.js", JAVASCRIPT),
    ("vendor/three/three.core.js", JAVASCRIPT),
    ("vendor/three/OrbitControls.js", JAVASCRIPT),
    ("vendor/three/LICENSE", TEXT),
    ("vendor/three/VERSION", TEXT),
];

/// Where browsers look for a site's icon.
pub const FAVICON_PATH: &str = "/favicon.ico";

/// The editor's routes (outside `/v1`, no API key, not in the OpenAPI document).
pub fn router<S: Clone + Send + Sync + 'static>() -> Router<S> {
    Router::new()
        .route("/", get(|| async { Redirect::to(EDITOR_PATH) }))
        .route("/editor", get(|| async { Redirect::to(EDITOR_PATH) }))
        .route(
            EDITOR_PATH,
            get(|headers: HeaderMap| async move { serve("index.html", &headers) }),
        )
        .route("/editor/{*path}", get(editor_file))
        .route(
            FAVICON_PATH,
            get(|headers: HeaderMap| async move { serve("favicon.svg", &headers) }),
        )
}

/// `GET /editor/{path}`: one of the editor's files, or 404.
async fn editor_file(Path(path): Path<String>, uri: Uri, headers: HeaderMap) -> Response {
    if ASSETS.iter().any(|asset| asset.path == path) {
        serve(&path, &headers)
    } else {
        ApiError::NotFound {
            path: uri.path().to_owned(),
        }
        .into_response()
    }
}

/// The file at `path` (one of [`ASSETS`]) with its headers; 304 when `If-None-Match` holds
/// its tag.
fn serve(path: &str, request_headers: &HeaderMap) -> Response {
    let Some(asset) = ASSETS.iter().find(|asset| asset.path == path) else {
        return ApiError::NotFound {
            path: format!("{EDITOR_PATH}{path}"),
        }
        .into_response();
    };
    let tag = entity_tag(asset.body.as_bytes());
    let unchanged = request_headers
        .get(header::IF_NONE_MATCH)
        .and_then(|value| value.to_str().ok())
        .is_some_and(|value| value.split(',').any(|candidate| candidate.trim() == tag));
    let mut response = if unchanged {
        StatusCode::NOT_MODIFIED.into_response()
    } else {
        asset.body.into_response()
    };
    let headers = response.headers_mut();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static(asset.content_type),
    );
    headers.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(CONTENT_SECURITY_POLICY),
    );
    headers.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    headers.insert(
        header::REFERRER_POLICY,
        HeaderValue::from_static("no-referrer"),
    );
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
    if let Ok(value) = HeaderValue::from_str(&tag) {
        headers.insert(header::ETAG, value);
    }
    response
}

/// A strong entity tag: the 64-bit FNV-1a hash of the bytes, quoted hex. The files are
/// fixed at compile time, so the tag changes exactly when a new binary ships a new file.
fn entity_tag(bytes: &[u8]) -> String {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let hash = bytes.iter().fold(OFFSET_BASIS, |hash, &byte| {
        (hash ^ u64::from(byte)).wrapping_mul(PRIME)
    });
    format!("\"{hash:016x}\"")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_asset_has_a_distinct_path_and_a_body() {
        for (index, asset) in ASSETS.iter().enumerate() {
            assert!(!asset.body.is_empty(), "{}", asset.path);
            assert!(
                ASSETS[..index].iter().all(|other| other.path != asset.path),
                "{} listed twice",
                asset.path
            );
        }
    }

    #[test]
    fn the_vendored_three_js_is_the_version_its_version_file_pins() {
        let body = |path: &str| {
            ASSETS
                .iter()
                .find(|asset| asset.path == path)
                .map(|asset| asset.body)
                .unwrap_or_else(|| panic!("{path} is not served"))
        };
        // "three 0.187.0" → three.js's revision 187.
        let version = body("vendor/three/VERSION");
        let pinned = version
            .lines()
            .next()
            .and_then(|line| line.strip_prefix("three 0."))
            .and_then(|rest| rest.split('.').next())
            .expect("VERSION starts with `three 0.N.M`");
        assert!(
            body("vendor/three/three.core.js").contains(&format!("REVISION = '{pinned}'")),
            "three.core.js is not revision {pinned}"
        );
        assert!(body("vendor/three/LICENSE").contains("MIT License"));
        assert!(
            body("vendor/three/OrbitControls.js").contains("from './three.module.js';"),
            "OrbitControls imports the vendored module"
        );
    }

    #[test]
    fn entity_tags_differ_for_different_bytes() {
        assert_ne!(entity_tag(b"a"), entity_tag(b"b"));
        assert_eq!(entity_tag(b""), "\"cbf29ce484222325\"");
    }

    #[test]
    fn the_page_loads_no_inline_script_or_style() {
        let page = ASSETS[0].body;
        assert!(!page.contains("<style"), "inline style in index.html");
        assert!(!page.contains("style="), "inline style attribute");
        for script in page.split("<script").skip(1) {
            let tag = script.split('>').next().unwrap_or_default();
            assert!(tag.contains("src="), "inline script: <script{tag}>");
        }
    }
}
