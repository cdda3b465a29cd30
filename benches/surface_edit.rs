//! Criterion benchmark of the surface edit (issue 28) on a bicubic 20 × 20-pole surface
//! (uniform interior knots, a smooth bump, picked at an interior point, a 3D target off the
//! surface, near enough for the thin tetrahedra of a nearly flat net): the control-point move alone, the three weights alone, and both in one edit,
//! each solution with its certified deviation; a control-point move under a pinned point and
//! pinned partials and the kept boundary; and, in the same run, today's curve edit with all
//! three methods on the worked example (benches/support/edit_cases.rs) for comparison. All
//! three surface methods run on the same surface (where the knots find no solution) and on
//! the knot benchmark's wavy bicubic (benches/surface_knots.rs) for a target the knots reach
//! (12 mixed solutions, each with its certified deviation).
//! `cargo bench --bench surface_edit`.
#![allow(clippy::unwrap_used)]

use criterion::{Criterion, black_box, criterion_group, criterion_main};

/// The service's allocator (src/main.rs), so that the solve is timed as the service runs it:
/// its many small allocations cost less under mimalloc than under glibc's malloc, more so
/// on two threads (docs/performance.md, "The knot method on every degree").
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "support/edit_cases.rs"]
mod edit_cases;

use edit_cases::{ALL, EXAMPLE_PARAMETER, EXAMPLE_TARGET, example_curve};
use knotshape::shape::{
    ConstraintSet, EditContext, EditOptions, FixedPoles, PoleVariables, ShapeQuery, edit,
};
use knotshape::spline::KnotForm;
use knotshape::surface::edit::knots::{SurfaceKnotFamily, solve_surface_knots};
use knotshape::surface::edit::{
    FixedNet, SurfaceConstraintSpec, SurfaceConstraints, SurfaceEditOptions, SurfaceEditRequest,
    SurfaceMethodKind, surface_edit, weight_moves, weight_triples,
};
use knotshape::surface::{Surface, SurfaceLimits};

/// The bicubic 20 × 20 net: `z = 0.3 sin(i / 3) cos(j / 4)` over the integer grid.
fn bicubic() -> Surface {
    let n = 20;
    let poles: Vec<Vec<[f64; 3]>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let (x, y) = (i as f64, j as f64);
                    [x, y, 0.3 * (x / 3.0).sin() * (y / 4.0).cos()]
                })
                .collect()
        })
        .collect();
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(|k| k as f64 / (n - 3) as f64));
    knots.extend(vec![1.0; 4]);
    Surface::from_knot_forms(
        (3, 3),
        &poles,
        (KnotForm::Flat(&knots), KnotForm::Flat(&knots)),
        None::<&[Vec<f64>]>,
        &SurfaceLimits::default(),
    )
    .unwrap()
}

/// The bicubic of benches/surface_knots.rs: 20 × 20 poles over `[0, 19]²` with a wavy height,
/// uneven clamped knots in both directions.
fn wavy_bicubic() -> Surface {
    let n = 20;
    let poles: Vec<Vec<[f64; 3]>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let (x, y) = (i as f64, j as f64);
                    [
                        x,
                        y,
                        1.5 * (0.45 * x).sin() * (0.35 * y).cos() + 0.1 * (1.3 * x + y).sin(),
                    ]
                })
                .collect()
        })
        .collect();
    let knots = |shift: f64| {
        let mut k = vec![0.0; 4];
        let interior = n - 4;
        k.extend((1..=interior).map(|i| {
            let s = i as f64 / (interior + 1) as f64;
            s + shift * (std::f64::consts::PI * 3.0 * s).sin() / (interior + 1) as f64
        }));
        k.extend([1.0; 4]);
        k
    };
    let (ku, kv) = (knots(0.3), knots(-0.25));
    Surface::from_knot_forms(
        (3, 3),
        &poles,
        (KnotForm::Flat(&ku), KnotForm::Flat(&kv)),
        None::<&[Vec<f64>]>,
        &SurfaceLimits::default(),
    )
    .unwrap()
}

/// The target of benches/surface_knots.rs: off the tangent plane along the normal and
/// across, shrunk by 0.7 from `0.05` until a mixed knot move reaches it; and that scale.
fn knots_target(surface: &Surface, (u, v): (f64, f64)) -> ([f64; 3], f64) {
    let point = surface.point(u, v);
    let partials = surface.partials(u, v, 1);
    let (du, dv) = (partials.du(), partials.dv());
    let normal = [
        du[1] * dv[2] - du[2] * dv[1],
        du[2] * dv[0] - du[0] * dv[2],
        du[0] * dv[1] - du[1] * dv[0],
    ];
    let length = (normal[0].powi(2) + normal[1].powi(2) + normal[2].powi(2)).sqrt();
    let mut scale = 0.05;
    loop {
        let target: [f64; 3] = std::array::from_fn(|k| {
            point[k] + scale * (normal[k] / length + 0.3 * du[k] / du[0].abs().max(1.0))
        });
        let found = solve_surface_knots(surface, u, v, target, true);
        if found
            .iter()
            .any(|s| matches!(s.family, SurfaceKnotFamily::Mixed { .. }))
        {
            return (target, scale);
        }
        scale *= 0.7;
        assert!(
            scale > 1e-4,
            "no mixed move reaches a target along the offset"
        );
    }
}

