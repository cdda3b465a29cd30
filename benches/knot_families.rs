//! Criterion benchmark of the knot method on every degree (docs/performance.md): a full
//! knots solve — every family that applies, both sides, each solution's certified deviation —
//! on the first worked example's 2D cubic, on a quintic and on a 3D cubic, beside today's
//! cubic solve (the envelope pairs Ω1–Ω6 of both sides with their deviation) in the same run.
#![allow(clippy::unwrap_used)]

use criterion::{Criterion, black_box, criterion_group, criterion_main};

/// The service's allocator (src/main.rs), so that the solve is timed as the service runs it:
/// its many small allocations cost less under mimalloc than under glibc's malloc, more so
/// on two threads (docs/performance.md, "The knot method on every degree").
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "support/edit_cases.rs"]
mod edit_cases;

use edit_cases::{EXAMPLE_PARAMETER, example_curve};
use knotshape::shape::{
    ConstraintSet, EditContext, EditOptions, FixedPoles, MethodKind, PoleVariables, ShapeQuery,
    SolveOptions, edit, solve,
};
use knotshape::spline::{Curve, CurveLimits};

/// The quintic of the fourth release's worked example (16 poles, ten interior knots).
fn quintic() -> Curve {
    let points: Vec<Vec<f64>> = [
        [0.0, 0.0],
        [1.0, 1.5],
        [2.0, 2.5],
        [3.2, 3.0],
        [4.5, 2.8],
        [5.5, 1.8],
        [6.3, 0.6],
        [7.5, 0.2],
        [8.8, 0.9],
        [9.8, 2.2],
        [11.0, 3.0],
        [12.2, 2.6],
        [13.0, 1.2],
        [14.0, 0.0],
        [15.0, 0.5],
        [16.0, 2.0],
    ]
    .iter()
    .map(|p| p.to_vec())
    .collect();
    let mut knots = vec![0.0; 6];
    knots.extend((0..10).map(|i| ((0.08 + 0.84 * i as f64 / 9.0) * 1e4).round() / 1e4));
    knots.extend([1.0; 6]);
    Curve::new(5, &points, &knots, None, &CurveLimits::default()).unwrap()
}

/// A 3D cubic: a helix-like polygon of eight poles, uniform clamped knots.
fn cubic_3d() -> Curve {
    let points: Vec<Vec<f64>> = (0..8)
        .map(|i| {
            let a = 0.9 * i as f64;
            vec![3.0 * a.cos(), 3.0 * a.sin(), 0.8 * i as f64]
        })
        .collect();
    let knots = [0.0, 0.0, 0.0, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.0, 1.0, 1.0];
    Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
}

fn full_knots_solve(c: &mut Criterion, name: &str, curve: &Curve, t: f64, offset: [f64; 3]) {
    let constraints = ConstraintSet::none();
    let fixed = FixedPoles::none(curve.control_points().len());
    let variables = PoleVariables::free_poles(&fixed);
    let context = EditContext {
        query: ShapeQuery::new(curve, t),
        constraints: &constraints,
        fixed: &fixed,
        variables: &variables,
    };
    let options = EditOptions {
        measure_deviation: true,
        nearest: false,
    };
    let point = curve.point(t).unwrap();
    let dimension = curve.dimension().count();
    // The offset, halved until some family reaches the target.
    let mut scale = 1.0;
    let target = loop {
        let target: Vec<f64> = (0..dimension)
            .map(|k| point[k] + scale * offset[k])
            .collect();
        if edit(&context, &[MethodKind::Knots], &target, options)
            .unwrap()
            .reachable()
        {
            break target;
        }
        scale *= 0.5;
        assert!(
            scale > 1e-3,
            "{name}: no target along the offset is reached"
        );
    };
    c.bench_function(name, |b| {
        b.iter(|| edit(&context, &[MethodKind::Knots], black_box(&target), options).unwrap())
    });
}

fn bench_families(c: &mut Criterion) {
    let cubic = example_curve();
    let target = [4.9, 3.4];
    let query = ShapeQuery::new(&cubic, EXAMPLE_PARAMETER);
    let options = SolveOptions {
        measure_deviation: true,
    };
    assert!(solve(&query, &target, options).unwrap().reachable());
    c.bench_function("knots/cubic_today_envelope_pairs", |b| {
        b.iter(|| solve(black_box(&query), black_box(&target), options).unwrap())
    });
    let point = cubic.point(EXAMPLE_PARAMETER).unwrap();
    full_knots_solve(
        c,
        "knots/cubic_every_family",
        &cubic,
        EXAMPLE_PARAMETER,
        [target[0] - point[0], target[1] - point[1], 0.0],
    );
    full_knots_solve(
        c,
        "knots/quintic_every_family",
        &quintic(),
        0.5,
        [0.1, 0.05, 0.0],
    );
    full_knots_solve(
        c,
        "knots/cubic_3d_every_family",
        &cubic_3d(),
        0.45,
        [0.05, -0.05, 0.05],
    );
}

criterion_group!(benches, bench_families);
criterion_main!(benches);
