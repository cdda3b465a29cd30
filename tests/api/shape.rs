//! `/v1/shape/*`: solutions re-evaluated through `/v1/curves/evaluate` and by the test's own
//! de Boor, targets made by moving known knot pairs, both conventions, the worked examples.

use serde_json::{Value, json};

use crate::helpers::{TestApp, numbers, points, spawn_app, spawn_app_with};
use crate::reference::{Lcg, ReferenceCurve, cubic_2d, distance};

/// A solution's curve passes through the target to this (coordinates ~10, knots in [0, 1]).
const REPRODUCTION_TOLERANCE: f64 = 1e-9;

/// Knot values recovered from a target agree with the ones that made it to this.
const RECOVERY_TOLERANCE: f64 = 1e-7;

/// Full-vector indices `[first, second]` of a pair's unknowns for span `j`.
fn pair_indices(region: &str, j: usize) -> [usize; 2] {
    let (a, b, c, e) = (j - 1, j, j + 2, j + 3);
    match region {
        "omega1" => [a, b],
        "omega2" => [b, c],
        "omega3" => [c, e],
        "omega4" => [a, c],
        "omega5" => [a, e],
        "omega6" => [b, e],
        other => panic!("unknown region {other}"),
    }
}

/// Re-evaluates `knots` at `t` through the service.
async fn evaluate_with_knots(
    app: &TestApp,
    curve: &ReferenceCurve,
    knots: &Value,
    t: f64,
) -> Vec<f64> {
    let mut body = curve.to_json(false);
    body["knots"] = knots.clone();
    let (status, answer) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": body, "parameters": [t]}),
        )
        .await;
    assert_eq!(status, 200, "{answer}");
    points(&answer["points"])[0].clone()
}

/// A generated case: region, side, the full knot vector that made the target, the target, `t`.
type MadeTarget = (String, &'static str, Vec<f64>, Vec<f64>, f64);

/// A target made by setting `u_{j+1} := t` and moving one pair to values inside its domain:
/// returns (region, side, new full knot vector, target), or `None` when the move would change
/// the domain's end knots (kept by default).
fn made_target(curve: &ReferenceCurve, rng: &mut Lcg) -> Option<MadeTarget> {
    let u = &curve.knots;
    let n = curve.points.len() - 1;
    let t = rng.between(0.21, 0.74);
    let m = (3..=n).rev().find(|&m| u[m] <= t).unwrap();
    let (side, j) = if rng.unit() < 0.5 {
        ("right", m)
    } else {
        ("left", m - 1)
    };
    if !((2..=n).contains(&j) && u[j] <= t && t <= u[j + 2]) {
        return None;
    }
    let regions = ["omega1", "omega2", "omega3", "omega4", "omega5", "omega6"];
    let region = regions[(rng.unit() * 6.0) as usize % 6];
    let (l, a, b, c, e, r) = (u[j - 2], u[j - 1], u[j], u[j + 2], u[j + 3], u[j + 4]);
    // Draw inside the domain table of MATH.md, away from its edges; skip degenerate
    // (zero-width) domains, whose regions have no interior.
    let inside = |rng: &mut Lcg, lo: f64, hi: f64| {
        (hi - lo > 0.02).then(|| rng.between(lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo)))
    };
    let (mut na, mut nb, mut nc, mut ne) = (a, b, c, e);
    match region {
        "omega1" => {
            nb = inside(rng, l, t)?;
            na = inside(rng, l, nb)?;
        }
        "omega2" => {
            nb = inside(rng, a, t)?;
            nc = inside(rng, t, e)?;
        }
        "omega3" => {
            nc = inside(rng, t, r)?;
            ne = inside(rng, nc, r)?;
        }
        "omega4" => {
            na = inside(rng, l, b)?;
            nc = inside(rng, t, e)?;
        }
        "omega5" => {
            na = inside(rng, l, b)?;
            ne = inside(rng, c, r)?;
        }
        _ => {
            nb = inside(rng, a, t)?;
            ne = inside(rng, c, r)?;
        }
    }
    let mut knots = u.clone();
    knots[j - 1] = na;
    knots[j] = nb;
    knots[j + 1] = t;
    knots[j + 2] = nc;
    knots[j + 3] = ne;
    if knots[3] != u[3] || knots[n + 1] != u[n + 1] || nc <= nb {
        return None;
    }
    let target = curve.with_knots(knots.clone()).point(t);
    Some((region.to_owned(), side, knots, target, t))
}

