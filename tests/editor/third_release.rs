//! The third release in the page: the regions it draws are asked with the solver's methods
//! and fixed control points (every sampled point of a drawn knot-pair or weight region is
//! reachable by solve with the page's own request), the weights method drags and commits a
//! rational curve, curves of other degrees and 3D curves move their points by control
//! points, pins, tangent locks and fixed control points hold on the committed curve
//! (re-evaluated through the API) and are undo steps, and a periodic curve is dragged
//! anywhere, next to its seam too. The toolkit and files in the page: curve_tools.rs.

use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::regions::{Polygon, drawn_knot_regions, points_inside, points_inside_rings, polygon};
use super::steps::{drag_target, numbers, paste, pick, point_at, sample};
use crate::helpers::{TestApp, spawn_app};

/// One drawn region: a knot pair's (its family, the envelope's side or "", its label) or a
/// weight pair's (family "weights", region "weights", the pair's poles), with its rings.
struct Drawn {
    family: String,
    side: String,
    region: String,
    poles: String,
    rings: Vec<Polygon>,
    /// How far its edges may be from the true boundary (0: the request's half pixel).
    tolerance: f64,
}

/// The drawn regions: the knot pairs' paths, then the weight pairs' quadrilaterals.
async fn drawn_regions(page: &Page<'_>) -> Vec<Drawn> {
    let mut drawn: Vec<Drawn> = drawn_knot_regions(page)
        .await
        .into_iter()
        .map(|r| Drawn {
            family: r.family,
            side: r.side,
            region: r.region,
            poles: String::new(),
            rings: r.rings,
            tolerance: r.tolerance,
        })
        .collect();
    let value = page
        .run(
            "return [...document.querySelectorAll('#scene polygon.weight-region')].map((p) => \
             [p.dataset.poles, p.getAttribute('points').split(' ').map((xy) => xy.split(',').map(Number))]);",
            vec![],
        )
        .await;
    drawn.extend(value.as_array().unwrap().iter().map(|r| Drawn {
        family: "weights".to_owned(),
        side: String::new(),
        region: "weights".to_owned(),
        poles: r[0].as_str().unwrap().to_owned(),
        rings: vec![polygon(&r[1])],
        tolerance: 0.0,
    }));
    drawn
}

/// The page's conditions: its constraints (pins, tangent locks) and fixed control points.
struct Conditions<'a> {
    constraints: Value,
    fixed: &'a [usize],
}

/// No pins, tangent locks or fixed control points.
const NONE: Conditions<'static> = Conditions {
    constraints: Value::Null,
    fixed: &[],
};

/// The page's request (methods as ticked, the domain kept, its conditions) for `target`:
/// whether it has a solution of the drawn region's own family (not a nearest one).
async fn solved_by_region(
    app: &TestApp,
    curve: &Value,
    t: f64,
    target: [f64; 2],
    methods: &[&str],
    conditions: &Conditions<'_>,
    drawn: &Drawn,
) -> bool {
    let mut request = json!({"curve": curve, "parameter": t, "target": target, "side": "both",
                             "keep_domain": true, "methods": methods});
    if !conditions.fixed.is_empty() {
        request["fixed_control_points"] = json!(conditions.fixed);
    }
    if !conditions.constraints.is_null() {
        request["constraints"] = conditions.constraints.clone();
    }
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    body["solutions"].as_array().unwrap().iter().any(|s| {
        if drawn.family == "weights" {
            let pair: Vec<String> = s["poles"]
                .as_array()
                .map(|p| p.iter().map(|k| k.to_string()).collect())
                .unwrap_or_default();
            s["method"] == "weights" && pair.join(",") == drawn.poles
        } else {
            s["method"] == "knots"
                && s["family"] == drawn.family.as_str()
                && s["region"] == drawn.region.as_str()
                && (drawn.side.is_empty() || s["side"] == drawn.side.as_str())
        }
    })
}

