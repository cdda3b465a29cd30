#![allow(clippy::unwrap_used)]
use knotshape::spline::KnotForm;
use knotshape::surface::edit::knots::{SurfaceKnotFamily, solve_surface_knots};
use knotshape::surface::edit::{
    FixedNet, SurfaceConstraints, SurfaceEditOptions, SurfaceEditRequest, SurfaceMethodKind,
    surface_edit,
};
use knotshape::surface::{Surface, SurfaceLimits};
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

fn main() {
    let wavy = wavy_bicubic();
    let (u, v) = (0.43, 0.57);
    let (target, _) = knots_target(&wavy, (u, v));
    let none = SurfaceConstraints::none();
    let free = FixedNet::none(&wavy);
    let methods: &[SurfaceMethodKind] = &[
        SurfaceMethodKind::Knots,
        SurfaceMethodKind::ControlPoints,
        SurfaceMethodKind::Weights,
    ];
    let request = SurfaceEditRequest {
        surface: &wavy,
        parameter: (u, v),
        target,
        methods,
        constraints: &none,
        fixed: &free,
        options: SurfaceEditOptions {
            nearest: false,
            keep_domain: true,
        },
    };
    let n: usize = std::env::var("PROBE_N")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(200);
    let start = std::time::Instant::now();
    for _ in 0..n {
        std::hint::black_box(surface_edit(&request));
    }
    eprintln!(
        "mean {:.1} us wall",
        start.elapsed().as_secs_f64() * 1e6 / n as f64
    );
}
