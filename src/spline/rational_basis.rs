//! The rational basis functions `R_i = N_i w_i / Σ_l N_l w_l` and their first two derivatives
//! at one parameter, and a curve with other weights: what the constrained shape edits need
//! (every derivative of a curve with fixed knots and weights is linear in its poles,
//! `s^(r)(u) = Σ_i R_i^(r)(u) d_i`).

use super::basis::{CAP, MAX_DEGREE, basis_derivatives};
use super::curve::Curve;

/// Highest derivative order of [`Curve::rational_basis_derivatives`].
pub const MAX_BASIS_ORDER: usize = 2;

/// The derivatives of the `p + 1` rational basis functions that can be non-zero at a parameter:
/// `rows[r][k]` is `R_{first + k}^(r)(u)` for `r <= order`, `k <= p` (rows above `order` are 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RationalBasis {
    /// Index of the first pole, `m - p` for the span `m` of `u`.
    pub first: usize,
    /// `rows[r][k] = R_{first+k}^(r)(u)`.
    pub rows: [[f64; MAX_DEGREE + 1]; MAX_BASIS_ORDER + 1],
}

impl Curve {
    /// The rational basis functions at `u` (in the domain) and their derivatives up to
    /// `order <= 2` (orders above the degree are 0), on the span that evaluation uses (the one
    /// right of a knot; the last non-empty one at the domain's right end).
    ///
    /// With `A_i = N_i w_i` and `W = Σ A_i` (quotient rule, The NURBS Book eq. 4.8):
    /// `R_i = A_i / W`, `R_i' = (A_i' - R_i W') / W`, `R_i'' = (A_i'' - 2 R_i' W' - R_i W'') / W`;
    /// for a non-rational curve `R_i^(r) = N_i^(r)`.
    pub fn rational_basis_derivatives(&self, u: f64, order: usize) -> RationalBasis {
        let p = self.degree();
        let order = order.min(MAX_BASIS_ORDER);
        let span = self.span(u);
        // Buffers sized for the degree (the basis table is `(p + 1)²`): low degrees, the
        // usual case, do not clear a table for degree 15.
        let mut ders = [[0.0; CAP]; MAX_BASIS_ORDER + 1];
        match p {
            0..=3 => copy_rows::<4>(self.knots(), p, span, u, order, &mut ders),
            4..=7 => copy_rows::<8>(self.knots(), p, span, u, order, &mut ders),
            _ => copy_rows::<CAP>(self.knots(), p, span, u, order, &mut ders),
        }
        let first = span - p;
        let mut rows = [[0.0; CAP]; MAX_BASIS_ORDER + 1];
        let top = order.min(p);
        if !self.is_rational() {
            for r in 0..=top {
                rows[r][..=p].copy_from_slice(&ders[r][..=p]);
            }
            return RationalBasis { first, rows };
        }
        // A_i^(r) = N_i^(r) w_i and W^(r) = Σ_i A_i^(r).
        let mut weighted = [[0.0; CAP]; MAX_BASIS_ORDER + 1];
        let mut total = [0.0; MAX_BASIS_ORDER + 1];
        for r in 0..=top {
            for k in 0..=p {
                weighted[r][k] = ders[r][k] * self.weight(first + k);
                total[r] += weighted[r][k];
            }
        }
        for k in 0..=p {
            let value = weighted[0][k] / total[0];
            rows[0][k] = value;
            if order >= 1 {
                rows[1][k] = (weighted[1][k] - value * total[1]) / total[0];
            }
            if order >= 2 {
                rows[2][k] =
                    (weighted[2][k] - 2.0 * rows[1][k] * total[1] - value * total[2]) / total[0];
            }
        }
        RationalBasis { first, rows }
    }

    /// The same curve with other weights (one finite positive weight per control point), or
    /// `None` when a weight is not. A non-rational curve becomes rational.
    pub fn with_weights(&self, weights: Vec<f64>) -> Option<Curve> {
        let valid = weights.len() == self.control_points().len()
            && weights.iter().all(|w| w.is_finite() && *w > 0.0);
        valid.then(|| {
            Curve::from_valid_parts(
                self.degree(),
                self.dimension(),
                self.control_points().to_vec(),
                Some(weights),
                self.knots().to_vec(),
                self.convention(),
            )
        })
    }
}

/// The basis derivatives up to `order` on `span` (A2.3 with `N × N` buffers, `p < N`), rows
/// `0..=order` copied into `out`.
fn copy_rows<const N: usize>(
    knots: &[f64],
    p: usize,
    span: usize,
    u: f64,
    order: usize,
    out: &mut [[f64; CAP]; MAX_BASIS_ORDER + 1],
) {
    let mut ders = [[0.0; N]; N];
    basis_derivatives(knots, p, span, u, order, &mut ders);
    for (row, values) in out.iter_mut().zip(&ders).take(order.min(p) + 1) {
        row[..=p].copy_from_slice(&values[..=p]);
    }
}

#[cfg(test)]
mod tests {
    use crate::spline::{Curve, CurveLimits};

    /// The rows reproduce the curve's own derivatives: `Σ_k R^(r)_k d_k = s^(r)(u)`.
    #[test]
    fn the_rows_reproduce_the_derivatives_of_a_rational_quadratic() {
        let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 1.0], [4.0, 3.0]];
        let curve = Curve::new(
            2,
            &points,
            &[0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0],
            Some(&[1.0, 0.5, 2.0, 1.0]),
            &CurveLimits::default(),
        )
        .unwrap();
        for u in [0.0, 0.2, 0.4, 0.7, 1.0] {
            let basis = curve.rational_basis_derivatives(u, 2);
            let mut expected = [[0.0; 3]; 3];
            curve.derivatives(u, &mut expected).unwrap();
            for (r, want) in expected.iter().enumerate() {
                let got: Vec<f64> = (0..2)
                    .map(|c| {
                        (0..=2)
                            .map(|k| basis.rows[r][k] * points[basis.first + k][c])
                            .sum()
                    })
                    .collect();
                for c in 0..2 {
                    assert!((got[c] - want[c]).abs() < 1e-12, "u {u} order {r}");
                }
            }
        }
    }
}