/// Checks every drawn region: a few points a pixel inside it are solved by its family.
/// Returns how many regions of each kind (knots, weights) were sampled.
async fn check_drawn_regions(
    page: &Page<'_>,
    app: &TestApp,
    t: f64,
    methods: &[&str],
    conditions: &Conditions<'_>,
) -> (usize, usize) {
    let pixel = 1.0 / page.frame().await["scale"].as_f64().unwrap();
    let mut sampled = (0, 0);
    for drawn in drawn_regions(page).await {
        let points = points_inside_rings(&drawn.rings, 4, pixel.max(drawn.tolerance));
        if points.is_empty() {
            continue;
        }
        if drawn.family == "weights" {
            sampled.1 += 1;
        } else {
            sampled.0 += 1;
        }
        for target in points {
            assert!(
                solved_by_region(app, &sample(), t, target, methods, conditions, &drawn).await,
                "t = {t}: {} {} {} {} drawn, but {target:?} is not solved by it",
                drawn.family,
                drawn.side,
                drawn.region,
                drawn.poles
            );
        }
    }
    sampled
}

pub(super) async fn count(page: &Page<'_>, selector: &str) -> u64 {
    page.run(
        "return document.querySelectorAll(arguments[0]).length;",
        vec![json!(selector)],
    )
    .await
    .as_u64()
    .unwrap()
}

#[tokio::test]
async fn drawn_knot_and_weight_regions_are_solved_by_the_pages_own_request() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    page.click_id("method-weights").await;
    page.settle().await;
    let all = ["knots", "control_points", "weights"];
    let (t, _) = pick(&page, &app, &sample(), 0.42).await;
    let (knots, weights) = check_drawn_regions(&page, &app, t, &all, &NONE).await;
    assert!(
        knots >= 3 && weights >= 4,
        "{knots} knot, {weights} weight regions sampled"
    );
    // Poles 2..=5 carry the basis at t = 0.42: six pairs, all drawn.
    assert_eq!(count(&page, "#scene polygon.weight-region").await, 6);

    // Control point 4 fixed with the Pin tool: its pairs are not drawn, the others are still
    // solved with the fixed control point in the request.
    let pole = sample()["control_points"][4].clone();
    let pole = page
        .to_screen([pole[0].as_f64().unwrap(), pole[1].as_f64().unwrap()])
        .await;
    page.click_id("tool-pin").await;
    page.click_at(pole).await;
    page.settle().await;
    assert_eq!(page.data("fixed").await, "[4]");
    assert_eq!(count(&page, "#scene .pole-fixed").await, 1);
    let pairs: Vec<String> = drawn_regions(&page)
        .await
        .into_iter()
        .filter(|r| r.family == "weights")
        .map(|r| r.poles)
        .collect();
    assert_eq!(pairs, ["2,3", "2,5", "3,5"], "pairs without pole 4");
    let fixed = Conditions {
        constraints: Value::Null,
        fixed: &[4],
    };
    let (_, weights) = check_drawn_regions(&page, &app, t, &all, &fixed).await;
    assert!(weights >= 2, "{weights} weight regions sampled");

    // A pin at u = 0.8: every knot-pair edit at t and the pairs with pole 4 or 5 change the
    // curve there (pole 5 acts up to u_9 = 1), so only the pair 2, 3 (up to u_7 = 0.75) is
    // drawn, and solved with the pin in the request.
    let at = page.to_screen(point_at(&app, &sample(), 0.8).await).await;
    page.click_at(at).await;
    page.settle().await;
    let constraints: Value = serde_json::from_str(&page.data("constraints").await).unwrap();
    assert_eq!(
        constraints.as_array().map(Vec::len),
        Some(1),
        "{constraints}: {}",
        page.describe().await
    );
    let pairs: Vec<(String, String)> = drawn_regions(&page)
        .await
        .into_iter()
        .map(|r| (r.region, r.poles))
        .collect();
    assert_eq!(pairs, [("weights".to_owned(), "2,3".to_owned())]);
    let pinned = Conditions {
        constraints,
        fixed: &[4],
    };
    let (_, weights) = check_drawn_regions(&page, &app, t, &all, &pinned).await;
    assert_eq!(weights, 1);
    page.click_id("clear-conditions").await;
    page.settle().await;

    // Weights off: only the knot pairs' regions.
    page.click_id("method-weights").await;
    page.settle().await;
    assert_eq!(count(&page, "#scene polygon.weight-region").await, 0);
    assert!(count(&page, "#scene path.region").await > 0);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// The target of the last edit as the page sent it (2 or 3 coordinates), after checking it
