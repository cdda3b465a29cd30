//! Evaluating a curve's control net over another knot vector, without building a new curve.
//!
//! The shape solver proposes knot vectors and must evaluate them quickly and allocation-free.

use super::basis::{CAP, basis_functions, find_span};
use super::curve::Curve;
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
