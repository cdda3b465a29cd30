//! Criterion benchmark of one full knot-pair solve (both sides, all six pairs), with and
//! without the deviation measure, on the first worked example of `tests/data/examples.json`
//! (a 2D cubic with 8 control points; the target is reachable through Ω2 of the left side).
#![allow(clippy::unwrap_used)]

use criterion::{Criterion, black_box, criterion_group, criterion_main};
use knotshape::shape::{ShapeQuery, SolveOptions, solve};
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
    group.finish();
}

criterion_group!(benches, bench_solve);
criterion_main!(benches);
