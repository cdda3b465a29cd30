//! A surface's Bézier patches: the net of the part of a patch of knot spans over a parameter
//! rectangle, by blossoming one direction at a time (the curves' [`bezier_of_net`], first
//! along each row, then along each column of the result).

use super::surface::Surface;
use crate::spline::{CAP, bezier_of_net};

/// A rectangle of the parameter domain inside one patch of knot spans.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PatchRect {
    /// The knot span `a` in `u` (`t_a <= u < t_{a+1}`) and `b` in `v`.
    pub(crate) spans: (usize, usize),
    /// `[u0, u1]`, inside `[t_a, t_{a+1}]`.
    pub(crate) u: (f64, f64),
    /// `[v0, v1]`, inside `[s_b, s_{b+1}]`.
    pub(crate) v: (f64, f64),
}

impl Surface {
    /// The rectangles of `[u0, u1] × [v0, v1]` (inside the domain) cut by the knot lines, row
    /// of `u` spans by row; empty rectangles (a zero-width range) are left out.
    pub(crate) fn patch_rects(&self, range: [(f64, f64); 2]) -> Vec<PatchRect> {
        let cuts = |axis: &super::surface::Axis, (lo, hi): (f64, f64)| -> Vec<(usize, f64, f64)> {
            axis.spans()
                .filter_map(|(m, a, b)| {
                    let (from, to) = (a.max(lo), b.min(hi));
                    (from < to).then_some((m, from, to))
                })
                .collect()
        };
        let (us, vs) = (cuts(self.u(), range[0]), cuts(self.v(), range[1]));
        us.iter()
            .flat_map(|&(a, u0, u1)| {
                vs.iter().map(move |&(b, v0, v1)| PatchRect {
                    spans: (a, b),
                    u: (u0, u1),
                    v: (v0, v1),
                })
            })
            .collect()
    }

    /// The homogeneous Bézier points `B_rs` (`r = 0..=p` along `u`, `s = 0..=q`, row by row:
    /// `out[r (q + 1) + s]`) of the surface over `rect`: with `σ, τ` the rectangle's local
    /// parameters, `A(u, v) = Σ_r Σ_s B_rs B_r^p(σ) B_s^q(τ)` for the homogeneous surface
    /// `A = (w x, w y, w z, w)`. Each point is a convex combination of the net's.
    pub(crate) fn bezier_net(&self, rect: &PatchRect, out: &mut [[f64; 4]]) {
        let (p, q) = (self.u().degree(), self.v().degree());
        let (a, b) = rect.spans;
        let n_v = self.v().count();
        let homogeneous = self.homogeneous();
        // Along v: each row of the patch's net blossomed over [v0, v1].
        let mut rows = [[[0.0; 4]; CAP]; CAP];
        for (r, row) in rows.iter_mut().enumerate().take(p + 1) {
            let first = (a - p + r) * n_v + b - q;
            let net = &homogeneous[first..=first + q];
            bezier_of_net(q, self.v().knots(), b, net, rect.v.0, rect.v.1, row);
        }
        // Along u: each column of those blossomed over [u0, u1].
        let mut column = [[0.0; 4]; CAP];
        let mut blossoms = [[0.0; 4]; CAP];
        for s in 0..=q {
            for (r, point) in column.iter_mut().enumerate().take(p + 1) {
                *point = rows[r][s];
            }
            bezier_of_net(
                p,
                self.u().knots(),
                a,
                &column[..=p],
                rect.u.0,
                rect.u.1,
                &mut blossoms,
            );
            for r in 0..=p {
                out[r * (q + 1) + s] = blossoms[r];
            }
        }
    }
}
