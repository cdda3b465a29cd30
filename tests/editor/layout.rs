//! Layout and hygiene: at 800 px the solution list stays in the window during a drag and is
//! numbered by solution; an error in pasted JSON is one message naming its line and column
//! in the pasted text, and no older message stays beside it; the same file opens twice; the
//! page has a favicon and asks for nothing that is missing; the drawing is reachable with Tab
//! and the shortcuts are listed.

use fantoccini::Locator;
use fantoccini::key::Key;
use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{
    numbers, paste, pick, pixel_inside_a_region, pixel_outside_every_region, sample, screenshot,
};
use crate::helpers::spawn_app;

/// Whether every solution in the list lies inside the window, and their count.
async fn list_in_view(page: &Page<'_>) -> (bool, usize) {
    let value = page
        .run(
            "const items = [...document.querySelectorAll('#solutions > li')]; \
             const inside = items.every((li) => { const r = li.getBoundingClientRect(); \
               return r.top >= 0 && r.left >= 0 && r.right <= window.innerWidth && r.height > 0 \
                 && r.top < window.innerHeight; }); \
             const list = document.querySelector('.solutions').getBoundingClientRect(); \
             return [inside && list.bottom <= window.innerHeight && document.documentElement.scrollWidth <= window.innerWidth, items.length];",
            vec![],
        )
        .await;
    (
        value[0].as_bool().unwrap(),
        value[1].as_u64().unwrap() as usize,
    )
}

#[tokio::test]
async fn at_800_px_the_list_stays_in_view_and_is_numbered_by_solution() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    browser.client.set_window_size(800, 700).await.unwrap();
    let page = Page::open(&browser.client, &app.address).await;
    let width = page.run("return window.innerWidth;", vec![]).await;
    assert!(width.as_f64().unwrap() <= 800.0, "{width}");
    let original = sample();
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    let inside = pixel_inside_a_region(&page, &app, &original, t, dot).await;
    page.press_at(dot).await;
    page.move_to(inside).await;
    page.wait_until(
        "the preview is drawn",
        "document.querySelector('#solutions > li') !== null",
    )
    .await;
    let (inside, count) = list_in_view(&page).await;
    assert!(
        inside && count > 1,
        "during the drag: {count} solutions, in view: {inside}"
    );
    screenshot(&browser.client, "editor-800px.png", true).await;
    page.release().await;
    page.settle().await;
    let (inside, count) = list_in_view(&page).await;
    assert!(inside, "after the release");
    assert_eq!(count.to_string(), page.data("solutions").await);

    // Outside every region with only the knots method: the note stands apart from the
    // numbered list, whose items are all solutions.
    page.ctrl_z(false).await;
    page.click_id("method-control-points").await;
    let (_, dot) = pick(&page, &app, &original, t).await;
    let outside = pixel_outside_every_region(&page, &app, &original, t, dot).await;
    page.drag(dot, &[outside]).await;
    let structure = page
        .run(
            "const note = document.getElementById('solutions-note'); \
             const items = [...document.querySelectorAll('#solutions > li')]; \
             return [note.textContent, note.parentElement.tagName, items.length, \
               items.every((li) => li.querySelector('input[name=solution]') !== null)];",
            vec![],
        )
        .await;
    assert!(
        structure[0].as_str().unwrap().contains("nearest"),
        "{structure}"
    );
    assert_ne!(structure[1], json!("OL"));
    assert_eq!(structure[3], json!(true), "{structure}");
    assert_eq!(structure[2].to_string(), page.data("solutions").await);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// The (line, column) of the first `needle` in `text`, both from 1.
fn line_column(text: &str, needle: &str) -> (usize, usize) {
    let offset = text.find(needle).unwrap();
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = offset - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, column)
}

async fn load_text(page: &Page<'_>, text: &str) {
    page.run(
        "document.getElementById('curve-json').value = arguments[0];",
        vec![json!(text)],
    )
    .await;
    page.click_id("load").await;
    page.settle().await;
}

