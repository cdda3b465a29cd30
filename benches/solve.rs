//! Criterion benchmark of one full knot-pair solve (both sides, all six pairs), with and
//! without the deviation measure, on the first worked example of `tests/data/examples.json`
//! (a 2D cubic with 8 control points; the target is reachable through Ω2 of the left side);
//! the third release's edit: the weight method on that cubic, a full solve with all three
//! methods, and a control-point move under four constraints on a 60-pole cubic.
#![allow(clippy::unwrap_used)]

use criterion::{Criterion, black_box, criterion_group, criterion_main};

#[path = "support/edit_cases.rs"]
mod edit_cases;

use edit_cases::{ALL, EXAMPLE_PARAMETER, EXAMPLE_TARGET, constrained_case, example_curve};
use knotshape::shape::{
    ConstraintSet, EditContext, EditOptions, FixedPoles, MethodKind, PoleVariables, ShapeQuery,
    SolveOptions, constrained_control_point_move, control_point_move, edit, nearest_reachable,
    solve,
};

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

fn bench_edit(c: &mut Criterion) {
    let mut group = c.benchmark_group("edit");
    // The worked example: weights alone, and all three methods, each solution measured (and
    // not).
    let curve = example_curve();
    let constraints = ConstraintSet::none();
    let fixed = FixedPoles::none(curve.control_points().len());
    let variables = PoleVariables::free_poles(&fixed);
    let context = EditContext {
        query: ShapeQuery::new(&curve, EXAMPLE_PARAMETER),
        constraints: &constraints,
        fixed: &fixed,
        variables: &variables,
    };
    let options = EditOptions {
        measure_deviation: true,
        nearest: false,
    };
    let target = EXAMPLE_TARGET;
    let outcome = edit(&context, &ALL, &target, options).unwrap();
    for kind in ALL {
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
            b.iter(|| edit(&context, &ALL, black_box(&target), options).unwrap())
        });
    }
    // Four constraints on a 60-pole cubic (benches/support/edit_cases.rs).
    let case = constrained_case();
    for (name, measure_deviation) in [
        ("four_constraints_60_poles", true),
        ("four_constraints_60_poles_without_deviation", false),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                constrained_control_point_move(
                    &case.curve,
                    case.t,
                    black_box(case.target),
                    &case.constraints,
                    &case.variables,
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
