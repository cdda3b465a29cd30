//! The worked examples of `docs/examples.json` (an independent reference): candidates, frames,
//! region membership and every solution's knot vector.
#![allow(clippy::unwrap_used)]

use knotshape::shape::{KnotPair, ShapeQuery, SolveOptions, membership, solve};
use knotshape::spline::{Curve, CurveLimits};
use serde_json::Value;

/// Knot values of the reference and ours agree to this (absolute; knots in [0, 1]).
const KNOT_TOLERANCE: f64 = 1e-9;
/// Frame coordinates agree to this.
const FRAME_TOLERANCE: f64 = 1e-9;

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

fn curve_of(value: &Value) -> Curve {
    let points: Vec<Vec<f64>> = value["control_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(numbers)
        .collect();
    let weights = value.get("weights").map(numbers);
    Curve::new(
        value["degree"].as_u64().unwrap() as usize,
        &points,
        &numbers(&value["knots"]),
        weights.as_deref(),
        &CurveLimits::default(),
    )
    .unwrap()
}

#[test]
fn worked_examples_match_the_reference() {
    let examples: Value = serde_json::from_str(include_str!("data/examples.json")).unwrap();
    for example in examples["examples"].as_array().unwrap() {
        let note = example["note"].as_str().unwrap();
        let curve = curve_of(&example["curve"]);
        let t = example["parameter"].as_f64().unwrap();
        let target = numbers(&example["target"]);
        let query = ShapeQuery::new(&curve, t);
        let outcome = solve(
            &query,
            &target,
            SolveOptions {
                measure_deviation: true,
            },
        )
        .unwrap();
        let member = membership(&query, &target).unwrap();
        for expected in example["expected"]["candidates"].as_array().unwrap() {
            let side = expected["side"].as_str().unwrap();
            let ours = outcome
                .candidates
                .iter()
                .find(|c| c.candidate.side.name() == side)
                .unwrap_or_else(|| panic!("{note}: no {side} candidate"));
            assert_eq!(
                ours.candidate.span as u64,
                expected["span"].as_u64().unwrap(),
                "{note}"
            );
            assert_eq!(
                ours.candidate.moved_knot as u64,
                expected["moved_knot"].as_u64().unwrap(),
                "{note}"
            );
            let applicable = expected["applicable"].as_bool().unwrap();
            assert_eq!(
                ours.candidate.is_applicable(),
                applicable,
                "{note}: {side} applicability"
            );
            if !applicable {
                continue;
            }
            let frame = ours.candidate.frame.unwrap();
            assert!(
                (frame.x - expected["frame"]["x"].as_f64().unwrap()).abs() < FRAME_TOLERANCE,
                "{note}"
            );
            assert!(
                (frame.y - expected["frame"]["y"].as_f64().unwrap()).abs() < FRAME_TOLERANCE,
                "{note}"
            );
            for pair in KnotPair::ALL {
                let want = expected["regions"][pair.name()].as_bool().unwrap();
                let got = ours
                    .regions
                    .iter()
                    .find(|r| r.pair == pair)
                    .unwrap()
                    .contains;
                let got_membership = member
                    .candidates
                    .iter()
                    .find(|c| c.candidate.side.name() == side)
                    .unwrap()
                    .regions
                    .iter()
                    .find(|r| r.pair == pair)
                    .unwrap()
                    .contains;
                assert_eq!(got, want, "{note}: {side} {}", pair.name());
                assert_eq!(
                    got_membership,
                    want,
                    "{note}: membership {side} {}",
                    pair.name()
                );
            }
            let expected_solutions = expected["solutions"].as_array().unwrap();
            let our_solutions: Vec<_> = outcome
                .solutions
                .iter()
                .filter(|s| s.side.name() == side)
                .collect();
            assert_eq!(
                our_solutions.len(),
                expected_solutions.len(),
                "{note}: {side} solution count"
            );
            for want in expected_solutions {
                let region = want["region"].as_str().unwrap();
                let got = our_solutions
                    .iter()
                    .find(|s| s.pair.name() == region)
                    .unwrap();
                let want_knots = numbers(&want["knots"]);
                assert_eq!(got.knots.len(), want_knots.len());
                for (g, w) in got.knots.iter().zip(&want_knots) {
                    assert!(
                        (g - w).abs() < KNOT_TOLERANCE,
                        "{note}: {region} knots {:?} vs {:?}",
                        got.knots,
                        want_knots
                    );
                }
                let want_changed: Vec<usize> = want["changed_knots"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_u64().unwrap() as usize)
                    .collect();
                assert_eq!(
                    got.changed_knots, want_changed,
                    "{note}: {region} changed knots"
                );
            }
        }
    }
}