#[tokio::test]
async fn solve_recovers_the_knots_that_made_a_target_and_every_solution_hits_it() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let mut rng = Lcg(20240611);
    let mut checked = 0;
    while checked < 12 {
        let Some((region, side, made_knots, target, t)) = made_target(&curve, &mut rng) else {
            continue;
        };
        checked += 1;
        let request = json!({"curve": curve.to_json(false), "parameter": t, "target": target});
        let (status, body) = app.post_json("/v1/shape/solve", &request).await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(body["reachable"], true, "{region} {side} t={t}: {body}");
        let solutions = body["solutions"].as_array().unwrap();
        let recovered = solutions.iter().any(|s| {
            s["region"] == region.as_str()
                && s["side"] == side
                && numbers(&s["knots"])
                    .iter()
                    .zip(&made_knots)
                    .all(|(x, y)| (x - y).abs() < RECOVERY_TOLERANCE)
        });
        assert!(recovered, "{region}/{side} at t={t} not recovered: {body}");

        let mut previous_deviation = 0.0;
        for solution in solutions {
            let knots = numbers(&solution["knots"]);
            // Independent re-evaluation: the service's evaluator and the test's de Boor.
            let through_service = evaluate_with_knots(&app, &curve, &solution["knots"], t).await;
            assert!(
                distance(&through_service, &target) < REPRODUCTION_TOLERANCE,
                "{solution}"
            );
            let new_curve = curve.with_knots(knots.clone());
            assert!(distance(&new_curve.point(t), &target) < REPRODUCTION_TOLERANCE);
            assert!(solution["residual"].as_f64().unwrap() < REPRODUCTION_TOLERANCE);
            assert!(
                distance(&points(&json!([solution["point"]]))[0], &target) < REPRODUCTION_TOLERANCE
            );
            // The envelope's moved knot is at t (the direct pairs move no knot to t), and
            // changed_knots lists exactly the changed values.
            if let Some(moved) = solution["moved_knot"].as_u64() {
                assert_eq!(solution["family"], "envelope", "{solution}");
                assert_eq!(knots[moved as usize], t);
            } else {
                assert_ne!(solution["family"], "envelope", "{solution}");
            }
            let changed: Vec<usize> = (0..knots.len())
                .filter(|&i| knots[i] != curve.knots[i])
                .collect();
            let listed: Vec<usize> = solution["changed_knots"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_u64().unwrap() as usize)
                .collect();
            assert_eq!(listed, changed);
            // The domain is kept by default.
            assert_eq!(knots[3], curve.knots[3]);
            assert_eq!(knots[curve.points.len()], curve.knots[curve.points.len()]);
            // Outside affected_domain the curves agree; inside, max_deviation bounds the gap.
            let [lo, hi] = <[f64; 2]>::try_from(numbers(&solution["affected_domain"])).unwrap();
            let max_deviation = solution["max_deviation"].as_f64().unwrap();
            assert!(
                max_deviation >= previous_deviation,
                "sorted by max_deviation"
            );
            previous_deviation = max_deviation;
            let mut sampled_max: f64 = 0.0;
            for i in 0..=400 {
                let u = i as f64 / 400.0;
                let gap = distance(&curve.point(u), &new_curve.point(u));
                if u < lo || u > hi {
                    assert!(gap < 1e-12, "changed outside affected_domain at {u}");
                }
                sampled_max = sampled_max.max(gap);
            }
            assert!(
                sampled_max <= max_deviation * (1.0 + 1e-6) + 1e-12,
                "{sampled_max} > {max_deviation}"
            );
            assert!(
                max_deviation <= sampled_max * 1.05 + 1e-9,
                "{max_deviation} >> {sampled_max}"
            );
        }

        // Membership agrees with solve, region by region.
        let (status, member) = app.post_json("/v1/shape/membership", &request).await;
        assert_eq!(status, 200, "{member}");
        assert_eq!(member["reachable"], true);
        for candidate in member["candidates"].as_array().unwrap() {
            let j = candidate["span"].as_u64().unwrap() as usize;
            for entry in candidate["regions"].as_array().unwrap() {
                let has_solution = solutions
                    .iter()
                    .any(|s| s["side"] == candidate["side"] && s["region"] == entry["region"]);
                assert_eq!(
                    entry["contains"].as_bool().unwrap(),
                    has_solution,
                    "{entry}"
                );
                let indices = pair_indices(entry["region"].as_str().unwrap(), j);
                assert_eq!(entry["knots"], json!(indices));
            }
        }
    }
}

