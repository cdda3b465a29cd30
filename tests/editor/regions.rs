//! The regions the page draws are what solving reaches: every sampled point of every drawn
//! region of every knot family (a pixel or more inside its edge) is reachable by
//! `/v1/shape/solve` (knots, that family, side and pair, the domain kept), and the regions
//! the API describes but the page leaves out reach nothing. Without the knots method, with
//! the layer hidden, or with a family's box unticked, its regions are not drawn.

use serde_json::{Value, json};

use super::browser::Browser;
use super::page::Page;
use super::steps::{pick, point_at, sample};
use crate::helpers::{TestApp, spawn_app};

pub type Polygon = Vec<[f64; 2]>;

/// Whether `point` is inside the region of closed `rings` by the non-zero winding rule (the
/// rule the page fills them with: outer rings counter-clockwise, holes clockwise).
pub fn inside_rings(point: [f64; 2], rings: &[Polygon]) -> bool {
    let mut winding = 0i32;
    for ring in rings {
        for (i, a) in ring.iter().enumerate() {
            let b = ring[(i + 1) % ring.len()];
            let cross = (b[0] - a[0]) * (point[1] - a[1]) - (point[0] - a[0]) * (b[1] - a[1]);
            if a[1] <= point[1] && b[1] > point[1] && cross > 0.0 {
                winding += 1;
            } else if a[1] > point[1] && b[1] <= point[1] && cross < 0.0 {
                winding -= 1;
            }
        }
    }
    winding != 0
}

/// `count` points inside the region of `rings` (non-zero rule) and at least `inset` from
/// every ring's edges, as [`points_inside`] picks them.
pub fn points_inside_rings(rings: &[Polygon], count: usize, inset: f64) -> Vec<[f64; 2]> {
    let all: Polygon = rings.iter().flatten().copied().collect();
    sample_box(&all, count, |p| {
        inside_rings(p, rings) && rings.iter().all(|ring| distance_to_edge(p, ring) >= inset)
    })
}

pub fn inside(point: [f64; 2], polygon: &Polygon) -> bool {
    let mut crossings = false;
    for (i, a) in polygon.iter().enumerate() {
        let b = polygon[(i + polygon.len() - 1) % polygon.len()];
        if (a[1] > point[1]) != (b[1] > point[1])
            && point[0] < a[0] + (point[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
        {
            crossings = !crossings;
        }
    }
    crossings
}

pub fn distance_to_edge(point: [f64; 2], polygon: &Polygon) -> f64 {
    let mut nearest = f64::INFINITY;
    for (i, a) in polygon.iter().enumerate() {
        let b = polygon[(i + polygon.len() - 1) % polygon.len()];
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let length = dx * dx + dy * dy;
        let u = if length > 0.0 {
            (((point[0] - a[0]) * dx + (point[1] - a[1]) * dy) / length).clamp(0.0, 1.0)
        } else {
            0.0
        };
        nearest = nearest.min((a[0] + u * dx - point[0]).hypot(a[1] + u * dy - point[1]));
    }
    nearest
}

/// `count` points inside `polygon` and at least `inset` from its edges, from a fixed
/// pseudo-random sequence over its box. (The page draws a region's edge within half a pixel
/// of the true boundary; a point closer to the edge than that may lie on either side.)
pub fn points_inside(polygon: &Polygon, count: usize, inset: f64) -> Vec<[f64; 2]> {
    sample_box(polygon, count, |p| {
        inside(p, polygon) && distance_to_edge(p, polygon) >= inset
    })
}

/// Up to `count` points of `keep` from a fixed pseudo-random sequence over the box of
/// `points`.
fn sample_box(points: &Polygon, count: usize, keep: impl Fn([f64; 2]) -> bool) -> Vec<[f64; 2]> {
    let (mut low, mut high) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for axis in 0..2 {
            low[axis] = low[axis].min(p[axis]);
            high[axis] = high[axis].max(p[axis]);
        }
    }
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut found = Vec::new();
    for _ in 0..10_000 {
        let p = [
            low[0] + (high[0] - low[0]) * next(),
            low[1] + (high[1] - low[1]) * next(),
        ];
        if keep(p) {
            found.push(p);
            if found.len() == count {
                break;
            }
        }
    }
    found
}

pub fn polygon(value: &Value) -> Polygon {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
        .collect()
}

/// A knot pair's region as the page draws it.
#[derive(Debug)]
pub struct DrawnRegion {
    pub family: String,
    /// The envelope's side ("" for the other families).
    pub side: String,
    pub region: String,
    /// Its closed rings (the first point not repeated), in the curve's coordinates.
    pub rings: Vec<Polygon>,
    /// How far its edges may be from the true boundary (the page asks the direct pairs'
    /// regions within a thousandth of the curve's size at least).
    pub tolerance: f64,
}

/// The knot pairs' regions drawn (each a path of closed rings `M…L…Z`).
pub async fn drawn_knot_regions(page: &Page<'_>) -> Vec<DrawnRegion> {
    let value = page
        .run(
            "return [...document.querySelectorAll('#scene path.region')].map((p) => \
             [p.dataset.family, p.dataset.side || '', p.dataset.region, \
              p.getAttribute('d').split('Z').filter((r) => r.length > 0).map((r) => \
                r.replace('M', '').split('L').map((xy) => xy.split(',').map(Number))), \
              Number(p.dataset.tolerance)]);",
            vec![],
        )
        .await;
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|r| DrawnRegion {
            family: r[0].as_str().unwrap().to_owned(),
            side: r[1].as_str().unwrap().to_owned(),
            region: r[2].as_str().unwrap().to_owned(),
            rings: r[3].as_array().unwrap().iter().map(polygon).collect(),
            tolerance: r[4].as_f64().unwrap(),
        })
        .collect()
}

