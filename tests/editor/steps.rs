//! The steps the browser tests share: what they ask the API (the reference answers), how
//! they find a target inside or outside the regions, and what they do to the page.

use std::path::PathBuf;

use serde_json::{Value, json};

use super::page::Page;
use crate::helpers::TestApp;

/// The page's sample cubic (editor/js/sample.js).
pub fn sample() -> Value {
    json!({"degree": 3, "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
           "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]})
}

/// Both methods, as the page sends them by default.
pub const BOTH: [&str; 2] = ["knots", "control_points"];

/// The curve's numbers, for comparison regardless of how JSON wrote them (`0` or `0.0`).
pub fn numbers(curve: &Value) -> (u64, Vec<f64>, Vec<f64>, Option<Vec<f64>>) {
    let list = |value: &Value| -> Vec<f64> {
        value
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    let points = curve["control_points"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(&list)
        .collect();
    let weights = curve.get("weights").filter(|w| !w.is_null()).map(list);
    (
        curve["degree"].as_u64().unwrap(),
        list(&curve["knots"]),
        points,
        weights,
    )
}

/// The curve a solution describes (its new knots or new control points).
pub fn apply(curve: &Value, solution: &Value) -> Value {
    let mut next = curve.clone();
    match solution["method"].as_str().unwrap() {
        "knots" => next["knots"] = solution["knots"].clone(),
        "control_points" => next["control_points"] = solution["control_points"].clone(),
        "weights" => next["weights"] = solution["weights"].clone(),
        other => panic!("unknown method {other}"),
    }
    next
}

/// The solution with the smallest `max_deviation` (the page's default choice).
pub fn smallest_deviation(solutions: &[Value]) -> &Value {
    solutions
        .iter()
        .min_by(|a, b| {
            a["max_deviation"]
                .as_f64()
                .unwrap()
                .total_cmp(&b["max_deviation"].as_f64().unwrap())
        })
        .expect("at least one solution")
}

pub async fn solve(
    app: &TestApp,
    curve: &Value,
    t: f64,
    target: [f64; 2],
    methods: &[&str],
) -> Value {
    let request = json!({"curve": curve, "parameter": t, "target": target, "side": "both",
                         "nearest": true, "methods": methods});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    body
}

pub async fn point_at(app: &TestApp, curve: &Value, t: f64) -> [f64; 2] {
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "parameters": [t]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let point = &body["points"][0];
    [point[0].as_f64().unwrap(), point[1].as_f64().unwrap()]
}

pub fn close(a: [f64; 2], b: [f64; 2]) -> bool {
    let scale = 1.0 + a[0].abs().max(a[1].abs());
    (a[0] - b[0]).hypot(a[1] - b[1]) <= 1e-9 * scale
}

/// Whether `a` and `b` are within `pixels` of each other at `scale` pixels per unit.
pub fn within_pixels(a: [f64; 2], b: [f64; 2], scale: f64, pixels: f64) -> bool {
    (a[0] - b[0]).hypot(a[1] - b[1]) * scale <= pixels
}

/// Pixels around `centre`, nearest first (rings of 8 px, 16 directions).
pub fn around(centre: (i64, i64), rings: std::ops::RangeInclusive<i64>) -> Vec<(i64, i64)> {
    let mut pixels = Vec::new();
    for ring in rings {
        for step in 0..16 {
            let angle = f64::from(step) * std::f64::consts::TAU / 16.0;
            let radius = 8.0 * ring as f64;
            pixels.push((
                centre.0 + (radius * angle.cos()).round() as i64,
                centre.1 + (radius * angle.sin()).round() as i64,
            ));
        }
    }
    pixels
}

/// The target of a drag from the dot at pixel `dot` to pixel `pixel`, as the page computes
/// it: the picked point moved by the pointer's displacement in curve coordinates.
pub async fn drag_target(page: &Page<'_>, dot: (i64, i64), pixel: (i64, i64)) -> [f64; 2] {
    let picked = page.picked().await.expect("a picked point");
    let point = [
        picked["point"][0].as_f64().unwrap(),
        picked["point"][1].as_f64().unwrap(),
    ];
    let (from, to) = (page.to_curve(dot).await, page.to_curve(pixel).await);
    [point[0] + to[0] - from[0], point[1] + to[1] - from[1]]
}

/// A pixel near the dot at `dot` whose drag target a knot pair reaches (inside a region).
pub async fn pixel_inside_a_region(
    page: &Page<'_>,
    app: &TestApp,
    curve: &Value,
    t: f64,
    dot: (i64, i64),
) -> (i64, i64) {
    for pixel in around(dot, 2..=8) {
        let target = drag_target(page, dot, pixel).await;
        let answer = solve(app, curve, t, target, &["knots"]).await;
        if answer["reachable"] == json!(true) {
            return pixel;
        }
    }
    panic!("no pixel near {dot:?} lies inside a region");
}

/// A pixel whose drag target no knot pair reaches, with a nearest reachable point.
pub async fn pixel_outside_every_region(
    page: &Page<'_>,
    app: &TestApp,
    curve: &Value,
    t: f64,
    dot: (i64, i64),
) -> (i64, i64) {
    for pixel in around(dot, 10..=24) {
        let (x, y) = pixel;
        if !(20..700).contains(&x) || !(100..560).contains(&y) {
            continue;
        }
        let target = drag_target(page, dot, pixel).await;
        let answer = solve(app, curve, t, target, &["knots"]).await;
        if answer["reachable"] == json!(false) && answer["nearest"].is_object() {
            return pixel;
        }
    }
    panic!("no pixel near {dot:?} lies outside every region");
}

/// Clicks the curve point at `t` and waits for the pick; returns the picked parameter and
/// the dot's pixel.
pub async fn pick(page: &Page<'_>, app: &TestApp, curve: &Value, t: f64) -> (f64, (i64, i64)) {
    let pixel = page.to_screen(point_at(app, curve, t).await).await;
    page.click_at(pixel).await;
    page.settle().await;
    let Some(picked) = page.picked().await else {
        panic!(
            "no pick after a click on the curve: {}",
            page.describe().await
        );
    };
    let parameter = picked["parameter"].as_f64().unwrap();
    assert!((parameter - t).abs() < 0.02, "picked {picked} near t = {t}");
    (parameter, pixel)
}

/// The family of a solution as the page keeps it (`body[data-family]`): `{method}`, for
/// knots also `family`, `region` and (the envelope's) `side`.
pub fn family_of(solution: &Value) -> Value {
    match solution["method"].as_str().unwrap() {
        "knots" => {
            let mut family = json!({"method": "knots", "family": solution["family"],
                                    "region": solution["region"]});
            if let Some(side) = solution.get("side").filter(|side| !side.is_null()) {
                family["side"] = side.clone();
            }
            family
        }
        method => json!({"method": method}),
    }
}

/// The API's solutions of `family` for the target (or for the nearest reachable point of
/// that family), asked as the page asks once a drag keeps a family: a knot pair whose map
/// folds has several, and the page commits the one its drag followed.
pub async fn solve_family(
    app: &TestApp,
    curve: &Value,
    t: f64,
    target: impl serde::Serialize,
    family: &Value,
) -> Vec<Value> {
    let mut request = json!({"curve": curve, "parameter": t, "target": target, "side": "both",
                             "nearest": true, "methods": [family["method"]]});
    if family["method"] == "knots" {
        request["knot_families"] = json!([family["family"]]);
        if let Some(side) = family.get("side") {
            request["side"] = side.clone();
        }
        if family["region"]
            .as_str()
            .is_some_and(|region| region.starts_with("omega"))
        {
            request["regions"] = json!([family["region"]]);
        }
    }
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    let solutions = body["solutions"].as_array().unwrap();
    let solutions = if solutions.is_empty() {
        body["nearest"]["solutions"].as_array().unwrap()
    } else {
        solutions
    };
    let found: Vec<Value> = solutions
        .iter()
        .filter(|s| family_of(s) == *family)
        .cloned()
        .collect();
    assert!(!found.is_empty(), "no solution of {family}: {body}");
    found
}

/// Asserts that `committed` is `curve` changed by one of `solutions`.
pub fn assert_one_of(committed: &Value, curve: &Value, solutions: &[Value], what: &str) {
    assert!(
        solutions
            .iter()
            .any(|s| numbers(&apply(curve, s)) == numbers(committed)),
        "{what}: the committed curve {committed} is none of {} solutions",
        solutions.len()
    );
}

/// A cubic with `n` control points along a wave, uniform knots (a large curve for the
/// editor's timings and thinning).
pub fn many_poles(n: usize) -> Value {
    let points: Vec<Value> = (0..n)
        .map(|i| {
            let x = i as f64;
            json!([x, 5.0 * (x * 0.3).sin() + 0.001 * x * x])
        })
        .collect();
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
    knots.extend([1.0; 4]);
    json!({"degree": 3, "control_points": points, "knots": knots})
}

/// The worked quintic of the fourth release (`benches/knot_families.rs`): 16 poles, ten
/// interior knots.
pub fn quintic() -> Value {
    let mut knots = vec![0.0; 6];
    knots.extend((0..10).map(|i| ((0.08 + 0.84 * f64::from(i) / 9.0) * 1e4).round() / 1e4));
    knots.extend([1.0; 6]);
    json!({"degree": 5, "control_points": [[0, 0], [1, 1.5], [2, 2.5], [3.2, 3], [4.5, 2.8],
        [5.5, 1.8], [6.3, 0.6], [7.5, 0.2], [8.8, 0.9], [9.8, 2.2], [11, 3], [12.2, 2.6],
        [13, 1.2], [14, 0], [15, 0.5], [16, 2]], "knots": knots})
}

/// The 3D cubic of `benches/knot_families.rs`: a helix-like polygon of eight poles, uniform
/// clamped knots.
pub fn helix() -> Value {
    let points: Vec<Value> = (0..8)
        .map(|i| {
            let a = 0.9 * f64::from(i);
            json!([3.0 * a.cos(), 3.0 * a.sin(), 0.8 * f64::from(i)])
        })
        .collect();
    json!({"degree": 3, "control_points": points,
           "knots": [0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1]})
}

/// Saves a screenshot of the page as `target/<name>`; one `for_docs` also as
/// `docs/pictures/<name>` when `UPDATE_PICTURES` is set (the pictures of README.md and
/// docs/editor.md: `UPDATE_PICTURES=1 cargo test --test editor`).
pub async fn screenshot(client: &fantoccini::Client, name: &str, for_docs: bool) {
    let png = client.screenshot().await.expect("screenshot");
    std::fs::create_dir_all(target_dir()).unwrap();
    std::fs::write(target_dir().join(name), &png).unwrap();
    if for_docs && std::env::var_os("UPDATE_PICTURES").is_some() {
        let docs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/pictures");
        std::fs::write(docs.join(name), &png).unwrap();
    }
}

pub fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target"))
}

/// The 95th percentile (nearest rank) of `values`.
pub fn p95(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let rank = ((0.95 * values.len() as f64).ceil() as usize).clamp(1, values.len());
    values[rank - 1]
}

/// Pastes `curve` into the JSON field and loads it.
pub async fn paste(page: &Page<'_>, curve: &Value) {
    page.run(
        "document.getElementById('curve-json').value = arguments[0];",
        vec![json!(curve.to_string())],
    )
    .await;
    page.click_id("load").await;
    page.settle().await;
    leave_3d(page).await;
}

/// Back to the 2D editor when a space curve or a file opened the 3D view too (these tests
/// edit curves in 2D; tests/editor/space.rs edits them in 3D).
pub async fn leave_3d(page: &Page<'_>) {
    page.wait_until(
        "the 3D view has its objects",
        "document.body.dataset.mode !== '3d' || (window.knotshapeSpace && !window.knotshapeSpace.busy())",
    )
    .await;
    if page.data("mode").await == "3d" {
        page.click_id("view-mode").await;
        page.settle().await;
    }
}
