//! The knot method on every curve in the page (issue 26): the regions of every knot family
//! with a legend per family whose boxes hide them, knot drags that put the point of a
//! quadratic and of a quintic onto their target, a 3D curve edited by knots (the point
//! keeping its z), and a solution list that names each solution's family. Every committed
//! curve is checked against the API's answer for the page's own request, and against the
//! target it must pass through.

use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::regions::{DrawnRegion, drawn_knot_regions, points_inside_rings};
use super::steps::{
    BOTH, assert_one_of, drag_target, helix, numbers, paste, pick, point_at, quintic, sample,
    screenshot, solve, solve_family,
};
use super::third_release::{count, point_of};
use crate::helpers::{TestApp, spawn_app};

/// Unticks the control points (when ticked): every solution is then a knot move.
async fn knots_only(page: &Page<'_>) {
    let ticked = page
        .run(
            "return document.getElementById('method-control-points').checked;",
            vec![],
        )
        .await;
    if ticked == json!(true) {
        page.click_id("method-control-points").await;
        page.settle().await;
    }
    let methods = page
        .run(
            "return [document.getElementById('method-knots').checked, \
             document.getElementById('method-control-points').checked];",
            vec![],
        )
        .await;
    assert_eq!(methods, json!([true, false]));
}

/// The solution list's entries, as shown.
async fn listed(page: &Page<'_>) -> Vec<String> {
    let value = page
        .run(
            "return [...document.querySelectorAll('#solutions li')].map((li) => li.textContent.trim());",
            vec![],
        )
        .await;
    serde_json::from_value(value).unwrap()
}

/// A pixel 25–90 px from the dot whose drag target lies well inside a drawn region (four
/// pixels or more from its edges), and that region.
async fn pixel_in_a_drawn_region(page: &Page<'_>, dot: (i64, i64)) -> ((i64, i64), DrawnRegion) {
    let scale = page.frame().await["scale"].as_f64().unwrap();
    for region in drawn_knot_regions(page).await {
        for p in points_inside_rings(&region.rings, 60, (4.0 / scale).max(2.0 * region.tolerance)) {
            let pixel = page.to_screen(p).await;
            let away = (((pixel.0 - dot.0).pow(2) + (pixel.1 - dot.1).pow(2)) as f64).sqrt();
            if (25.0..90.0).contains(&away) {
                return (pixel, region);
            }
        }
    }
    let regions = drawn_knot_regions(page).await;
    panic!(
        "no drawn region reaches 25–90 px from the dot {dot:?} at scale {scale}: {:?}",
        regions
            .iter()
            .map(|r| (
                &r.family,
                &r.region,
                r.rings.iter().map(Vec::len).collect::<Vec<_>>(),
                r.rings.first().map(|ring| ring[0])
            ))
            .collect::<Vec<_>>()
    );
}

/// Drags the picked point from `dot` to `aim` in three moves and waits for the commit.
async fn drag_to(page: &Page<'_>, dot: (i64, i64), aim: (i64, i64)) {
    let third = |k: i64| {
        (
            dot.0 + (aim.0 - dot.0) * k / 3,
            dot.1 + (aim.1 - dot.1) * k / 3,
        )
    };
    page.drag(dot, &[third(1), third(2), aim]).await;
}

/// `a` and `b` agree to roundoff (relative to their size).
fn same_point(a: &[f64], b: &[f64]) -> bool {
    let scale = 1.0 + b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt()
            <= 1e-9 * scale
}

