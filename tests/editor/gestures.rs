//! Gestures on the drawing, with real pointer and key events: a click changes nothing, a
//! press on the curve drags in the same gesture, Esc restores, the cursor says what a press
//! would do, a dragged control point is in the export, and one family of solutions is kept
//! through a drag unless the user switches with a digit key.

use fantoccini::key::Key;
use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{
    BOTH, assert_one_of, drag_target, family_of, numbers, pick, point_at, sample,
    smallest_deviation, solve, solve_family, within_pixels,
};
use crate::helpers::spawn_app;

async fn undo_disabled(page: &Page<'_>) -> bool {
    page.run("return document.getElementById('undo').disabled;", vec![])
        .await
        .as_bool()
        .unwrap()
}

#[tokio::test]
async fn a_click_changes_nothing_and_a_press_on_the_curve_drags_in_one_gesture() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    let (_, dot) = pick(&page, &app, &original, 0.42).await;
    // A click on the dot, one 7 px beside it, and a press that jitters by 2 px: no change.
    page.click_at(dot).await;
    page.settle().await;
    page.click_at((dot.0 + 7, dot.1)).await;
    page.settle().await;
    page.drag(dot, &[(dot.0 + 2, dot.1 - 1), (dot.0 - 1, dot.1 + 1)])
        .await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    assert!(undo_disabled(&page).await, "a click made an undo step");
    assert_eq!(page.data("solutions").await, "0");

    // A fresh page: press on the curve (no pick yet), move, release — one gesture edits.
    let page = Page::open(&browser.client, &app.address).await;
    let on_curve = page.to_screen(point_at(&app, &original, 0.3).await).await;
    let to = (on_curve.0 + 6, on_curve.1 - 14);
    page.drag(on_curve, &[(on_curve.0 + 3, on_curve.1 - 7), to])
        .await;
    let picked = page.picked().await.expect("the press picked");
    let t = picked["parameter"].as_f64().unwrap();
    assert!((t - 0.3).abs() < 0.02, "{picked}");
    let target = page.target().await;
    let committed = page.curve().await;
    assert_ne!(numbers(&committed), numbers(&original));
    let family: Value = serde_json::from_str(&page.data("family").await).unwrap();
    let expected = solve_family(&app, &original, t, target, &family).await;
    assert_one_of(&committed, &original, &expected, "the one-gesture drag");
    // The target is where the pointer went, relative to the press.
    let scale = page.frame().await["scale"].as_f64().unwrap();
    let press = page.to_curve(on_curve).await;
    let release = page.to_curve(to).await;
    let moved = [release[0] - press[0], release[1] - press[1]];
    let start = point_at(&app, &original, t).await;
    assert!(
        within_pixels(
            target,
            [start[0] + moved[0], start[1] + moved[1]],
            scale,
            0.6
        ),
        "{target:?}"
    );
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

fn picked_point(picked: &Value) -> [f64; 2] {
    [
        picked["point"][0].as_f64().unwrap(),
        picked["point"][1].as_f64().unwrap(),
    ]
}