#[tokio::test]
async fn trimmed_knots_round_trip_through_solve() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let examples: Value = serde_json::from_str(include_str!("../data/examples.json")).unwrap();
    let example = &examples["examples"][0];
    let (t, target) = (
        example["parameter"].as_f64().unwrap(),
        numbers(&example["target"]),
    );
    let full_request = json!({"curve": curve.to_json(false), "parameter": t, "target": target});
    let trimmed_request = json!({"curve": curve.to_json(true), "parameter": t, "target": target});
    let (_, full) = app.post_json("/v1/shape/solve", &full_request).await;
    let (status, trimmed) = app.post_json("/v1/shape/solve", &trimmed_request).await;
    assert_eq!(status, 200, "{trimmed}");
    let full_solutions = full["solutions"].as_array().unwrap();
    let trimmed_solutions = trimmed["solutions"].as_array().unwrap();
    assert!(!full_solutions.is_empty());
    assert_eq!(full_solutions.len(), trimmed_solutions.len());
    for (f, tr) in full_solutions.iter().zip(trimmed_solutions) {
        let full_knots = numbers(&f["knots"]);
        assert_eq!(
            numbers(&tr["knots"]),
            full_knots[1..full_knots.len() - 1].to_vec()
        );
        assert_eq!(
            tr["moved_knot"].as_u64().unwrap() + 1,
            f["moved_knot"].as_u64().unwrap()
        );
        let shifted: Vec<u64> = f["changed_knots"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap() - 1)
            .collect();
        assert_eq!(tr["changed_knots"], json!(shifted));
        // The trimmed vector goes straight back into the service and reproduces the target.
        let mut curve_back = curve.to_json(true);
        curve_back["knots"] = tr["knots"].clone();
        let (status, evaluated) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": curve_back, "parameters": [t]}),
            )
            .await;
        assert_eq!(status, 200);
        assert!(distance(&points(&evaluated["points"])[0], &target) < REPRODUCTION_TOLERANCE);
    }
    for (f, tr) in full["candidates"]
        .as_array()
        .unwrap()
        .iter()
        .zip(trimmed["candidates"].as_array().unwrap())
    {
        assert_eq!(
            tr["moved_knot"].as_u64().unwrap() + 1,
            f["moved_knot"].as_u64().unwrap()
        );
        assert_eq!(tr["span"], f["span"], "span keeps MATH.md's numbering");
        for (fr, trr) in f["regions"]
            .as_array()
            .unwrap()
            .iter()
            .zip(tr["regions"].as_array().unwrap())
        {
            let fk = numbers(&fr["knots"]);
            assert_eq!(numbers(&trr["knots"]), vec![fk[0] - 1.0, fk[1] - 1.0]);
            assert_eq!(fr["contains"], trr["contains"]);
        }
    }
}

