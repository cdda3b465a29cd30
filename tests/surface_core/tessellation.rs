//! Meshes against their certificate: the mesh is checked as a piecewise-linear map of the
//! parameter domain — every triangle turns counter-clockwise in `(u, v)`, the triangles cover
//! the domain exactly once, every inner edge is shared by two triangles in opposite senses
//! (no cracks), each triangle faces the side of its vertices' normals — and densely sampled:
//! at points of every triangle (its vertices, edges and inside), the surface point by the
//! test's own evaluator is within `max_error <= tolerance` of the mesh point at the same
//! parameters (so within it both ways); a sample of mesh points is also within it of the
//! surface by the closest-point search. Coarse meshes of real surfaces are checked at 45
//! points of every triangle as well, and must come close to their bound somewhere.

use std::collections::HashMap;

use knotshape::surface::{Mesh, SurfaceClosestSearch};
use proptest::prelude::*;

use crate::config;
use crate::corpus::{SurfaceData, surfaces};
use crate::generators::surface_data;

/// Barycentric samples per triangle side (`(k + 1)(k + 2) / 2` points per triangle).
const SAMPLES: usize = 3;

/// Samples per side of the dense check (45 points per triangle, as the benchmark measures).
const DENSE_SAMPLES: usize = 8;

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Checks `mesh` of `data` made with `tolerance` (module docs); `Err` says what broke.
fn check(
    data: &SurfaceData,
    mesh: &Mesh,
    tolerance: f64,
    closest_samples: usize,
    samples: usize,
) -> Result<(), String> {
    if mesh.max_error.is_nan() || mesh.max_error > tolerance {
        return Err(format!(
            "max_error {} over the tolerance {tolerance}",
            mesh.max_error
        ));
    }
    let [(u0, u1), (v0, v1)] = data.domain();
    let mut area = 0.0;
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    let magnitude = data
        .poles
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let size = data.size();
    // The test's evaluator and the service's differ by rounding of the magnitude.
    let allowance = mesh.max_error + 1e-13 * magnitude;
    let mut worst: f64 = 0.0;
    let surface = data.surface();
    for triangle in &mesh.triangles {
        let [a, b, c] = triangle.map(|k| mesh.parameters[k as usize]);
        let twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if twice.is_nan() || twice <= 0.0 {
            return Err(format!(
                "triangle {triangle:?} is not counter-clockwise in (u, v)"
            ));
        }
        area += 0.5 * twice;
        for (p, q) in [(0, 1), (1, 2), (2, 0)] {
            let (x, y) = (triangle[p], triangle[q]);
            *edges.entry((x.min(y), x.max(y))).or_default() += if x < y { 1 } else { -1 };
        }
        // Faces the side of the normals, where that side is defined: the triangle is large
        // against the deviation, its vertices' normals agree within 60° (no pole they turn
        // around) and the parametrisation does not fold inside it.
        let [pa, pb, pc] = triangle.map(|k| mesh.vertices[k as usize]);
        let face = {
            let (e, f) = (sub(pb, pa), sub(pc, pa));
            [
                e[1] * f[2] - e[2] * f[1],
                e[2] * f[0] - e[0] * f[2],
                e[0] * f[1] - e[1] * f[0],
            ]
        };
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let normals = triangle.map(|k| mesh.normals[k as usize]);
        let agree = (0..3).all(|i| dot(normals[i], normals[(i + 1) % 3]) > 0.5);
        // Large against the deviation: its height at least ten times `max_error` (a triangle
        // the size of the tolerance may turn any way and still be within it, as may three
        // points along a bent iso-line across a span of 1e-13).
        let longest = norm(sub(pb, pa))
            .max(norm(sub(pc, pb)))
            .max(norm(sub(pa, pc)));
        let solid =
            norm(face) > 10.0 * mesh.max_error * longest && norm(face) > 1e-12 * size * size;
        let sum: [f64; 3] = std::array::from_fn(|c| normals.iter().map(|n| n[c]).sum());
        // The parametrisation does not fold inside the triangle: `S_u × S_v` keeps the
        // vertices' side at its edges' midpoints and its centroid.
        let params = triangle.map(|k| mesh.parameters[k as usize]);
        let unfolded = || {
            let inside = [
                (0.5, 0.5, 0.0),
                (0.0, 0.5, 0.5),
                (0.5, 0.0, 0.5),
                (1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0),
            ];
            inside.iter().all(|&(x, y, z)| {
                let u = x * params[0][0] + y * params[1][0] + z * params[2][0];
                let v = x * params[0][1] + y * params[1][1] + z * params[2][1];
                let partials = surface.partials(u.clamp(u0, u1), v.clamp(v0, v1), 1);
                let (du, dv) = (partials.du(), partials.dv());
                let n = [
                    du[1] * dv[2] - du[2] * dv[1],
                    du[2] * dv[0] - du[0] * dv[2],
                    du[0] * dv[1] - du[1] * dv[0],
                ];
                dot(n, sum) > 0.0
            })
        };
        if agree && solid && dot(face, sum) <= 0.0 && unfolded() {
            return Err(format!(
                "triangle {triangle:?} faces away from its normals {normals:?} (face {face:?})"
            ));
        }
        // The samples' parameters are rounded: the surface moves by up to |S_u| ulp(u) there
        // (taken at the vertices, doubled).
        let rounding = 4.0
            * f64::EPSILON
            * params
                .iter()
                .map(|&[u, v]| {
                    let partials = surface.partials(u, v, 1);
                    norm(partials.du()) * u.abs() + norm(partials.dv()) * v.abs()
                })
                .fold(0.0, f64::max);
        for i in 0..=samples {
            for j in 0..=samples - i {
                let (l1, l2) = (i as f64 / samples as f64, j as f64 / samples as f64);
                let l0 = 1.0 - l1 - l2;
                let u = l0 * a[0] + l1 * b[0] + l2 * c[0];
                let v = l0 * a[1] + l1 * b[1] + l2 * c[1];
                let on_mesh: [f64; 3] =
                    std::array::from_fn(|k| l0 * pa[k] + l1 * pb[k] + l2 * pc[k]);
                let (u, v) = (u.clamp(u0, u1), v.clamp(v0, v1));
                let gap = norm(sub(data.point_f64(u, v), on_mesh));
                worst = worst.max(gap);
                if gap > allowance + rounding {
                    return Err(format!(
                        "at ({u}, {v}) the surface is {gap:e} from the mesh, over max_error {}",
                        mesh.max_error
                    ));
                }
            }
        }
    }
    let domain = (u1 - u0) * (v1 - v0);
    if (area - domain).abs() > 1e-9 * domain {
        return Err(format!(
            "the triangles cover {area} of the domain's {domain}"
        ));
    }
    // Inner edges: two triangles, opposite senses; boundary edges: on the domain's boundary.
    for (&(x, y), &balance) in &edges {
        let (p, q) = (mesh.parameters[x as usize], mesh.parameters[y as usize]);
        let on_boundary = (p[0] == q[0] && (p[0] == u0 || p[0] == u1))
            || (p[1] == q[1] && (p[1] == v0 || p[1] == v1));
        if balance != 0 && !on_boundary {
            return Err(format!(
                "edge {p:?}–{q:?} is not shared by two triangles: a crack"
            ));
        }
    }
    // Mesh points near the surface by the closest-point search.
    let search = SurfaceClosestSearch::new(&surface, None).unwrap();
    for triangle in mesh
        .triangles
        .iter()
        .step_by((mesh.triangles.len() / closest_samples.max(1)).max(1))
    {
        let [pa, pb, pc] = triangle.map(|k| mesh.vertices[k as usize]);
        let centroid: [f64; 3] = std::array::from_fn(|k| (pa[k] + pb[k] + pc[k]) / 3.0);
        let found = search.closest(centroid);
        if found.distance > allowance {
            return Err(format!(
                "mesh point {centroid:?} is {} from the surface",
                found.distance
            ));
        }
    }
    let _ = worst;
    Ok(())
}