#[tokio::test]
async fn esc_cancels_a_drag_and_the_cursor_says_grab_and_grabbing() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    // Hovering the curve: the grab cursor and a highlighted curve.
    let on_curve = page.to_screen(point_at(&app, &original, 0.42).await).await;
    let width = "return getComputedStyle(document.querySelector('#scene .layer-curve .curve')).strokeWidth;";
    let plain = page.run(width, vec![]).await;
    page.move_to((on_curve.0 - 200, on_curve.1 - 200)).await;
    assert_eq!(
        page.style_at((on_curve.0 - 200, on_curve.1 - 200), "cursor")
            .await,
        "crosshair"
    );
    page.move_to(on_curve).await;
    assert_eq!(page.style_at(on_curve, "cursor").await, "grab");
    let hovered = page.run(width, vec![]).await;
    assert_ne!(hovered, plain, "the hovered curve looks the same");

    let (_, dot) = pick(&page, &app, &original, 0.42).await;
    assert_eq!(page.style_at(dot, "cursor").await, "grab");
    page.press_at(dot).await;
    page.move_to((dot.0 + 9, dot.1 - 9)).await;
    page.move_to((dot.0 + 14, dot.1 - 16)).await;
    page.wait_until(
        "the preview is drawn",
        "document.querySelector('#scene .layer-preview .preview') !== null",
    )
    .await;
    assert_eq!(
        page.style_at((dot.0 + 14, dot.1 - 16), "cursor").await,
        "grabbing"
    );
    page.key(Key::Escape.into(), false).await;
    page.settle().await;
    let preview = "return document.querySelectorAll('#scene .layer-preview > *').length;";
    assert_eq!(page.run(preview, vec![]).await, json!(0));
    page.move_to((dot.0 + 30, dot.1 - 30)).await;
    page.release().await;
    page.settle().await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    assert!(undo_disabled(&page).await);
    assert!(page.data("message").await.contains("cancelled"));
    // The dot is back where it was picked.
    let dot_now = page
        .run(
            "const c = document.querySelector('#scene circle.picked'); return [Number(c.getAttribute('cx')), Number(c.getAttribute('cy'))];",
            vec![],
        )
        .await;
    let picked = picked_point(&page.picked().await.unwrap());
    assert_eq!(dot_now, json!(picked));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_dragged_control_point_is_in_the_export_and_undoes() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    let pole = [8.0, 0.0]; // control point 5 of the sample
    let from = page.to_screen(pole).await;
    assert_eq!(page.style_at(from, "cursor").await, "grab");
    let to = (from.0 + 25, from.1 - 30);
    page.drag(from, &[(from.0 + 10, from.1 - 12), to]).await;
    page.click_id("export").await;
    let exported = page
        .run(
            "return document.getElementById('curve-json').value;",
            vec![],
        )
        .await;
    let exported: Value = serde_json::from_str(exported.as_str().unwrap()).unwrap();
    let moved = page.target().await;
    let scale = page.frame().await["scale"].as_f64().unwrap();
    let (a, b) = (page.to_curve(from).await, page.to_curve(to).await);
    let expected = [pole[0] + b[0] - a[0], pole[1] + b[1] - a[1]];
    assert!(
        within_pixels(moved, expected, scale, 1e-3),
        "{moved:?} vs {expected:?}"
    );
    let mut wanted = original.clone();
    wanted["control_points"][5] = json!(moved);
    assert_eq!(numbers(&exported), numbers(&wanted));
    assert_eq!(numbers(&page.curve().await), numbers(&wanted));
    // The drawn curve is the moved one: its path goes near the new pole's neighbourhood.
    let (_, drawn) = app
        .post_json("/v1/curves/bezier", &json!({"curve": wanted}))
        .await;
    let path = page
        .run(
            "return document.querySelector('#scene .layer-curve .curve').getAttribute('d');",
            vec![],
        )
        .await;
    assert_eq!(path, drawn["svg_path"]);
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// Pixels of a straight path from `dot` along which the API's default choice (smallest
/// deviation, both methods) changes family at least once, with those families.
async fn path_where_the_default_switches(
    page: &Page<'_>,
    app: &crate::helpers::TestApp,
    curve: &Value,
    t: f64,
    dot: (i64, i64),
) -> Vec<(i64, i64)> {
    for direction in 0..16 {
        let angle = f64::from(direction) * std::f64::consts::TAU / 16.0;
        let path: Vec<(i64, i64)> = (3..=24)
            .map(|step| {
                let r = f64::from(step) * 2.0;
                (
                    dot.0 + (r * angle.cos()).round() as i64,
                    dot.1 + (r * angle.sin()).round() as i64,
                )
            })
            .collect();
        let mut families = Vec::new();
        for &pixel in &path {
            let target = drag_target(page, dot, pixel).await;
            let answer = solve(app, curve, t, target, &BOTH).await;
            let solutions = answer["solutions"].as_array().unwrap();
            families.push(family_of(smallest_deviation(solutions)));
        }
        families.dedup();
        if families.len() >= 2 {
            return path;
        }
    }
    panic!("no path from {dot:?} where the default family switches");
}

