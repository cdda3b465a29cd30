//! knotshape's side of the curves-from-points comparison (`benches/fitting_compare.sh` runs
//! it between the two Python steps): reads the point sets and curves that
//! `benches/fitting_compare.py prepare` wrote, times interpolation, approximation and knot
//! removal (best of the given repeats, one thread), and writes the answers for the Python
//! side to compare with SciPy and Open CASCADE and to certify the same way as theirs.
//!
//! `KNOTSHAPE_FITTING_INPUT=in.json KNOTSHAPE_FITTING_OUTPUT=out.json cargo bench --bench fitting`
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use knotshape::spline::{
    ApproximationSpec, Curve, CurveLimits, InterpolationSpec, ParameterChoice, Parametrization,
    PointSet, approximate, interpolate,
};
use serde_json::{Value, json};

/// Limits well above the comparison's sizes.
fn limits() -> CurveLimits {
    CurveLimits {
        max_control_points: 1_000_000,
        ..CurveLimits::default()
    }
}

fn points_of(value: &Value) -> Vec<Vec<f64>> {
    serde_json::from_value(value.clone()).expect("points")
}

fn curve_json(curve: &Curve) -> Value {
    let dimension = curve.dimension().count();
    json!({
        "degree": curve.degree(),
        "control_points": curve
            .control_points()
            .iter()
            .map(|p| p[..dimension].to_vec())
            .collect::<Vec<_>>(),
        "knots": curve.knots(),
    })
}

/// The best time of `repeats` runs of `work`, and its last answer.
fn best_of<T>(repeats: usize, mut work: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut answer = None;
    for _ in 0..repeats.max(1) {
        let start = Instant::now();
        let result = work();
        best = best.min(start.elapsed().as_secs_f64());
        answer = Some(result);
    }
    (best, answer.expect("at least one run"))
}

fn main() {
    let (Ok(input), Ok(output)) = (
        std::env::var("KNOTSHAPE_FITTING_INPUT"),
        std::env::var("KNOTSHAPE_FITTING_OUTPUT"),
    ) else {
        eprintln!(
            "benches/fitting.rs is one step of benches/fitting_compare.sh; set KNOTSHAPE_FITTING_INPUT and KNOTSHAPE_FITTING_OUTPUT to run it alone"
        );
        return;
    };
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(&input).expect("the input file"))
            .expect("JSON input");
    let repeats = data["repeats"].as_u64().unwrap_or(5) as usize;
    let limits = limits();

    // Interpolation: chord length, averaged knots, cubic.
    let raw = points_of(&data["interpolation"]["points"]);
    let set = PointSet::new(&raw, usize::MAX).unwrap();
    let spec = InterpolationSpec {
        degree: data["interpolation"]["degree"].as_u64().unwrap() as usize,
        parameters: ParameterChoice::By(Parametrization::ChordLength),
        knots: None,
        end_tangents: [None, None],
        closed: false,
    };
    let (seconds, interpolation) = best_of(repeats, || interpolate(&set, &spec, &limits).unwrap());
    eprintln!(
        "interpolation of {} points: {:.3} ms",
        raw.len(),
        seconds * 1e3
    );
    let interpolation = json!({
        "seconds": seconds,
        "parameters": interpolation.parameters,
        "curve": curve_json(&interpolation.curve),
    });

    // Approximation at each tolerance of each point set.
    let mut approximations = Vec::new();
    for case in data["approximation"].as_array().unwrap() {
        let raw = points_of(&case["points"]);
        let set = PointSet::new(&raw, usize::MAX).unwrap();
        for tolerance in case["tolerances"].as_array().unwrap() {
            let tolerance = tolerance.as_f64().unwrap();
            let spec = ApproximationSpec {
                degree: 3,
                tolerance,
                parametrization: Parametrization::ChordLength,
                end_points_exact: true,
            };
            let (seconds, answer) = best_of(repeats, || approximate(&set, &spec, &limits).unwrap());
            eprintln!(
                "approximation {} at {tolerance:e}: {} poles, max error {:e}, {:.2} ms",
                case["name"],
                answer.curve.control_points().len(),
                answer.max_error,
                seconds * 1e3
            );
            approximations.push(json!({
                "name": case["name"],
                "tolerance": tolerance,
                "seconds": seconds,
                "poles": answer.curve.control_points().len(),
                "max_error": answer.max_error,
                "curve": curve_json(&answer.curve),
            }));
        }
    }

    // Knot removal at each tolerance of each curve.
    let mut removals = Vec::new();
    for case in data["removal"].as_array().unwrap() {
        let curve = &case["curve"];
        let curve = Curve::new(
            curve["degree"].as_u64().unwrap() as usize,
            &points_of(&curve["control_points"]),
            &serde_json::from_value::<Vec<f64>>(curve["knots"].clone()).unwrap(),
            None,
            &limits,
        )
        .unwrap();
        for tolerance in case["tolerances"].as_array().unwrap() {
            let tolerance = tolerance.as_f64().unwrap();
            let (seconds, removal) =
                best_of(repeats, || curve.remove_knots(tolerance, None).unwrap());
            eprintln!(
                "removal {} at {tolerance:e}: {} removed, bound {:e}, {:.2} ms",
                case["name"],
                removal.removed.len(),
                removal.max_deviation,
                seconds * 1e3
            );
            removals.push(json!({
                "name": case["name"],
                "tolerance": tolerance,
                "seconds": seconds,
                "removed": removal.removed.len(),
                "max_deviation": removal.max_deviation,
                "curve": curve_json(&removal.curve),
            }));
        }
    }

    let answer = json!({
        "interpolation": interpolation,
        "approximation": approximations,
        "removal": removals,
    });
    std::fs::write(&output, serde_json::to_string(&answer).unwrap()).expect("the output file");
}