/// is the one the pointer's displacement gives (`expected`, within a thousandth of a pixel).
async fn sent_target(page: &Page<'_>, expected: [f64; 2]) -> Vec<f64> {
    let sent: Vec<f64> = serde_json::from_str(&page.data("target").await).unwrap();
    let scale = page.frame().await["scale"].as_f64().unwrap();
    assert!(
        (sent[0] - expected[0]).hypot(sent[1] - expected[1]) * scale < 1e-3,
        "sent {sent:?}, expected {expected:?}"
    );
    sent
}

/// `curve`'s point at `t` (2 or 3 coordinates) through the API.
pub(super) async fn point_of(app: &TestApp, curve: &Value, t: f64) -> Vec<f64> {
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "parameters": [t]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    serde_json::from_value(body["points"][0].clone()).unwrap()
}

fn assert_close(got: &[f64], expected: &[f64], what: &str) {
    let scale = 1.0 + expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let distance = got
        .iter()
        .zip(expected)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt();
    assert!(
        got.len() == expected.len() && distance <= 1e-9 * scale,
        "{what}: {got:?} vs {expected:?}"
    );
}

#[tokio::test]
async fn the_weights_method_drags_with_a_polyline_preview_and_commits_a_rational_curve() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    page.click_id("method-weights").await;
    page.click_id("method-knots").await;
    page.click_id("method-control-points").await;
    page.settle().await;
    let (t, dot) = pick(&page, &app, &sample(), 0.42).await;
    // A pixel well inside a drawn weight quadrilateral, away from the dot.
    let scale = page.frame().await["scale"].as_f64().unwrap();
    let mut aim = None;
    for drawn in drawn_regions(&page).await {
        assert_eq!(drawn.region, "weights", "only weight regions are drawn");
        for p in points_inside(&drawn.rings[0], 40, 4.0 / scale) {
            let pixel = page.to_screen(p).await;
            let away = ((pixel.0 - dot.0).pow(2) + (pixel.1 - dot.1).pow(2)) as f64;
            if (400.0..6400.0).contains(&away) && aim.is_none() {
                aim = Some(pixel);
            }
        }
    }
    let aim = aim.expect("a weight region reaches 20–80 px from the dot");
    let target = drag_target(&page, dot, aim).await;
    page.press_at(dot).await;
    page.move_to(((dot.0 + aim.0) / 2, (dot.1 + aim.1) / 2))
        .await;
    page.move_to(aim).await;
    // The preview of a weight solution is a polyline (there is no SVG path of a rational curve).
    page.wait_until(
        "a polyline preview",
        "document.querySelector('#scene .layer-preview polyline.preview') !== null",
    )
    .await;
    super::steps::screenshot(&browser.client, "editor-weights.png", true).await;
    page.release().await;
    page.settle().await;
    let committed = page.curve().await;
    let weights = committed["weights"].as_array().expect("a rational curve");
    let changed: Vec<usize> = (0..weights.len())
        .filter(|&k| weights[k].as_f64().unwrap() != 1.0)
        .collect();
    assert_eq!(changed.len(), 2, "two weights change: {weights:?}");
    assert_eq!(numbers(&committed).2, numbers(&sample()).2, "poles stay");
    let target = sent_target(&page, target).await;
    assert_close(
        &point_of(&app, &committed, t).await,
        &target,
        "s(t) is the target",
    );
    assert!(page.data("message").await.contains("weights · poles"));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn points_of_quadratic_and_3d_curves_move_by_control_points_and_polylines_have_no_knots() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    // A polyline's shape does not depend on its knots: the knots box is off, with a note.
    let polyline = json!({"degree": 1, "control_points": [[0, 0], [2, 4], [5, 4], [7, 0]],
                          "knots": [0, 0, 0.3, 0.6, 1, 1]});
    paste(&page, &polyline).await;
    let knots_off = page
        .run(
            "return [document.getElementById('method-knots').disabled, \
             document.getElementById('methods-note').textContent];",
            vec![],
        )
        .await;
    assert_eq!(knots_off[0], json!(true), "{knots_off}");
    assert!(
        knots_off[1].as_str().unwrap().contains("degree 1"),
        "{knots_off}"
    );
    let quadratic = json!({"degree": 2, "control_points": [[0, 0], [2, 4], [5, 4], [7, 0]],
                           "knots": [0, 0, 0, 0.5, 1, 1, 1]});
    let spatial = json!({"degree": 3, "control_points": [[0, 0, 1], [2, 4, 2], [5, 4, 3], [7, 0, 4]],
                         "knots": [0, 0, 0, 0, 1, 1, 1, 1]});
    // The knots move their points too (tests/editor/families.rs); here only the control
    // points are ticked.
    page.click_id("method-knots").await;
    page.settle().await;
    for curve in [quadratic, spatial] {
        paste(&page, &curve).await;
        let knots_on = page
            .run(
                "return document.getElementById('method-knots').disabled;",
                vec![],
            )
            .await;
        assert_eq!(knots_on, json!(false));
        let (t, dot) = pick(&page, &app, &curve, 0.3).await;
        let before = point_of(&app, &curve, t).await;
        let aim = (dot.0 + 18, dot.1 - 22);
        let target = drag_target(&page, dot, aim).await;
        page.drag(dot, &[(dot.0 + 9, dot.1 - 11), aim]).await;
        let committed = page.curve().await;
        assert_ne!(numbers(&committed), numbers(&curve), "the curve changed");
        let sent = sent_target(&page, target).await;
        assert_eq!(sent.len(), before.len());
        if before.len() == 3 {
            assert_eq!(sent[2], before[2], "the point moves in its x–y plane");
        }
        assert_close(&point_of(&app, &committed, t).await, &sent, "s(t)");
        assert!(page.data("message").await.contains("control points"));
    }
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// `curve`'s first derivative at `t` through the API.
async fn tangent_of(app: &TestApp, curve: &Value, t: f64) -> [f64; 2] {
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "parameters": [t], "derivatives": 1}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let d = &body["derivatives"][0][0];
    [d[0].as_f64().unwrap(), d[1].as_f64().unwrap()]
}