#[tokio::test]
async fn the_worked_examples_are_reproduced_over_http() {
    let app = spawn_app().await;
    let examples: Value = serde_json::from_str(include_str!("../data/examples.json")).unwrap();
    for example in examples["examples"].as_array().unwrap() {
        let note = example["note"].as_str().unwrap();
        // The cubic's envelope pairs alone give exactly the worked answer; every family (the
        // default) gives it too, among the other families' solutions.
        let mut request = json!({"curve": example["curve"], "parameter": example["parameter"], "target": example["target"],
                                 "knot_families": ["envelope"]});
        let (status, body) = app.post_json("/v1/shape/solve", &request).await;
        assert_eq!(status, 200, "{note}: {body}");
        request.as_object_mut().unwrap().remove("knot_families");
        let (status, every_family) = app.post_json("/v1/shape/solve", &request).await;
        assert_eq!(status, 200, "{note}: {every_family}");
        for solution in body["solutions"].as_array().unwrap() {
            let same = every_family["solutions"]
                .as_array()
                .unwrap()
                .iter()
                .any(|s| {
                    s["region"] == solution["region"]
                        && s["side"] == solution["side"]
                        && s["knots"] == solution["knots"]
                });
            assert!(
                same,
                "{note}: {solution} missing from the answer with every family"
            );
        }
        assert_eq!(every_family["candidates"], body["candidates"], "{note}");
        let candidates = body["candidates"].as_array().unwrap();
        let mut expected_solutions = 0;
        for expected in example["expected"]["candidates"].as_array().unwrap() {
            let got = candidates
                .iter()
                .find(|c| c["side"] == expected["side"])
                .unwrap_or_else(|| panic!("{note}: side missing"));
            assert_eq!(got["applicable"], expected["applicable"], "{note}");
            assert_eq!(got["span"], expected["span"], "{note}");
            assert_eq!(got["moved_knot"], expected["moved_knot"], "{note}");
            if expected["applicable"] == false {
                assert!(got["reason"].is_string(), "{note}");
                continue;
            }
            for axis in ["x", "y"] {
                let (g, e) = (
                    got["frame"][axis].as_f64().unwrap(),
                    expected["frame"][axis].as_f64().unwrap(),
                );
                assert!((g - e).abs() < 1e-9, "{note}: frame {axis} {g} vs {e}");
            }
            for entry in got["regions"].as_array().unwrap() {
                let region = entry["region"].as_str().unwrap();
                assert_eq!(
                    entry["contains"], expected["regions"][region],
                    "{note}: {region}"
                );
            }
            for solution in expected["solutions"].as_array().unwrap() {
                expected_solutions += 1;
                let knots = numbers(&solution["knots"]);
                let found = body["solutions"].as_array().unwrap().iter().any(|s| {
                    s["side"] == expected["side"]
                        && s["region"] == solution["region"]
                        && s["changed_knots"] == solution["changed_knots"]
                        && numbers(&s["knots"])
                            .iter()
                            .zip(&knots)
                            .all(|(a, b)| (a - b).abs() < 1e-9)
                });
                assert!(found, "{note}: expected solution {solution} in {body}");
            }
        }
        assert_eq!(
            body["solutions"].as_array().unwrap().len(),
            expected_solutions,
            "{note}"
        );
        assert_eq!(body["reachable"], expected_solutions > 0, "{note}");
    }
}