fn bench_surface_edit(c: &mut Criterion) {
    let surface = bicubic();
    let (u, v) = (0.43, 0.57);
    let point = surface.point(u, v);
    let target = [point[0] + 0.002, point[1] - 0.001, point[2] + 0.004];
    let none = SurfaceConstraints::none();
    let free = FixedNet::none(&surface);
    let request = |methods: &'static [SurfaceMethodKind]| SurfaceEditRequest {
        surface: &surface,
        parameter: (u, v),
        target,
        methods,
        constraints: &none,
        fixed: &free,
        options: SurfaceEditOptions::default(),
    };
    const POLES: &[SurfaceMethodKind] = &[SurfaceMethodKind::ControlPoints];
    const WEIGHTS: &[SurfaceMethodKind] = &[SurfaceMethodKind::Weights];
    const BOTH: &[SurfaceMethodKind] =
        &[SurfaceMethodKind::ControlPoints, SurfaceMethodKind::Weights];
    // All three methods: the knots reach no solution for this target (the net is nearly
    // flat and the target close), so they add their search only.
    const ALL_THREE: &[SurfaceMethodKind] = &[
        SurfaceMethodKind::Knots,
        SurfaceMethodKind::ControlPoints,
        SurfaceMethodKind::Weights,
    ];
    let outcome = surface_edit(&request(BOTH));
    for kind in BOTH {
        assert!(
            outcome.solutions.iter().any(|s| s.detail.method() == *kind),
            "{kind:?} reaches the benchmark's target"
        );
    }
    let mut group = c.benchmark_group("surface_edit");
    for (name, methods) in [
        ("control_points_20x20", POLES),
        ("weights_20x20", WEIGHTS),
        ("control_points_and_weights_20x20", BOTH),
        ("all_three_methods_20x20", ALL_THREE),
    ] {
        let request = request(methods);
        group.bench_function(name, |b| b.iter(|| surface_edit(black_box(&request))));
    }
    // The weight triples and their verified moves, without measuring the deviations.
    group.bench_function("weights_without_deviation_20x20", |b| {
        b.iter(|| {
            let triples = weight_triples(&surface, u, v).unwrap();
            weight_moves(&surface, (u, v), black_box(target), &triples, &none, &free)
        })
    });
    // All three methods on the knot benchmark's bicubic (benches/surface_knots.rs: wavy
    // height, uneven knots) for a target off the tangent plane that the knots reach.
    let wavy = wavy_bicubic();
    let (wavy_target, scale) = knots_target(&wavy, (u, v));
    let wavy_free = FixedNet::none(&wavy);
    let all_three = SurfaceEditRequest {
        surface: &wavy,
        parameter: (u, v),
        target: wavy_target,
        methods: ALL_THREE,
        constraints: &none,
        fixed: &wavy_free,
        options: SurfaceEditOptions {
            nearest: false,
            keep_domain: true,
        },
    };
    let outcome = surface_edit(&all_three);
    let counts: Vec<String> = ALL_THREE
        .iter()
        .map(|kind| {
            let count = outcome
                .solutions
                .iter()
                .filter(|s| s.detail.method() == *kind)
                .count();
            assert!(count > 0, "{kind:?} reaches the wavy target");
            format!("{} {count}", kind.name())
        })
        .collect();
    eprintln!(
        "all three methods, wavy bicubic 20 × 20, target offset {scale:.4}: {}",
        counts.join(", ")
    );
    group.bench_function("all_three_methods_wavy_20x20", |b| {
        b.iter(|| surface_edit(black_box(&all_three)))
    });
    // A pinned point, pinned first partials and the kept boundary.
    let pinned = [0.43, 0.57];
    let specs = [
        SurfaceConstraintSpec {
            parameter: [0.3, 0.6],
            order: 0,
            value: None,
        },
        SurfaceConstraintSpec {
            parameter: [0.5, 0.5],
            order: 1,
            value: None,
        },
    ];
    let constraints = SurfaceConstraints::new(&surface, (pinned[0], pinned[1]), &specs).unwrap();
    let boundary = FixedNet::new(&surface, &[], true).unwrap();
    let constrained = SurfaceEditRequest {
        surface: &surface,
        parameter: (u, v),
        target,
        methods: POLES,
        constraints: &constraints,
        fixed: &boundary,
        options: SurfaceEditOptions::default(),
    };
    assert!(!surface_edit(&constrained).solutions.is_empty());
    group.bench_function("control_points_constrained_20x20", |b| {
        b.iter(|| surface_edit(black_box(&constrained)))
    });
    group.finish();

    // Today's curve edit in the same run: all three methods on the worked example.
    let curve = example_curve();
    let curve_constraints = ConstraintSet::none();
    let fixed = FixedPoles::none(curve.control_points().len());
    let variables = PoleVariables::free_poles(&fixed);
    let context = EditContext {
        query: ShapeQuery::new(&curve, EXAMPLE_PARAMETER),
        constraints: &curve_constraints,
        fixed: &fixed,
        variables: &variables,
    };
    let options = EditOptions {
        measure_deviation: true,
        nearest: false,
    };
    let mut group = c.benchmark_group("curve_edit");
    group.bench_function("all_three_methods", |b| {
        b.iter(|| edit(&context, &ALL, black_box(&EXAMPLE_TARGET), options).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench_surface_edit);
criterion_main!(benches);
