//! The toolkit and files in the page: the curvature comb agrees with finite differences of
//! the API's evaluation, "draw by points" interpolates or approximates the clicked points (and
//! undo goes back), and STEP and DXF files open and export through the service.

use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{numbers, sample};
use super::third_release::{count, point_of};
use crate::helpers::{TestApp, spawn_app};

#[tokio::test]
async fn the_curvature_comb_agrees_with_finite_differences() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    assert_eq!(count(&page, "#scene .comb-teeth").await, 0);
    page.click_id("layer-comb").await;
    page.settle().await;
    super::steps::screenshot(&browser.client, "editor-comb.png", true).await;
    let d = page
        .run(
            "const p = document.querySelector('#scene .comb-teeth'); return p ? p.getAttribute('d') : '';",
            vec![],
        )
        .await;
    let numbers: Vec<f64> = d
        .as_str()
        .unwrap()
        .split(['M', 'L', ' '])
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    let teeth: Vec<[f64; 4]> = numbers
        .chunks(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    assert_eq!(teeth.len(), 201);
    // Curvature by central differences of points (h = 1e-4), against each tooth.
    let h = 1e-4;
    let curve = sample();
    let mut ratios = Vec::new();
    for i in [10usize, 30, 50, 70, 90, 110, 130, 150, 170, 190] {
        let u = i as f64 / 200.0;
        let p = |v: f64| point_of(&app, &curve, v);
        let (a, m, b) = (p(u - h).await, p(u).await, p(u + h).await);
        let d1 = [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)];
        let d2 = [
            (b[0] - 2.0 * m[0] + a[0]) / (h * h),
            (b[1] - 2.0 * m[1] + a[1]) / (h * h),
        ];
        let kappa = (d1[0] * d2[1] - d1[1] * d2[0]) / d1[0].hypot(d1[1]).powi(3);
        if kappa.abs() < 0.05 {
            continue; // near an inflection the ratio says nothing
        }
        let [x, y, ex, ey] = teeth[i];
        assert!(
            (x - m[0]).abs() < 1e-9 && (y - m[1]).abs() < 1e-9,
            "tooth {i} starts on the curve"
        );
        let tooth = [ex - x, ey - y];
        let length = tooth[0].hypot(tooth[1]);
        let along = (tooth[0] * d1[0] + tooth[1] * d1[1]) / (length * d1[0].hypot(d1[1]));
        assert!(
            along.abs() < 1e-4,
            "tooth {i} is normal to the curve ({along})"
        );
        let side = d1[0] * tooth[1] - d1[1] * tooth[0];
        assert!(
            side * kappa > 0.0,
            "tooth {i} points to the centre of curvature"
        );
        ratios.push(length / kappa.abs());
    }
    assert!(ratios.len() >= 5, "{ratios:?}");
    for ratio in &ratios {
        assert!(
            (ratio / ratios[0] - 1.0).abs() < 1e-3,
            "teeth in proportion to the curvature: {ratios:?}"
        );
    }
    page.click_id("layer-comb").await;
    assert_eq!(count(&page, "#scene .comb-teeth").await, 0);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// The distance from `point` to `curve` (closest point, through the API).
