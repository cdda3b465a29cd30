//! Editing periodic curves (Open CASCADE's form) over HTTP: solve, membership and regions take
//! them, near the seam too; every solution comes back in the periodic form and is checked by
//! re-evaluating it through `/v1/curves/evaluate` (whose periodic evaluation is checked against
//! Open CASCADE in tests/spline_core/periodic.rs): the target is met at `t` and one period
//! later, pins across the seam hold, fixed poles stay, the curve outside `affected_domain`
//! (modulo the period) is unchanged, and `max_deviation` matches dense sampling.

use serde_json::{Value, json};

use crate::helpers::{TestApp, assert_problem, numbers, points, spawn_app};

/// A small deterministic generator (xorshift), so the cases are the same on every run.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A periodic curve of `poles` control points on a wobbly loop, degree `degree`, knots of one
/// period `[0, 2]` (multiplicity 1 inside, `seam` at the ends), rational when asked.
fn periodic_curve(
    random: &mut Random,
    degree: usize,
    poles: usize,
    seam: usize,
    rational: bool,
    spatial: bool,
) -> Value {
    let control_points: Vec<Vec<f64>> = (0..poles)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / poles as f64;
            let radius = 2.0 + random.next();
            let mut point = vec![radius * angle.cos(), radius * angle.sin()];
            if spatial {
                point.push(random.next() - 0.5);
            }
            point
        })
        .collect();
    // Σ multiplicities but the last = poles: interior knots make up the rest.
    let interior = poles - seam;
    let mut knots = vec![0.0];
    let mut spacing: Vec<f64> = (0..=interior).map(|_| 0.5 + random.next()).collect();
    let total: f64 = spacing.iter().sum();
    spacing.iter_mut().for_each(|s| *s *= 2.0 / total);
    let mut u = 0.0;
    for s in &spacing[..interior] {
        u += s;
        knots.push(u);
    }
    knots.push(2.0);
    let mut multiplicities = vec![seam];
    multiplicities.extend(std::iter::repeat_n(1, interior));
    multiplicities.push(seam);
    let mut curve = json!({"degree": degree, "periodic": true, "control_points": control_points,
        "knots": knots, "multiplicities": multiplicities});
    if rational {
        let weights: Vec<f64> = (0..poles).map(|_| 0.5 + random.next()).collect();
        curve["weights"] = json!(weights);
    }
    curve
}

/// The curve's points (and derivatives up to `order`) at `parameters`.
async fn evaluate(app: &TestApp, curve: &Value, parameters: &[f64], order: usize) -> Value {
    let (status, body) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "parameters": parameters, "derivatives": order}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    body
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The new curve of a solution, in the periodic form of `curve`.
fn solution_curve(curve: &Value, solution: &Value) -> Value {
    let mut new = curve.clone();
    match solution["method"].as_str().unwrap() {
        "knots" => {
            new["knots"] = solution["knots"].clone();
            new["multiplicities"] = solution["multiplicities"].clone();
        }
        "control_points" => new["control_points"] = solution["control_points"].clone(),
        "weights" => new["weights"] = solution["weights"].clone(),
        other => panic!("unknown method {other}"),
    }
    new
}

/// Whether `u` lies in `[lo, hi]` modulo the period 2.
fn inside_modulo(u: f64, [lo, hi]: [f64; 2]) -> bool {
    let shifted = lo + (u - lo).rem_euclid(2.0);
    shifted <= hi + 1e-12
}

