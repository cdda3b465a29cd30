//! Criterion benchmark of one full knot-pair solve (both sides, all six pairs), with and
//! without the deviation measure, on the first worked example of `tests/data/examples.json`
//! (a 2D cubic with 8 control points; the target is reachable through Ω2 of the left side).
#![allow(clippy::unwrap_used)]

use criterion::{Criterion, black_box, criterion_group, criterion_main};
use knotshape::shape::{ShapeQuery, SolveOptions, control_point_move, nearest_reachable, solve};
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

criterion_group!(benches, bench_solve);
criterion_main!(benches);