#[tokio::test]
async fn an_unreachable_target_is_a_normal_answer() {
    let app = spawn_app().await;
    let request =
        json!({"curve": cubic_2d().to_json(false), "parameter": 0.42, "target": [40.0, -30.0]});
    for path in ["/v1/shape/solve", "/v1/shape/membership"] {
        let (status, body) = app.post_json(path, &request).await;
        assert_eq!(status, 200, "{body}");
        assert_eq!(body["reachable"], false);
        for candidate in body["candidates"].as_array().unwrap() {
            assert!(
                candidate["regions"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .all(|r| r["contains"] == false)
            );
        }
    }
    let (_, body) = app.post_json("/v1/shape/solve", &request).await;
    assert_eq!(body["solutions"], json!([]));
}

#[tokio::test]
async fn side_and_region_selection_and_keep_domain_are_honoured() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let examples: Value = serde_json::from_str(include_str!("../data/examples.json")).unwrap();
    let example = &examples["examples"][0];
    let request = json!({
        "curve": curve.to_json(false), "parameter": example["parameter"], "target": example["target"],
        "side": "left", "regions": ["omega4", "omega2"]
    });
    let (status, body) = app.post_json("/v1/shape/membership", &request).await;
    assert_eq!(status, 200, "{body}");
    let candidates = body["candidates"].as_array().unwrap();
    assert_eq!(candidates.len(), 1);
    assert_eq!(candidates[0]["side"], "left");
    let regions: Vec<&str> = candidates[0]["regions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["region"].as_str().unwrap())
        .collect();
    assert_eq!(regions, ["omega4", "omega2"]);

    // A target made by moving the domain's first knot u_3: t = 0.1 lies in span m = 3, the
    // right candidate is j = 3 (u_4 := t) and omega1 moves a = u_2, b = u_3. Such a solution
    // is dropped unless keep_domain is false.
    let t = 0.1;
    let mut knots = curve.knots.clone();
    knots[3] = 0.04; // b
    knots[4] = t; // the moved knot u_{j+1}, j = 3
    let target = curve.with_knots(knots.clone()).point(t);
    let request = json!({"curve": curve.to_json(false), "parameter": t, "target": target, "side": "right", "regions": ["omega1"]});
    let (_, kept) = app.post_json("/v1/shape/solve", &request).await;
    assert!(
        kept["solutions"]
            .as_array()
            .unwrap()
            .iter()
            .all(|s| numbers(&s["knots"])[3] == 0.0),
        "{kept}"
    );
    let mut free = request.clone();
    free["keep_domain"] = json!(false);
    let (status, moved) = app.post_json("/v1/shape/solve", &free).await;
    assert_eq!(status, 200, "{moved}");
    assert!(
        moved["solutions"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| (numbers(&s["knots"])[3] - 0.04).abs() < RECOVERY_TOLERANCE),
        "{moved}"
    );
}

/// Whether `point` lies inside the closed `polygon` (even-odd rule).
fn inside(point: [f64; 2], polygon: &[Vec<f64>]) -> bool {
    let mut inside = false;
    for edge in polygon.windows(2) {
        let (p, q) = (&edge[0], &edge[1]);
        if (p[1] > point[1]) != (q[1] > point[1]) {
            let x = p[0] + (point[1] - p[1]) * (q[0] - p[0]) / (q[1] - p[1]);
            if point[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[tokio::test]
async fn region_polygons_are_closed_consistent_and_hold_targets_made_in_them() {
    let app = spawn_app().await;
    let curve = cubic_2d();
    let mut rng = Lcg(77);
    let mut checked = 0;
    while checked < 6 {
        let Some((region, side, made_knots, target, t)) = made_target(&curve, &mut rng) else {
            continue;
        };
        checked += 1;
        let (status, body) = app
            .post_json(
                "/v1/shape/regions",
                &json!({"curve": curve.to_json(false), "parameter": t, "side": side, "regions": [region], "tolerance": 1e-4}),
            )
            .await;
        assert_eq!(status, 200, "{body}");
        let candidate = &body["candidates"][0];
        assert!(candidate.get("frame").is_none(), "no target, no frame");
        let triangle = points(&candidate["triangle"]);
        let polygon_entry = &candidate["regions"][0];
        assert_eq!(polygon_entry["region"], region.as_str());
        let polygon = points(&polygon_entry["polygon"]);
        let frame = points(&polygon_entry["polygon_frame"]);
        assert_eq!(polygon.len(), frame.len());
        assert!(polygon.len() >= 4);
        assert_eq!(polygon.first(), polygon.last(), "closed");
        // Each vertex is its frame point mapped through the triangle (non-rational curve).
        for (p, f) in polygon.iter().zip(&frame) {
            let mapped: Vec<f64> = (0..2)
                .map(|c| {
                    triangle[1][c]
                        + f[0] * (triangle[0][c] - triangle[1][c])
                        + f[1] * (triangle[2][c] - triangle[1][c])
                })
                .collect();
            assert!(distance(p, &mapped) < 1e-9);
        }
        assert!(
            inside([target[0], target[1]], &polygon),
            "{region}/{side} t={t} knots={made_knots:?} target {target:?} outside its polygon {polygon_entry}"
        );
    }
}

#[tokio::test]
async fn polygon_size_is_bounded_by_the_vertex_limit() {
    let app = spawn_app_with(|config| config.max_polygon_vertices = 128).await;
    let (status, body) = app
        .post_json(
            "/v1/shape/regions",
            &json!({"curve": cubic_2d().to_json(false), "parameter": 0.42, "tolerance": 1e-300}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    let mut any_unmet = false;
    for candidate in body["candidates"].as_array().unwrap() {
        for region in candidate["regions"].as_array().unwrap() {
            assert!(
                region["polygon"].as_array().unwrap().len() <= 128,
                "{region}"
            );
            any_unmet |= region["tolerance_met"] == false;
        }
    }
    assert!(
        any_unmet,
        "a curved boundary cannot meet 1e-300 within 128 vertices"
    );
}

/// `/v1/shape/solve` answers parse into the typed response, and serializing that again gives
/// the same bytes (no field is lost or renamed on the way). Targets made by known pairs (2D, rational 3D,
/// full and trimmed knots, one side or both), picks near the ends (sides that do not apply,
/// with a `reason`) and unreachable targets.
#[tokio::test]
async fn solve_answers_round_trip_through_the_typed_response() {
    use knotshape::http::wire::shape_answer::SolveResponse;
    let app = spawn_app().await;
    let mut rng = Lcg(31);
    let mut requests = Vec::new();
    for curve in [cubic_2d(), crate::reference::rational_3d()] {
        for round in 0..40 {
            let trimmed = round % 2 == 1;
            let Some((_, side, _, target, t)) = made_target(&curve, &mut rng) else {
                continue;
            };
            let side = if round % 3 == 0 { "both" } else { side };
            requests.push(json!({"curve": curve.to_json(trimmed), "parameter": t,
                                 "target": target, "side": side}));
        }
        let (lo, hi) = curve.domain();
        let far: Vec<f64> = curve.point(lo).iter().map(|x| x + 50.0).collect();
        for t in [lo, lo + 1e-3 * (hi - lo), hi] {
            requests.push(json!({"curve": curve.to_json(false), "parameter": t, "target": far}));
        }
    }
    let mut with_reason = 0;
    let mut with_solutions = 0;
    for request in &requests {
        let response = app.post("/v1/shape/solve", request).await;
        assert_eq!(response.status(), 200, "{request}");
        let body = response.bytes().await.unwrap();
        let typed: SolveResponse = serde_json::from_slice(&body).unwrap();
        let expected = serde_json::to_vec(&typed).unwrap();
        assert_eq!(
            String::from_utf8_lossy(&body),
            String::from_utf8_lossy(&expected),
            "{request}"
        );
        with_reason += typed
            .candidates
            .iter()
            .filter(|c| c.candidate.reason.is_some())
            .count();
        with_solutions += usize::from(!typed.solutions.is_empty());
    }
    assert!(
        with_reason > 0 && with_solutions > 10,
        "{with_reason} {with_solutions}"
    );
}

/// Numbers are read exactly and written as the shortest text that reads back the same: the
/// knots a solution leaves alone come back as the very text that was sent, even for values
/// whose correctly rounded reading needs all 17 digits (a fast, inexact reader is one unit in
/// the last place off for `0.45895123948091443`: 45895123948091443 / 10^17 in doubles).
#[tokio::test]
async fn unchanged_knots_come_back_bit_for_bit() {
    let app = spawn_app().await;
    let hard = "0.45895123948091443";
    let mut curve = cubic_2d();
    curve.knots[5] = hard.parse().unwrap();
    let mut rng = Lcg(7);
    let mut checked = 0;
    for _ in 0..200 {
        let Some((_, side, knots, target, t)) = made_target(&curve, &mut rng) else {
            continue;
        };
        if knots[5] != curve.knots[5] {
            continue;
        }
        let request = json!({"curve": curve.to_json(false), "parameter": t, "target": target,
                             "side": side, "keep_domain": false});
        let body = request.to_string();
        assert_eq!(knot_texts(&body)[0][5], hard);
        let response = app.post("/v1/shape/solve", &request).await;
        assert_eq!(response.status(), 200);
        let answer = response.text().await.unwrap();
        let solutions = &answer[answer.find("\"solutions\"").unwrap()..];
        for returned in knot_texts(solutions) {
            if returned[5] != hard {
                assert_ne!(
                    returned[5].parse::<f64>().unwrap(),
                    curve.knots[5],
                    "{answer}"
                );
                continue; // this solution moved knot 5
            }
            checked += 1;
        }
    }
    assert!(checked > 5, "only {checked} solutions kept knot 5");
}

/// The texts of the numbers in every `"knots":[...]` array of a JSON text.
fn knot_texts(json: &str) -> Vec<Vec<&str>> {
    json.match_indices("\"knots\":[")
        .map(|(at, key)| {
            let rest = &json[at + key.len()..];
            rest[..rest.find(']').unwrap()].split(',').collect()
        })
        .collect()
}
