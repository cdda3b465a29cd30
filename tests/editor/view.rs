//! The view, with real wheel, pointer, touch and key events: zoom keeps the point under the
//! cursor (wheel and pinch), the background and Space+drag pan, F and the Fit button fit,
//! loading, undo and redo refit when the curve would leave the view, the drawing follows the
//! window's size, and knot marks and control-point grips thin out when dense.

use fantoccini::key::Key;
use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{many_poles, numbers, paste, point_at, sample, screenshot};
use crate::helpers::spawn_app;

fn scale_of(frame: &Value) -> f64 {
    frame["scale"].as_f64().unwrap()
}

fn distance(a: (i64, i64), b: (f64, f64)) -> f64 {
    (a.0 as f64 - b.0).hypot(a.1 as f64 - b.1)
}

/// The exact (unrounded) pixel of curve point `point`.
async fn pixel_of(page: &Page<'_>, point: [f64; 2]) -> (f64, f64) {
    let value = page
        .run(
            "const m = document.getElementById('scene').getScreenCTM(); \
             const p = new DOMPoint(arguments[0], arguments[1]).matrixTransform(m); return [p.x, p.y];",
            vec![json!(point[0]), json!(point[1])],
        )
        .await;
    (value[0].as_f64().unwrap(), value[1].as_f64().unwrap())
}

/// The canvas's box in viewport pixels: [left, top, right, bottom].
async fn canvas_box(page: &Page<'_>) -> [f64; 4] {
    let value = page
        .run(
            "const r = document.getElementById('canvas').getBoundingClientRect(); \
             return [r.left, r.top, r.right, r.bottom];",
            vec![],
        )
        .await;
    [0, 1, 2, 3].map(|i| value[i].as_f64().unwrap())
}

/// The screen box of the curve's control points: [left, top, right, bottom].
async fn curve_box(page: &Page<'_>, curve: &Value) -> [f64; 4] {
    let mut bounds = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for point in curve["control_points"].as_array().unwrap() {
        let (x, y) = pixel_of(
            page,
            [point[0].as_f64().unwrap(), point[1].as_f64().unwrap()],
        )
        .await;
        bounds = [
            bounds[0].min(x),
            bounds[1].min(y),
            bounds[2].max(x),
            bounds[3].max(y),
        ];
    }
    bounds
}

/// Whether `inner` lies inside `outer` and fills most of it one way (a fitted view).
fn fitted(inner: [f64; 4], outer: [f64; 4]) -> bool {
    let inside = inner[0] >= outer[0]
        && inner[1] >= outer[1]
        && inner[2] <= outer[2]
        && inner[3] <= outer[3];
    let share = ((inner[2] - inner[0]) / (outer[2] - outer[0]))
        .max((inner[3] - inner[1]) / (outer[3] - outer[1]));
    inside && share > 0.8
}

/// A pixel where the drawing shows nothing to grab (the bare canvas).
async fn background_pixel(page: &Page<'_>) -> (i64, i64) {
    let [left, top, right, bottom] = canvas_box(page).await;
    for (fx, fy) in [(0.5, 0.93), (0.2, 0.9), (0.8, 0.1), (0.1, 0.1), (0.9, 0.9)] {
        let pixel = (
            (left + (right - left) * fx) as i64,
            (top + (bottom - top) * fy) as i64,
        );
        let tag = page
            .run(
                "return document.elementFromPoint(arguments[0], arguments[1]).id;",
                vec![json!(pixel.0), json!(pixel.1)],
            )
            .await;
        if tag == json!("canvas") {
            return pixel;
        }
    }
    panic!("no bare background pixel");
}

