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

    /// The polynomial piece `h ↦ self.point(h) - other.point(h)`, when neither piece is
    /// rational (a difference of rational pieces is no polynomial: then `None`). Both pieces
    /// must start at the same parameter.
    pub fn difference(&self, other: &PowerPiece) -> Option<PowerPiece> {
        if self.rational || other.rational {
            return None;
        }
        let degree = self.degree.max(other.degree);
        let mut coefficients = [[0.0; 4]; CAP];
        for (d, difference) in coefficients.iter_mut().enumerate().take(degree + 1) {
            let (mine, theirs) = (self.coefficients[d], other.coefficients[d]);
            *difference = [
                mine[0] - theirs[0],
                mine[1] - theirs[1],
                mine[2] - theirs[2],
                0.0,
            ];
        }
        Some(PowerPiece {
            degree,
            rational: false,
            coefficients,
        })
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
