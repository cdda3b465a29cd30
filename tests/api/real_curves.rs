//! The real-curve corpus (tests/data/real_curves.json.gz) through the HTTP API: every curve
//! form to `/v1/curves/evaluate` (points and first and second derivatives at its hardest
//! parameters) and to `/v1/curves/closest-point`, checked against exact rational arithmetic
//! (the spline-core tests' tests/spline_core/exact.rs). The other paths (insertion, pieces,
//! polylines, solve) are checked on the same corpus in tests/spline_core/real_curves.rs.

#[path = "../spline_core/corpus.rs"]
#[allow(dead_code)]
mod corpus;
#[path = "../spline_core/exact.rs"]
#[allow(dead_code)]
mod exact;

use serde_json::{Value, json};

use crate::helpers::spawn_app;
use corpus::RealCurve;
use exact::Judge;

/// Parameters per curve form (the hardest first).
const PARAMETERS_PER_CURVE: usize = 12;

fn curve_json(real: &RealCurve) -> Value {
    let mut curve = json!({
        "degree": real.degree,
        "control_points": real.poles,
        "knots": real.knots,
    });
    if let Some(weights) = &real.weights {
        curve["weights"] = json!(weights);
    }
    curve
}

/// A wire point (2 or 3 numbers) as a 3D point.
fn point(value: &Value) -> [f64; 3] {
    let v: Vec<f64> = value
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    [v[0], v[1], v.get(2).copied().unwrap_or(0.0)]
}

#[tokio::test]
async fn every_real_curve_evaluates_as_exactly_as_de_boor() {
    let app = spawn_app().await;
    let curves = corpus::load();
    let mut failures = Vec::new();
    for (index, real) in curves.iter().enumerate() {
        let judge = Judge::new(&real.input());
        let parameters = real.hard_parameters(PARAMETERS_PER_CURVE, index as u64);
        let (status, body) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": curve_json(real), "parameters": parameters, "derivatives": 2}),
            )
            .await;
        assert_eq!(status, 200, "{}: {body}", real.id);
        for (i, &t) in parameters.iter().enumerate() {
            let exact = judge.at(t, 2);
            let values = [
                point(&body["points"][i]),
                point(&body["derivatives"][0][i]),
                point(&body["derivatives"][1][i]),
            ];
            for (k, value) in values.into_iter().enumerate() {
                let verdict = exact.judge(k, value);
                if !verdict.passes() {
                    failures.push(format!(
                        "{} order {k} at {t:e}: error {:e} > {:e}",
                        real.id, verdict.error, verdict.allowed
                    ));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures: {:#?}",
        failures.len(),
        &failures[..failures.len().min(8)]
    );
}

#[tokio::test]
async fn every_real_curve_answers_closest_points_on_and_next_to_it() {
    let app = spawn_app().await;
    let curves = corpus::load();
    let mut failures = Vec::new();
    for (index, real) in curves.iter().enumerate() {
        let judge = Judge::new(&real.input());
        let size = judge.size();
        let dimension = real.poles[0].len();
        // The curve at two of its hardest parameters, and those points moved by 1e-9 and 1e-4
        // of the size (a fixed direction).
        let mut queries = Vec::new();
        for &t in real
            .hard_parameters(PARAMETERS_PER_CURVE, index as u64)
            .iter()
            .skip(2)
            .take(2)
        {
            let base = judge.at(t, 0).value(0);
            for offset in [0.0, 1e-9, 1e-4] {
                let q: Vec<f64> = (0..dimension)
                    .map(|c| base[c] + offset * size * [0.6, -0.8, 0.0][c])
                    .collect();
                queries.push((q, offset * size));
            }
        }
        let points: Vec<&Vec<f64>> = queries.iter().map(|(q, _)| q).collect();
        let (status, body) = app
            .post_json(
                "/v1/curves/closest-point",
                &json!({"curve": curve_json(real), "points": points}),
            )
            .await;
        assert_eq!(status, 200, "{}: {body}", real.id);
        for ((q, bound), result) in queries.iter().zip(body["results"].as_array().unwrap()) {
            let u = result["parameter"].as_f64().unwrap();
            let found = point(&result["point"]);
            let distance = result["distance"].as_f64().unwrap();
            let verdict = judge.at(u, 0).judge(0, found);
            if !verdict.passes() {
                failures.push(format!(
                    "{}: the point at {u} is off the curve: {verdict:?}",
                    real.id
                ));
            }
            // Never farther than the curve point the query was made from (which is within the
            // exact point's rounding of `bound`).
            let allowed = bound + 1e-12 * (size + bound) + verdict.allowed;
            if distance > allowed {
                failures.push(format!(
                    "{}: q {q:?} at {distance:e} > {allowed:e}",
                    real.id
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures: {:#?}",
        failures.len(),
        &failures[..failures.len().min(8)]
    );
}
