//! `/v1/shape/regions` under `constraints`: the knot-pair regions and weight quadrilaterals
//! drawn are only those whose edits surely keep every constraint. Checked from both sides on
//! a 14-pole cubic: every drawn region's inner points are reached by membership or solve
//! with the same constraints, and every region left out moves the constrained quantity when
//! solved without them (re-evaluated by the test's own de Boor and finite differences).

use serde_json::{Value, json};

use crate::constraints::{derivative, inside, segment_distance, solution_curve};
use crate::helpers::{numbers, points, spawn_app};
use crate::reference::{ReferenceCurve, distance};

/// A cubic of 14 poles over the knots 0, 1, …, 11 (clamped): every knot-pair edit at
/// t = 5.5 changes only part of it.
fn long_cubic() -> ReferenceCurve {
    let mut knots = vec![0.0; 4];
    knots.extend((1..=10).map(f64::from));
    knots.extend([11.0; 4]);
    ReferenceCurve {
        degree: 3,
        points: (0..14)
            .map(|i| {
                let x = f64::from(i);
                vec![x, 2.0 * (0.7 * x).sin() + 0.1 * x]
            })
            .collect(),
        knots,
        weights: None,
    }
}

const T: f64 = 5.5;

async fn regions(
    app: &crate::helpers::TestApp,
    curve: &ReferenceCurve,
    constraints: &Value,
) -> Value {
    let request = json!({"curve": curve.to_json(false), "parameter": T,
                         "methods": ["knots", "weights"], "constraints": constraints});
    let (status, body) = app.post_json("/v1/shape/regions", &request).await;
    assert_eq!(status, 200, "{body}");
    body
}

/// (side, region) of every drawn knot region, with its polygon.
fn knot_regions(answer: &Value) -> Vec<(String, String, Vec<Vec<f64>>)> {
    let mut drawn = Vec::new();
    for candidate in answer["candidates"].as_array().unwrap() {
        for region in candidate["regions"].as_array().unwrap() {
            drawn.push((
                candidate["side"].as_str().unwrap().to_owned(),
                region["region"].as_str().unwrap().to_owned(),
                points(&region["polygon"]),
            ));
        }
    }
    drawn
}

