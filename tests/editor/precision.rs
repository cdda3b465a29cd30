//! Precision, with real key and pointer events: arrow keys nudge the target (Shift: ten
//! pixels) in one undo step, typed coordinates move the picked point there, snapping puts the
//! target on the grid or onto a control point (and can be turned off), and the readout shows
//! the pointer's coordinates.

use fantoccini::Locator;
use fantoccini::key::Key;
use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{close, numbers, pick, point_at, sample};
use crate::helpers::spawn_app;

fn point(value: &Value) -> [f64; 2] {
    [value[0].as_f64().unwrap(), value[1].as_f64().unwrap()]
}

#[tokio::test]
async fn arrow_keys_nudge_the_target_and_typed_coordinates_move_the_point() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    // Control points reach any target, so the point lands on it exactly.
    page.click_id("method-knots").await;
    let (t, _) = pick(&page, &app, &original, 0.42).await;
    let start = point(&page.picked().await.unwrap()["point"]);
    let scale = page.frame().await["scale"].as_f64().unwrap();
    let focused = page.run("return document.activeElement.id;", vec![]).await;
    assert_eq!(focused, json!("canvas"), "the press focuses the drawing");
    for _ in 0..3 {
        page.key(Key::Right.into(), false).await;
    }
    page.key(Key::Up.into(), true).await;
    page.settle().await;
    let target = page.target().await;
    let expected = [start[0] + 3.0 / scale, start[1] + 10.0 / scale];
    assert!(close(target, expected), "{target:?} vs {expected:?}");
    let committed = page.curve().await;
    assert!(close(point_at(&app, &committed, t).await, target));
    // The nudges in a row are one undo step.
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));

    // Typed coordinates (Enter in the field).
    let (t, _) = pick(&page, &app, &original, 0.42).await;
    let x = browser.client.find(Locator::Id("target-x")).await.unwrap();
    x.clear().await.unwrap();
    x.send_keys("5.25").await.unwrap();
    let y = browser.client.find(Locator::Id("target-y")).await.unwrap();
    y.clear().await.unwrap();
    y.send_keys(&format!("2.75{}", char::from(Key::Enter)))
        .await
        .unwrap();
    page.settle().await;
    let committed = page.curve().await;
    assert!(
        close(point_at(&app, &committed, t).await, [5.25, 2.75]),
        "{}",
        page.describe().await
    );
    assert_eq!(page.target().await, [5.25, 2.75]);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn snapping_to_the_grid_and_to_control_points_and_the_readout() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    page.click_id("method-knots").await;
    page.click_id("snap-grid").await;
    let (t, dot) = pick(&page, &app, &original, 0.42).await;
    page.drag(dot, &[(dot.0 + 6, dot.1 - 4), (dot.0 + 13, dot.1 - 9)])
        .await;
    let target = page.target().await;
    // The grid step is 1, 2 or 5 times a power of ten; the target is on a grid point.
    let grid = page
        .run(
            "const d = document.querySelector('#scene .layer-grid path').getAttribute('d'); \
             const xs = [...d.matchAll(/M(-?[0-9.e-]+) /g)].map((m) => Number(m[1])); return xs[1] - xs[0];",
            vec![],
        )
        .await
        .as_f64()
        .unwrap();
    for value in target {
        let steps = value / grid;
        assert!(
            (steps - steps.round()).abs() < 1e-6,
            "{target:?} on a grid of {grid}"
        );
    }
    assert!(close(point_at(&app, &page.curve().await, t).await, target));
    page.ctrl_z(false).await;
    page.click_id("snap-grid").await;

    // Control point 5 dragged next to control point 4 lands on it; snapping off, it does not.
    page.click_id("snap-poles").await;
    let (from, beside) = (
        page.to_screen([8.0, 0.0]).await,
        page.to_screen([6.0, 1.0]).await,
    );
    page.drag(
        from,
        &[(from.0 - 20, from.1 - 10), (beside.0 + 4, beside.1 - 3)],
    )
    .await;
    assert_eq!(point(&page.curve().await["control_points"][5]), [6.0, 1.0]);
    page.ctrl_z(false).await;
    page.click_id("snap-poles").await;
    page.drag(
        from,
        &[(from.0 - 20, from.1 - 10), (beside.0 + 4, beside.1 - 3)],
    )
    .await;
    assert_ne!(point(&page.curve().await["control_points"][5]), [6.0, 1.0]);

    // Control point 6 dragged next to the curve's point at the knot 0.75 lands on it.
    page.ctrl_z(false).await;
    page.click_id("snap-knots").await;
    let knot = point_at(&app, &original, 0.75).await;
    let (from, beside) = (page.to_screen([9.0, 2.0]).await, page.to_screen(knot).await);
    page.drag(
        from,
        &[(from.0 - 10, from.1 + 10), (beside.0 - 3, beside.1 + 4)],
    )
    .await;
    assert_eq!(point(&page.curve().await["control_points"][6]), knot);

    // The readout shows the pointer's coordinates.
    let pixel = (beside.0 + 40, beside.1 + 30);
    page.move_to(pixel).await;
    let at = page.to_curve(pixel).await;
    let readout = page
        .run(
            "return document.getElementById('readout').textContent;",
            vec![],
        )
        .await;
    let shown = format!("pointer x {:.2}  y {:.2}", at[0], at[1]);
    assert!(
        readout.as_str().unwrap().contains(&shown),
        "{readout} vs {shown}"
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
