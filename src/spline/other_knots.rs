//! Evaluating a curve's control net over another knot vector, without building a new curve.
//!
//! The shape solver proposes knot vectors and must evaluate them quickly and allocation-free.

use super::basis::{CAP, basis_derivatives, basis_functions, find_span};
use super::curve::Curve;
use super::eval::multiply_add;
use super::vector::Point;

impl Curve {
    /// The point at `t` of the curve with this curve's control points and weights but the full
    /// knot vector `knots`.
    ///
    /// Preconditions: `knots.len() == self.knots().len()`, `knots` non-decreasing with a
    /// non-empty domain `[u_p, u_{n+1}]`, and `t` in that domain (outside it the end span is
    /// extrapolated). The right end is evaluated as the limit from the left.
    pub fn point_with_knots(&self, knots: &[f64], t: f64) -> Point {
        debug_assert_eq!(knots.len(), self.knots().len());
        let p = self.degree();
        let span = find_span(knots, p, t);
        let mut basis = [0.0; CAP];
        basis_functions(knots, p, span, t, &mut basis);
        let mut acc = [0.0; 4];
        for (r, &n) in basis.iter().enumerate().take(p + 1) {
            let pw = self.homogeneous()[span - p + r];
            for c in 0..4 {
                acc[c] += n * pw[c];
            }
        }
        if self.is_rational() {
            [acc[0] / acc[3], acc[1] / acc[3], acc[2] / acc[3]]
        } else {
            [acc[0], acc[1], acc[2]]
        }
    }
}

impl Curve {
    /// The piece from `a` to the end of its knot span: writes to `out[0..=p]` the homogeneous
    /// Bézier control points `B_0 ..= B_p` of the piece `[a, b]` of the curve with this
    /// control net over the full knot vector `knots`, for `b` the first knot above `a` (the
    /// domain's end in the last span), and returns `b`. With `s = (u - a) / (b - a)`,
    /// `A(u) = Σ_i B_i C(p, i) s^i (1 - s)^(p-i)` for the homogeneous curve
    /// `A = (w x, w y, w z, w)`.
    ///
    /// `B_i` is the blossom `A[a, …, a, b, …, b]` (`p - i` times `a`, `i` times `b`): de Boor's
    /// algorithm run with those arguments (The NURBS Book, §5; Ramshaw's blossoming). Every
    /// de Boor weight lies in `[0, 1]`, so the points are convex combinations of the net.
    ///
    /// Preconditions as for [`Curve::point_with_knots`], and `a` below the domain's end. No
    /// allocation.
    pub fn bezier_span_rest_with_knots(&self, knots: &[f64], a: f64, out: &mut [[f64; 4]]) -> f64 {
        let span = find_span(knots, self.degree(), a);
        let b = knots[span + 1];
        self.bezier_piece_in_span(knots, span, a, b, out);
        b
    }

    /// The Bézier points of `[a, b]` inside `span` (the span of `knots` that holds `a`, so
    /// `b <=` its end), as [`Curve::bezier_span_rest_with_knots`] describes them.
    pub(crate) fn bezier_piece_in_span(
        &self,
        knots: &[f64],
        span: usize,
        a: f64,
        b: f64,
        out: &mut [[f64; 4]],
    ) {
        let net = &self.homogeneous()[span - self.degree()..=span];
        self.bezier_piece_of_net(knots, span, net, a, b, out);
    }

    /// [`Curve::bezier_piece_in_span`] for another net: `net` holds the `p + 1` homogeneous
    /// points that stand for the control points `span - p ..= span` (e.g. the curve's own,
    /// moved to a local origin: blossoming is affine invariant).
    pub(crate) fn bezier_piece_of_net(
        &self,
        knots: &[f64],
        span: usize,
        net: &[[f64; 4]],
        a: f64,
        b: f64,
        out: &mut [[f64; 4]],
    ) {
        bezier_of_net(self.degree(), knots, span, net, a, b, out);
    }
}

/// [`Curve::bezier_piece_of_net`] for a spline of degree `degree` over the full knots `knots`:
/// the homogeneous Bézier points of `[a, b]` inside `span` of the net `net` (the `p + 1`
/// homogeneous points that stand for the control points `span - p ..= span`). Shared by the
/// curves and by each direction of a surface's patches.
pub(crate) fn bezier_of_net(
    degree: usize,
    knots: &[f64],
    span: usize,
    net: &[[f64; 4]],
    a: f64,
    b: f64,
    out: &mut [[f64; 4]],
) {
    // Cubics (every shape request) get the blossoms written out.
    if degree == 3 {
        cubic_bezier_piece(knots, span, net, a, b, out);
    } else {
        bezier_piece_of_any_degree(degree, knots, span, net, a, b, out);
    }
}

