//! Points the certified tessellation (`tolerance` on evaluate) needs against uniform sampling
//! for the same maximum error, on a few typical curves. Prints a Markdown table.
//!
//! `cargo bench --bench tessellation_vs_uniform`
//!
//! The error of a polyline is measured by dense sampling: 64 curve points per polyline edge
//! (uniform in the edge's parameter interval), each point's distance to the nearest of the
//! edges within two of its own (its distance to the polyline, unless the polyline doubles
//! back farther than that).
//!
//! Uniform sampling may meet a tolerance by luck (a sample that lands on a corner), so two
//! counts are given: the "robust" `N`, where `N .. N + 9` all meet it, found by doubling and
//! then bisection (which takes the robust predicate as monotone in `N`, as it is but for
//! such luck), and the smallest `N` that meets it at all, by a scan from 2 up to the robust
//! one.

#![allow(clippy::unwrap_used)]

use knotshape::spline::{Curve, CurveLimits, Point, distance_to_segment};

/// Curve points sampled per polyline edge to measure its error.
const SAMPLES_PER_EDGE: usize = 64;

/// The largest distance from the curve to the polyline through its points at `parameters`.
fn polyline_error(curve: &Curve, parameters: &[f64]) -> f64 {
    polyline_error_up_to(curve, parameters, f64::INFINITY)
}

/// [`polyline_error`], stopping as soon as the error exceeds `stop` (then some value above it).
fn polyline_error_up_to(curve: &Curve, parameters: &[f64], stop: f64) -> f64 {
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
            if worst > stop {
                return worst;
            }
        }
    }
    worst
}

/// The error of `count` uniform samples.
fn uniform_error(curve: &Curve, count: usize) -> f64 {
    let parameters: Vec<f64> = curve.uniform_parameters(count).collect();
    polyline_error(curve, &parameters)
}

/// Whether `count` uniform samples meet `tolerance`.
fn uniform_meets(curve: &Curve, count: usize, tolerance: f64) -> bool {
    let parameters: Vec<f64> = curve.uniform_parameters(count).collect();
    polyline_error_up_to(curve, &parameters, tolerance) <= tolerance
}

/// Consecutive uniform counts that must all meet the tolerance for the "robust" count.
const RUN: usize = 10;

/// Whether `count .. count + RUN` uniform samples all meet `tolerance`.
fn run_meets(curve: &Curve, count: usize, tolerance: f64) -> bool {
    (count..count + RUN).all(|n| uniform_meets(curve, n, tolerance))
}

/// The smallest uniform count that meets `tolerance`, and the robust count (see the module).
fn smallest_uniform_counts(curve: &Curve, tolerance: f64) -> (usize, usize) {
    let mut high = 2;
    while !run_meets(curve, high, tolerance) {
        high *= 2;
    }
    let mut low = high / 2;
    while high - low > 1 {
        let middle = (low + high) / 2;
        if run_meets(curve, middle, tolerance) {
            high = middle;
        } else {
            low = middle;
        }
    }
    let first = (2..=high)
        .find(|&n| uniform_meets(curve, n, tolerance))
        .unwrap_or(high);
    (first, high)
}

fn curve(degree: usize, points: &[&[f64]], knots: &[f64], weights: Option<&[f64]>) -> Curve {
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
                &[
                    0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
                ],
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
                    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0,
                ],
                None,
            ),
        ),
    ];
    println!(
        "| curve | tolerance | certified: points | its measured error | uniform: smallest N meeting it | its measured error | uniform: smallest N with N..N+9 all meeting it | uniform / certified (robust N) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (name, curve) in &cases {
        for tolerance in [1e-2, 1e-3, 1e-4] {
            let parameters = curve.tessellate(tolerance, 1_000_000).unwrap();
            let certified_error = polyline_error(curve, &parameters);
            assert!(certified_error <= tolerance);
            let (uniform, robust) = smallest_uniform_counts(curve, tolerance);
            let uniform_measured = uniform_error(curve, uniform);
            println!(
                "| {name} | {tolerance:e} | {} | {certified_error:.2e} | {uniform} | {uniform_measured:.2e} | {robust} | {:.2} |",
                parameters.len(),
                robust as f64 / parameters.len() as f64
            );
        }
    }
}
