//! Drag-to-redraw as the page measures it: 240 pointer moves at 60 Hz (each sent by
//! chromedriver once the page has taken the one before, once a frame) around the picked
//! point, on the sample cubic and on a 300-pole curve. For every preview drawn the page keeps
//! the pointer event's timestamp and when the preview was in the page (and the next animation
//! frame); the test prints the 95th percentile and median, split into the parts (event to
//! handler, waiting for the request before, the request, drawing) and beside the floor (a
//! bare request's round trip from the page under the same load), with the page's main-thread
//! time per move split by DevTools' counters (script, style, layout, all tasks), and writes
//! them to `target/editor-drag-timings.txt`. A measurement, not a pass/fail timing: it checks that the
//! drag ran (every move seen, previews drawn) and committed the kept family's solution. Run it
//! alone for numbers: `cargo test --test editor drag_to_redraw -- --nocapture`.

use serde_json::Value;

use super::browser::{Browser, devtools};
use super::page::Page;
use super::steps::{
    apply, many_poles, numbers, p95, paste, pick, sample, solve_family, target_dir,
};
use crate::helpers::{TestApp, spawn_app};

/// Pointer moves of the measured drag.
const MOVES: usize = 240;

/// One preview's timing, read from `window.editorTimings`.
struct Timing {
    stamp: f64,
    handled: f64,
    sent: f64,
    answered: f64,
    drawn: f64,
    frame: Option<f64>,
}

/// The page's main-thread counters from DevTools' `Performance.getMetrics`: script, style,
/// layout and all tasks, in milliseconds, and how often style and layout ran.
async fn main_thread_work(browser: &Browser) -> Vec<(&'static str, f64)> {
    let answer = devtools(
        &browser.client,
        "Performance.getMetrics",
        serde_json::json!({}),
    )
    .await;
    let metrics = answer["metrics"].as_array().cloned().unwrap_or_default();
    let read = |name: &str| {
        metrics
            .iter()
            .find(|metric| metric["name"] == name)
            .and_then(|metric| metric["value"].as_f64())
            .unwrap_or(f64::NAN)
    };
    vec![
        ("script ms", 1000.0 * read("ScriptDuration")),
        ("style ms", 1000.0 * read("RecalcStyleDuration")),
        ("layout ms", 1000.0 * read("LayoutDuration")),
        ("tasks ms", 1000.0 * read("TaskDuration")),
        ("style runs", read("RecalcStyleCount")),
        ("layouts", read("LayoutCount")),
    ]
}

/// Seconds the server spent on `route` so far and how many requests: the latency
/// histogram's sum and count (from receiving a request to sending its response head).
async fn server_time(app: &TestApp, route: &str) -> (f64, f64) {
    let text = app.get("/metrics").await.text().await.unwrap();
    let read = |suffix: &str| {
        text.lines()
            .filter(|line| {
                line.starts_with(&format!(
                    "knotshape_http_request_duration_seconds_{suffix}{{"
                )) && line.contains(&format!("route=\"{route}\""))
            })
            .filter_map(|line| line.rsplit(' ').next()?.parse::<f64>().ok())
            .sum::<f64>()
    };
    (read("sum"), read("count"))
}

fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted[sorted.len() / 2]
}

