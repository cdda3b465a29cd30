//! Criterion benchmark of the knot method for surfaces (docs/performance.md, docs/method.md
//! §48): a knots-only solve of a bicubic 20 × 20-pole surface — every iso-curve family in
//! both directions and the mixed moves — for a 3D target off the tangent plane (and of the
//! same net at degrees 4 and 5, whose mixed moves solve a curved pair), beside
//! today's cubic curve knots solve (the envelope pairs Ω1–Ω6 of both sides with their
//! deviation, as `benches/knot_families.rs` measures it) in the same run; the iso families
//! and the mixed moves are also timed alone to show where the time goes.
//!
//! `cargo bench --bench surface_knots`
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
use knotshape::shape::family::Family;
use knotshape::shape::{ShapeQuery, SolveOptions, solve};
use knotshape::spline::KnotForm;
use knotshape::surface::edit::knots::{
    SurfaceKnotFamily, SurfaceKnotOptions, nearest_surface_knot_target, solve_surface_knots,
    solve_surface_knots_with,
};
use knotshape::surface::{Surface, SurfaceLimits};

/// A smooth bicubic of 20 × 20 poles over `[0, 19]²` with a wavy height, uneven clamped
/// knots in both directions.
pub fn bicubic_20() -> Surface {
    wavy_20(3)
}

/// [`bicubic_20`]'s net and knot spacing at degree `p` in both directions.
pub fn wavy_20(p: usize) -> Surface {
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
        let mut k = vec![0.0; p + 1];
        let interior = n - p - 1;
        k.extend((1..=interior).map(|i| {
            let s = i as f64 / (interior + 1) as f64;
            s + shift * (std::f64::consts::PI * 3.0 * s).sin() / (interior + 1) as f64
        }));
        k.extend(vec![1.0; p + 1]);
        k
    };
    let (ku, kv) = (knots(0.3), knots(-0.25));
    Surface::from_knot_forms(
        (p, p),
        &poles,
        (KnotForm::Flat(&ku), KnotForm::Flat(&kv)),
        None::<&[Vec<f64>]>,
        &SurfaceLimits::default(),
    )
    .unwrap()
}

/// The picked parameters of the bench.
pub const PICK: (f64, f64) = (0.43, 0.57);

fn bench_surface_knots(c: &mut Criterion) {
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

    for p in [3, 4, 5] {
        every_family(c, p);
    }
}

/// The knots-only solve of [`wavy_20`] of degree `p` for a target off the tangent plane that
/// a mixed move reaches (every degree), and for `p = 3` the families alone and the nearest
/// point of a target out of reach.
fn every_family(c: &mut Criterion, p: usize) {
    let surface = wavy_20(p);
    let name = ["bicubic", "biquartic", "biquintic"][p - 3];
    let (u, v) = PICK;
    let point = surface.point(u, v);
    let partials = surface.partials(u, v, 1);
    let (du, dv) = (partials.du(), partials.dv());
    let normal = [
        du[1] * dv[2] - du[2] * dv[1],
        du[2] * dv[0] - du[0] * dv[2],
        du[0] * dv[1] - du[1] * dv[0],
    ];
    let length = (normal[0].powi(2) + normal[1].powi(2) + normal[2].powi(2)).sqrt();
    // A target off the tangent plane (along the normal and across), shrunk until a mixed
    // move reaches it.
    let mut scale = 0.05;
    let target = loop {
        let target: [f64; 3] = std::array::from_fn(|k| {
            point[k] + scale * (normal[k] / length + 0.3 * du[k] / du[0].abs().max(1.0))
        });
        let found = solve_surface_knots(&surface, u, v, target, true);
        if found
            .iter()
            .any(|s| matches!(s.family, SurfaceKnotFamily::Mixed { .. }))
        {
            break target;
        }
        scale *= 0.7;
        assert!(
            scale > 1e-4,
            "no mixed move reaches a target along the offset"
        );
    };
    let found = solve_surface_knots(&surface, u, v, target, true);
    eprintln!(
        "{name} 20 × 20 at {PICK:?}, target offset {scale:.4}: {} solutions ({} mixed, {} iso triples)",
        found.len(),
        found
            .iter()
            .filter(|s| matches!(s.family, SurfaceKnotFamily::Mixed { .. }))
            .count(),
        found
            .iter()
            .filter(|s| matches!(
                s.family,
                SurfaceKnotFamily::Iso {
                    family: Family::Triples,
                    ..
                }
            ))
            .count()
    );
    c.bench_function(&format!("surface_knots/{name}_20x20_every_family"), |b| {
        b.iter(|| solve_surface_knots(black_box(&surface), u, v, black_box(target), true))
    });
    if p != 3 {
        return;
    }
    let mixed_only = SurfaceKnotOptions {
        iso_u: false,
        iso_v: false,
        ..SurfaceKnotOptions::all(true)
    };
    c.bench_function("surface_knots/bicubic_20x20_mixed_only", |b| {
        b.iter(|| {
            solve_surface_knots_with(black_box(&surface), u, v, black_box(target), &mixed_only)
        })
    });
    let iso_only = SurfaceKnotOptions {
        mixed: false,
        ..SurfaceKnotOptions::all(true)
    };
    c.bench_function("surface_knots/bicubic_20x20_iso_only", |b| {
        b.iter(|| solve_surface_knots_with(black_box(&surface), u, v, black_box(target), &iso_only))
    });
    // A target ten times as far along the same offset, out of every move's reach: the
    // nearest reachable point (one-direction families, then the mixed moves' search).
    let far: [f64; 3] = std::array::from_fn(|k| point[k] + 10.0 * (target[k] - point[k]));
    assert!(solve_surface_knots(&surface, u, v, far, true).is_empty());
    let near = nearest_surface_knot_target(&surface, u, v, far, true).unwrap();
    let gap = |p: [f64; 3]| (0..3).map(|k| (p[k] - far[k]).powi(2)).sum::<f64>().sqrt();
    eprintln!(
        "out of reach by {:.4} (the point {:.4} away)",
        gap(near),
        gap(point)
    );
    c.bench_function("surface_knots/bicubic_20x20_nearest_out_of_reach", |b| {
        b.iter(|| nearest_surface_knot_target(black_box(&surface), u, v, black_box(far), true))
    });
}

criterion_group!(benches, bench_surface_knots);
criterion_main!(benches);
