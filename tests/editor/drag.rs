//! The editor in Chromium, as a designer uses it: pick a point of the sample, drag it into
//! a region and outside every region, undo and redo, and edit a single Bézier piece (knots
//! inserted first, as part of the edit). Each committed curve is checked against what the
//! API answers for the same request, and against the target it must pass through.

use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{
    BOTH, apply, close, drag_target, numbers, paste, pick, pixel_inside_a_region,
    pixel_outside_every_region, point_at, sample, screenshot, smallest_deviation, solve,
    within_pixels,
};
use crate::helpers::spawn_app;

/// The page's target, checked to be `expected` (computed by the test from the pixels) up to
/// roundoff.
async fn same_target(page: &Page<'_>, expected: [f64; 2]) -> [f64; 2] {
    let target = page.target().await;
    let scale = page.frame().await["scale"].as_f64().unwrap();
    assert!(
        within_pixels(target, expected, scale, 1e-3),
        "{target:?} vs {expected:?}"
    );
    target
}

#[tokio::test]
async fn pick_drag_into_a_region_commit_undo_redo_and_drag_outside_onto_nearest() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    let original = sample();
    assert_eq!(numbers(&page.curve().await), numbers(&original));

    // Zoomed in about the point (the wheel), then picked: the envelope's regions of both
    // sides appear, with the control triangles, and the direct pairs' regions, with a legend
    // of each family (the envelope's Ω colours, a tint per direct pair).
    let at = page.to_screen(point_at(&app, &original, 0.42).await).await;
    page.wheel_at(at, -350).await;
    page.settle().await;
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    let drawn = page
        .run(
            "return [document.querySelectorAll('#scene path.region[data-side=left]').length, \
             document.querySelectorAll('#scene path.region[data-side=right]').length, \
             document.querySelectorAll('#scene polygon.triangle').length, \
             document.querySelectorAll('#families [data-family=envelope] .pair-swatch').length, \
             document.querySelectorAll('#scene path.region[data-family=direct]').length, \
             document.querySelectorAll('#families [data-family=direct] .pair-swatch').length];",
            vec![],
        )
        .await;
    assert!(
        drawn[0].as_u64().unwrap() > 0 && drawn[1].as_u64().unwrap() > 0,
        "{drawn}"
    );
    assert_eq!(drawn[2], json!(2), "{drawn}");
    // Right Ω1, Ω2, Ω4 and left Ω2, Ω3, Ω6: five colours.
    assert_eq!(drawn[3], json!(5), "{drawn}");
    assert!(drawn[4].as_u64().unwrap() > 0, "{drawn}");
    assert_eq!(drawn[4], drawn[5], "{drawn}");

    // Drag into a region in one move: the committed curve is the API's smallest-deviation
    // solution for the same request, and passes through the target.
    let inside = pixel_inside_a_region(&page, &app, &original, t, dot).await;
    let target = drag_target(&page, dot, inside).await;
    page.press_at(dot).await;
    page.move_to(inside).await;
    page.wait_until(
        "the preview is drawn",
        "document.body.dataset.busy !== 'true' && document.querySelector('#scene .layer-preview .preview') !== null",
    )
    .await;
    screenshot(&browser.client, "editor.png", true).await;
    page.release().await;
    page.settle().await;
    // The page's target is the pointer's displacement added to the picked point.
    let target = same_target(&page, target).await;
    let committed = page.curve().await;
    let answer = solve(&app, &original, t, target, &BOTH).await;
    let solutions = answer["solutions"].as_array().unwrap();
    let expected = apply(&original, smallest_deviation(solutions));
    assert_eq!(
        numbers(&committed),
        numbers(&expected),
        "{}",
        page.describe().await
    );
    let through = point_at(&app, &committed, t).await;
    assert!(close(through, target), "{through:?} vs target {target:?}");
    assert_eq!(
        page.data("solutions").await.parse::<usize>().unwrap(),
        solutions.len()
    );
    // Another solution from the list replaces the commit (the list is in the API's order).
    let committed = match solutions
        .iter()
        .position(|s| apply(&original, s) != expected)
    {
        Some(other) => {
            page.client
                .find(fantoccini::Locator::Css(&format!(
                    "#solutions input[name=solution][value='{other}']"
                )))
                .await
                .expect("the other solution's radio button")
                .click()
                .await
                .unwrap();
            page.settle().await;
            let chosen = page.curve().await;
            assert_eq!(
                numbers(&chosen),
                numbers(&apply(&original, &solutions[other]))
            );
            assert!(close(point_at(&app, &chosen, t).await, target));
            chosen
        }
        None => committed,
    };

    // Undo (Ctrl+Z) restores the original, redo (Ctrl+Shift+Z) the edit, the button undoes.
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    page.ctrl_z(true).await;
    assert_eq!(numbers(&page.curve().await), numbers(&committed));
    page.click_id("undo").await;
    page.settle().await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));

    // Outside every region (knots only: the control-point move reaches any target, so the
    // API gives `nearest` only without it): the point lands on the nearest reachable point.
    page.click_id("sample").await;
    page.settle().await;
    page.click_id("method-control-points").await;
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    let outside = pixel_outside_every_region(&page, &app, &original, t, dot).await;
    let target = drag_target(&page, dot, outside).await;
    page.drag(dot, &[outside]).await;
    let target = same_target(&page, target).await;
    let committed = page.curve().await;
    let answer = solve(&app, &original, t, target, &["knots"]).await;
    let nearest = &answer["nearest"];
    let nearest_point = [
        nearest["point"][0].as_f64().unwrap(),
        nearest["point"][1].as_f64().unwrap(),
    ];
    let expected = apply(
        &original,
        smallest_deviation(nearest["solutions"].as_array().unwrap()),
    );
    assert_eq!(
        numbers(&committed),
        numbers(&expected),
        "{}",
        page.describe().await
    );
    let through = point_at(&app, &committed, t).await;
    assert!(
        close(through, nearest_point),
        "{through:?} vs nearest {nearest_point:?}"
    );

    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_single_bezier_gets_knots_inserted_and_then_drags() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    page.click_id("bezier-sample").await;
    page.settle().await;
    let bezier = page.curve().await;
    assert_eq!(
        numbers(&bezier).1,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
    );

    let (t, dot) = pick(&page, &app, &bezier, 0.5).await;
    let message = page.data("message").await;
    assert!(message.contains("inserted knots"), "message: {message}");
    // The pick inserted knots into the curve being edited, not into the history: a click
    // changes nothing.
    assert_eq!(numbers(&page.curve().await), numbers(&bezier));
    let refined = page.edited().await;
    assert!(numbers(&refined).1.len() > 8, "{refined}");
    for u in [0.1, 0.3, 0.5, 0.77, 0.95] {
        let (before, after) = (
            point_at(&app, &bezier, u).await,
            point_at(&app, &refined, u).await,
        );
        assert!(
            close(before, after),
            "knot insertion changed the shape at {u}"
        );
    }

    let inside = pixel_inside_a_region(&page, &app, &refined, t, dot).await;
    let target = drag_target(&page, dot, inside).await;
    page.press_at(dot).await;
    page.move_to(inside).await;
    page.wait_until(
        "the preview is drawn",
        "document.body.dataset.busy !== 'true' && document.querySelector('#scene .layer-preview .preview') !== null",
    )
    .await;
    screenshot(&browser.client, "editor-bezier.png", false).await;
    page.release().await;
    page.settle().await;
    let target = same_target(&page, target).await;
    let committed = page.curve().await;
    let answer = solve(&app, &refined, t, target, &BOTH).await;
    let expected = apply(
        &refined,
        smallest_deviation(answer["solutions"].as_array().unwrap()),
    );
    assert_eq!(
        numbers(&committed),
        numbers(&expected),
        "{}",
        page.describe().await
    );
    assert!(close(point_at(&app, &committed, t).await, target));
    assert_ne!(numbers(&committed), numbers(&refined));

    // One undo takes back the drag and the insertion it needed.
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&bezier));

    // A pasted rational curve in the trimmed (openNURBS) convention: drawn as a certified
    // polyline, exported as it is.
    let rational = json!({"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]],
                          "knots": [0, 0, 0, 0.5, 1, 1, 1], "weights": [1, 1, 2, 1, 1]});
    paste(&page, &rational).await;
    assert_eq!(numbers(&page.curve().await), numbers(&rational));
    let polyline = page
        .run(
            "return document.querySelectorAll('#scene polyline.curve').length;",
            vec![],
        )
        .await;
    assert_eq!(polyline, json!(1));
    page.click_id("export").await;
    let exported = page
        .run(
            "return document.getElementById('curve-json').value;",
            vec![],
        )
        .await;
    let exported: Value = serde_json::from_str(exported.as_str().unwrap()).unwrap();
    assert_eq!(numbers(&exported), numbers(&rational));

    // A 3D curve: shown in projection, the knots on, with a note saying how it is edited; a
    // click picks its point (moving it is in the `families` and `third_release` tests).
    let spatial = json!({"degree": 3, "control_points": [[0, 0, 0], [1, 2, 1], [3, 2, 2], [4, 0, 3]],
                         "knots": [0, 0, 0, 0, 1, 1, 1, 1]});
    paste(&page, &spatial).await;
    assert!(page.data("message").await.contains("3D"));
    let pixel = page.to_screen(point_at(&app, &spatial, 0.5).await).await;
    page.click_at(pixel).await;
    page.settle().await;
    let picked = page.picked().await.expect("a 3D curve's point is picked");
    assert_eq!(picked["point"].as_array().unwrap().len(), 3, "{picked}");
    let knots_off = page
        .run(
            "return [document.getElementById('method-knots').disabled, \
             document.getElementById('methods-note').textContent];",
            vec![],
        )
        .await;
    assert_eq!(knots_off[0], json!(false), "{knots_off}");
    assert!(
        knots_off[1].as_str().unwrap().contains("keeps its z"),
        "{knots_off}"
    );

    // Broken JSON and a curve the API refuses: readable messages, the page keeps working.
    page.run(
        "document.getElementById('curve-json').value = '{not json';",
        vec![],
    )
    .await;
    page.click_id("load").await;
    assert!(page.data("error").await.contains("not JSON"));
    paste(
        &page,
        &json!({"degree": 3, "control_points": [[0, 0], [1, 1]], "knots": [0, 1]}),
    )
    .await;
    let error = page.data("error").await;
    assert!(
        error.contains("Cannot load this curve: line 1, column ")
            && error.contains("(/control_points)"),
        "{error}"
    );
    assert_eq!(numbers(&page.curve().await), numbers(&spatial));

    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