/// Drags the point at `t` of `curve` around a circle of pixels and reports the timings.
async fn measure(curve: Value, t: f64, label: &str) -> String {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    if numbers(&curve) != numbers(&sample()) {
        paste(&page, &curve).await;
    }
    let (t, dot) = pick(&page, &app, &curve, t).await;
    // A path that stays near the curve (inside regions and out of them), one pixel per move
    // or more: every move changes the target.
    let path: Vec<(i64, i64)> = (1..=MOVES)
        .map(|step| {
            let angle = step as f64 * std::f64::consts::TAU / 80.0;
            let radius = 6.0 + (step % 40) as f64 / 2.0;
            (
                dot.0 + (radius * angle.cos()).round() as i64,
                dot.1 + (radius * angle.sin()).round() as i64,
            )
        })
        .collect();
    let before = server_time(&app, "/v1/shape/solve").await;
    devtools(&browser.client, "Performance.enable", serde_json::json!({})).await;
    let work_before = main_thread_work(&browser).await;
    page.drag_paced(dot, &path).await;
    page.settle().await;
    let work_after = main_thread_work(&browser).await;
    let after = server_time(&app, "/v1/shape/solve").await;
    let work: Vec<String> = work_after
        .iter()
        .zip(&work_before)
        .map(|((name, after), (_, before))| {
            format!("{name} {:.2}", (after - before) / MOVES as f64)
        })
        .collect();
    let server_ms = 1000.0 * (after.0 - before.0) / (after.1 - before.1);
    let raw = page
        .run(
            "return window.editorTimings.map((t) => [t.stamp, t.handled, t.sent, t.answered, \
             t.drawn, t.frame ?? null]);",
            vec![],
        )
        .await;
    let timings: Vec<Timing> = raw
        .as_array()
        .unwrap()
        .iter()
        .map(|row| Timing {
            stamp: row[0].as_f64().unwrap(),
            handled: row[1].as_f64().unwrap(),
            sent: row[2].as_f64().unwrap(),
            answered: row[3].as_f64().unwrap(),
            drawn: row[4].as_f64().unwrap(),
            frame: row[5].as_f64(),
        })
        .collect();
    // Every move reached the drag (the first one again when the drag began).
    let moves = page.run("return window.editorMoves.count;", vec![]).await;
    assert!(
        moves.as_u64().unwrap() as usize >= MOVES,
        "{label}: {moves} moves seen"
    );
    assert!(!timings.is_empty(), "{label}: no preview drawn");
    // The commit is the kept family's solution for the last target, as the API answers it.
    let family: Value = serde_json::from_str(&page.data("family").await).unwrap();
    let target = page.target().await;
    let expected = apply(
        &curve,
        &solve_family(&app, &curve, t, target, &family).await,
    );
    assert_eq!(numbers(&page.curve().await), numbers(&expected), "{label}");
    // What the last preview showed (solved on the local piece) is what was committed (solved
    // on the whole curve).
    let shown = page
        .run(
            "return window.editorTimings[window.editorTimings.length - 1].point;",
            vec![],
        )
        .await;
    let committed = page.picked().await.unwrap()["point"].clone();
    assert_eq!(shown, committed, "{label}");

    // The floor under the same load: a bare request from the page (GET /healthz, no work on
    // the server), one every 16 ms, timed from fetch to its body.
    let bare = browser
        .client
        .execute_async(
            "const done = arguments[arguments.length - 1]; (async () => { const times = []; \
             for (let i = 0; i < 120; i++) { const start = performance.now(); \
             const answer = await fetch('/healthz', { cache: 'no-store' }); await answer.text(); \
             times.push(performance.now() - start); await new Promise((r) => setTimeout(r, 16)); } \
             done(times); })();",
            vec![],
        )
        .await
        .expect("bare requests");
    let bare: Vec<f64> = serde_json::from_value(bare).unwrap();

    let part = |f: &dyn Fn(&Timing) -> f64| timings.iter().map(f).collect::<Vec<f64>>();
    let total = part(&|t| t.drawn - t.stamp);
    let framed: Vec<f64> = timings
        .iter()
        .filter_map(|t| t.frame.map(|f| f - t.stamp))
        .collect();
    let intervals: Vec<f64> = timings
        .windows(2)
        .map(|w| w[1].stamp - w[0].stamp)
        .collect();
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let report = format!(
        "{label}: {} previews of {MOVES} moves (median {:.1} ms apart), pointer event to \
         preview in the page: p95 {:.2} ms, median {:.2} ms; to the next frame: p95 {:.2} ms; \
         p95 of the parts: event to handler {:.2}, waiting {:.2}, request {:.2} (median {:.2}; \
         the server's own mean {:.2}), drawing {:.2} ms; a bare request from the page: p95 \
         {:.2} ms, median {:.2} ms; the page's main thread per move: {}; load average {}\n",
        timings.len(),
        median(&intervals),
        p95(&mut total.clone()),
        median(&total),
        p95(&mut framed.clone()),
        p95(&mut part(&|t| t.handled - t.stamp)),
        p95(&mut part(&|t| t.sent - t.handled)),
        p95(&mut part(&|t| t.answered - t.sent)),
        median(&part(&|t| t.answered - t.sent)),
        server_ms,
        p95(&mut part(&|t| t.drawn - t.answered)),
        p95(&mut bare.clone()),
        median(&bare),
        work.join(", "),
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" "),
    );
    print!("{report}");
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
    report
}

#[tokio::test]
async fn drag_to_redraw_at_60_hz_on_the_sample_and_on_300_poles() {
    let mut report = measure(sample(), 0.42, "sample cubic").await;
    report += &measure(many_poles(300), 0.5, "300 poles").await;
    std::fs::create_dir_all(target_dir()).unwrap();
    std::fs::write(target_dir().join("editor-drag-timings.txt"), report).unwrap();
}
