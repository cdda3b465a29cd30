//! Arc length (`Curve::arc_length`) against adaptive Simpson quadrature of `|s'|` written
//! here on the reference evaluator's derivatives, and known lengths; curvature
//! (`Curve::curvatures`) against central finite differences of the reference's points.

use knotshape::spline::{Curve, CurveLimits, LENGTH_RELATIVE_ERROR};
use proptest::prelude::*;
use proptest::test_runner::Config;

use super::config;
use super::generators::{CaseOptions, curve_case};
use super::reference::{P3, Reference, central_difference};

/// The test's quadrature aims at this relative accuracy.
const SIMPSON_TARGET: f64 = 1e-12;
/// Halvings of one span at most in the test's quadrature.
const SIMPSON_DEPTH: u32 = 40;

fn reference_of(curve: &Curve) -> Reference {
    Reference {
        degree: curve.degree(),
        knots: curve.knots().to_vec(),
        points: curve.control_points().to_vec(),
        weights: curve.weights().map(<[f64]>::to_vec),
    }
}

fn norm(v: P3) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// `|s'(t)|` by the reference, from the left at `end` (a span's right end).
fn speed(reference: &Reference, t: f64, end: f64) -> f64 {
    if t >= end {
        norm(reference.derivatives_from_left(t, 1)[1])
    } else {
        norm(reference.derivatives(t, 1)[1])
    }
}

/// Adaptive Simpson on `[a, b]` inside one span (`end` its right end), to absolute `tol`.
#[allow(clippy::too_many_arguments)]
fn simpson(
    reference: &Reference,
    end: f64,
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    whole: f64,
    tol: f64,
    depth: u32,
) -> f64 {
    let m = 0.5 * (a + b);
    let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
    let (flm, frm) = (speed(reference, lm, end), speed(reference, rm, end));
    let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    let delta = left + right - whole;
    if depth == 0 || delta.abs() <= 15.0 * tol {
        return left + right + delta / 15.0;
    }
    simpson(
        reference,
        end,
        a,
        m,
        fa,
        flm,
        fm,
        left,
        tol / 2.0,
        depth - 1,
    ) + simpson(
        reference,
        end,
        m,
        b,
        fm,
        frm,
        fb,
        right,
        tol / 2.0,
        depth - 1,
    )
}

/// The test's length of `[lo, hi]`: adaptive Simpson on each knot span.
fn test_length(reference: &Reference, lo: f64, hi: f64, scale: f64) -> f64 {
    let mut breaks: Vec<f64> = reference
        .knots
        .iter()
        .copied()
        .filter(|&u| lo < u && u < hi)
        .chain([lo, hi])
        .collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    breaks
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let m = 0.5 * (a + b);
            let (fa, fm, fb) = (
                speed(reference, a, b),
                speed(reference, m, b),
                speed(reference, b, b),
            );
            let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
            simpson(
                reference,
                b,
                a,
                b,
                fa,
                fm,
                fb,
                whole,
                SIMPSON_TARGET * scale,
                SIMPSON_DEPTH,
            )
        })
        .sum()
}

fn fewer_cases() -> Config {
    Config {
        cases: 24,
        ..config()
    }
}

proptest! {
    #![proptest_config(fewer_cases())]

    /// Random curves (degrees 1–6, rational, 3D, both conventions): the length of the
    /// domain and of a random range equals the test's adaptive Simpson quadrature, and the
    /// parameter at a fraction of the length has that length before it.
    #[test]
    fn lengths_match_adaptive_simpson(
        case in curve_case(CaseOptions { min_degree: 1, max_degree: 6, clamped: None }),
        range in (0.0..0.5f64, 0.5..1.0f64),
        fraction in 0.0..1.0f64,
    ) {
        let curve = case.curve();
        let reference = reference_of(&curve);
        let (lo, hi) = curve.domain();
        let (a, b) = (lo + range.0 * (hi - lo), lo + range.1 * (hi - lo));
        for (from, to) in [(lo, hi), (a, b)] {
            let arc = curve.arc_length(Some((from, to))).unwrap();
            // The test's quadrature aims at 1e-12 of the length.
            let expected = test_length(&reference, from, to, arc.length().max(1e-300));
            let error = (arc.length() - expected).abs();
            prop_assert!(error <= 2.0 * LENGTH_RELATIVE_ERROR * expected.max(1e-300),
                "length {} vs {expected} (relative {:e})", arc.length(), error / expected);
            let target = fraction * arc.length();
            let t = arc.parameter_at(target);
            prop_assert!(from <= t && t <= to);
            let before = test_length(&reference, from, t, expected.max(1e-300));
            prop_assert!((before - target).abs() <= 1e-9 * expected.max(1e-300),
                "L(u) = {before} for {target}");
        }
    }

}

