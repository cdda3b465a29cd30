//! Points the certified tessellation (`tolerance` on evaluate) needs against uniform sampling
//! for the same maximum error, on a few typical curves. Prints a Markdown table.
//!
//! `cargo bench --bench tessellation_vs_uniform`
//!
//! The error of a polyline is measured by dense sampling: 64 curve points per polyline edge
//! (uniform in the edge's parameter interval), each point's distance to the nearest of the
//! edges within two of its own (its distance to the polyline, unless the polyline doubles
//! back farther than that). The uniform count is the smallest `N` whose polyline meets the
//! tolerance, found by bisection over `N` (the error of uniform sampling falls with `N`
//! on these curves; the bisection's answer is checked, and `N - 1` is checked to fail).

#![allow(clippy::unwrap_used)]

use knotshape::spline::{Curve, CurveLimits, Point, distance_to_segment};

/// Curve points sampled per polyline edge to measure its error.
const SAMPLES_PER_EDGE: usize = 64;

/// The largest distance from the curve to the polyline through its points at `parameters`.
fn polyline_error(curve: &Curve, parameters: &[f64]) -> f64 {
    let vertices: Vec<Point> = parameters
        .iter()
        .map(|&t| curve.point_unchecked(t))
        .collect();
    let edges = vertices.len() - 1;
    let mut worst = 0.0f64;
    for edge in 0..edges {
        let (a, b) = (parameters[edge], parameters[edge + 1]);
        for k in 0..=SAMPLES_PER_EDGE {
            let u = a + (b - a) * k as f64 / SAMPLES_PER_EDGE as f64;
            let q = curve.point_unchecked(u.min(b));
            let nearest = (edge.saturating_sub(2)..(edge + 3).min(edges))
                .map(|e| distance_to_segment(q, vertices[e], vertices[e + 1]))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(nearest);
        }
    }
    worst
}

/// The error of `count` uniform samples.
fn uniform_error(curve: &Curve, count: usize) -> f64 {
    let parameters: Vec<f64> = curve.uniform_parameters(count).collect();
    polyline_error(curve, &parameters)
}

/// The smallest uniform count whose error is at most `tolerance` (bisection; see the module).
fn smallest_uniform_count(curve: &Curve, tolerance: f64) -> usize {
    let mut high = 2;
    while uniform_error(curve, high) > tolerance {
        high *= 2;
    }
    let mut low = high / 2; // fails (or is below 2)
    while high - low > 1 {
        let middle = (low + high) / 2;
        if uniform_error(curve, middle) <= tolerance {
            high = middle;
        } else {
            low = middle;
        }
    }
    assert!(uniform_error(curve, high) <= tolerance);
    high
}

fn curve(
    degree: usize,
    points: &[&[f64]],
    knots: &[f64],
    weights: Option<&[f64]>,
) -> Curve {
    Curve::new(degree, points, knots, weights, &CurveLimits::default()).unwrap()
}

fn main() {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let cases: Vec<(&str, Curve)> = vec![
        (
            "S-shaped planar cubic, 8 control points (size ~10)",
            curve(
                3,
                &[
                    &[0.0, 0.0],
                    &[1.0, 3.0],
                    &[3.0, 4.0],
                    &[5.0, 3.5],
                    &[6.0, 1.0],
                    &[8.0, 0.0],
                    &[9.0, 2.0],
                    &[10.0, 4.0],
                ],
                &[0.0, 0.0, 0.0, 0.0, 0.2, 0.35, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0],
                None,
            ),
        ),
        (
            "NURBS unit circle, degree 2, 9 control points",
            curve(
                2,
                &[
                    &[1.0, 0.0],
                    &[1.0, 1.0],
                    &[0.0, 1.0],
                    &[-1.0, 1.0],
                    &[-1.0, 0.0],
                    &[-1.0, -1.0],
                    &[0.0, -1.0],
                    &[1.0, -1.0],
                    &[1.0, 0.0],
                ],
                &[0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0],
                Some(&[1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0]),
            ),
        ),
        (
            "Cubic with a corner (triple knot) and a long straight run",
            curve(
                3,
                &[
                    &[0.0, 0.0],
                    &[0.5, 2.0],
                    &[1.5, 2.0],
                    &[2.0, 0.0],
                    &[4.0, 0.0],
                    &[6.0, 0.0],
                    &[8.0, 0.0],
                    &[9.0, 3.0],
                ],
                &[0.0, 0.0, 0.0, 0.0, 0.4, 0.4, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0],
                None,
            ),
        ),
        (
            "3D quintic helix-like curve, 10 control points",
            curve(
                5,
                &[
                    &[1.0, 0.0, 0.0],
                    &[1.0, 1.0, 0.2],
                    &[-1.0, 1.0, 0.4],
                    &[-1.0, -1.0, 0.6],
                    &[1.0, -1.0, 0.8],
                    &[1.0, 1.0, 1.0],
                    &[-1.0, 1.0, 1.2],
                    &[-1.0, -1.0, 1.4],
                    &[1.0, -1.0, 1.6],
                    &[1.0, 0.0, 1.8],
                ],
                &[
                    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.0, 1.0, 1.0, 1.0,
                    1.0,
                ],
                None,
            ),
        ),
    ];
    println!(
        "| curve | tolerance | certified: points | its measured error | uniform: points for the same tolerance | its measured error | uniform / certified |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, curve) in &cases {
        for tolerance in [1e-2, 1e-3, 1e-4] {
            let parameters = curve.tessellate(tolerance, 1_000_000).unwrap();
            let certified_error = polyline_error(curve, &parameters);
            let uniform = smallest_uniform_count(curve, tolerance);
            let uniform_measured = uniform_error(curve, uniform);
            assert!(uniform_error(curve, uniform - 1) > tolerance || uniform == 2);
            println!(
                "| {name} | {tolerance:e} | {} | {certified_error:.2e} | {uniform} | {uniform_measured:.2e} | {:.2} |",
                parameters.len(),
                uniform as f64 / parameters.len() as f64
            );
        }
    }
}