#[tokio::test]
async fn a_drag_keeps_one_family_unless_a_digit_switches_it() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    let path = path_where_the_default_switches(&page, &app, &original, t, dot).await;

    page.press_at(dot).await;
    for &pixel in &path {
        page.move_to(pixel).await;
        page.wait_until(
            "the move is solved",
            "document.body.dataset.busy !== 'true'",
        )
        .await;
    }
    page.release().await;
    page.settle().await;
    let families = page
        .run("return window.editorTimings.map((t) => t.family);", vec![])
        .await;
    let families: Vec<Value> = families
        .as_array()
        .unwrap()
        .iter()
        .map(|f| serde_json::from_str(f.as_str().unwrap()).unwrap())
        .collect();
    assert!(families.len() >= path.len() / 2, "{families:?}");
    assert!(
        families.iter().all(|f| *f == families[0]),
        "the family switched: {families:?}"
    );
    let target = page.target().await;
    let expected = solve_family(&app, &original, t, target, &families[0]).await;
    assert_one_of(&page.curve().await, &original, &expected, "the kept family");
    page.ctrl_z(false).await;

    // The same drag, switching to the list's second entry with the key 2 halfway.
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    page.press_at(dot).await;
    let half = path.len() / 2;
    for &pixel in &path[..half] {
        page.move_to(pixel).await;
        page.wait_until(
            "the move is solved",
            "document.body.dataset.busy !== 'true'",
        )
        .await;
    }
    let first: Value = serde_json::from_str(&page.data("family").await).unwrap();
    page.key('2', false).await;
    for &pixel in &path[half..] {
        page.move_to(pixel).await;
        page.wait_until(
            "the move is solved",
            "document.body.dataset.busy !== 'true'",
        )
        .await;
    }
    let switched: Value = serde_json::from_str(&page.data("family").await).unwrap();
    assert_ne!(switched, first);
    page.release().await;
    page.settle().await;
    let target = page.target().await;
    let expected = solve_family(&app, &original, t, target, &switched).await;
    assert_one_of(
        &page.curve().await,
        &original,
        &expected,
        "the switched family",
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn control_points_of_any_degree_and_of_3d_curves_drag() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let quadratic = json!({"degree": 2, "control_points": [[0, 0], [2, 4], [5, 4], [7, 0]],
                           "knots": [0, 0, 0, 0.5, 1, 1, 1]});
    let spatial = json!({"degree": 3, "control_points": [[0, 0, 1], [2, 4, 2], [5, 4, 3], [7, 0, 4]],
                         "knots": [0, 0, 0, 0, 1, 1, 1, 1]});
    for curve in [quadratic, spatial] {
        super::steps::paste(&page, &curve).await;
        // Knots move their points too; the page says how a 3D curve is edited.
        let note = page
            .run(
                "return document.getElementById('methods-note').textContent;",
                vec![],
            )
            .await;
        let note = note.as_str().unwrap();
        if curve["control_points"][0].as_array().unwrap().len() == 3 {
            assert!(note.contains("keeps its z"), "{note}");
        } else {
            assert_eq!(note, "");
        }
        let from = page.to_screen([5.0, 4.0]).await;
        let to = (from.0 + 20, from.1 + 25);
        page.drag(from, &[(from.0 + 10, from.1 + 12), to]).await;
        let moved = page.curve().await;
        let (a, b) = (page.to_curve(from).await, page.to_curve(to).await);
        let pole = &moved["control_points"][2];
        let scale = page.frame().await["scale"].as_f64().unwrap();
        let expected = [5.0 + b[0] - a[0], 4.0 + b[1] - a[1]];
        let got = [pole[0].as_f64().unwrap(), pole[1].as_f64().unwrap()];
        assert!(
            within_pixels(got, expected, scale, 1e-3),
            "{got:?} vs {expected:?}"
        );
        if curve["control_points"][2].as_array().unwrap().len() == 3 {
            assert_eq!(pole[2], json!(3), "z is kept");
        }
        for other in [0, 1, 3] {
            assert_eq!(
                moved["control_points"][other],
                curve["control_points"][other]
            );
        }
    }
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