#[tokio::test]
async fn pins_tangent_locks_and_fixed_poles_hold_on_the_committed_curve() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    // Pin tool: a click on the curve pins, a click on control point 6 fixes it.
    page.click_id("tool-pin").await;
    let at = page.to_screen(point_at(&app, &original, 0.15).await).await;
    page.click_at(at).await;
    page.settle().await;
    let pole = page.to_screen([9.0, 2.0]).await;
    page.click_at(pole).await;
    page.settle().await;
    // Tangent tool (the key T): a click locks the tangent's direction.
    page.run("document.getElementById('canvas').focus();", vec![])
        .await;
    page.key('t', false).await;
    assert_eq!(page.data("tool").await, "tangent");
    let at = page.to_screen(point_at(&app, &original, 0.7).await).await;
    page.click_at(at).await;
    page.settle().await;
    // A click beside the pin (3 px off) locks the tangent exactly at the pin's parameter.
    let on_pin = page.to_screen(point_at(&app, &original, 0.15).await).await;
    page.click_at((on_pin.0 + 3, on_pin.1)).await;
    page.settle().await;
    let constraints: Value = serde_json::from_str(&page.data("constraints").await).unwrap();
    let list = constraints.as_array().unwrap();
    assert_eq!(list.len(), 3, "{constraints}");
    assert_eq!(list[0]["order"], json!(0));
    for lock in &list[1..] {
        assert_eq!(lock["order"], json!(1));
        assert_eq!(lock["direction_only"], json!(true));
    }
    assert_eq!(
        list[2]["parameter"], list[0]["parameter"],
        "the lock is at the pin"
    );
    assert_eq!(page.data("fixed").await, "[6]");
    assert_eq!(count(&page, "#scene .pin").await, 1);
    assert_eq!(count(&page, "#scene .tangent-lock").await, 2);
    let pin = list[0]["parameter"].as_f64().unwrap();
    let locks = [list[1]["parameter"].as_f64().unwrap(), pin];

    // The edit tool: the fixed pole and a pole under the pin do not move by hand.
    page.key('v', false).await;
    for pole in [[9.0, 2.0], [1.0, 3.0]] {
        let from = page.to_screen(pole).await;
        page.drag(
            from,
            &[(from.0 + 8, from.1 + 8), (from.0 + 20, from.1 + 20)],
        )
        .await;
        assert_eq!(numbers(&page.curve().await), numbers(&original));
    }
    // A drag of the curve point at 0.42 solves the whole curve under the conditions.
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    // Only the regions whose edits leave the conditions alone are drawn, and solve reaches
    // them under the same conditions.
    let conditions = Conditions {
        constraints: constraints.clone(),
        fixed: &[6],
    };
    check_drawn_regions(&page, &app, t, &["knots", "control_points"], &conditions).await;
    // Into a knot-pair region (as drawn without conditions): the conditions rule its
    // solution out, the control-point move under them is committed.
    let aim = super::steps::pixel_inside_a_region(&page, &app, &original, t, dot).await;
    let target = drag_target(&page, dot, aim).await;
    page.drag(dot, &[((dot.0 + aim.0) / 2, (dot.1 + aim.1) / 2), aim])
        .await;
    let committed = page.curve().await;
    super::steps::screenshot(&browser.client, "editor-constraints.png", true).await;
    assert_ne!(
        numbers(&committed),
        numbers(&original),
        "{}",
        page.describe().await
    );
    let target = sent_target(&page, target).await;
    assert_close(&point_of(&app, &committed, t).await, &target, "s(t)");
    assert_close(
        &point_of(&app, &committed, pin).await,
        &point_of(&app, &original, pin).await,
        "the pinned point",
    );
    for lock in locks {
        let (a, b) = (
            tangent_of(&app, &original, lock).await,
            tangent_of(&app, &committed, lock).await,
        );
        let cross = (a[0] * b[1] - a[1] * b[0]) / (a[0].hypot(a[1]) * b[0].hypot(b[1]));
        assert!(
            cross.abs() < 1e-8 && a[0] * b[0] + a[1] * b[1] > 0.0,
            "tangent at {lock}: {a:?} → {b:?}"
        );
    }
    assert_eq!(
        committed["control_points"][6],
        original["control_points"][6]
    );
    // What the conditions ruled out, as the API says for the page's own request, is listed.
    let request = json!({"curve": original, "parameter": t, "target": target, "side": "both",
                         "nearest": true, "methods": ["knots", "control_points"],
                         "constraints": constraints, "fixed_control_points": [6]});
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    let excluded = body["excluded"].as_array().unwrap();
    assert!(!excluded.is_empty(), "{body}");
    let note = page
        .run(
            "return document.getElementById('solutions-note').textContent;",
            vec![],
        )
        .await;
    let note = note.as_str().unwrap();
    assert!(note.contains("Left out under the conditions"), "{note}");
    for dropped in excluded {
        assert!(note.contains(dropped["reason"].as_str().unwrap()), "{note}");
    }

    // Clicking the pin again with the Pin tool removes it; Clear removes the rest.
    page.key('p', false).await;
    let at = page.to_screen(point_at(&app, &committed, pin).await).await;
    page.click_at(at).await;
    page.settle().await;
    assert_eq!(count(&page, "#scene .pin").await, 0);
    page.click_id("clear-conditions").await;
    page.settle().await;
    assert_eq!(page.data("constraints").await, "[]");
    assert_eq!(page.data("fixed").await, "[]");

    // Every change of the conditions is a step of the history: undo takes back the Clear,
    // then the pin's removal, then the drag (its conditions stay), and redo goes forward.
    let conditions = || async {
        let constraints: Value = serde_json::from_str(&page.data("constraints").await).unwrap();
        (
            constraints.as_array().unwrap().len(),
            page.data("fixed").await,
        )
    };
    page.run("document.getElementById('canvas').focus();", vec![])
        .await;
    page.ctrl_z(false).await;
    page.settle().await;
    assert_eq!(
        conditions().await,
        (2, "[6]".to_owned()),
        "the Clear undone"
    );
    assert_eq!(numbers(&page.curve().await), numbers(&committed));
    page.ctrl_z(false).await;
    page.settle().await;
    assert_eq!(conditions().await, (3, "[6]".to_owned()), "the pin is back");
    assert_eq!(count(&page, "#scene .pin").await, 1);
    page.ctrl_z(false).await;
    page.settle().await;
    assert_eq!(
        numbers(&page.curve().await),
        numbers(&original),
        "the drag undone"
    );
    assert_eq!(conditions().await, (3, "[6]".to_owned()));
    page.ctrl_z(true).await;
    page.settle().await;
    assert_eq!(
        numbers(&page.curve().await),
        numbers(&committed),
        "the drag redone"
    );
    page.ctrl_z(true).await;
    page.settle().await;
    assert_eq!(
        conditions().await,
        (2, "[6]".to_owned()),
        "the pin's removal redone"
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// Whether `curve` (periodic) closes: its points at the two ends of the period agree.
async fn closes(app: &TestApp, curve: &Value) -> bool {
    let knots = curve["knots"].as_array().unwrap();
    let (first, last) = (
        knots[0].as_f64().unwrap(),
        knots[knots.len() - 1].as_f64().unwrap(),
    );
    let a = point_of(app, curve, first).await;
    let b = point_of(app, curve, last).await;
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12)
}