/// [`bezier_of_net`] for a cubic, written out (the loops of
/// [`bezier_piece_of_any_degree`] do not unroll). For knots `u` and the net `P_0 ..= P_3` of
/// `span = s` (`P_i` the control point `s - 3 + i`), de Boor's levels with arguments
/// `x, y, z` are
///
/// * `Q_i(x) = P_{i-1} + (x - u_{s-3+i}) / (u_{s+i} - u_{s-3+i}) (P_i - P_{i-1})`, `i = 1, 2, 3`;
/// * `R_i(x, y) = Q_{i-1} + (y - u_{s-3+i}) / (u_{s-1+i} - u_{s-3+i}) (Q_i - Q_{i-1})`, `i = 2, 3`;
/// * `f(x, y, z) = R_2 + (z - u_s) / (u_{s+1} - u_s) (R_3 - R_2)`,
///
/// and `B_0 = f(a, a, a)`, `B_1 = f(a, a, b)`, `B_2 = f(a, b, b)`, `B_3 = f(b, b, b)`:
/// 16 blends, sharing `Q(a)`, `Q(b)` and `R(a, a)`.
#[inline(always)]
fn cubic_bezier_piece(
    knots: &[f64],
    span: usize,
    net: &[[f64; 4]],
    a: f64,
    b: f64,
    out: &mut [[f64; 4]],
) {
    let u = &knots[span - 2..=span + 3]; // u[k] = u_{s-2+k}
    let blend = |from: [f64; 4], to: [f64; 4], weight: f64| -> [f64; 4] {
        std::array::from_fn(|c| multiply_add(weight, to[c] - from[c], from[c]))
    };
    // Level 1: Q_i blends P_{i-1}, P_i over [u_{s-3+i}, u_{s+i}].
    let first = [
        1.0 / (u[3] - u[0]),
        1.0 / (u[4] - u[1]),
        1.0 / (u[5] - u[2]),
    ];
    let level_1 = |x: f64| {
        [
            blend(net[0], net[1], (x - u[0]) * first[0]),
            blend(net[1], net[2], (x - u[1]) * first[1]),
            blend(net[2], net[3], (x - u[2]) * first[2]),
        ]
    };
    // Level 2: R_2 blends Q_1, Q_2 over [u_{s-1}, u_{s+1}]; R_3 blends Q_2, Q_3 over
    // [u_s, u_{s+2}].
    let second = [1.0 / (u[3] - u[1]), 1.0 / (u[4] - u[2])];
    let level_2 = |q: &[[f64; 4]; 3], y: f64| {
        [
            blend(q[0], q[1], (y - u[1]) * second[0]),
            blend(q[1], q[2], (y - u[2]) * second[1]),
        ]
    };
    // Level 3 over the span itself, [u_s, u_{s+1}].
    let third = 1.0 / (u[3] - u[2]);
    let level_3 = |r: &[[f64; 4]; 2], z: f64| blend(r[0], r[1], (z - u[2]) * third);
    let (q_a, q_b) = (level_1(a), level_1(b));
    let r_aa = level_2(&q_a, a);
    out[0] = level_3(&r_aa, a);
    out[1] = level_3(&r_aa, b);
    out[2] = level_3(&level_2(&q_a, b), b);
    out[3] = level_3(&level_2(&q_b, b), b);
}

/// [`bezier_of_net`] for any degree.
///
/// The blossoms share work: `S_k` is the net after `k` de Boor levels with argument `a`
/// (`S_0` the net itself); `B_{p-k}` continues `S_k` with `p - k` levels of argument `b`.
/// For a cubic that would be 16 blends instead of 24.
fn bezier_piece_of_any_degree(
    degree: usize,
    knots: &[f64],
    span: usize,
    net: &[[f64; 4]],
    a: f64,
    b: f64,
    out: &mut [[f64; 4]],
) {
    // Work arrays sized for the degree (N = p + 1) for the common degrees: those of the
    // largest degree cost more to clear and copy than the blends (a quintic's deviation
    // measured 2,100 instructions per piece with them, 1,500 without).
    let p = degree;
    match p {
        2 => bezier_piece_sized::<3>(p, knots, span, net, a, b, out),
        4 => bezier_piece_sized::<5>(p, knots, span, net, a, b, out),
        5 => bezier_piece_sized::<6>(p, knots, span, net, a, b, out),
        6 => bezier_piece_sized::<7>(p, knots, span, net, a, b, out),
        7 => bezier_piece_sized::<8>(p, knots, span, net, a, b, out),
        _ => bezier_piece_sized::<CAP>(p, knots, span, net, a, b, out),
    }
}

