//! The curves and conditions of the edit benchmarks (`benches/solve.rs`, `benches/edit_cost.rs`):
//! the first worked example with a target all three methods reach, and a 60-pole cubic with
//! four constraints.
#![allow(dead_code, clippy::unwrap_used)]

use knotshape::shape::{ConstraintSet, ConstraintSpec, FixedPoles, MethodKind, PoleVariables};
use knotshape::spline::{Curve, CurveLimits, Point};

/// All three methods.
pub const ALL: [MethodKind; 3] = [
    MethodKind::Knots,
    MethodKind::ControlPoints,
    MethodKind::Weights,
];

/// The first worked example (`tests/data/examples.json`): a 2D cubic with 8 control points.
pub fn example_curve() -> Curve {
    let points: Vec<Vec<f64>> = [
        [0.0, 0.0],
        [1.0, 3.0],
        [3.0, 4.0],
        [5.0, 3.5],
        [6.0, 1.0],
        [8.0, 0.0],
        [9.0, 2.0],
        [10.0, 4.0],
    ]
    .iter()
    .map(|p| p.to_vec())
    .collect();
    let knots = [0.0, 0.0, 0.0, 0.0, 0.2, 0.35, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0];
    Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
}

/// The picked parameter of the example and a target that all three methods reach (two
/// weight pairs, Ω2 of the left side, the poles).
pub const EXAMPLE_PARAMETER: f64 = 0.42;
pub const EXAMPLE_TARGET: [f64; 2] = [4.9, 3.4];

/// A planar cubic with 60 control points on a wavy line, uniform clamped knots on [0, 1].
pub fn sixty_pole_curve() -> Curve {
    let count = 60;
    let points: Vec<Vec<f64>> = (0..count)
        .map(|i| {
            let x = i as f64;
            vec![x, 2.0 * (0.7 * x).sin() + 0.5 * (1.9 * x).cos()]
        })
        .collect();
    let interior = count - 4;
    let mut knots = vec![0.0; 4];
    knots.extend((1..=interior).map(|i| i as f64 / (interior + 1) as f64));
    knots.extend([1.0; 4]);
    Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
}

/// The constrained move: on the 60-pole cubic at `t = 0.43`, the point and tangent pinned at
/// u = 0.40, the tangent's direction kept at the pick, the second derivative pinned at
/// u = 0.47; the target 0.5 above the curve point.
pub struct ConstrainedCase {
    pub curve: Curve,
    pub t: f64,
    pub target: Point,
    pub constraints: ConstraintSet,
    pub variables: PoleVariables,
}

pub fn constrained_case() -> ConstrainedCase {
    let curve = sixty_pole_curve();
    let t = 0.43;
    let spec = |parameter, order, direction_only| ConstraintSpec {
        parameter,
        order,
        value: None,
        direction_only,
    };
    let specs = [
        spec(0.40, 0, false),
        spec(0.40, 1, false),
        spec(t, 1, true),
        spec(0.47, 2, false),
    ];
    let constraints = ConstraintSet::new(&curve, t, &specs).unwrap();
    let variables = PoleVariables::free_poles(&FixedPoles::none(curve.control_points().len()));
    let mut target = curve.point(t).unwrap();
    target[1] += 0.5;
    ConstrainedCase {
        curve,
        t,
        target,
        constraints,
        variables,
    }
}
