//! The 3D view in Chromium (software WebGL), as a designer uses it: a surface and a space
//! curve shown and orbited (the view changes, the model does not), the standard views, the
//! perspective toggle, pan and zoom; a surface point picked and dragged onto a target in the
//! plane facing the viewer, checked through the page's STEP export read back by the service;
//! Esc, undo and redo; a real surface and a real space curve (from `tests/data`) loaded and
//! edited; a STEP file's surfaces and curves listed together; and drag-to-redraw on a
//! 30 × 30-pole surface within a frame.

use std::io::Read;

use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{p95, screenshot, target_dir};
use super::timing::{main_thread_work, server_time};
use crate::helpers::{TestApp, spawn_app, spawn_app_with};

/// A bicubic of `n × n` poles waved as the page's sample (`sampleSurface` in sample.js).
fn waved_surface(n: usize) -> Value {
    let poles: Vec<Vec<[f64; 3]>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let (x, y) = (i as f64, j as f64);
                    [x, y, 0.6 * (x / 2.0).sin() * (y / 3.0).cos()]
                })
                .collect()
        })
        .collect();
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(|k| k as f64 / (n - 3) as f64));
    knots.extend([1.0; 4]);
    json!({"degree_u": 3, "degree_v": 3, "control_points": poles, "knots_u": knots, "knots_v": knots})
}

/// Waits until the 3D view shows its objects, meshed, and nothing is on its way.
async fn space_settled(page: &Page<'_>) {
    page.wait_until(
        "the 3D view is drawn and idle",
        "document.body.dataset.mode === '3d' && window.knotshapeSpace && !window.knotshapeSpace.busy() \
         && window.knotshapeSpace.shapes().length > 0 \
         && window.knotshapeSpace.shapes().every(s => s.kind === 'curve' || s.triangles > 0)",
    )
    .await;
    // The frame after the last change has been drawn.
    page.run(
        "return new Promise(done => requestAnimationFrame(() => requestAnimationFrame(() => done(true))));",
        vec![],
    )
    .await;
}

/// Pastes `{key: object}` into the JSON field and loads it (a surface or a space curve opens
/// in 3D).
async fn paste_object(page: &Page<'_>, key: &str, object: &Value) {
    page.run(
        "document.getElementById('curve-json').value = arguments[0];",
        vec![json!(json!({ key: object }).to_string())],
    )
    .await;
    page.click_id("load").await;
    space_settled(page).await;
}

async fn shapes(page: &Page<'_>) -> Value {
    page.run(
        "return window.knotshapeSpace.shapes().map(s => s.shape);",
        vec![],
    )
    .await
}

async fn camera(page: &Page<'_>) -> Value {
    page.run("return window.knotshapeSpace.camera();", vec![])
        .await
}

/// The viewport pixel of model point `point`, rounded.
async fn pixel_of(page: &Page<'_>, point: &[f64]) -> (i64, i64) {
    let value = page
        .run(
            "return window.knotshapeSpace.project(arguments[0]);",
            vec![json!(point)],
        )
        .await;
    (
        value[0].as_f64().unwrap().round() as i64,
        value[1].as_f64().unwrap().round() as i64,
    )
}

/// How many of the 3D canvas's pixels are not the white background (what WebGL drew).
async fn drawn_pixels(page: &Page<'_>) -> u64 {
    page.run(
        "window.knotshapeSpace.renderNow(); const c = document.getElementById('space'); const t = document.createElement('canvas'); \
         t.width = c.width; t.height = c.height; const g = t.getContext('2d'); g.drawImage(c, 0, 0); \
         const d = g.getImageData(0, 0, t.width, t.height).data; let n = 0; \
         for (let i = 0; i < d.length; i += 4) if (d[i] < 245 || d[i + 1] < 245 || d[i + 2] < 245) n += 1; \
         return n;",
        vec![],
    )
    .await
    .as_u64()
    .unwrap()
}