proptest! {
    #![proptest_config(config())]

    /// Curvature against finite differences of the reference's points (away from knots,
    /// where `s''` may jump), for curves of degree 2–6, planar (signed) and spatial.
    #[test]
    fn curvature_matches_finite_differences(
        case in curve_case(CaseOptions { min_degree: 2, max_degree: 6, clamped: None }),
        fractions in proptest::collection::vec(0.0..1.0f64, 1..6),
    ) {
        let curve = case.curve();
        let reference = reference_of(&curve);
        let (lo, hi) = curve.domain();
        let planar = case.control_points[0].len() == 2;
        for f in fractions {
            let t = lo + f * (hi - lo);
            let span = reference.knots.windows(2).position(|w| w[0] <= t && t < w[1]);
            let Some(span) = span else { continue };
            let (a, b) = (reference.knots[span], reference.knots[span + 1]);
            let h = 1e-3 * (b - a);
            if t - 2.0 * h <= a || t + 2.0 * h >= b {
                continue;
            }
            let point = |u: f64| reference.point(u);
            let d1 = central_difference(&point, t, 1, h);
            let d2 = central_difference(&point, t, 2, h);
            let speed = norm(d1);
            let first_scale = reference.derivative_scale(t, 1);
            if speed < 1e-3 * first_scale {
                continue;
            }
            let cross = [
                d1[1] * d2[2] - d1[2] * d2[1],
                d1[2] * d2[0] - d1[0] * d2[2],
                d1[0] * d2[1] - d1[1] * d2[0],
            ];
            let expected = if planar { cross[2] } else { norm(cross) } / speed.powi(3);
            let ours = curve.curvatures(&[t]).unwrap()[0].unwrap();
            // Finite differences of order h^4, relative to the curvature's scale |s''|/|s'|².
            let scale = reference.derivative_scale(t, 2) / (speed * speed);
            prop_assert!((ours - expected).abs() <= 1e-5 * scale,
                "κ({t}) = {ours} vs {expected} (scale {scale})");
        }
    }
}

#[test]
fn known_lengths() {
    // A straight line, a quarter circle of radius 3 (rational quadratic) and a helix-like
    // cubic whose length the adaptive rule must also meet where its speed has a kink.
    let limits = CurveLimits::default();
    let line = Curve::new(
        3,
        &[
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 2.0],
            [2.0, 4.0, 4.0],
            [3.0, 6.0, 6.0],
        ],
        &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        None,
        &limits,
    )
    .unwrap();
    let length = line.arc_length(None).unwrap().length();
    assert!((length - 9.0).abs() < 1e-13, "{length}");
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let quarter = Curve::new(
        2,
        &[[3.0, 0.0], [3.0, 3.0], [0.0, 3.0]],
        &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        Some(&[1.0, w, 1.0]),
        &limits,
    )
    .unwrap();
    let arc = quarter.arc_length(None).unwrap();
    let exact = 1.5 * std::f64::consts::PI;
    assert!((arc.length() - exact).abs() <= 1e-13 * exact);
    // The parameter of the point at 30°: the arc length π/2 · (1/3) · 3.
    let t = arc.parameter_at(exact / 3.0);
    let p = quarter.point(t).unwrap();
    let angle = p[1].atan2(p[0]);
    assert!(
        (angle - std::f64::consts::FRAC_PI_6).abs() < 1e-11,
        "{angle}"
    );
    // A cubic going back and forth along a line, x = -1, 2, -2, 1 as a Bézier piece:
    // x'(t) = 3 (14 t² − 14 t + 3) changes sign at t = 1/2 ± √28/28, where the speed has a
    // kink; the length is x's total variation.
    let back_and_forth = Curve::new(
        3,
        &[[-1.0, 0.0], [2.0, 0.0], [-2.0, 0.0], [1.0, 0.0]],
        &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        None,
        &limits,
    )
    .unwrap();
    let x = |t: f64| {
        let s = 1.0 - t;
        -s * s * s + 6.0 * t * s * s - 6.0 * t * t * s + t * t * t
    };
    let root = 28f64.sqrt() / 28.0;
    let (t1, t2) = (0.5 - root, 0.5 + root);
    let expected = (x(t1) - x(0.0)).abs() + (x(t2) - x(t1)).abs() + (x(1.0) - x(t2)).abs();
    let length = back_and_forth.arc_length(None).unwrap().length();
    assert!(
        (length - expected).abs() <= LENGTH_RELATIVE_ERROR * expected,
        "{length} vs {expected}"
    );
}