/// Checks one solution of an edit of `curve` at `t` towards `target` (see the module docs).
async fn check_solution(
    app: &TestApp,
    curve: &Value,
    t: f64,
    target: &[f64],
    pin: f64,
    pinned: bool,
    solution: &Value,
) {
    let new = solution_curve(curve, solution);
    let size = 4.0;
    // The form is kept: as many control points, weights and a valid periodic curve.
    assert_eq!(
        new["control_points"].as_array().unwrap().len(),
        curve["control_points"].as_array().unwrap().len(),
        "{solution}"
    );
    // The target, at t and one period later.
    let at = evaluate(app, &new, &[t, t + 2.0], 0).await;
    for point in points(&at["points"]) {
        assert!(
            distance(&point, target) <= 1e-9 * size,
            "{solution}: {point:?} is not the target {target:?}"
        );
    }
    // The pin across the seam holds.
    let old_pin = evaluate(app, curve, &[pin], 0).await;
    let new_pin = evaluate(app, &new, &[pin], 0).await;
    let gap = distance(
        &points(&old_pin["points"])[0],
        &points(&new_pin["points"])[0],
    );
    assert!(
        !pinned || gap <= 1e-9 * size,
        "{solution}: the pin moved by {gap}"
    );
    // Dense sampling of the period: the change stays in affected_domain (mod the period), and
    // max_deviation is its largest gap (certified from above, sampled from below).
    let samples: Vec<f64> = (0..=1200).map(|i| 2.0 * i as f64 / 1200.0).collect();
    let old_points = points(&evaluate(app, curve, &samples, 0).await["points"]);
    let new_points = points(&evaluate(app, &new, &samples, 0).await["points"]);
    let affected: [f64; 2] = numbers(&solution["affected_domain"]).try_into().unwrap();
    assert!(
        (0.0..2.0).contains(&affected[0]) && affected[1] - affected[0] <= 2.0 + 1e-12,
        "{affected:?}"
    );
    let reported = solution["max_deviation"].as_f64().unwrap();
    let mut sampled: f64 = 0.0;
    for ((u, old), new) in samples.iter().zip(&old_points).zip(&new_points) {
        let gap = distance(old, new);
        sampled = sampled.max(gap);
        if !inside_modulo(*u, affected) {
            assert!(
                gap <= 1e-12 * size,
                "{solution}: moved by {gap} at u = {u} outside {affected:?}"
            );
        }
    }
    assert!(
        sampled <= reported * (1.0 + 1e-9) + 1e-12,
        "{solution}: sampled {sampled} above the reported {reported}"
    );
    assert!(
        reported <= sampled * 1.05 + 1e-9,
        "{solution}: reported {reported}, sampled only {sampled}"
    );
}

/// Solve on periodic curves of degrees 2–5, rational or not, 2D and 3D, at parameters next to
/// the seam (on either side) and inside, with a pin on the other side of the seam: every
/// solution passes the checks of [`check_solution`]; membership agrees with solve.
#[tokio::test]
async fn periodic_curves_are_edited_by_every_method_across_the_seam() {
    let app = spawn_app().await;
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    let mut solutions_checked = 0;
    let mut methods_seen = std::collections::BTreeSet::new();
    for case in 0..12 {
        let degree = 2 + case % 4;
        let poles = 8 + case % 5;
        let seam = 1 + case % 2;
        let curve = periodic_curve(
            &mut random,
            degree,
            poles,
            seam.min(degree),
            case % 3 == 1,
            case % 4 == 3,
        );
        for t in [0.004, 1.993, 0.9] {
            let start = evaluate(&app, &curve, &[t], 1).await;
            let point = &points(&start["points"])[0];
            // A small move across the tangent.
            let tangent = &points(&start["derivatives"][0])[0];
            let length = tangent.iter().map(|c| c * c).sum::<f64>().sqrt();
            let mut target = point.clone();
            target[0] -= 0.05 * tangent[1] / length;
            target[1] += 0.05 * tangent[0] / length;
            let pin = (t + 1.0).rem_euclid(2.0);
            let mut methods = vec!["control_points", "weights"];
            if degree == 3 {
                methods.push("knots");
            }
            // With a pin across the seam, and without constraints (the knot pairs change
            // much of a short period, so the pin often rules them out).
            for pinned in [true, false] {
                let constraints = if pinned {
                    json!([{"parameter": pin, "order": 0}])
                } else {
                    json!([])
                };
                let request = json!({"curve": curve, "parameter": t, "target": target,
                    "methods": methods, "keep_domain": false, "constraints": constraints});
                let (status, solved) = app.post_json("/v1/shape/solve", &request).await;
                assert_eq!(status, 200, "{solved}");
                let solutions = solved["solutions"].as_array().unwrap();
                assert!(
                    solutions.iter().any(|s| s["method"] == "control_points"),
                    "case {case}, t = {t}: no control-point move: {solved}"
                );
                for solution in solutions {
                    check_solution(&app, &curve, t, &target, pin, pinned, solution).await;
                    methods_seen.insert(solution["method"].as_str().unwrap().to_owned());
                    solutions_checked += 1;
                }
                let (status, member) = app.post_json("/v1/shape/membership", &request).await;
                assert_eq!(status, 200, "{member}");
                assert_eq!(member["reachable"], solved["reachable"], "{member}");
            }
        }
    }
    assert!(solutions_checked >= 60, "{solutions_checked} solutions");
    assert_eq!(methods_seen.len(), 3, "{methods_seen:?}");
}