#[tokio::test]
async fn a_periodic_curve_is_dragged_anywhere_even_across_its_seam_and_stays_periodic() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let closed = json!({"degree": 3, "periodic": true,
        "control_points": [[2, 0], [1, 1.7], [-1, 1.7], [-2, 0], [-1, -1.7], [1, -1.7]],
        "knots": [0, 0.5, 1, 1.5, 2, 2.5, 3], "multiplicities": [1, 1, 1, 1, 1, 1, 1]});
    // In the middle of the period, and next to its seam (t = 0 = 3) from both sides.
    for t in [1.2, 0.05, 2.95] {
        paste(&page, &closed).await;
        let (t, dot) = pick(&page, &app, &closed, t).await;
        let aim = (dot.0 + 14, dot.1 - 17);
        let target = drag_target(&page, dot, aim).await;
        page.drag(dot, &[(dot.0 + 7, dot.1 - 8), aim]).await;
        let committed = page.curve().await;
        assert_eq!(committed["periodic"], json!(true), "t = {t}: {committed}");
        assert_ne!(
            numbers(&committed),
            numbers(&closed),
            "t = {t}: the curve changed"
        );
        assert!(closes(&app, &committed).await, "t = {t}: {committed}");
        let sent = sent_target(&page, target).await;
        assert_close(&point_of(&app, &committed, t).await, &sent, "s(t)");
    }
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
