//! When the service goes away or sheds load: a server stopped mid-drag shows the banner, the
//! release commits nothing, undo changes nothing, and the drawing stays; once a server
//! listens again, Retry hides the banner and editing works. A 503 with Retry-After is
//! retried after the time it names, and the page says so meanwhile.

use serde_json::json;

use super::browser::Browser;
use super::page::Page;
use super::steps::{numbers, paste, pick, sample};
use crate::helpers::{spawn_app, spawn_app_with};

const CURVE_PATH: &str =
    "return document.querySelector('#scene .layer-curve .curve')?.getAttribute('d') ?? null;";

async fn banner(page: &Page<'_>) -> (bool, String) {
    let value = page
        .run(
            "const b = document.getElementById('banner'); \
             return [!b.hidden && b.getBoundingClientRect().height > 0, b.textContent];",
            vec![],
        )
        .await;
    (
        value[0].as_bool().unwrap(),
        value[1].as_str().unwrap().to_owned(),
    )
}

#[tokio::test]
async fn a_stopped_server_shows_the_banner_and_commits_nothing() {
    let mut app = spawn_app().await;
    let socket = app.socket;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    assert!(!banner(&page).await.0);
    // One edit, so that there is something to undo.
    let (_, dot) = pick(&page, &app, &original, 0.42).await;
    page.drag(dot, &[(dot.0 + 5, dot.1 - 6), (dot.0 + 10, dot.1 - 12)])
        .await;
    let edited = page.curve().await;
    assert_ne!(numbers(&edited), numbers(&original));
    let drawn = page.run(CURVE_PATH, vec![]).await;

    // Mid-drag, the server stops.
    let (_, dot) = pick(&page, &app, &edited, 0.42).await;
    page.press_at(dot).await;
    page.move_to((dot.0 + 8, dot.1 + 6)).await;
    page.wait_until(
        "the preview is drawn",
        "document.querySelector('#scene .layer-preview .preview') !== null",
    )
    .await;
    app.trigger_shutdown();
    app.stopped().await.unwrap();
    page.move_to((dot.0 + 16, dot.1 + 12)).await;
    page.wait_until(
        "the banner shows",
        "document.body.dataset.connection === 'unreachable'",
    )
    .await;
    let (shown, text) = banner(&page).await;
    assert!(shown && text.contains("does not answer"), "{text}");
    page.release().await;
    page.settle().await;
    assert_eq!(numbers(&page.curve().await), numbers(&edited));
    assert_eq!(
        page.run(CURVE_PATH, vec![]).await,
        drawn,
        "the drawing changed"
    );
    assert_eq!(
        page.run(
            "return document.querySelectorAll('#scene .layer-preview > *').length;",
            vec![]
        )
        .await,
        json!(0)
    );
    // Undo needs the previous curve's drawing: without the service nothing changes.
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&edited));
    assert_eq!(page.run(CURVE_PATH, vec![]).await, drawn);
    // One message at most, and no red error beside the banner.
    assert_eq!(page.data("error").await, "");

    // A server on the same port again: Retry hides the banner, and the page edits.
    let app = spawn_app_with(|config| config.listen = socket).await;
    page.click_id("retry").await;
    page.wait_until(
        "the banner hides",
        "document.body.dataset.connection === 'ok'",
    )
    .await;
    assert!(!banner(&page).await.0);
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    let (_, dot) = pick(&page, &app, &original, 0.42).await;
    page.drag(dot, &[(dot.0 + 5, dot.1 - 6), (dot.0 + 10, dot.1 - 12)])
        .await;
    assert_ne!(numbers(&page.curve().await), numbers(&original));
    // The failed requests are network errors, not script errors.
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_503_with_retry_after_is_retried() {
    let app = spawn_app_with(|config| {
        config.concurrency_limit = 1;
        config.retry_after_secs = 1;
    })
    .await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    paste(&page, &json!({"degree": 2, "control_points": [[0, 0], [1, 2], [3, 1]], "knots": [0, 0, 0, 1, 1, 1]})).await;
    // The only permit is held by a request whose body is half sent.
    let body = json!({"curve": sample(), "parameters": [0.5]});
    let slow = app.start_slow_post("/v1/curves/evaluate", &body).await;
    app.wait_for_in_flight(1).await;
    page.click_id("sample").await;
    page.wait_until(
        "the page says it retries",
        "document.body.dataset.connection === 'retrying'",
    )
    .await;
    let (shown, text) = banner(&page).await;
    assert!(
        shown && text.contains("503") && text.contains("1 s"),
        "{text}"
    );
    let finished = slow.finish().await;
    assert_eq!(finished.status, 200);
    page.settle().await;
    page.wait_until(
        "the banner hides",
        "document.body.dataset.connection === 'ok'",
    )
    .await;
    assert_eq!(numbers(&page.curve().await), numbers(&sample()));
    assert_eq!(page.data("error").await, "");
    assert_eq!(page.data("message").await, "The sample cubic.");
    let metrics = app.get("/metrics").await.text().await.unwrap();
    assert!(
        metrics.lines().any(|line| line.contains("status=\"503\"")
            && line.starts_with("knotshape_http_requests_total")),
        "no 503 was answered"
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