/// Real surfaces (every 10th) at a tolerance of `3e-3` of their size.
#[test]
fn meshes_of_real_surfaces_meet_their_certificate() {
    let mut failures = Vec::new();
    let mut triangles = 0;
    for data in surfaces().iter().step_by(10) {
        let surface = data.surface();
        let tolerance = 3e-3 * data.size();
        let mesh = surface
            .tessellate(tolerance, 200_000)
            .unwrap_or_else(|e| panic!("{}: {e}", data.id));
        triangles += mesh.triangles.len();
        if let Err(failure) = check(data, &mesh, tolerance, 20, SAMPLES) {
            failures.push(format!("{}: {failure}", data.id));
        }
    }
    eprintln!("{triangles} triangles");
    assert!(
        failures.is_empty(),
        "{} failures: {:#?}",
        failures.len(),
        &failures[..failures.len().min(8)]
    );
}

/// Coarse meshes, whose triangles span whole patches and are certified by the triangle bound
/// (method.md §38) more than by the cell's: other real surfaces (every 10th from the 5th) at
/// `1e-2` of their size, 45 points of every triangle, and the bound not vacuous (the largest
/// sampled deviation over all of them within 20 % of its `max_error`).
#[test]
fn coarse_meshes_of_real_surfaces_hold_their_bound_densely() {
    let mut failures = Vec::new();
    let mut closest: f64 = 0.0;
    for data in surfaces().iter().skip(5).step_by(10) {
        let surface = data.surface();
        let tolerance = 1e-2 * data.size();
        let mesh = surface
            .tessellate(tolerance, 200_000)
            .unwrap_or_else(|e| panic!("{}: {e}", data.id));
        if let Err(failure) = check(data, &mesh, tolerance, 5, DENSE_SAMPLES) {
            failures.push(format!("{}: {failure}", data.id));
        }
        let [(u0, u1), (v0, v1)] = data.domain();
        for triangle in &mesh.triangles {
            let [a, b, c] = triangle.map(|k| mesh.parameters[k as usize]);
            let [pa, pb, pc] = triangle.map(|k| mesh.vertices[k as usize]);
            for i in 0..=DENSE_SAMPLES {
                for j in 0..=DENSE_SAMPLES - i {
                    let (l1, l2) = (
                        i as f64 / DENSE_SAMPLES as f64,
                        j as f64 / DENSE_SAMPLES as f64,
                    );
                    let l0 = 1.0 - l1 - l2;
                    let u = (l0 * a[0] + l1 * b[0] + l2 * c[0]).clamp(u0, u1);
                    let v = (l0 * a[1] + l1 * b[1] + l2 * c[1]).clamp(v0, v1);
                    let on_mesh: [f64; 3] =
                        std::array::from_fn(|k| l0 * pa[k] + l1 * pb[k] + l2 * pc[k]);
                    let gap = norm(sub(data.point_f64(u, v), on_mesh));
                    closest = closest.max(gap / mesh.max_error);
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures: {:#?}",
        failures.len(),
        &failures[..failures.len().min(8)]
    );
    assert!(closest > 0.8, "{closest}");
}

proptest! {
    #![proptest_config(proptest::test_runner::Config { cases: 64, ..config() })]

    /// Random surfaces (degrees 1–7, rational, coincident knots, tiny spans) at tolerances
    /// from `1e-1` to `1e-3` of their size.
    #[test]
    fn meshes_of_random_surfaces_meet_their_certificate(
        data in surface_data(),
        exponent in 1..=3i32,
    ) {
        let surface = data.surface();
        let tolerance = 10f64.powi(-exponent) * data.size();
        match surface.tessellate(tolerance, 10_000) {
            Ok(mesh) => {
                let result = check(&data, &mesh, tolerance, 10, SAMPLES);
                prop_assert!(result.is_ok(), "{}", result.unwrap_err());
            }
            Err(knotshape::surface::TessellationError::TooManyTriangles { .. }) => {}
            // Spans a few units of roundoff wide cannot be resolved finer than this.
            Err(knotshape::surface::TessellationError::BelowFloor { .. }) => {}
            Err(error) => prop_assert!(false, "{error}"),
        }
    }
}