#[tokio::test]
async fn zoom_keeps_the_point_under_the_cursor_pan_and_fit() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    let point = point_at(&app, &original, 0.6).await;
    let near = pixel_of(&page, point).await;
    let cursor = (near.0 as i64 + 12, near.1 as i64 + 7);
    let under = page.to_curve(cursor).await;
    let before = page.frame().await;
    page.wheel_at(cursor, -300).await;
    page.wait_until(
        "the view zoomed",
        &format!(
            "JSON.parse(document.body.dataset.frame).scale > {}",
            scale_of(&before) * 1.2
        ),
    )
    .await;
    let after = page.frame().await;
    let ratio = scale_of(&after) / scale_of(&before);
    // The curve point under the cursor stays under it; other points move away from it in
    // proportion to the zoom.
    let still = page.to_curve(cursor).await;
    assert!(
        (still[0] - under[0]).hypot(still[1] - under[1]) * scale_of(&after) < 0.5,
        "{under:?} → {still:?}"
    );
    let moved = pixel_of(&page, point).await;
    assert!(
        (distance(cursor, moved) - ratio * distance(cursor, near)).abs() < 0.5,
        "{near:?} → {moved:?} (×{ratio})"
    );
    // Turning back restores the scale.
    page.wheel_at(cursor, 300).await;
    page.wait_until(
        "the view zoomed out",
        &format!(
            "JSON.parse(document.body.dataset.frame).scale < {}",
            scale_of(&after)
        ),
    )
    .await;
    assert!((scale_of(&page.frame().await) / scale_of(&before) - 1.0).abs() < 1e-9);

    // Dragging the background pans by the pointer's displacement; so do Space+drag and the
    // pan tool on the curve itself. The curve never changes.
    let background = background_pixel(&page).await;
    let start = pixel_of(&page, point).await;
    page.drag(
        background,
        &[
            (background.0 + 30, background.1 - 20),
            (background.0 + 60, background.1 - 40),
        ],
    )
    .await;
    let panned = pixel_of(&page, point).await;
    assert!(
        (panned.0 - start.0 - 60.0).abs() < 0.01 && (panned.1 - start.1 + 40.0).abs() < 0.01,
        "{start:?} → {panned:?}"
    );
    let on_curve = (panned.0.round() as i64, panned.1.round() as i64);
    page.key_down(' ').await;
    page.drag(
        on_curve,
        &[
            (on_curve.0 - 20, on_curve.1 + 10),
            (on_curve.0 - 40, on_curve.1 + 20),
        ],
    )
    .await;
    page.key_up(' ').await;
    let spaced = pixel_of(&page, point).await;
    assert!(
        (spaced.0 - panned.0 + 40.0).abs() < 0.01 && (spaced.1 - panned.1 - 20.0).abs() < 0.01,
        "{panned:?} → {spaced:?}"
    );
    page.click_id("tool-pan").await;
    let on_curve = (spaced.0.round() as i64, spaced.1.round() as i64);
    page.drag(on_curve, &[(on_curve.0 + 25, on_curve.1 + 5)])
        .await;
    page.key('v', false).await;
    let tooled = pixel_of(&page, point).await;
    assert!(
        (tooled.0 - spaced.0 - 25.0).abs() < 0.01,
        "{spaced:?} → {tooled:?}"
    );
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    assert!(page.picked().await.is_none(), "panning picked a point");

    // F fits the curve into the view again; so does the button.
    assert!(!fitted(
        curve_box(&page, &original).await,
        canvas_box(&page).await
    ));
    page.run("document.getElementById('canvas').focus();", vec![])
        .await;
    page.key('f', false).await;
    assert!(fitted(
        curve_box(&page, &original).await,
        canvas_box(&page).await
    ));
    page.wheel_at(cursor, -600).await;
    page.settle().await;
    page.click_id("fit").await;
    assert!(fitted(
        curve_box(&page, &original).await,
        canvas_box(&page).await
    ));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_pinch_zooms_about_the_fingers() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let background = background_pixel(&page).await;
    let middle = (background.0, background.1 - 60);
    let under = page.to_curve(middle).await;
    let before = scale_of(&page.frame().await);
    page.pinch(
        ((middle.0 - 20, middle.1), (middle.0 + 20, middle.1)),
        ((middle.0 - 60, middle.1), (middle.0 + 60, middle.1)),
        8,
    )
    .await;
    page.settle().await;
    let after = scale_of(&page.frame().await);
    assert!(
        (after / before - 3.0).abs() < 0.05,
        "pinch ×{}",
        after / before
    );
    let still = page.to_curve(middle).await;
    assert!(
        (still[0] - under[0]).hypot(still[1] - under[1]) * after < 1.0,
        "{under:?} → {still:?}"
    );
    assert_eq!(numbers(&page.curve().await), numbers(&sample()));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn loading_undo_and_redo_refit_the_view_and_dense_marks_thin_out() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let original = sample();
    let large = many_poles(300);
    paste(&page, &large).await;
    assert!(fitted(
        curve_box(&page, &large).await,
        canvas_box(&page).await
    ));

    // 298 distinct knots: the marks drawn are at least 8 px apart, so far fewer; no grips on
    // control points that crowd each other.
    let marks = "const r = [...document.querySelectorAll('#scene .layer-marks rect')].map((e) => e.getBoundingClientRect()); \
                 let gap = Infinity; for (let i = 1; i < r.length; i++) gap = Math.min(gap, Math.hypot(r[i].x - r[i-1].x, r[i].y - r[i-1].y)); \
                 return [r.length, gap, document.querySelectorAll('#scene .pole-grip').length];";
    let fit = page.run(marks, vec![]).await;
    let (count, gap) = (fit[0].as_u64().unwrap(), fit[1].as_f64().unwrap());
    assert!(count < 200 && count > 20, "{fit}");
    assert!(gap >= 7.9, "{fit}");
    assert_eq!(fit[2], json!(0), "{fit}");
    screenshot(&browser.client, "editor-300-poles.png", true).await;
    // Zoomed in 16 times: more marks, still apart, and grips on the control points.
    let [left, top, right, bottom] = canvas_box(&page).await;
    let centre = (((left + right) / 2.0) as i64, ((top + bottom) / 2.0) as i64);
    for _ in 0..4 {
        page.key('+', false).await;
    }
    page.key('+', true).await;
    page.settle().await;
    let zoom = scale_of(&page.frame().await) / page.frame().await["fitted"].as_f64().unwrap();
    assert!(zoom > 2.0, "zoom {zoom}");
    page.wheel_at(centre, -700).await;
    page.settle().await;
    let zoomed = page.run(marks, vec![]).await;
    assert!(zoomed[0].as_u64().unwrap() > count, "{zoomed} vs {fit}");
    assert!(zoomed[1].as_f64().unwrap() >= 7.9, "{zoomed}");
    assert!(zoomed[2].as_u64().unwrap() > 0, "{zoomed}");

    // Undo back to the sample: the view that showed 300 poles is refitted to it; redo too.
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&original));
    assert!(fitted(
        curve_box(&page, &original).await,
        canvas_box(&page).await
    ));
    page.ctrl_z(true).await;
    assert_eq!(numbers(&page.curve().await), numbers(&large));
    assert!(fitted(
        curve_box(&page, &large).await,
        canvas_box(&page).await
    ));

    // The knot strip's label fits its width.
    let label = page
        .run(
            "const t = document.querySelector('#knot-strip .strip-label').getBBox(); \
             const s = document.getElementById('knot-strip').getBoundingClientRect(); return [t.x + t.width, s.width, document.querySelector('#knot-strip .strip-label').textContent];",
            vec![],
        )
        .await;
    assert!(
        label[0].as_f64().unwrap() <= label[1].as_f64().unwrap(),
        "{label}"
    );
    assert!(
        label[2].as_str().unwrap().starts_with("knots (304)"),
        "{label}"
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn the_drawing_follows_the_window_size() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let size = "const c = document.getElementById('canvas'); return [c.clientWidth, c.clientHeight, c.viewBox.baseVal.width, c.viewBox.baseVal.height, window.innerWidth];";
    let wide = page.run(size, vec![]).await;
    assert!(
        wide[0].as_f64().unwrap() > wide[4].as_f64().unwrap() - 420.0,
        "{wide}"
    );
    assert_eq!(wide[0], wide[2]);
    assert_eq!(wide[1], wide[3]);
    browser.client.set_window_size(900, 700).await.unwrap();
    page.wait_until(
        "the drawing shrinks",
        &format!(
            "document.getElementById('canvas').clientWidth < {}",
            wide[0].as_f64().unwrap() - 200.0
        ),
    )
    .await;
    let narrow = page.run(size, vec![]).await;
    assert_eq!(narrow[0], narrow[2], "{narrow}");
    assert_eq!(narrow[1], narrow[3], "{narrow}");
    // The curve is still in view (the centre stays); F fits it to the new size.
    page.run("document.getElementById('canvas').focus();", vec![])
        .await;
    page.key('f', false).await;
    assert!(fitted(
        curve_box(&page, &sample()).await,
        canvas_box(&page).await
    ));
    page.key(Key::Escape.into(), false).await;
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