/// The poles of every drawn weight quadrilateral, with its polygon.
fn weight_regions(answer: &Value) -> Vec<(Vec<f64>, Vec<Vec<f64>>)> {
    answer["weight_regions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (numbers(&r["poles"]), points(&r["polygon"])))
        .collect()
}

/// Up to `most` points well inside `polygon` (its vertex average and midpoints of vertex
/// pairs, away from its edges), spread over the candidates.
fn inner_points(polygon: &[Vec<f64>], most: usize) -> Vec<[f64; 2]> {
    let extent = polygon
        .iter()
        .flat_map(|p| polygon.iter().map(move |q| distance(p, q)))
        .fold(0.0, f64::max);
    let count = polygon.len() as f64;
    let mut candidates = vec![[
        polygon.iter().map(|p| p[0]).sum::<f64>() / count,
        polygon.iter().map(|p| p[1]).sum::<f64>() / count,
    ]];
    for i in 0..polygon.len() {
        for j in i + 1..polygon.len() {
            candidates.push([
                0.5 * (polygon[i][0] + polygon[j][0]),
                0.5 * (polygon[i][1] + polygon[j][1]),
            ]);
        }
    }
    let inner: Vec<[f64; 2]> = candidates
        .into_iter()
        .filter(|&point| {
            inside(polygon, point)
                && polygon
                    .windows(2)
                    .all(|e| segment_distance(point, &e[0], &e[1]) > 0.02 * extent)
        })
        .collect();
    let step = inner.len().div_ceil(most.max(1)).max(1);
    inner.into_iter().step_by(step).take(most).collect()
}

#[tokio::test]
async fn pins_at_the_ends_keep_every_region_drawn() {
    let app = spawn_app().await;
    let curve = long_cubic();
    let free = regions(&app, &curve, &json!([])).await;
    let pinned = regions(
        &app,
        &curve,
        &json!([{"parameter": 0.0, "order": 0}, {"parameter": 11.0, "order": 0}]),
    )
    .await;
    assert!(!knot_regions(&free).is_empty() && !weight_regions(&free).is_empty());
    assert_eq!(knot_regions(&pinned), knot_regions(&free));
    assert_eq!(weight_regions(&pinned), weight_regions(&free));
}

#[tokio::test]
async fn knot_regions_under_an_inner_pin_are_reached_and_the_ones_left_out_move_it() {
    let app = spawn_app().await;
    let curve = long_cubic();
    let pin = 1.5;
    let constraints = json!([{"parameter": pin, "order": 0}]);
    let free = knot_regions(&regions(&app, &curve, &json!([])).await);
    let drawn = knot_regions(&regions(&app, &curve, &constraints).await);
    let left_out: Vec<_> = free.iter().filter(|r| !drawn.contains(r)).collect();
    assert!(!drawn.is_empty() && !left_out.is_empty(), "{drawn:?}");
    assert!(
        drawn.iter().all(|r| free.contains(r)),
        "drawn ⊆ drawn without the pin"
    );
    let mut checked = 0;
    for (side, region, polygon) in &drawn {
        for target in inner_points(polygon, 4) {
            let request = json!({"curve": curve.to_json(false), "parameter": T, "target": target,
                                 "side": side, "regions": [region], "constraints": constraints});
            let (status, answer) = app.post_json("/v1/shape/membership", &request).await;
            assert_eq!(status, 200, "{answer}");
            assert_eq!(
                answer["candidates"][0]["regions"][0]["contains"],
                json!(true),
                "{side} {region} at {target:?}: {answer}"
            );
            checked += 1;
        }
    }
    for (side, region, polygon) in left_out {
        for target in inner_points(polygon, 2) {
            let request = json!({"curve": curve.to_json(false), "parameter": T, "target": target,
                                 "side": side, "regions": [region], "methods": ["knots"],
                                 "knot_families": ["envelope"]});
            let (status, answer) = app.post_json("/v1/shape/solve", &request).await;
            assert_eq!(status, 200, "{answer}");
            let solution = &answer["solutions"][0];
            let moved = solution_curve(&curve, solution);
            let shift = distance(&moved.point(pin), &curve.point(pin));
            assert!(
                shift > 1e-6,
                "{side} {region} at {target:?} keeps the pin: {shift}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked}");
}

#[tokio::test]
async fn weight_regions_under_a_tangent_lock_are_reached_and_the_ones_left_out_turn_it() {
    let app = spawn_app().await;
    let curve = long_cubic();
    let lock = 3.5;
    let constraints = json!([{"parameter": lock, "order": 1, "direction_only": true}]);
    let free = weight_regions(&regions(&app, &curve, &json!([])).await);
    let answer = regions(&app, &curve, &constraints).await;
    let drawn = weight_regions(&answer);
    assert!(
        knot_regions(&answer).is_empty(),
        "every knot-pair edit reaches u = 3.5"
    );
    let left_out: Vec<_> = free.iter().filter(|r| !drawn.contains(r)).collect();
    assert!(!drawn.is_empty() && !left_out.is_empty(), "{drawn:?}");
    let before = derivative(&curve, lock, 1);
    let mut checked = 0;
    for (poles, polygon, keeps) in drawn
        .iter()
        .map(|(poles, polygon)| (poles, polygon, true))
        .chain(
            left_out
                .iter()
                .map(|(poles, polygon)| (poles, polygon, false)),
        )
    {
        for target in inner_points(polygon, 3) {
            let mut request = json!({"curve": curve.to_json(false), "parameter": T,
                                     "target": target, "methods": ["weights"]});
            if keeps {
                request["constraints"] = constraints.clone();
            }
            let (status, answer) = app.post_json("/v1/shape/solve", &request).await;
            assert_eq!(status, 200, "{answer}");
            let solution = answer["solutions"]
                .as_array()
                .unwrap()
                .iter()
                .find(|s| numbers(&s["poles"]) == *poles)
                .unwrap_or_else(|| panic!("poles {poles:?} at {target:?}: {answer}"));
            let after = derivative(&solution_curve(&curve, solution), lock, 1);
            let turn = (before[0] * after[1] - before[1] * after[0])
                / (before[0].hypot(before[1]) * after[0].hypot(after[1]));
            if keeps {
                assert!(
                    turn.abs() < 1e-6,
                    "poles {poles:?} at {target:?} turn {turn}"
                );
            } else {
                assert!(
                    turn.abs() > 1e-6,
                    "poles {poles:?} at {target:?} keep it: {turn}"
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 6, "{checked}");
}
