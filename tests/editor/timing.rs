//! Drag-to-redraw as the page measures it: 240 pointer moves at 60 Hz (each sent by
//! chromedriver once the page has taken the one before, once a frame) around the picked
//! point, on the sample cubic, a 300-pole curve, and — the knot method alone, so that every
//! move solves a knot family — the worked quintic of the fourth release and a 3D cubic (the
//! curves of `benches/knot_families.rs`). For every preview drawn the page keeps the pointer
//! event's timestamp and when the preview was in the page (and the next animation frame);
//! the test prints the 95th percentile and median, split into the parts (event to handler,
//! waiting for the request before, the request, drawing) and beside the floor (a bare
//! request's round trip from the page under the same load), with the page's main-thread
//! time per move split by DevTools' counters (script, style, layout, all tasks), and writes
//! them to `target/editor-drag-timings.txt`. It checks that the drag ran (every move seen,
//! previews drawn), committed the kept family's solution, and drew each curve within a
//! frame: p95 of pointer event to preview at most 16 ms. Run it alone for numbers:
//! `cargo test --release --test editor drag_to_redraw -- --nocapture`.

use serde_json::Value;

use super::browser::{Browser, devtools};
use super::page::Page;
use super::steps::{
    assert_one_of, helix, many_poles, numbers, p95, paste, pick, point_at, quintic, sample,
    solve_family, target_dir,
};
use crate::helpers::{TestApp, spawn_app_with};

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
pub async fn main_thread_work(browser: &Browser) -> Vec<(&'static str, f64)> {
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
pub async fn server_time(app: &TestApp, route: &str) -> (f64, f64) {
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

/// What a measured drag shows: its report line, the p95 of pointer event to preview, and
/// the page's own main-thread work per move (script, style and layout, in ms).
struct Measured {
    report: String,
    p95: f64,
    page_work: f64,
}

/// One measured drag: the curve, the picked parameter, a label, whether only the knots are
/// ticked (every move then solves a knot family), and a wheel turn that zooms in about the
/// point first (0: the fitted view) — a knot family's reach near the point is small, and a
/// designer zooms in to move it a little.
struct Drag {
    curve: Value,
    t: f64,
    label: &'static str,
    knots_only: bool,
    wheel: i64,
}

/// Drags the point of `drag` around a circle of pixels and reports the timings.
async fn measure(drag: &Drag) -> Measured {
    let Drag {
        curve,
        t,
        label,
        knots_only,
        wheel,
    } = drag;
    let (curve, t, label, knots_only) = (curve.clone(), *t, *label, *knots_only);
    // Alone: another test's browser would be measured too.
    let browser = Browser::start_alone().await;
    // The browser and the service share this machine's two cores: the service solves each
    // request on its own thread (`--solve-threads 1`), as on a designer's small machine
    // running both; spread over both cores the solve would take them from the page's frames.
    let app = spawn_app_with(|config| config.solve_threads = 1).await;
    let page = Page::open(&browser.client, &app.address).await;
    if numbers(&curve) != numbers(&sample()) {
        paste(&page, &curve).await;
    }
    if knots_only {
        page.click_id("method-control-points").await;
        page.settle().await;
    }
    if *wheel != 0 {
        let at = page.to_screen(point_at(&app, &curve, t).await).await;
        page.wheel_at(at, *wheel).await;
        page.settle().await;
    }
    let zoom = {
        let frame = page.frame().await;
        frame["scale"].as_f64().unwrap() / frame["fitted"].as_f64().unwrap()
    };
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
    let per_move: Vec<(&str, f64)> = work_after
        .iter()
        .zip(&work_before)
        .map(|((name, after), (_, before))| (*name, (after - before) / MOVES as f64))
        .collect();
    let work: Vec<String> = per_move
        .iter()
        .map(|(name, value)| format!("{name} {value:.2}"))
        .collect();
    let page_work: f64 = per_move
        .iter()
        .filter(|(name, _)| ["script ms", "style ms", "layout ms"].contains(name))
        .map(|(_, value)| value)
        .sum();
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
    // The path stays where the kept family reaches: most solved targets have its solution.
    let solved = page
        .run(
            "return [window.editorMoves.solved, window.editorMoves.missed];",
            vec![],
        )
        .await;
    let (solved, missed) = (solved[0].as_u64().unwrap(), solved[1].as_u64().unwrap());
    assert!(
        !timings.is_empty() && missed * 4 <= solved,
        "{label}: {} previews of {MOVES} moves, {missed} of {solved} targets solved out of reach",
        timings.len()
    );
    // The commit is the kept family's solution for the last target, as the API answers it.
    let family: Value = serde_json::from_str(&page.data("family").await).unwrap();
    if knots_only {
        assert_eq!(family["method"], "knots", "{label}: {family}");
    }
    let target = page.target_sent().await;
    let expected = solve_family(&app, &curve, t, target, &family).await;
    assert_one_of(&page.curve().await, &curve, &expected, label);
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
    let p95_total = p95(&mut total.clone());
    let report = format!(
        "{label}: {} previews of {MOVES} moves (median {:.1} ms apart, zoom {zoom:.1}×, {missed} of {solved} targets out of reach), kept {}, pointer event \
         to preview in the page: p95 {:.2} ms, median {:.2} ms; to the next frame: p95 {:.2} ms; \
         p95 of the parts: event to handler {:.2}, waiting {:.2}, request {:.2} (median {:.2}; \
         the server's own mean {:.2}), drawing {:.2} ms; a bare request from the page: p95 \
         {:.2} ms, median {:.2} ms; the page's main thread per move: {}; load average {}\n",
        timings.len(),
        median(&intervals),
        describe_family(&family),
        p95_total,
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
    Measured {
        report,
        p95: p95_total,
        page_work,
    }
}

/// The kept family in a few words ("knots direct:7,9", "control_points").
fn describe_family(family: &Value) -> String {
    let method = family["method"].as_str().unwrap_or_default();
    match family.get("region").and_then(Value::as_str) {
        Some(region) => match family.get("side").and_then(Value::as_str) {
            Some(side) => format!("{method} {region} ({side})"),
            None => format!("{method} {region}"),
        },
        None => method.to_owned(),
    }
}

/// A frame at 60 Hz, in milliseconds: the budget of a drag move's p95.
const FRAME_MS: f64 = 16.0;

/// Runs of one drag at most: a timing on a machine shared with other work is retried (the
/// frame budget holds when one run meets it; every run is reported).
const RUNS: usize = 3;

#[tokio::test]
async fn drag_to_redraw_at_60_hz_within_a_frame_on_cubics_a_quintic_and_a_3d_cubic() {
    // The solver of an unoptimized build takes 10–40 ms per knot solve of the quintic and
    // the 3D cubic (under a millisecond optimized): their frame budget is the shipped
    // build's, asserted with `--release`; the cubics' solves take about a millisecond in
    // either build.
    let optimized = !cfg!(debug_assertions);
    let drags = [
        (
            Drag {
                curve: sample(),
                t: 0.42,
                label: "sample cubic",
                knots_only: false,
                wheel: 0,
            },
            true,
        ),
        (
            Drag {
                curve: many_poles(300),
                t: 0.5,
                label: "300 poles",
                knots_only: false,
                wheel: 0,
            },
            true,
        ),
        (
            Drag {
                curve: quintic(),
                t: 0.42,
                label: "quintic, knots",
                knots_only: true,
                wheel: -1400,
            },
            optimized,
        ),
        (
            Drag {
                curve: helix(),
                t: 0.5,
                label: "3D cubic, knots",
                knots_only: true,
                wheel: -1400,
            },
            optimized,
        ),
    ];
    let mut report = String::new();
    let mut over = Vec::new();
    for (drag, budget) in &drags {
        let mut runs = Vec::new();
        for _ in 0..RUNS {
            let measured = measure(drag).await;
            // The page's own work per move (script, style, layout) is a small part of a frame
            // in every build.
            assert!(
                measured.page_work <= FRAME_MS / 2.0,
                "the page's own work per move: {}",
                measured.report
            );
            report += &measured.report;
            let within = measured.p95 <= FRAME_MS;
            runs.push(measured);
            if within || !budget {
                break;
            }
        }
        if *budget && runs.iter().all(|m| m.p95 > FRAME_MS) {
            over.push(drag.label);
        }
    }
    std::fs::create_dir_all(target_dir()).unwrap();
    std::fs::write(target_dir().join("editor-drag-timings.txt"), &report).unwrap();
    assert!(
        over.is_empty(),
        "not within a frame ({FRAME_MS} ms at p95) in {RUNS} runs: {over:?}\n{report}"
    );
}