/// Drags the point at `t` of `curve` (knots only) into one of its drawn regions and checks
/// the commit: only knots moved, the point is on its target, the curve is the kept family's
/// solution, and the message and the list name that family. Returns the kept family.
async fn knot_drag_onto_a_target(
    page: &Page<'_>,
    app: &TestApp,
    curve: &Value,
    t: f64,
    picture: Option<&str>,
    browser: &Browser,
) -> Value {
    paste(page, curve).await;
    knots_only(page).await;
    // Zoomed in about the point (the wheel), so that its regions are some pixels wide.
    let at = page.to_screen(point_at(app, curve, t).await).await;
    page.wheel_at(at, -500).await;
    page.settle().await;
    let (t, dot) = pick(page, app, curve, t).await;
    let (aim, region) = pixel_in_a_drawn_region(page, dot).await;
    let target = drag_target(page, dot, aim).await;
    if let Some(name) = picture {
        // Mid-drag, for the guide: the families' regions, the preview and the list.
        page.press_at(dot).await;
        page.move_to(aim).await;
        page.wait_until(
            "the preview is drawn",
            "document.body.dataset.busy !== 'true' && document.querySelector('#scene .layer-preview .preview') !== null",
        )
        .await;
        screenshot(&browser.client, name, true).await;
        page.release().await;
        page.settle().await;
    } else {
        // One move: the drag keeps the family of its first answer, and a knot family of a
        // curve other than a cubic has no nearest point to follow outside its region.
        page.drag(dot, &[aim]).await;
    }
    let committed = page.curve().await;
    let label = format!("degree {} into {}", curve["degree"], region.region);
    assert_eq!(
        numbers(&committed).2,
        numbers(curve).2,
        "{label}: knots only move"
    );
    assert_ne!(
        numbers(&committed),
        numbers(curve),
        "{label}: the curve changed"
    );
    let sent = page.target_sent().await;
    let scale = page.frame().await["scale"].as_f64().unwrap();
    assert!(
        (sent[0] - target[0]).hypot(sent[1] - target[1]) * scale < 1e-3,
        "{label}: sent {sent:?}, expected {target:?}"
    );
    assert!(
        same_point(&point_of(app, &committed, t).await, &sent),
        "{label}: s(t) is the target {sent:?}; {}",
        page.describe().await
    );
    let family: Value = serde_json::from_str(&page.data("family").await).unwrap();
    assert_eq!(family["method"], "knots", "{label}: {family}");
    let expected = solve_family(app, curve, t, &sent, &family).await;
    assert_one_of(&committed, curve, &expected, &label);
    // The message and the list say which family moved the point.
    let name = family["family"].as_str().unwrap();
    let message = page.data("message").await;
    assert!(
        message.contains(&format!("knots · {}", region_words(&family))),
        "{label}: {message} ({family})"
    );
    let list = listed(page).await;
    assert!(
        list.iter().all(|entry| entry.starts_with("knots · ")),
        "{list:?}"
    );
    assert!(
        list.iter()
            .any(|entry| entry.contains(name) || entry.contains('Ω')),
        "{list:?}"
    );
    family
}

/// A knot family's region in the page's words: "Ω2 (left)", "direct u5,u7",
/// "envelope u6,u9 (right)".
fn region_words(family: &Value) -> String {
    let region = family["region"].as_str().unwrap();
    let name = match region.split_once(':') {
        None => region.replace("omega", "Ω"),
        Some((name, indices)) => {
            let knots: Vec<String> = indices.split(',').map(|k| format!("u{k}")).collect();
            format!("{name} {}", knots.join(","))
        }
    };
    match family.get("side").and_then(Value::as_str) {
        Some(side) => format!("{name} ({side})"),
        None => name,
    }
}