async fn distance_to(app: &TestApp, curve: &Value, point: [f64; 2]) -> f64 {
    let (status, body) = app
        .post_json(
            "/v1/curves/closest-point",
            &json!({"curve": curve, "points": [point]}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    body["results"][0]["distance"].as_f64().unwrap()
}

/// Clicks `pixels` one by one with the Points tool (key D); returns the points the page
/// took (checked against the pixels clicked, within half a pixel).
async fn click_points(page: &Page<'_>, pixels: &[(i64, i64)]) -> Vec<[f64; 2]> {
    page.run("document.getElementById('canvas').focus();", vec![])
        .await;
    page.key('d', false).await;
    assert_eq!(page.data("tool").await, "points");
    let mut points = Vec::new();
    for &pixel in pixels {
        page.click_at(pixel).await;
        points.push(page.to_curve(pixel).await);
    }
    page.settle().await;
    let taken: Vec<[f64; 2]> = serde_json::from_str(&page.data("sketch").await).unwrap();
    let scale = page.frame().await["scale"].as_f64().unwrap();
    assert_eq!(taken.len(), points.len());
    for (a, b) in taken.iter().zip(&points) {
        assert!(
            (a[0] - b[0]).hypot(a[1] - b[1]) * scale < 0.5,
            "{a:?} vs {b:?}"
        );
    }
    taken
}

#[tokio::test]
async fn draw_by_points_interpolates_or_approximates_and_undo_goes_back() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let corner = page.to_screen([1.0, 0.5]).await;
    let pixels: Vec<(i64, i64)> = [(0, 0), (60, -80), (140, -100), (220, -40), (300, -90)]
        .iter()
        .map(|(dx, dy)| (corner.0 + dx, corner.1 + dy))
        .collect();
    let points = click_points(&page, &pixels).await;
    page.click_id("sketch-finish").await;
    page.settle().await;
    let through = page.curve().await;
    assert_eq!(through["degree"], json!(3));
    for point in &points {
        let distance = distance_to(&app, &through, *point).await;
        assert!(distance < 1e-9, "{point:?} is {distance} from the curve");
    }
    assert_eq!(page.data("sketch").await, "[]");
    assert_eq!(page.data("tool").await, "edit");
    page.ctrl_z(false).await;
    assert_eq!(numbers(&page.curve().await), numbers(&sample()));

    // Twelve points along a gentle wave, within a tolerance: fewer control points.
    let pixels: Vec<(i64, i64)> = (0..12)
        .map(|i| {
            let x = f64::from(i) * 28.0;
            (
                corner.0 + x as i64,
                corner.1 - 60 - (25.0 * (x / 60.0).sin()) as i64,
            )
        })
        .collect();
    let points = click_points(&page, &pixels).await;
    let scale = page.frame().await["scale"].as_f64().unwrap();
    let tolerance = 3.0 / scale; // three pixels
    page.client
        .find(fantoccini::Locator::Id("sketch-tolerance"))
        .await
        .unwrap()
        .send_keys(&format!("{tolerance}"))
        .await
        .unwrap();
    page.key('\u{E007}', false).await; // Enter, in the field
    page.settle().await;
    let near = page.curve().await;
    assert!(
        near["control_points"].as_array().unwrap().len() < points.len(),
        "{near}"
    );
    for point in &points {
        let distance = distance_to(&app, &near, *point).await;
        assert!(
            distance <= tolerance * (1.0 + 1e-9),
            "{point:?} is {distance} from the curve"
        );
    }
    assert!(page.data("message").await.contains("within"));
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

/// The text of the page's download link (a data: URL).
async fn downloaded(page: &Page<'_>) -> String {
    let text = page
        .run(
            "const href = document.getElementById('download').href; \
             return href.startsWith('data:') ? decodeURIComponent(href.slice(href.indexOf(',') + 1)) : '';",
            vec![],
        )
        .await;
    text.as_str().unwrap().to_owned()
}

/// Points of `curve` at eleven parameters over its domain (x and y), through the API.
async fn samples_of(app: &TestApp, curve: &Value) -> Vec<[f64; 2]> {
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "samples": 11}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    body["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
        .collect()
}

/// Writes `text` as `target/<name>` and opens it with the page's file field.
async fn open_file(page: &Page<'_>, name: &str, text: &str) {
    let path = super::steps::target_dir().join(name);
    std::fs::create_dir_all(super::steps::target_dir()).unwrap();
    std::fs::write(&path, text).unwrap();
    page.client
        .find(fantoccini::Locator::Id("open-file"))
        .await
        .unwrap()
        .send_keys(path.to_str().unwrap())
        .await
        .unwrap();
    page.wait_until(
        "the file is read",
        "document.body.dataset.message.startsWith('Opened') || document.body.dataset.error !== ''",
    )
    .await;
    page.settle().await;
    super::steps::leave_3d(page).await;
}

#[tokio::test]
async fn step_and_dxf_files_open_and_export_through_the_service() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    // Export: the STEP file the page offers reads back (through the API) as the sample.
    for format in ["step", "dxf"] {
        page.click_id(&format!("export-{format}")).await;
        page.settle().await;
        let text = downloaded(&page).await;
        let (status, body) = app
            .post_json(
                "/v1/curves/import",
                &json!({"format": format, "data": text}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let curves = body["curves"].as_array().unwrap();
        assert_eq!(curves.len(), 1);
        let mut read = curves[0].clone();
        read.as_object_mut().unwrap().remove("source");
        let (a, b) = (
            samples_of(&app, &read).await,
            samples_of(&app, &sample()).await,
        );
        for (p, q) in a.iter().zip(&b) {
            assert!(
                (p[0] - q[0]).hypot(p[1] - q[1]) < 1e-12,
                "{format}: {p:?} vs {q:?}"
            );
        }
    }

    // A STEP file of two curves: the first is loaded (planar, full knots), the list offers
    // the second.
    let quadratic = json!({"degree": 2, "control_points": [[0, 0], [2, 4], [5, 4], [7, 0]],
                           "knots": [0, 0, 0, 0.5, 1, 1, 1]});
    let response = app
        .post(
            "/v1/curves/export",
            &json!({"format": "step", "curves": [sample(), quadratic]}),
        )
        .await;
    assert_eq!(response.status(), 200);
    let file = response.text().await.unwrap();
    open_file(&page, "editor-two-curves.step", &file).await;
    assert_eq!(numbers(&page.curve().await), numbers(&sample()));
    let options = page
        .run(
            "const s = document.getElementById('imported'); return [s.hidden, s.options.length];",
            vec![],
        )
        .await;
    assert_eq!(options, json!([false, 2]));
    page.client
        .find(fantoccini::Locator::Id("imported"))
        .await
        .unwrap()
        .select_by_value("1")
        .await
        .unwrap();
    page.settle().await;
    assert_eq!(numbers(&page.curve().await), numbers(&quadratic));

    // The DXF file ezdxf wrote (the API's example): its first spline, as the API reads it.
    let example: Value = serde_json::from_str(
        &std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/curves-import-dxf.json"
        ))
        .unwrap(),
    )
    .unwrap();
    let data = example["data"].as_str().unwrap();
    open_file(&page, "editor-example.dxf", data).await;
    let (_, body) = app.post_json("/v1/curves/import", &example).await;
    let mut first = body["curves"][0].clone();
    first.as_object_mut().unwrap().remove("source");
    let (a, b) = (
        samples_of(&app, &page.curve().await).await,
        samples_of(&app, &first).await,
    );
    for (p, q) in a.iter().zip(&b) {
        assert!(
            (p[0] - q[0]).hypot(p[1] - q[1]) < 1e-12,
            "dxf: {p:?} vs {q:?}"
        );
    }
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