/// [`bezier_piece_of_any_degree`] with work arrays of `N > p` entries.
#[inline(always)]
fn bezier_piece_sized<const N: usize>(
    p: usize,
    knots: &[f64],
    span: usize,
    net: &[[f64; 4]],
    a: f64,
    b: f64,
    out: &mut [[f64; 4]],
) {
    // Level k (1 <= k <= p) of de Boor's algorithm blends local points j - 1 and j
    // (k <= j <= p) with weight (x - lower) / (upper - lower), where
    // lower = u_{span-p+j} = below[j - 1] and upper = u_{span+1+j-k} = above[j - k].
    let mut below = [0.0; N];
    let mut above = [0.0; N];
    below[..p].copy_from_slice(&knots[span + 1 - p..=span]);
    above[..p].copy_from_slice(&knots[span + 1..=span + p]);
    let lower = |j: usize| below[j - 1];
    let upper = |j: usize, k: usize| above[j - k];
    let mut reciprocal = [[0.0; N]; N];
    for (k, row) in reciprocal.iter_mut().enumerate().take(p + 1).skip(1) {
        for (j, value) in row.iter_mut().enumerate().take(p + 1).skip(k) {
            *value = 1.0 / (upper(j, k) - lower(j));
        }
    }
    let level = |points: &mut [[f64; 4]; N], k: usize, x: f64| {
        for j in (k..p + 1).rev() {
            let alpha = (x - lower(j)) * reciprocal[k][j];
            let (before, current) = (points[j - 1], points[j]);
            for c in 0..4 {
                points[j][c] = multiply_add(alpha, current[c] - before[c], before[c]);
            }
        }
    };
    let mut with_a = [[0.0; 4]; N];
    with_a[..=p].copy_from_slice(&net[..=p]);
    let mut blossom = [[0.0; 4]; N];
    for k in 0..p + 1 {
        // Levels after k read entries k..=p only.
        blossom[k..=p].copy_from_slice(&with_a[k..=p]);
        for later in k + 1..p + 1 {
            level(&mut blossom, later, b);
        }
        out[p - k] = blossom[p];
        if k < p {
            level(&mut with_a, k + 1, a);
        }
    }
}

/// One polynomial piece of a curve in power form about its left end: `A(s0 + h) =
/// Σ_d coefficients[d] h^d` for the homogeneous curve `A = (w x, w y, w z, w)`.
#[derive(Debug, Clone, Copy)]
pub struct PowerPiece {
    degree: usize,
    rational: bool,
    coefficients: [[f64; 4]; CAP],
}

impl PowerPiece {
    /// The `p + 1` homogeneous coefficients, lowest power first.
    pub fn coefficients(&self) -> &[[f64; 4]] {
        &self.coefficients[..=self.degree]
    }

    /// The curve point at offset `h` from the piece's left end (Horner's rule).
    #[inline]
    pub fn point(&self, h: f64) -> Point {
        // Cubics get a copy of Horner's loop with a fixed trip count (unrolled).
        let acc = if self.degree == 3 {
            horner(&self.coefficients, 3, h)
        } else {
            horner(&self.coefficients, self.degree, h)
        };
        if self.rational {
            [acc[0] / acc[3], acc[1] / acc[3], acc[2] / acc[3]]
        } else {
            [acc[0], acc[1], acc[2]]
        }
    }
}

/// `Σ_{d <= degree} c[d] h^d` in all four homogeneous coordinates (Horner's rule).
#[inline(always)]
fn horner(c: &[[f64; 4]; CAP], degree: usize, h: f64) -> [f64; 4] {
    let mut acc = c[degree];
    for coefficient in c[..degree].iter().rev() {
        for i in 0..4 {
            acc[i] = multiply_add(acc[i], h, coefficient[i]);
        }
    }
    acc
}

impl Curve {
    /// The polynomial piece that starts at `at`, of the curve with this control net over the
    /// full knot vector `knots`: Taylor coefficients `A^(d)(at) / d!` of the span holding `at`
    /// (the span on its right when `at` is a knot). Valid on `[at, next knot]`.
    ///
    /// Preconditions as for [`Curve::point_with_knots`]. No allocation.
    pub fn power_piece_with_knots(&self, knots: &[f64], at: f64) -> PowerPiece {
        // Cubics (every shape request) get a copy compiled for degree 3, with 4 × 4 basis
        // buffers and fully unrolled loops.
        if self.degree() == 3 {
            self.power_piece_in::<4>(knots, at, 3)
        } else {
            self.power_piece_in::<CAP>(knots, at, self.degree())
        }
    }