/// The request that asks for one knot family (and the envelope's side, and a cubic's
/// envelope pair), as the page narrows a drag.
pub fn family_request(curve: &Value, t: f64, target: [f64; 2], region: &DrawnRegion) -> Value {
    let mut request = json!({"curve": curve, "parameter": t, "target": target, "side": "both",
                             "methods": ["knots"], "knot_families": [region.family]});
    if !region.side.is_empty() {
        request["side"] = json!(region.side);
    }
    if region.region.starts_with("omega") {
        request["regions"] = json!([region.region]);
    }
    request
}

/// Whether the region's own pair (and side) solves `target`.
pub fn solved_by(answer: &Value, region: &DrawnRegion) -> bool {
    answer["solutions"].as_array().unwrap().iter().any(|s| {
        s["method"] == "knots"
            && s["family"] == region.family.as_str()
            && s["region"] == region.region.as_str()
            && (region.side.is_empty() || s["side"] == region.side.as_str())
    })
}

async fn reachable(app: &TestApp, t: f64, region: &DrawnRegion, target: [f64; 2]) -> bool {
    let request = family_request(&sample(), t, target, region);
    let (status, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(status, 200, "{body}");
    solved_by(&body, region)
}

#[tokio::test]
async fn every_drawn_region_point_is_reachable_and_only_those_regions_are_drawn() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let mut total_sampled = 0;
    for wanted in [0.42, 0.1, 0.8] {
        // Zoomed in about the point (regions are slivers at some parameters), then picked.
        page.run("document.getElementById('canvas').focus();", vec![])
            .await;
        page.key('f', false).await;
        let at = page
            .to_screen(point_at(&app, &sample(), wanted).await)
            .await;
        page.wheel_at(at, -800).await;
        page.settle().await;
        let (t, _) = pick(&page, &app, &sample(), wanted).await;
        let pixel = 1.0 / page.frame().await["scale"].as_f64().unwrap();
        let regions = drawn_knot_regions(&page).await;
        assert!(!regions.is_empty(), "no region drawn at t = {t}");
        assert!(
            regions.iter().any(|r| r.family == "direct"),
            "t = {t}: no direct pair drawn"
        );
        let mut sampled = 0;
        for region in &regions {
            // A sliver narrower than two pixels has no point a pixel inside its edge.
            let points = points_inside_rings(&region.rings, 6, pixel.max(region.tolerance));
            sampled += usize::from(!points.is_empty());
            for target in points {
                assert!(
                    reachable(&app, t, region, target).await,
                    "t = {t}: {} {} {} drawn, but {target:?} is not reachable",
                    region.family,
                    region.side,
                    region.region
                );
            }
        }
        // Some regions have no inside at all (their polygon has no area); most do.
        assert!(
            sampled >= 1,
            "t = {t}: no region sampled of {}",
            regions.len()
        );
        total_sampled += sampled;
        // What the page left out of every pair's region (keep_domain off) reaches nothing.
        let (_, all) = app
            .post_json(
                "/v1/shape/regions",
                &json!({"curve": sample(), "parameter": t, "side": "both", "keep_domain": false}),
            )
            .await;
        let mut left_out = 0;
        for candidate in all["candidates"].as_array().unwrap() {
            let side = candidate["side"].as_str().unwrap();
            for described in candidate["regions"].as_array().unwrap() {
                let region = described["region"].as_str().unwrap();
                if regions
                    .iter()
                    .any(|r| r.family == "envelope" && r.side == side && r.region == region)
                {
                    continue;
                }
                left_out += 1;
                let pair = DrawnRegion {
                    family: "envelope".to_owned(),
                    side: side.to_owned(),
                    region: region.to_owned(),
                    rings: Vec::new(),
                    tolerance: pixel,
                };
                for target in points_inside(&polygon(&described["polygon"]), 4, pixel) {
                    assert!(
                        !reachable(&app, t, &pair, target).await,
                        "t = {t}: {side} {region} left out, but {target:?} is reachable"
                    );
                }
            }
        }
        if (t - 0.42).abs() < 0.01 {
            // The example: right Ω3, Ω5, Ω6 and left Ω1, Ω4, Ω5 reach nothing.
            assert_eq!(left_out, 6, "{regions:?}");
        }
    }
    assert!(total_sampled >= 8, "{total_sampled} regions sampled");
    browser.close().await;
}

#[tokio::test]
async fn no_regions_without_the_knots_method_or_with_the_layer_hidden() {
    let app = spawn_app().await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let count = "return document.querySelectorAll('#scene .layer-regions > *').length;";
    page.click_id("method-knots").await;
    pick(&page, &app, &sample(), 0.42).await;
    assert_eq!(page.run(count, vec![]).await, json!(0));
    page.click_id("method-knots").await;
    page.settle().await;
    assert!(page.run(count, vec![]).await.as_u64().unwrap() > 0);
    page.click_id("layer-regions").await;
    assert_eq!(page.run(count, vec![]).await, json!(0));
    page.click_id("layer-regions").await;
    assert!(page.run(count, vec![]).await.as_u64().unwrap() > 0);
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}
