//! The real surfaces of `tests/data/real_surfaces.json.gz` (898 B-spline surfaces of CAD
//! faces read with Open CASCADE; provenance in tests/data/real_curves.md) through the surface
//! edit: at the centre of each domain a target off the surface (along the normal and a
//! tangent, 2 % of the net's size) is reached by the control-point move on every surface and
//! by the weights where a tetrahedron holds it; each solution is checked with the brute-force
//! evaluator of `surface_edit_common`, and its certified deviation is at least the distance
//! the picked point moved.

#![allow(clippy::unwrap_used)]

#[path = "common/real_surfaces.rs"]
mod real_surfaces;
mod surface_edit_common;

use knotshape::surface::edit::{
    FixedNet, SurfaceConstraints, SurfaceEditOptions, SurfaceEditRequest, SurfaceMethodKind,
    surface_edit,
};
use real_surfaces::SurfaceData;
use surface_edit_common::{Plain, distance};

/// Every surface of the corpus.
fn corpus() -> Vec<SurfaceData> {
    real_surfaces::load()
}

fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let length = distance(a, [0.0; 3]);
    (length > 0.0).then(|| a.map(|x| x / length))
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[test]
fn real_surfaces_are_moved_by_poles_and_weights() {
    let entries = corpus();

    let (mut by_weights, mut tested) = (0, 0);
    assert!(entries.len() > 800);
    for entry in &entries {
        let plain = Plain {
            p: entry.degree_u,
            q: entry.degree_v,
            knots_u: entry.knots_u.clone(),
            knots_v: entry.knots_v.clone(),
            poles: entry.poles.clone(),
            weights: entry.weights.clone(),
        };
        let surface = plain.surface();
        let [(u0, u1), (v0, v1)] = plain.domain();
        let (u, v) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let [point, du, dv] = plain.eval(u, v);
        let Some(normal) = unit(cross(du, dv)) else {
            continue;
        };
        let tangent = unit(du).unwrap_or([0.0; 3]);
        let size = plain.size();
        let step = 0.02 * size;
        let target: [f64; 3] =
            std::array::from_fn(|c| point[c] + step * (normal[c] + 0.5 * tangent[c]));
        let moved = distance(point, target);
        let constraints = SurfaceConstraints::none();
        let fixed = FixedNet::none(&surface);
        let outcome = surface_edit(&SurfaceEditRequest {
            surface: &surface,
            parameter: (u, v),
            target,
            methods: &[SurfaceMethodKind::ControlPoints, SurfaceMethodKind::Weights],
            constraints: &constraints,
            fixed: &fixed,
            options: SurfaceEditOptions::default(),
        });
        tested += 1;
        let magnitude = size.max(point.iter().fold(0.0f64, |m, x| m.max(x.abs())));
        assert!(
            outcome
                .solutions
                .iter()
                .any(|s| s.detail.method() == SurfaceMethodKind::ControlPoints),
            "{}: the control points always reach the target",
            entry.id
        );
        if outcome
            .solutions
            .iter()
            .any(|s| s.detail.method() == SurfaceMethodKind::Weights)
        {
            by_weights += 1;
        }
        for solution in &outcome.solutions {
            let new = Plain::of(&solution.surface);
            let reached = new.point(u, v);
            assert!(
                distance(reached, target) <= 1e-8 * magnitude,
                "{}: {:?} misses by {}",
                entry.id,
                solution.detail.method(),
                distance(reached, target)
            );
            let bound = solution.max_deviation.unwrap();
            assert!(
                bound >= moved * (1.0 - 1e-9),
                "{}: deviation {bound} below the moved distance {moved}",
                entry.id
            );
            // Unchanged at the domain's corners outside the affected rectangle.
            let [(a0, a1), (b0, b1)] = solution.affected_domain;
            for (cu, cv) in [(u0, v0), (u0, v1), (u1, v0), (u1, v1)] {
                if !((a0..=a1).contains(&cu) && (b0..=b1).contains(&cv)) {
                    assert!(
                        distance(plain.point(cu, cv), new.point(cu, cv)) <= 1e-12 * magnitude,
                        "{}: a corner outside the affected domain moved",
                        entry.id
                    );
                }
            }
        }
    }
    println!("{tested} surfaces moved by control points, {by_weights} also by weights");
    assert!(tested > 800);
    assert!(
        by_weights > tested / 10,
        "the weights reach {by_weights} of {tested}"
    );
}