    /// [`Curve::power_piece_with_knots`] for `p = degree` (the curve's) with `N × N` basis
    /// buffers (precondition `p < N`).
    #[inline(always)]
    fn power_piece_in<const N: usize>(&self, knots: &[f64], at: f64, degree: usize) -> PowerPiece {
        debug_assert_eq!(degree, self.degree());
        let p = degree;
        let span = find_span(knots, p, at);
        let mut ders = [[0.0; N]; N];
        basis_derivatives(knots, p, span, at, p, &mut ders);
        let mut coefficients = [[0.0; 4]; CAP];
        let net = &self.homogeneous()[span - p..=span];
        let mut factorial = 1.0;
        for (d, row) in ders.iter().enumerate().take(p + 1) {
            if d > 0 {
                factorial *= d as f64;
            }
            let inverse_factorial = 1.0 / factorial;
            let mut c = [0.0; 4];
            for (&value, pw) in row.iter().zip(net) {
                for (cv, &w) in c.iter_mut().zip(pw) {
                    *cv += value * w;
                }
            }
            coefficients[d] = c.map(|v| v * inverse_factorial);
        }
        PowerPiece {
            degree: p,
            rational: self.is_rational(),
            coefficients,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    /// De Casteljau on homogeneous Bézier points, projected.
    fn bezier_point(points: &[[f64; 4]], s: f64) -> Point {
        let mut work = points.to_vec();
        for level in 1..points.len() {
            for i in 0..points.len() - level {
                let next = work[i + 1];
                for (value, later) in work[i].iter_mut().zip(next) {
                    *value = (1.0 - s) * *value + s * later;
                }
            }
        }
        let w = work[0][3];
        [work[0][0] / w, work[0][1] / w, work[0][2] / w]
    }

    fn assert_pieces_match(curve: &Curve, knots: &[f64]) {
        let p = curve.degree();
        let domain = (knots[p], knots[knots.len() - p - 1]);
        for span in p..knots.len() - p - 1 {
            let (lo, hi) = (knots[span].max(domain.0), knots[span + 1].min(domain.1));
            if hi <= lo {
                continue;
            }
            // The whole span (what the deviation measure extracts) and a piece strictly
            // inside it (what the extraction serves any `[a, b]` with).
            let mut whole = [[0.0; 4]; CAP];
            assert_eq!(curve.bezier_span_rest_with_knots(knots, lo, &mut whole), hi);
            let (a, b) = (lo + 0.3 * (hi - lo), lo + 0.8 * (hi - lo));
            let mut inside = [[0.0; 4]; CAP];
            curve.bezier_piece_in_span(knots, span, a, b, &mut inside);
            for (a, b, bezier) in [(lo, hi, whole), (a, b, inside)] {
                for i in 0..=8 {
                    let s = i as f64 / 8.0;
                    let expected = curve.point_with_knots(knots, a + s * (b - a));
                    let found = bezier_point(&bezier[..=p], s);
                    for c in 0..3 {
                        assert!(
                            (found[c] - expected[c]).abs() < 1e-12,
                            "span {span}, [{a}, {b}], s {s}: {found:?} vs {expected:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn bezier_pieces_agree_with_the_basis_function_evaluator() {
        let points: Vec<Vec<f64>> = [
            [0.0, 0.0, 1.0],
            [1.0, 3.0, -1.0],
            [3.0, 4.0, 2.0],
            [5.0, 3.5, 0.0],
            [6.0, 1.0, 1.5],
            [8.0, 0.0, -2.0],
        ]
        .iter()
        .map(|p| p.to_vec())
        .collect();
        let knots = [0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
        let weights = [1.0, 0.5, 2.5, 1.0, 0.7, 1.2];
        let limits = CurveLimits::default();
        let rational = Curve::new(3, &points, &knots, Some(&weights), &limits).unwrap();
        assert_pieces_match(&rational, &knots);
        // Other knots over the same net (a double knot), and a quintic with unclamped knots.
        assert_pieces_match(
            &rational,
            &[0.0, 0.0, 0.0, 0.0, 0.45, 0.45, 1.0, 1.0, 1.0, 1.0],
        );
        let quintic_knots: Vec<f64> = (0..14).map(|i| 0.1 * i as f64).collect();
        let quintic_points: Vec<Vec<f64>> = (0..8)
            .map(|i| vec![i as f64, ((i * 7) % 5) as f64])
            .collect();
        let quintic = Curve::new(5, &quintic_points, &quintic_knots, None, &limits).unwrap();
        assert_pieces_match(&quintic, &quintic_knots);
    }
}
