//! The rational tensor-product basis of a surface and its first partials at one parameter
//! pair: with the knots and weights kept, the point and both first partials are linear in the
//! poles, `S^(k,l)(u, v) = Σ_i Σ_j R_ij^(k,l)(u, v) d_ij`, which makes the control-point move a
//! linear system (docs/method.md §41).

use crate::spline::{CAP, MAX_DEGREE, basis_functions};
use crate::surface::Surface;

/// The `(p + 1)(q + 1)` basis functions that can be non-zero at `(u, v)`, with their first
/// partials: `values[k][r (q + 1) + s]` is `R^(k)_{first_u + r, first_v + s}(u, v)` for
/// `k = 0` (the value), `1` (`∂/∂u`) and `2` (`∂/∂v`).
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceBasis {
    /// The first pole index in `u` (`a - p` for the span `a` of `u`).
    pub first_u: usize,
    /// The first pole index in `v`.
    pub first_v: usize,
    /// `p + 1`.
    pub count_u: usize,
    /// `q + 1`.
    pub count_v: usize,
    /// Value, `∂/∂u`, `∂/∂v` of each active function, row by row.
    pub values: [Vec<f64>; 3],
}

impl SurfaceBasis {
    /// The active functions at `(u, v)` (in the domain) on the patch that evaluation uses (the
    /// one right of a knot; the last one at the domain's end).
    ///
    /// With `N_i^(r)`, `M_j^(r)` the B-spline functions and derivatives of each direction,
    /// `A_ij = N_i M_j w_ij` and `W = Σ A_ij` (quotient rule, The NURBS Book eq. 4.8 in two
    /// variables): `R_ij = A_ij / W`, `R_ij,u = (A_ij,u - R_ij W_u) / W` and likewise in `v`.
    /// For a non-rational surface `R_ij = N_i M_j`.
    // The loops fill the tensor product's tables by both indices at once.
    #[allow(clippy::needless_range_loop)]
    pub fn at(surface: &Surface, u: f64, v: f64) -> SurfaceBasis {
        let (p, q) = (surface.u().degree(), surface.v().degree());
        let (a, b) = (surface.u().span(u), surface.v().span(v));
        let nu = derivatives(surface.u().knots(), p, a, u);
        let nv = derivatives(surface.v().knots(), q, b, v);
        let (first_u, first_v) = (a - p, b - q);
        let len = (p + 1) * (q + 1);
        let mut values = [vec![0.0; len], vec![0.0; len], vec![0.0; len]];
        let mut total = [0.0; 3];
        for r in 0..=p {
            for s in 0..=q {
                let w = surface.weight(first_u + r, first_v + s);
                let k = r * (q + 1) + s;
                values[0][k] = nu[0][r] * nv[0][s] * w;
                values[1][k] = nu[1][r] * nv[0][s] * w;
                values[2][k] = nu[0][r] * nv[1][s] * w;
                for (t, value) in total.iter_mut().zip(&values) {
                    *t += value[k];
                }
            }
        }
        if surface.is_rational() {
            for k in 0..len {
                let value = values[0][k] / total[0];
                values[0][k] = value;
                values[1][k] = (values[1][k] - value * total[1]) / total[0];
                values[2][k] = (values[2][k] - value * total[2]) / total[0];
            }
        }
        SurfaceBasis {
            first_u,
            first_v,
            count_u: p + 1,
            count_v: q + 1,
            values,
        }
    }

    /// The pole `(i, j)` and the three values of active function `k`.
    pub fn entries(&self) -> impl Iterator<Item = ((usize, usize), [f64; 3])> + '_ {
        (0..self.count_u * self.count_v).map(move |k| {
            (
                (
                    self.first_u + k / self.count_v,
                    self.first_v + k % self.count_v,
                ),
                [self.values[0][k], self.values[1][k], self.values[2][k]],
            )
        })
    }
}

/// `N_{a-p+r}(t)` and its first derivative (rows 0, 1) on span `a` of `knots`, by the
/// derivative of the degree-`p` functions from those of degree `p - 1`:
/// `N'_{i,p} = p (N_{i,p-1} / (t_{i+p} - t_i) - N_{i+1,p-1} / (t_{i+p+1} - t_{i+1}))`.
fn derivatives(knots: &[f64], p: usize, a: usize, t: f64) -> [[f64; MAX_DEGREE + 1]; 2] {
    let mut out = [[0.0; MAX_DEGREE + 1]; 2];
    let mut full = [0.0; CAP];
    basis_functions(knots, p, a, t, &mut full);
    out[0][..=p].copy_from_slice(&full[..=p]);
    // The p functions of degree p - 1 on the span, N_{a-p+1..=a, p-1}.
    let mut lower = [0.0; CAP];
    basis_functions(knots, p - 1, a, t, &mut lower);
    let degree = p as f64;
    for r in 0..=p {
        let i = a - p + r;
        // N_{i,p-1} is lower[r - 1] (it exists for r >= 1), N_{i+1,p-1} is lower[r].
        let left = if r >= 1 {
            let gap = knots[i + p] - knots[i];
            if gap > 0.0 { lower[r - 1] / gap } else { 0.0 }
        } else {
            0.0
        };
        let right = if r < p {
            let gap = knots[i + p + 1] - knots[i + 1];
            if gap > 0.0 { lower[r] / gap } else { 0.0 }
        } else {
            0.0
        };
        out[1][r] = degree * (left - right);
    }
    out
}