/// S(u, v) by the service.
async fn surface_point(app: &TestApp, surface: &Value, parameter: [f64; 2]) -> Vec<f64> {
    let (status, body) = app
        .post_json(
            "/v1/surfaces/evaluate",
            &json!({"surface": surface, "parameters": [parameter]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    floats(&body["points"][0])
}

async fn curve_point(app: &TestApp, curve: &Value, t: f64) -> Vec<f64> {
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "parameters": [t]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    floats(&body["points"][0])
}

fn floats(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Pointer moves from `from` to `to` in `steps` even steps.
fn path(from: (i64, i64), to: (i64, i64), steps: i64) -> Vec<(i64, i64)> {
    (1..=steps)
        .map(|k| {
            (
                from.0 + (to.0 - from.0) * k / steps,
                from.1 + (to.1 - from.1) * k / steps,
            )
        })
        .collect()
}

/// The last committed drag: `{index, parameter, target, solution}`.
async fn last_commit(page: &Page<'_>) -> Value {
    page.run("return window.knotshapeSpace.lastCommit();", vec![])
        .await
}

/// The page's STEP export (every object, edited), read back by the service's import.
async fn exported_step(page: &Page<'_>, app: &TestApp) -> Value {
    page.run(
        "document.getElementById('download').href = ''; return true;",
        vec![],
    )
    .await;
    page.click_id("space-export-step").await;
    page.wait_until(
        "the STEP export is offered",
        "document.getElementById('download').href.startsWith('data:model/step')",
    )
    .await;
    let href = page
        .run("return document.getElementById('download').href;", vec![])
        .await;
    let href = href.as_str().unwrap();
    let encoded = href.split_once(',').unwrap().1;
    let text = percent_decode(encoded);
    assert!(text.starts_with("ISO-10303-21;"), "{}", &text[..40]);
    let (status, body) = app
        .post_json(
            "/v1/curves/import",
            &json!({"format": "step", "data": text}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    body
}

fn percent_decode(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() + 1 {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).unwrap();
            out.push(u8::from_str_radix(hex, 16).unwrap());
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).unwrap()
}

/// The corner of the 3D canvas (background: the fitted model sits in the middle).
async fn background_pixel(page: &Page<'_>) -> (i64, i64) {
    let value = page
        .run(
            "const r = document.getElementById('space').getBoundingClientRect(); return [r.left + 30, r.top + 30];",
            vec![],
        )
        .await;
    (value[0].as_i64().unwrap(), value[1].as_i64().unwrap())
}

#[tokio::test]
async fn the_3d_view_orbits_pans_zooms_and_switches_views_without_changing_the_model() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    page.click_id("surface-sample").await;
    space_settled(&page).await;
    assert!(drawn_pixels(&page).await > 5_000, "WebGL drew the surface");
    let model = shapes(&page).await;
    let before = camera(&page).await;

    // Orbit: a drag on the background turns the view about the focus.
    let corner = background_pixel(&page).await;
    page.drag(corner, &path(corner, (corner.0 + 120, corner.1 + 40), 8))
        .await;
    space_settled(&page).await;
    let orbited = camera(&page).await;
    assert_ne!(
        orbited["position"], before["position"],
        "orbit moved the eye"
    );
    assert_eq!(orbited["target"], before["target"], "orbit keeps the focus");
    assert_eq!(shapes(&page).await, model, "orbit leaves the model alone");

    // Pan with Shift: the focus moves; zoom with the wheel: the eye comes closer.
    page.key_down('\u{E008}').await;
    page.drag(corner, &path(corner, (corner.0 + 60, corner.1), 4))
        .await;
    page.key_up('\u{E008}').await;
    let panned = camera(&page).await;
    assert_ne!(panned["target"], orbited["target"], "Shift + drag pans");
    let centre = pixel_of(&page, &floats(&panned["target"])).await;
    let far = distance(&floats(&panned["position"]), &floats(&panned["target"]));
    page.wheel_at(centre, -400).await;
    space_settled(&page).await;
    let zoomed = camera(&page).await;
    let near = distance(&floats(&zoomed["position"]), &floats(&zoomed["target"]));
    assert!(near < 0.9 * far, "the wheel zooms in: {far} -> {near}");
    // Zoomed in further, the pixel is much smaller: the surface is meshed again, finer.
    let triangles = |page: &Page<'_>| {
        let page = page.client.clone();
        async move {
            page.execute(
                "return window.knotshapeSpace.shapes()[0].triangles;",
                vec![],
            )
            .await
            .unwrap()
            .as_u64()
            .unwrap()
        }
    };
    let coarse = triangles(&page).await;
    for _ in 0..4 {
        page.wheel_at(centre, -600).await;
    }
    page.wait_until(
        "the surface is meshed again",
        &format!("window.knotshapeSpace.shapes()[0].triangles > {coarse}"),
    )
    .await;
    space_settled(&page).await;
    assert!(triangles(&page).await > coarse);

    // Standard views (Shift+5: top) and the orthographic camera (O); F fits again.
    page.key('5', true).await;
    let top = camera(&page).await;
    let eye = floats(&top["position"]);
    let focus = floats(&top["target"]);
    let direction: Vec<f64> = eye.iter().zip(&focus).map(|(e, f)| e - f).collect();
    let length = distance(&eye, &focus);
    assert!(direction[2] / length > 0.999, "top view looks down: {top}");
    page.key('o', false).await;
    assert_eq!(camera(&page).await["perspective"], json!(false));
    page.key('o', false).await;
    assert_eq!(camera(&page).await["perspective"], json!(true));
    page.key('f', false).await;
    assert_eq!(shapes(&page).await, model);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// The iso-lines drawn on a surface stay within the mesh's tolerance of the surface's own
/// iso-curves, with far fewer chords than a fixed count per span: every chord's interior,
/// evaluated by the service at seven parameters, lies within the tolerance of the chord
/// (objects.js `isoSpans` takes the chords per span from a bound on the second derivative).
#[tokio::test]
async fn the_iso_lines_stay_within_the_mesh_tolerance_with_few_chords() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    // Strong waves and uneven knots: some spans need several chords, some one.
    let n = 12;
    let poles: Vec<Vec<[f64; 3]>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let (x, y) = (i as f64, j as f64);
                    [x, y, 2.5 * (x / 1.3).sin() * (y / 2.0).cos() + 0.1 * x]
                })
                .collect()
        })
        .collect();
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(|k| (k as f64 / (n - 3) as f64).powf(1.4)));
    knots.extend([1.0; 4]);
    let surface = json!({"degree_u": 3, "degree_v": 3, "control_points": poles, "knots_u": knots, "knots_v": knots});
    paste_object(&page, "surface", &surface).await;
    space_settled(&page).await;
    let iso = page
        .run("return window.knotshapeSpace.isoLines();", vec![])
        .await;
    let ends = floats(&iso["parameters"]);
    let tolerance = iso["tolerance"].as_f64().unwrap();
    assert!(tolerance > 0.0, "{iso}");
    let chords = ends.len() / 4;
    // Lines at the 10 distinct knots of each direction, 9 spans each: 12 chords per span
    // would be 2 × 10 × 9 × 12.
    let fixed = 2 * 10 * 9 * 12;
    assert!(chords < fixed / 2, "{chords} chords against {fixed}");
    assert!(
        chords > 2 * 10 * 9,
        "some span needs more than one chord: {chords}"
    );
    const INSIDE: usize = 7;
    let mut parameters = Vec::new();
    for chord in ends.chunks(4) {
        for k in 0..=INSIDE + 1 {
            let s = k as f64 / (INSIDE + 1) as f64;
            parameters.push([
                chord[0] + s * (chord[2] - chord[0]),
                chord[1] + s * (chord[3] - chord[1]),
            ]);
        }
    }
    let mut points = Vec::new();
    for batch in parameters.chunks(900) {
        let (status, body) = app
            .post_json(
                "/v1/surfaces/evaluate",
                &json!({"surface": surface, "parameters": batch}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        points.extend(body["points"].as_array().unwrap().iter().map(floats));
    }
    let mut worst = 0.0f64;
    for chord in points.chunks(INSIDE + 2) {
        let (a, b) = (&chord[0], &chord[INSIDE + 1]);
        let ab: Vec<f64> = (0..3).map(|c| b[c] - a[c]).collect();
        let length2: f64 = ab.iter().map(|x| x * x).sum();
        for point in &chord[1..=INSIDE] {
            let ap: Vec<f64> = (0..3).map(|c| point[c] - a[c]).collect();
            let t = if length2 > 0.0 {
                (ap.iter().zip(&ab).map(|(x, y)| x * y).sum::<f64>() / length2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let gap = (0..3)
                .map(|c| (ap[c] - t * ab[c]).powi(2))
                .sum::<f64>()
                .sqrt();
            worst = worst.max(gap);
        }
    }
    assert!(
        worst <= tolerance * (1.0 + 1e-9),
        "a chord is {worst} from its iso-curve, above the tolerance {tolerance}"
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_surface_point_dragged_in_3d_lands_on_its_target_esc_cancels_and_undo_redo() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let surface = waved_surface(6);
    paste_object(&page, "surface", &surface).await;
    let original = shapes(&page).await[0].clone();

    // Esc during a drag: nothing changes.
    let again = pixel_of(&page, &surface_point(&app, &original, [0.45, 0.55]).await).await;
    page.press_at(again).await;
    for pixel in path(again, (again.0 - 50, again.1 + 30), 5) {
        page.move_to(pixel).await;
    }
    // Mid-drag, what the picked point reaches is drawn: the knot families' regions.
    page.wait_until(
        "the regions are drawn",
        "window.knotshapeSpace.regions() !== null",
    )
    .await;
    let regions = page
        .run("return window.knotshapeSpace.regions();", vec![])
        .await;
    assert!(regions["knots"].as_u64().unwrap() > 0, "{regions}");
    page.run("window.knotshapeSpace.renderNow(); return true;", vec![])
        .await;
    screenshot(&browser.client, "editor-3d-surface.png", true).await;
    page.key('\u{E00C}', false).await;
    page.release().await;
    space_settled(&page).await;
    assert_eq!(shapes(&page).await[0], original, "Esc cancels the drag");

    // The cursor shows grab over the surface, not over the background.
    let over = pixel_of(&page, &surface_point(&app, &original, [0.5, 0.5]).await).await;
    page.move_to(over).await;
    page.wait_until(
        "grab over the surface",
        "getComputedStyle(document.getElementById('space')).cursor === 'grab'",
    )
    .await;
    let corner = background_pixel(&page).await;
    page.move_to(corner).await;
    page.wait_until(
        "no grab over the background",
        "getComputedStyle(document.getElementById('space')).cursor === 'crosshair'",
    )
    .await;

    // Press on S(0.45, 0.55) and drag it 60 px right and 40 px up.
    let picked = surface_point(&app, &surface, [0.45, 0.55]).await;
    let at = pixel_of(&page, &picked).await;
    let to = (at.0 + 60, at.1 - 40);
    page.drag(at, &path(at, to, 6)).await;
    space_settled(&page).await;
    let commit = last_commit(&page).await;
    let parameter = [
        commit["parameter"][0].as_f64().unwrap(),
        commit["parameter"][1].as_f64().unwrap(),
    ];
    let target = floats(&commit["target"]);
    // The pick is the surface point under the pointer (within a few pixels of the press).
    let under = surface_point(&app, &original, parameter).await;
    let pixel = pixel_of(&page, &under).await;
    assert!(
        (pixel.0 - at.0).abs() <= 3 && (pixel.1 - at.1).abs() <= 3,
        "picked {pixel:?} for a press at {at:?}"
    );
    // The target is where the pointer was released, on the plane through the pick.
    let released = pixel_of(&page, &target).await;
    assert!(
        (released.0 - to.0).abs() <= 1 && (released.1 - to.1).abs() <= 1,
        "target at {released:?}, released at {to:?}"
    );
    // Read back through the export: the edited surface passes through the target.
    let imported = exported_step(&page, &app).await;
    let mut edited = imported["surfaces"][0].clone();
    edited.as_object_mut().unwrap().remove("source");
    let moved = surface_point(&app, &edited, parameter).await;
    assert!(
        distance(&moved, &target) <= 1e-9 * 7.0,
        "S{parameter:?} = {moved:?}, target {target:?}"
    );
    let committed = shapes(&page).await[0].clone();
    assert_ne!(committed, original);

    // Undo and redo (the toolbar's buttons follow the 3D view's history).
    let undo_enabled = page
        .run("return !document.getElementById('undo').disabled;", vec![])
        .await;
    assert_eq!(undo_enabled, json!(true));
    page.ctrl_z(false).await;
    space_settled(&page).await;
    assert_eq!(shapes(&page).await[0], original, "undo");
    page.ctrl_z(true).await;
    space_settled(&page).await;
    assert_eq!(shapes(&page).await[0], committed, "redo");

    // With Alt held the target moves along the surface normal at the picked point.
    let from = pixel_of(&page, &surface_point(&app, &committed, [0.6, 0.4]).await).await;
    page.key_down('\u{E00A}').await;
    page.drag(from, &path(from, (from.0 + 10, from.1 - 35), 5))
        .await;
    page.key_up('\u{E00A}').await;
    space_settled(&page).await;
    let commit = last_commit(&page).await;
    let parameter = [
        commit["parameter"][0].as_f64().unwrap(),
        commit["parameter"][1].as_f64().unwrap(),
    ];
    let (status, frame) = app
        .post_json(
            "/v1/surfaces/evaluate",
            &json!({"surface": committed, "parameters": [parameter], "normals": true}),
        )
        .await;
    assert_eq!(status, 200, "{frame}");
    let base = floats(&frame["points"][0]);
    let normal = floats(&frame["normals"][0]);
    let offset: Vec<f64> = floats(&commit["target"])
        .iter()
        .zip(&base)
        .map(|(t, b)| t - b)
        .collect();
    let along: f64 = offset.iter().zip(&normal).map(|(o, n)| o * n).sum();
    let length = distance(&offset, &[0.0, 0.0, 0.0]);
    assert!(length > 1e-3, "the Alt drag moved the target: {offset:?}");
    assert!(
        along.abs() >= length * (1.0 - 1e-9),
        "Alt drags along the normal {normal:?}: offset {offset:?}"
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_drag_on_a_large_surface_solves_its_local_piece_as_the_whole_surface_would() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let surface = waved_surface(20);
    paste_object(&page, "surface", &surface).await;
    let at = pixel_of(&page, &surface_point(&app, &surface, [0.52, 0.47]).await).await;
    page.drag(at, &path(at, (at.0 + 30, at.1 - 25), 5)).await;
    space_settled(&page).await;
    let commit = last_commit(&page).await;
    let piece = page
        .run("return window.knotshapeSpace.lastPiece();", vec![])
        .await;
    // A bicubic's piece: 3p + 3 = 12 rows and columns around the span, not the 20.
    let rows = floats(&piece["rows"]);
    let columns = floats(&piece["columns"]);
    assert!(
        rows[1] - rows[0] < 19.0 && columns[1] - columns[0] < 19.0,
        "{piece}"
    );
    // The whole surface solved by the service for the same pick and target: its best
    // solution is the page's committed edit.
    let (status, whole) = app
        .post_json(
            "/v1/surfaces/shape/solve",
            &json!({"surface": surface, "parameter": commit["parameter"], "target": commit["target"],
                    "methods": ["knots", "control_points"], "keep_domain": true}),
        )
        .await;
    assert_eq!(status, 200, "{whole}");
    let best = &whole["solutions"][0];
    assert_eq!(best["method"], commit["solution"]["method"], "{best}");
    let committed = shapes(&page).await[0].clone();
    let field = if best["method"] == "control_points" {
        "control_points"
    } else {
        "knots_u"
    };
    let flat = |value: &Value| -> Vec<f64> {
        let mut out = Vec::new();
        let mut stack = vec![value.clone()];
        while let Some(item) = stack.pop() {
            match item {
                Value::Array(items) => stack.extend(items.into_iter().rev()),
                Value::Number(number) => out.push(number.as_f64().unwrap()),
                _ => {}
            }
        }
        out
    };
    let (page_values, service_values) = (flat(&committed[field]), flat(&best[field]));
    assert_eq!(page_values.len(), service_values.len());
    for (a, b) in page_values.iter().zip(&service_values) {
        assert!(
            (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
            "{field}: {a} vs {b}"
        );
    }
    if field == "control_points" {
        let knots: Vec<f64> = flat(&committed["knots_v"]);
        assert_eq!(knots, flat(&surface["knots_v"]));
    }
    let reached = surface_point(
        &app,
        &committed,
        [
            commit["parameter"][0].as_f64().unwrap(),
            commit["parameter"][1].as_f64().unwrap(),
        ],
    )
    .await;
    assert!(distance(&reached, &floats(&commit["target"])) <= 1e-9 * 20.0);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// The real-model data of `tests/data/<name>` (gzipped JSON).
fn real_data(name: &str) -> Value {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).unwrap())
        .read_to_string(&mut text)
        .unwrap();
    serde_json::from_str(&text).unwrap()
}

#[tokio::test]
async fn a_real_surface_and_a_real_space_curve_load_and_edit_in_3d() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;

    // The first polynomial real surface with at least 6 × 6 poles.
    let data = real_data("real_surfaces.json.gz");
    let face = data["surfaces"]
        .as_array()
        .unwrap()
        .iter()
        .find(|face| {
            face["rational"] == json!(false)
                && face["n_u"].as_u64().unwrap() >= 6
                && face["n_v"].as_u64().unwrap() >= 6
        })
        .expect("a real surface");
    let surface = json!({"degree_u": face["degree_u"], "degree_v": face["degree_v"],
        "control_points": face["poles"], "knots_u": face["knots_u"], "knots_v": face["knots_v"]});
    paste_object(&page, "surface", &surface).await;
    let bounds = floats(&face["bounds"]);
    let parameter = [
        bounds[0] + 0.4 * (bounds[1] - bounds[0]),
        bounds[2] + 0.6 * (bounds[3] - bounds[2]),
    ];
    let at = pixel_of(&page, &surface_point(&app, &surface, parameter).await).await;
    page.drag(at, &path(at, (at.0 + 25, at.1 + 20), 4)).await;
    space_settled(&page).await;
    let commit = last_commit(&page).await;
    assert!(!commit.is_null(), "{} committed", face["id"]);
    let edited = shapes(&page).await[0].clone();
    let reached = surface_point(
        &app,
        &edited,
        [
            commit["parameter"][0].as_f64().unwrap(),
            commit["parameter"][1].as_f64().unwrap(),
        ],
    )
    .await;
    let target = floats(&commit["target"]);
    let size = distance(&floats(&json!(face["poles"][0][0])), &target).max(1e-3);
    assert!(
        distance(&reached, &target) <= 1e-9 * size.max(1.0),
        "{}: {reached:?} vs {target:?}",
        face["id"]
    );

    // A real 3D cubic (not planar), opened from JSON: in 3D, picked and dragged.
    let curves = real_data("real_curves.json.gz");
    let real = curves["curves"]
        .as_array()
        .unwrap()
        .iter()
        .find(|curve| {
            curve["degree"] == json!(3)
                && curve["periodic"] == json!(false)
                && curve["poles"].as_array().unwrap().len() >= 6
                && curve.get("weights").is_none_or(Value::is_null)
                && {
                    let z: Vec<f64> = curve["poles"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|p| p[2].as_f64().unwrap())
                        .collect();
                    z.iter().cloned().fold(f64::MIN, f64::max)
                        - z.iter().cloned().fold(f64::MAX, f64::min)
                        > 1e-3
                }
        })
        .expect("a real space curve");
    let curve = json!({"degree": 3, "control_points": real["poles"], "knots": real["knots"]});
    paste_object(&page, "curve", &curve).await;
    let range = floats(&real["range"]);
    let t = range[0] + 0.45 * (range[1] - range[0]);
    let at = pixel_of(&page, &curve_point(&app, &curve, t).await).await;
    page.drag(at, &path(at, (at.0 + 12, at.1 - 15), 4)).await;
    space_settled(&page).await;
    let commit = last_commit(&page).await;
    assert!(!commit.is_null(), "{} committed", real["id"]);
    let edited = shapes(&page).await[0].clone();
    assert_ne!(edited, curve);
    let reached = curve_point(&app, &edited, commit["parameter"].as_f64().unwrap()).await;
    let target = floats(&commit["target"]);
    assert!(
        distance(&reached, &target) <= 1e-9 * target.iter().map(|x| x.abs()).fold(1.0, f64::max),
        "{}: {reached:?} vs {target:?}",
        real["id"]
    );
    screenshot(&browser.client, "editor-3d-curve.png", true).await;
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

#[tokio::test]
async fn a_step_file_opens_its_surfaces_and_curves_together_in_3d() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let surface = waved_surface(5);
    let curve = json!({"degree": 3, "control_points": [[0, 0, 0], [1, 2, 1], [2, 2, 2], [3, 0, 1], [4, 1, 0]],
        "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]});
    let (status, step) = {
        let response = app
            .post(
                "/v1/curves/export",
                &json!({"format": "step", "curves": [curve], "surfaces": [surface]}),
            )
            .await;
        (response.status().as_u16(), response.text().await.unwrap())
    };
    assert_eq!(status, 200, "{step}");
    let path = target_dir().join("editor-3d-two-objects.step");
    std::fs::create_dir_all(target_dir()).unwrap();
    std::fs::write(&path, &step).unwrap();
    page.client
        .find(fantoccini::Locator::Id("open-file"))
        .await
        .unwrap()
        .send_keys(path.to_str().unwrap())
        .await
        .unwrap();
    space_settled(&page).await;
    let listed = page
        .run(
            "return [...document.querySelectorAll('#space-objects option')].map(o => o.text);",
            vec![],
        )
        .await;
    let listed = listed.as_array().unwrap();
    assert_eq!(listed.len(), 2, "{listed:?}");
    assert!(
        listed[0].as_str().unwrap().contains("surface"),
        "{listed:?}"
    );
    assert!(listed[1].as_str().unwrap().contains("curve"), "{listed:?}");
    // Choosing the curve in the list makes it the one edited.
    page.run(
        "const s = document.getElementById('space-objects'); s.value = '1'; s.dispatchEvent(new Event('change')); return true;",
        vec![],
    )
    .await;
    assert_eq!(
        page.run("return window.knotshapeSpace.selected();", vec![])
            .await,
        json!(1)
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// A frame at 60 Hz, milliseconds.
const FRAME_MS: f64 = 16.0;

/// Pointer moves of the measured 3D drag.
const MOVES_3D: usize = 120;

/// Runs of the 3D drag at most: as in tests/editor/timing.rs, a timing on a machine shared
/// with other work is retried, and the frame budget holds when one run meets it (every run
/// is reported).
const RUNS_3D: usize = 3;

/// What one measured 3D drag gave.
struct Drag3d {
    /// Pointer event to the preview drawn (the WebGL calls done), 95th percentile, ms.
    p95: f64,
    /// The page's part (evaluating the solution at the mesh's parameters and drawing), p95.
    p95_draw: f64,
    previews: usize,
    report: String,
}

/// Drag-to-redraw on a 30 × 30-pole bicubic (knots and control points, the page's default
/// methods for a surface): 120 pointer moves at 60 Hz around the picked point. For every
/// preview the page keeps the pointer event's time, when the preview was drawn (the WebGL
/// calls done, as the 2D editor's preview is in the page when its drawing is) and when that
/// frame was rasterized (the page waits for it right after drawing). Reports the 95th
/// percentiles and their parts in `target/editor-3d-drag-timings.txt` (run alone for
/// numbers: `cargo test --release --test editor drag_to_redraw_in_3d -- --nocapture`).
/// Asserts that a preview was drawn for at least every fourth move and the page's own part
/// within a frame in every build, and in the optimized build (the service's solve is some
/// 10× slower unoptimized) the p95 within a frame, in one of up to three runs.
#[tokio::test]
async fn drag_to_redraw_in_3d_on_a_30_by_30_surface_within_a_frame() {
    let optimized = !cfg!(debug_assertions);
    let mut report = String::new();
    let mut within = false;
    for _ in 0..RUNS_3D {
        let measured = measure_3d_drag().await;
        println!("{}", measured.report);
        report += &measured.report;
        assert!(measured.p95_draw <= FRAME_MS, "{}", measured.report);
        assert!(measured.previews * 4 >= MOVES_3D, "{}", measured.report);
        within = measured.p95 <= FRAME_MS;
        if within || !optimized {
            break;
        }
    }
    std::fs::create_dir_all(target_dir()).unwrap();
    std::fs::write(target_dir().join("editor-3d-drag-timings.txt"), &report).unwrap();
    assert!(
        within || !optimized,
        "not within a frame ({FRAME_MS} ms at p95) in {RUNS_3D} runs:\n{report}"
    );
}

/// One measured drag (drag_to_redraw_in_3d_on_a_30_by_30_surface_within_a_frame).
async fn measure_3d_drag() -> Drag3d {
    // The browser and the service share the machine's cores: one solve thread per request
    // (as in tests/editor/timing.rs).
    let app = spawn_app_with(|config| config.solve_threads = 1).await;
    let browser = Browser::start_alone().await;
    let page = Page::open(&browser.client, &app.address).await;
    let surface = waved_surface(30);
    paste_object(&page, "surface", &surface).await;
    let triangles = page
        .run(
            "return window.knotshapeSpace.shapes()[0].triangles;",
            vec![],
        )
        .await;
    // The browsers of these tests have no GPU: the page must see WebGL drawn in software,
    // where it waits for each preview's raster (scene.js `finishFrame`).
    assert_eq!(
        page.run("return window.knotshapeSpace.software();", vec![])
            .await,
        json!(true),
        "the page did not recognise SwiftShader's WebGL as software"
    );
    let at = pixel_of(&page, &surface_point(&app, &surface, [0.5, 0.5]).await).await;
    let moves: Vec<(i64, i64)> = (0..MOVES_3D)
        .map(|k| {
            let angle = k as f64 / MOVES_3D as f64 * std::f64::consts::TAU;
            (
                at.0 + (30.0 * angle.cos()).round() as i64 - 30 + (k % 2) as i64,
                at.1 + (30.0 * angle.sin()).round() as i64,
            )
        })
        .collect();
    let route = "/v1/surfaces/shape/solve";
    let (seconds_before, count_before) = server_time(&app, route).await;
    super::browser::devtools(&browser.client, "Performance.enable", json!({})).await;
    let work_before = main_thread_work(&browser).await;
    let started = std::time::Instant::now();
    page.drag_paced(at, &moves).await;
    let elapsed_ms = started.elapsed().as_secs_f64() * 1000.0;
    let work_after = main_thread_work(&browser).await;
    space_settled(&page).await;
    let work: Vec<String> = work_before
        .iter()
        .zip(&work_after)
        .map(|((name, before), (_, after))| format!("{name} {:.0}", after - before))
        .collect();
    let (seconds_after, count_after) = server_time(&app, route).await;
    let server_ms =
        1000.0 * (seconds_after - seconds_before) / (count_after - count_before).max(1.0);
    let timings = page
        .run(
            "return window.knotshapeSpace.timings.map(t => [t.drawn - t.stamp, t.sent - t.stamp, \
             t.answered - t.sent, t.drawn - t.answered, t.rasterized - t.stamp, t.handled - t.stamp]);",
            vec![],
        )
        .await;
    let rows: Vec<Vec<f64>> = timings.as_array().unwrap().iter().map(floats).collect();
    let column = |k: usize| rows.iter().map(|row| row[k]).collect::<Vec<f64>>();
    let median = |mut values: Vec<f64>| {
        values.sort_by(f64::total_cmp);
        values[values.len() / 2]
    };
    let p95_total = p95(&mut column(0));
    let p95_wait = p95(&mut column(1));
    let p95_request = p95(&mut column(2));
    let p95_draw = p95(&mut column(3));
    let p95_rasterized = p95(&mut column(4));
    let p95_handled = p95(&mut column(5));
    let size = page
        .run(
            "const c = document.getElementById('space'); return [c.width, c.height];",
            vec![],
        )
        .await;
    let report = format!(
        "3D drag-to-redraw, bicubic 30 x 30 poles ({triangles} triangles), {} previews of \
         {MOVES_3D} moves: p95 {p95_total:.1} ms, median {:.1} ms; to the frame rasterized: \
         p95 {p95_rasterized:.1} ms, median {:.1} ms; p95 of the parts: event to its handler \
         {p95_handled:.1} ms (median {:.1} ms), event to request {p95_wait:.1} ms, request \
         {p95_request:.1} ms (the server's mean {server_ms:.2} ms over {} solves), preview \
         drawn {p95_draw:.1} ms; canvas {size}; the page's main thread over the \
         {elapsed_ms:.0} ms drag: {}\n",
        rows.len(),
        median(column(0)),
        median(column(4)),
        median(column(5)),
        count_after - count_before,
        work.join(", ")
    );
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
    Drag3d {
        p95: p95_total,
        p95_draw,
        previews: rows.len(),
        report,
    }
}
