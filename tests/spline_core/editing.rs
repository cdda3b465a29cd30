//! Knots inserted for editing make a single cubic Bézier piece editable by the knot-pair
//! method: before, every solution moves an end of the domain; after, targets near the picked point are reachable with
//! the domain kept, and each solution's knots, evaluated by the reference, hit the target.

use knotshape::shape::{ShapeQuery, SolveOptions, solve};
use knotshape::spline::{Curve, CurveLimits};

use super::reference::Reference;

/// A reached target, by the reference evaluator, relative to the curve's size (~4).
const HIT_TOL: f64 = 1e-8;

fn bezier() -> Curve {
    let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
    let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
}

/// Targets on circles of radii 0.02 to 0.3 around `center`, 16 directions each.
fn targets_around(center: [f64; 3]) -> Vec<[f64; 2]> {
    let mut targets = Vec::new();
    for radius in [0.02, 0.05, 0.1, 0.2, 0.3] {
        for k in 0..16 {
            let angle = std::f64::consts::TAU * k as f64 / 16.0;
            targets.push([
                center[0] + radius * angle.cos(),
                center[1] + radius * angle.sin(),
            ]);
        }
    }
    targets
}

#[test]
fn inserted_editing_knots_make_a_bezier_piece_editable() {
    let options = SolveOptions {
        measure_deviation: false,
    };
    let curve = bezier();
    let t = 0.5;
    let center = curve.point(t).unwrap();
    let targets = targets_around(center);
    // The Bézier piece alone: every pair moves u_3 or u_4, the ends of the domain.
    for target in &targets {
        let outcome = solve(&ShapeQuery::new(&curve, t), target, options).unwrap();
        assert!(outcome.solutions.is_empty(), "{target:?}");
    }
    let values = curve.knots_for_editing(t, None).unwrap();
    let editable = curve.insert_knots(&values, 100).unwrap();
    let n = editable.control_points().len() - 1;
    let mut reached = 0;
    let mut sides = std::collections::BTreeSet::new();
    let mut pairs = std::collections::BTreeSet::new();
    for target in &targets {
        let outcome = solve(&ShapeQuery::new(&editable, t), target, options).unwrap();
        assert!(
            outcome
                .candidates
                .iter()
                .all(|c| c.candidate.is_applicable())
        );
        reached += usize::from(outcome.reachable());
        for solution in &outcome.solutions {
            // Domain kept: u_3 and u_{n+1} unchanged.
            assert_eq!(solution.knots[3], 0.0);
            assert_eq!(solution.knots[n + 1], 1.0);
            let moved = Reference {
                degree: 3,
                knots: solution.knots.clone(),
                points: editable.control_points().to_vec(),
                weights: None,
            };
            let point = moved.point(t);
            let miss = ((point[0] - target[0]).powi(2) + (point[1] - target[1]).powi(2)).sqrt();
            assert!(miss < HIT_TOL, "{target:?}: {point:?}");
            sides.insert(solution.side.name());
            pairs.insert(format!("{:?}", solution.pair));
        }
    }
    assert!(
        reached >= targets.len() / 8,
        "{reached} of {} targets reached",
        targets.len()
    );
    assert_eq!(sides.len(), 2, "{sides:?}");
    assert!(pairs.len() >= 3, "{pairs:?}");
}