#[tokio::test]
async fn errors_point_into_the_pasted_json_once_and_nothing_stale_stays() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    paste(&page, &json!({"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0]], "knots": [0, 0, 0, 0, 1, 1, 1, 1]})).await;
    assert_eq!(page.data("message").await, "Curve loaded.");

    for text in [
        "{\n  \"degree\": 3,\n  \"control_points\": [[0, 0], [1, 2], [3, 2], [4, 0]],\n  \"knots\": [0, 0, 0, 0, 1, 1, 1, 0.5]\n}",
        "{\"curve\": {\n    \"degree\": 3,\n    \"control_points\": [[0, 0], [1, 2], [3, 2], [4, 0]],\n\n    \"knots\": [0, 0, 0, 0, 1, 1, 1, 0.5]}}",
    ] {
        load_text(&page, text).await;
        let error = page.data("error").await;
        let (line, column) = line_column(text, "0.5");
        let place = format!("line {line}, column {column}");
        assert!(error.contains(&place), "{error} (expected {place})");
        assert_eq!(error.matches("non-decreasing").count(), 1, "{error}");
        assert!(
            !error.contains("line 1 column"),
            "points into the editor's request: {error}"
        );
        assert_eq!(
            page.data("message").await,
            "",
            "a stale message beside the error"
        );
        let shown = page
            .run("return [document.getElementById('message').offsetHeight, document.getElementById('error').textContent];", vec![])
            .await;
        assert_eq!(shown[0], json!(0), "{shown}");
        assert_eq!(shown[1].as_str().unwrap(), error);
    }
    // A type error deep inside (a string for a number), and a syntax error.
    let text = "{\"degree\": 3, \"control_points\": [[0, 0], [1, 2], [3, \"x\"], [4, 0]],\n \"knots\": [0, 0, 0, 0, 1, 1, 1, 1]}";
    load_text(&page, text).await;
    let error = page.data("error").await;
    let (line, column) = line_column(text, "\"x\"");
    assert!(
        error.contains(&format!("line {line}, column {column}")),
        "{error}"
    );
    let text = "{\"degree\": 3,\n \"knots\": [0, 1,, 2]}";
    load_text(&page, text).await;
    let error = page.data("error").await;
    let (line, column) = line_column(text, ",,");
    let place = format!(
        "The text is not JSON: line {line}, column {}: unexpected \",\"",
        column + 1
    );
    assert_eq!(error, place);
    // The next action clears the error.
    page.click_id("sample").await;
    page.settle().await;
    assert_eq!(page.data("error").await, "");
    assert_eq!(numbers(&page.curve().await), numbers(&sample()));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn the_same_file_opens_twice() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let curve = json!({"degree": 3, "control_points": [[0, 0], [2, 3], [4, 3], [6, 0]], "knots": [0, 0, 0, 0, 1, 1, 1, 1]});
    let path =
        std::env::temp_dir().join(format!("knotshape-editor-open-{}.json", std::process::id()));
    std::fs::write(&path, curve.to_string()).unwrap();
    for _ in 0..2 {
        let input = browser.client.find(Locator::Id("open-file")).await.unwrap();
        input.send_keys(path.to_str().unwrap()).await.unwrap();
        page.wait_until(
            "the file is loaded",
            "document.body.dataset.message.startsWith('Opened')",
        )
        .await;
        page.settle().await;
        assert_eq!(numbers(&page.curve().await), numbers(&curve));
        page.click_id("sample").await;
        page.settle().await;
        assert_eq!(numbers(&page.curve().await), numbers(&sample()));
    }
    std::fs::remove_file(&path).unwrap();
    browser.close().await;
}

#[tokio::test]
async fn a_favicon_no_missing_file_and_keyboard_reachability() {
    let app = spawn_app().await;
    let favicon = app.get("/favicon.ico").await;
    assert_eq!(favicon.status().as_u16(), 200);
    assert_eq!(favicon.headers()["content-type"], "image/svg+xml");
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let icon = page
        .run(
            "return document.querySelector('link[rel=icon]').href;",
            vec![],
        )
        .await;
    assert!(
        icon.as_str().unwrap().ends_with("/editor/favicon.svg"),
        "{icon}"
    );

    // Tab reaches the drawing; its keys work there.
    let mut reached = false;
    for _ in 0..40 {
        page.key(Key::Tab.into(), false).await;
        let focused = page.run("return document.activeElement.id;", vec![]).await;
        if focused == json!("canvas") {
            reached = true;
            break;
        }
    }
    assert!(reached, "Tab never reaches the drawing");
    let before = page.frame().await["scale"].as_f64().unwrap();
    page.key('+', false).await;
    assert!(page.frame().await["scale"].as_f64().unwrap() > before * 1.2);
    page.key('f', false).await;
    assert!((page.frame().await["scale"].as_f64().unwrap() / before - 1.0).abs() < 1e-9);
    // Every shortcut the page handles is listed.
    let listed: Value = page
        .run(
            "return [...document.querySelectorAll('#shortcuts dt')].map((d) => d.textContent);",
            vec![],
        )
        .await;
    let listed: Vec<String> = serde_json::from_value(listed).unwrap();
    for key in [
        "Tab",
        "Esc",
        "F",
        "Space + drag",
        "1 – 9",
        "Ctrl+Z / Ctrl+Shift+Z",
        "← ↑ → ↓",
        "+ / −",
        "V / H / P / T / D",
        "Enter / Backspace",
    ] {
        assert!(
            listed.iter().any(|entry| entry == key),
            "{key} not listed in {listed:?}"
        );
    }
    // Nothing the page asked for was missing (no 404, e.g. for /favicon.ico).
    let metrics = app.get("/metrics").await.text().await.unwrap();
    let missing: Vec<&str> = metrics
        .lines()
        .filter(|line| {
            line.starts_with("knotshape_http_requests_total") && line.contains("status=\"404\"")
        })
        .collect();
    assert!(missing.is_empty(), "{missing:?}");
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
