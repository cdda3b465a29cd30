//! Criterion benchmark of one full knot-pair solve (both sides, all six pairs), with and
//! without the deviation measure, on the first worked example of `tests/data/examples.json`
//! (a 2D cubic with 8 control points; the target is reachable through Ω2 of the left side);
//! the third release's edit: the weight method on that cubic, a full solve with all three
//! methods, and a control-point move under four constraints on a 60-pole cubic.
#![allow(clippy::unwrap_used)]

use criterion::{Criterion, black_box, criterion_group, criterion_main};
use knotshape::shape::{
    ConstraintSet, ConstraintSpec, EditContext, EditOptions, FixedPoles, MethodKind, PoleVariables,
    ShapeQuery, SolveOptions, constrained_control_point_move, control_point_move, edit,
    nearest_reachable, solve,
};
use knotshape::spline::{Curve, CurveLimits};

fn example_curve() -> Curve {
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

fn bench_solve(c: &mut Criterion) {
    let curve = example_curve();
    let target = [4.746666666666666, 3.3233333333333333];
    let query = ShapeQuery::new(&curve, 0.42);
    let mut group = c.benchmark_group("solve");
    for (name, measure_deviation) in [("without_deviation", false), ("with_deviation", true)] {
        let options = SolveOptions { measure_deviation };
        // Sanity: the benchmarked call really finds the solution.
        assert!(solve(&query, &target, options).unwrap().reachable());
        group.bench_function(name, |b| {
            b.iter(|| solve(black_box(&query), black_box(&target), options).unwrap())
        });
    }
    // Both methods, as `methods: ["knots", "control_points"]` asks: the knot pairs and the
    // least-squares pole move, each with its deviation.
    let options = SolveOptions {
        measure_deviation: true,
    };
    let point = [target[0], target[1], 0.0];
    group.bench_function("both_methods", |b| {
        b.iter(|| {
            let knots = solve(black_box(&query), black_box(&target), options).unwrap();
            let poles = control_point_move(&curve, 0.42, black_box(point), true).unwrap();
            (knots, poles)
        })
    });
    group.finish();

    // The nearest reachable point for targets outside every region: 64 targets on a circle
    // of radius 3 around the picked point (all unreachable), one query each.
    let picked = curve.point(0.42).unwrap();
    let targets: Vec<[f64; 3]> = (0..64)
        .map(|i| {
            let angle = i as f64 * std::f64::consts::TAU / 64.0;
            [
                picked[0] + 3.0 * angle.cos(),
                picked[1] + 3.0 * angle.sin(),
                0.0,
            ]
        })
        .filter(|t| !solve(&query, &t[..2], options).unwrap().reachable())
        .collect();
    assert!(targets.len() > 30, "{} unreachable targets", targets.len());
    let mut group = c.benchmark_group("nearest");
    group.throughput(criterion::Throughput::Elements(targets.len() as u64));
    for (name, measure_deviation) in [("per_query", true), ("per_query_without_deviation", false)] {
        group.bench_function(name, |b| {
            b.iter(|| {
                for &t in &targets {
                    black_box(nearest_reachable(&query, black_box(t), measure_deviation).unwrap());
                }
            })
        });
    }
    group.finish();
}

/// A planar cubic with 60 control points on a wavy line, uniform clamped knots on [0, 1].
fn sixty_pole_curve() -> Curve {
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

fn bench_edit(c: &mut Criterion) {
    let mut group = c.benchmark_group("edit");
    // The worked example: weights alone, and all three methods, each solution measured.
    let curve = example_curve();
    let t = 0.42;
    let constraints = ConstraintSet::none();
    let fixed = FixedPoles::none(curve.control_points().len());
    let variables = PoleVariables::free_poles(&fixed);
    let context = EditContext {
        query: ShapeQuery::new(&curve, t),
        constraints: &constraints,
        fixed: &fixed,
        variables: &variables,
    };
    let options = EditOptions {
        measure_deviation: true,
        nearest: false,
    };
    // A target that all three methods reach (two weight pairs, Ω2 of the left side, poles).
    let target = [4.9, 3.4];
    let all = [
        MethodKind::Knots,
        MethodKind::ControlPoints,
        MethodKind::Weights,
    ];
    let outcome = edit(&context, &all, &target, options).unwrap();
    for kind in all {
        assert!(
            outcome.solutions.iter().any(|s| s.detail.method() == kind),
            "{kind:?} reaches the benchmark's target"
        );
    }
    let unmeasured = EditOptions {
        measure_deviation: false,
        ..options
    };
    for (suffix, options) in [("", options), ("_without_deviation", unmeasured)] {
        group.bench_function(format!("weights_on_a_cubic{suffix}"), |b| {
            b.iter(|| {
                edit(
                    &context,
                    &[MethodKind::Weights],
                    black_box(&target),
                    options,
                )
                .unwrap()
            })
        });
        group.bench_function(format!("all_three_methods{suffix}"), |b| {
            b.iter(|| edit(&context, &all, black_box(&target), options).unwrap())
        });
    }

    // Four constraints on a 60-pole cubic: the point and tangent pinned at u = 0.40, the
    // tangent's direction kept at the pick, the second derivative pinned at u = 0.47.
    let curve = sixty_pole_curve();
    let t = 0.43;
    let specs = [
        ConstraintSpec {
            parameter: 0.40,
            order: 0,
            value: None,
            direction_only: false,
        },
        ConstraintSpec {
            parameter: 0.40,
            order: 1,
            value: None,
            direction_only: false,
        },
        ConstraintSpec {
            parameter: t,
            order: 1,
            value: None,
            direction_only: true,
        },
        ConstraintSpec {
            parameter: 0.47,
            order: 2,
            value: None,
            direction_only: false,
        },
    ];
    let constraints = ConstraintSet::new(&curve, t, &specs).unwrap();
    let fixed = FixedPoles::none(curve.control_points().len());
    let variables = PoleVariables::free_poles(&fixed);
    let mut target = curve.point(t).unwrap();
    target[1] += 0.5;
    assert!(
        constrained_control_point_move(&curve, t, target, &constraints, &variables, true).is_ok()
    );
    for (name, measure_deviation) in [
        ("four_constraints_60_poles", true),
        ("four_constraints_60_poles_without_deviation", false),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                constrained_control_point_move(
                    &curve,
                    t,
                    black_box(target),
                    &constraints,
                    &variables,
                    measure_deviation,
                )
                .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_solve, bench_edit);
criterion_main!(benches);
