//! Knot insertion, Bézier pieces and the certified polyline on a 2D cubic B-spline with 60
//! control points (uniform interior knots, a zig-zag control polygon).
//!
//! `cargo bench --bench toolkit`
#![allow(clippy::unwrap_used)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use knotshape::spline::{Curve, CurveLimits};

/// Number of control points of the benchmark curve (degree 3).
const CONTROL_POINTS: usize = 60;

fn bench_curve() -> Curve {
    let points: Vec<[f64; 2]> = (0..CONTROL_POINTS)
        .map(|i| [i as f64, if i % 2 == 0 { 0.0 } else { 3.0 }])
        .collect();
    let interior = CONTROL_POINTS - 4;
    let mut knots = vec![0.0; 4];
    knots.extend((1..=interior).map(|i| i as f64 / (interior + 1) as f64));
    knots.extend([1.0; 4]);
    Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
}

fn toolkit(c: &mut Criterion) {
    let curve = bench_curve();
    let midpoints: Vec<f64> = curve
        .knots()
        .windows(2)
        .filter(|w| w[0] < w[1])
        .map(|w| 0.5 * (w[0] + w[1]))
        .collect();
    let mut group = c.benchmark_group("toolkit");
    group.measurement_time(Duration::from_secs(3));
    group.bench_function("insert one knot per span (57 knots)", |b| {
        b.iter(|| {
            black_box(
                curve
                    .insert_knots(black_box(&midpoints), usize::MAX)
                    .unwrap(),
            )
        });
    });
    group.bench_function("bezier pieces (57)", |b| {
        b.iter(|| black_box(curve.bezier_pieces().count()));
    });
    for tolerance in [1e-2, 1e-4] {
        let points = curve.tessellate(tolerance, 1_000_000).unwrap().len();
        group.bench_function(
            format!("tessellate tolerance {tolerance:e} ({points} points)"),
            |b| {
                b.iter(|| black_box(curve.tessellate(black_box(tolerance), 1_000_000).unwrap()));
            },
        );
    }
    group.finish();
}

criterion_group!(benches, toolkit);
criterion_main!(benches);