#[tokio::test]
async fn knots_drag_the_points_of_a_quadratic_and_a_quintic_onto_their_targets() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let quadratic = json!({"degree": 2,
        "control_points": [[0, 0], [1.5, 3], [4, 4], [6.5, 3], [8, 0.5], [10, 1]],
        "knots": [0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1]});
    let family = knot_drag_onto_a_target(&page, &app, &quadratic, 0.4, None, &browser).await;
    // A quadratic has the direct pairs only (the envelope needs degree 3).
    assert_eq!(family["family"], "direct", "{family}");
    let notes = page
        .run(
            "return [...document.querySelectorAll('#families .family')].map((row) => \
             [row.dataset.family, row.dataset.pairs, row.querySelector('.family-note').textContent]);",
            vec![],
        )
        .await;
    assert_eq!(notes[0][1], "0", "{notes}");
    assert!(
        notes[0][2].as_str().unwrap().contains("degree 3"),
        "{notes}"
    );
    assert_ne!(notes[1][1], "0", "{notes}");
    knot_drag_onto_a_target(
        &page,
        &app,
        &quintic(),
        0.42,
        Some("editor-families.png"),
        &browser,
    )
    .await;
    // The quintic's envelope pairs are drawn too, a tint of one colour per pair.
    assert!(
        count(&page, "#families [data-family=envelope] .pair-swatch").await > 0
            || count(&page, "#scene path.region[data-family=envelope]").await == 0
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn the_family_legend_hides_and_shows_each_familys_regions() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let drawn = |family: &'static str| {
        let page = &page;
        async move { count(page, &format!("#scene path.region[data-family={family}]")).await }
    };
    pick(&page, &app, &sample(), 0.42).await;
    let (envelope, direct) = (drawn("envelope").await, drawn("direct").await);
    assert!(envelope > 0 && direct > 0, "{envelope} {direct}");
    assert_eq!(count(&page, "#scene polygon.triangle").await, 2);
    // Each family's row: its pairs' colours, and how many pairs are drawn.
    assert_eq!(
        count(&page, "#families [data-family=direct] .pair-swatch").await,
        direct
    );
    assert_eq!(page.data("family").await, "");
    let triples = page
        .run(
            "return document.querySelector('#families [data-family=triples] .family-note').textContent;",
            vec![],
        )
        .await;
    assert!(triples.as_str().unwrap().contains("3D"), "{triples}");

    // The direct pairs' box hides their regions, the envelope's stay; and back.
    page.click_id("family-direct").await;
    assert_eq!(drawn("direct").await, 0);
    assert_eq!(drawn("envelope").await, envelope);
    assert_eq!(
        count(&page, "#families .family.hidden-family").await,
        1,
        "the row says it is hidden"
    );
    page.click_id("family-envelope").await;
    assert_eq!(drawn("envelope").await, 0);
    assert_eq!(count(&page, "#scene polygon.triangle").await, 0);
    assert_eq!(count(&page, "#scene .layer-regions > *").await, 0);
    page.click_id("family-envelope").await;
    assert_eq!(drawn("envelope").await, envelope);
    assert_eq!(drawn("direct").await, 0);
    // The boxes hold for the next pick and the next curve.
    pick(&page, &app, &sample(), 0.3).await;
    assert!(drawn("envelope").await > 0);
    assert_eq!(drawn("direct").await, 0);
    page.click_id("family-direct").await;
    assert!(drawn("direct").await > 0);
    assert_eq!(count(&page, "#families .family.hidden-family").await, 0);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn the_solution_list_names_each_solutions_family() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    // A pixel whose target both an envelope pair and a direct pair reach.
    let mut aim = None;
    'search: for radius in [10.0, 16.0, 24.0, 32.0] {
        for step in 0..24 {
            let angle = f64::from(step) * std::f64::consts::TAU / 24.0;
            let pixel = (
                dot.0 + (radius * angle.cos()).round() as i64,
                dot.1 + (radius * angle.sin()).round() as i64,
            );
            let target = drag_target(&page, dot, pixel).await;
            let answer = solve(&app, &original, t, target, &BOTH).await;
            let families: Vec<&str> = answer["solutions"]
                .as_array()
                .unwrap()
                .iter()
                .filter_map(|s| s["family"].as_str())
                .collect();
            if families.contains(&"envelope") && families.contains(&"direct") {
                aim = Some((pixel, answer));
                break 'search;
            }
        }
    }
    let (aim, answer) = aim.expect("a target both families reach");
    drag_to(&page, dot, aim).await;
    let list = listed(&page).await;
    let solutions = answer["solutions"].as_array().unwrap();
    assert_eq!(list.len(), solutions.len(), "{list:?}");
    // In the API's order; each names its method and, for knots, family and pair.
    for (entry, solution) in list.iter().zip(solutions) {
        let expected = match solution["method"].as_str().unwrap() {
            "knots" => format!(
                "knots · {}",
                region_words(&super::steps::family_of(solution))
            ),
            _ => "control points · poles".to_owned(),
        };
        assert!(entry.starts_with(&expected), "{entry:?} vs {expected:?}");
    }
    assert!(list.iter().any(|entry| entry.starts_with("knots · Ω")));
    assert!(
        list.iter()
            .any(|entry| entry.starts_with("knots · direct u"))
    );
    // A pair whose map folds has several solutions: they are numbered.
    for (entry, solution) in list.iter().zip(solutions) {
        let key = super::steps::family_of(solution);
        let siblings = solutions
            .iter()
            .filter(|s| super::steps::family_of(s) == key)
            .count();
        if siblings > 1 {
            assert!(entry.contains(&format!("of {siblings}")), "{entry}");
        }
    }
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_3d_curve_is_edited_by_knots_its_point_keeping_its_z() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let curve = helix();
    paste(&page, &curve).await;
    knots_only(&page).await;
    let (t, dot) = pick(&page, &app, &curve, 0.45).await;
    let picked = page.picked().await.unwrap();
    let z = picked["point"][2].as_f64().expect("the picked point is 3D");
    // The legend says why no region of this tilted curve is drawn.
    assert_eq!(count(&page, "#scene path.region").await, 0);
    let notes = page
        .run(
            "return [...document.querySelectorAll('#families .family-note')].map((n) => n.textContent);",
            vec![],
        )
        .await;
    assert!(
        notes
            .as_array()
            .unwrap()
            .iter()
            .all(|n| !n.as_str().unwrap().is_empty()),
        "{notes}"
    );
    // A pixel near the dot whose target (its z kept) a knot move reaches.
    let mut aim = None;
    'search: for radius in [6.0, 9.0, 12.0, 16.0, 4.0] {
        for step in 0..16 {
            let angle = f64::from(step) * std::f64::consts::TAU / 16.0;
            let pixel = (
                dot.0 + (radius * angle.cos()).round() as i64,
                dot.1 + (radius * angle.sin()).round() as i64,
            );
            let xy = drag_target(&page, dot, pixel).await;
            let request = json!({"curve": curve, "parameter": t, "target": [xy[0], xy[1], z],
                                 "side": "both", "keep_domain": true, "methods": ["knots"]});
            let (status, body) = app.post_json("/v1/shape/solve", &request).await;
            assert_eq!(status, 200, "{body}");
            if body["reachable"] == json!(true) {
                aim = Some(pixel);
                break 'search;
            }
        }
    }
    let aim = aim.expect("a knot move reaches a target near the point");
    drag_to(&page, dot, aim).await;
    let committed = page.curve().await;
    assert_eq!(numbers(&committed).2, numbers(&curve).2, "knots only move");
    assert_ne!(numbers(&committed), numbers(&curve));
    let sent = page.target_sent().await;
    assert_eq!(sent.len(), 3, "{sent:?}");
    assert_eq!(sent[2], z, "the point keeps its z");
    assert!(
        same_point(&point_of(&app, &committed, t).await, &sent),
        "s(t) is the target {sent:?}: {}",
        page.describe().await
    );
    let family: Value = serde_json::from_str(&page.data("family").await).unwrap();
    assert_eq!(family["method"], "knots", "{family}");
    let expected = solve_family(&app, &curve, t, &sent, &family).await;
    assert_one_of(&committed, &curve, &expected, "the 3D knot drag");
    let message = page.data("message").await;
    assert!(
        message.contains(&format!("knots · {}", region_words(&family))),
        "{message}"
    );
    // The preview of a 3D curve is drawn in the page (no second request per move).
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