/// Indices in a periodic answer are the periodic form's: the unconstrained control-point move
/// changes the `degree + 1` poles active at `t` (modulo `N`, next to the seam too), each
/// moved along `target - s(t)` (the least-norm move of one point condition); fixed poles stay.
#[tokio::test]
async fn periodic_indices_are_the_periodic_forms() {
    let app = spawn_app().await;
    let mut random = Random(7);
    let curve = periodic_curve(&mut random, 3, 9, 1, false, false);
    let old = points(&curve["control_points"]);
    for t in [0.01, 1.99] {
        let start = evaluate(&app, &curve, &[t], 0).await;
        let point = &points(&start["points"])[0];
        let target = vec![point[0] + 0.1, point[1] - 0.05];
        let (status, solved) = app
            .post_json(
                "/v1/shape/solve",
                &json!({"curve": curve, "parameter": t, "target": target,
                    "methods": ["control_points"]}),
            )
            .await;
        assert_eq!(status, 200, "{solved}");
        let solution = &solved["solutions"][0];
        let changed: Vec<usize> = solution["changed_control_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|i| i.as_u64().unwrap() as usize)
            .collect();
        assert_eq!(changed.len(), 4, "{solution}");
        assert!(changed.iter().all(|&i| i < 9), "{changed:?}");
        let new = points(&solution["control_points"]);
        let direction = [target[0] - point[0], target[1] - point[1]];
        for (i, (a, b)) in old.iter().zip(&new).enumerate() {
            let moved = [b[0] - a[0], b[1] - a[1]];
            if changed.contains(&i) {
                let cross = moved[0] * direction[1] - moved[1] * direction[0];
                assert!(cross.abs() < 1e-12, "pole {i} moved across the direction");
                assert!(moved[0] * direction[0] + moved[1] * direction[1] > 0.0);
            } else {
                assert_eq!(moved, [0.0, 0.0], "pole {i} moved");
            }
        }
        // Open CASCADE's numbering (BSplCLib::PoleIndex): the first span uses P_0 … P_3, the
        // last one wraps around the seam, P_8, P_0, P_1, P_2.
        let expected = if t < 1.0 { [0, 1, 2, 3] } else { [0, 1, 2, 8] };
        assert_eq!(changed, expected, "t = {t}");
        // Fixing one of them keeps it.
        let fixed = changed[0];
        let (status, solved) = app
            .post_json(
                "/v1/shape/solve",
                &json!({"curve": curve, "parameter": t, "target": target,
                    "methods": ["control_points"], "fixed_control_points": [fixed]}),
            )
            .await;
        assert_eq!(status, 200, "{solved}");
        let moved = points(&solved["solutions"][0]["control_points"]);
        assert_eq!(moved[fixed], old[fixed]);
        // An index of the periodic form's range only: N is out of range.
        let (status, body) = app
            .post_json(
                "/v1/shape/solve",
                &json!({"curve": curve, "parameter": t, "target": target,
                    "methods": ["control_points"], "fixed_control_points": [9]}),
            )
            .await;
        assert_eq!(status, 422, "{body}");
        assert_problem(422, &body, Some("/fixed_control_points/0"));
    }
    // Regions of a periodic cubic: knot indices inside one period's flat knots.
    let (status, drawn) = app
        .post_json(
            "/v1/shape/regions",
            &json!({"curve": curve, "parameter": 0.01, "methods": ["knots", "weights"],
                "keep_domain": false}),
        )
        .await;
    assert_eq!(status, 200, "{drawn}");
    for candidate in drawn["candidates"].as_array().unwrap() {
        for region in candidate["regions"].as_array().unwrap_or(&vec![]) {
            for index in region["knots"].as_array().unwrap() {
                assert!(index.as_u64().unwrap() < 9, "{region}");
            }
        }
    }
    for region in drawn["weight_regions"].as_array().unwrap() {
        for index in region["poles"].as_array().unwrap() {
            assert!(index.as_u64().unwrap() < 9, "{region}");
        }
    }
}
