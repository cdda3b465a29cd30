//! Points and partial derivatives up to order 2, as exact as de Boor's algorithm: the
//! curves' evaluation (crate::spline, `eval.rs`) applied one direction at a time.
//!
//! On the patch of spans `(a, b)` (`t_a <= u < t_{a+1}`, `s_b <= v < s_{b+1}`) the surface is
//! `O + X / W` with the net moved to a local origin `O` (the patch's first control point),
//! `H_ij = (w_ij (d_ij - O), w_ij)` and the homogeneous surface
//! `A(u, v) = Σ_i Σ_j N_{i,p}(u) M_{j,q}(v) H_ij`. Its partials are, as for a curve,
//! `A^(k,l) = Σ_i Σ_j N_{i,p-k}(u) M_{j,q-l}(v) Q^(k,l)_ij`, `Q^(k,l)` the hodograph net: `k`
//! differences in `u`, `l` in `v` (The NURBS Book eq. 3.17). The first difference in either
//! direction is taken from the data themselves
//! ([`crate::spline::first_hodograph_point`]), the others from the level below; every sum
//! weights them with non-negative basis functions. The rational quotient rule (The NURBS Book
//! A4.4) gives `S^(k,l) = (A^(k,l) - Σ_{(i,j) ≠ (0,0)} C(k,i) C(l,j) W^(i,j) S^(k-i,l-j)) / W`.
//!
//! At a knot the partials are those of the patch on its right (and at the domain's end, the
//! limit from the left), as for the curves.

use super::surface::Surface;
use crate::spline::{
    CAP, Point, basis_functions, basis_functions_of_every_degree, first_hodograph_point,
    hodograph_difference, multiply_add,
};

/// Highest order of the partial derivatives evaluated (`k + l <= 2`).
pub const MAX_PARTIAL_ORDER: usize = 2;

/// The point and partials at one parameter pair: `values[k][l] = ∂^(k+l) S / ∂u^k ∂v^l` for
/// `k + l <= order` (zero elsewhere), and the scales the partials' rounding is relative to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Partials {
    /// `values[k][l]`; `values[0][0]` is the point.
    pub values: [[Point; MAX_PARTIAL_ORDER + 1]; MAX_PARTIAL_ORDER + 1],
    /// The largest first `u`- and `v`-hodograph point of the patch (`|Q^(1,0)|`, `|Q^(0,1)|`
    /// divided by the smallest weight): the size against which `S_u`, `S_v` are small or zero
    /// (0 when `order = 0`).
    pub scales: [f64; 2],
}

impl Partials {
    /// `S(u, v)`.
    pub fn point(&self) -> Point {
        self.values[0][0]
    }

    /// `S_u`.
    pub fn du(&self) -> Point {
        self.values[1][0]
    }

    /// `S_v`.
    pub fn dv(&self) -> Point {
        self.values[0][1]
    }
}

impl Surface {
    /// The point `S(u, v)` for `(u, v)` in the domain (outside it the end patches are
    /// extrapolated). No allocation.
    pub fn point(&self, u: f64, v: f64) -> Point {
        self.point_in_spans(self.u().span(u), self.v().span(v), u, v)
    }

    /// [`Surface::point`] on the patch `(a, b)` (which holds `(u, v)`, or ends there).
    pub(crate) fn point_in_spans(&self, a: usize, b: usize, u: f64, v: f64) -> Point {
        let (p, q) = (self.u().degree(), self.v().degree());
        let mut nu = [0.0; CAP];
        let mut nv = [0.0; CAP];
        basis_functions(self.u().knots(), p, a, u, &mut nu);
        basis_functions(self.v().knots(), q, b, v, &mut nv);
        let origin = self.control_point(a - p, b - q);
        // Column by column, as `partials_in_spans` sums (the same point to the last bit).
        let mut sum = [0.0; 4];
        for (s, &m) in nv[..=q].iter().enumerate() {
            let j = b - q + s;
            let mut column = [0.0; 4];
            for (r, &n) in nu[..=p].iter().enumerate() {
                let i = a - p + r;
                let h = local(self.control_point(i, j), self.weight(i, j), origin);
                for c in 0..4 {
                    column[c] = multiply_add(n, h[c], column[c]);
                }
            }
            for c in 0..4 {
                sum[c] = multiply_add(m, column[c], sum[c]);
            }
        }
        if self.is_rational() {
            std::array::from_fn(|c| origin[c] + sum[c] / sum[3])
        } else {
            std::array::from_fn(|c| origin[c] + sum[c])
        }
    }

    /// The point and its partials up to `order` (at most [`MAX_PARTIAL_ORDER`]) at `(u, v)`
    /// in the domain (module docs).
    pub fn partials(&self, u: f64, v: f64, order: usize) -> Partials {
        self.partials_in_spans(self.u().span(u), self.v().span(v), u, v, order)
    }

    /// [`Surface::partials`] on the patch `(a, b)`.
    pub(crate) fn partials_in_spans(
        &self,
        a: usize,
        b: usize,
        u: f64,
        v: f64,
        order: usize,
    ) -> Partials {
        let order = order.min(MAX_PARTIAL_ORDER);
        if order == 0 {
            return Partials {
                values: [[[0.0; 3]; 3]; 3],
                scales: [0.0; 2],
            }
            .with_point(self.point_in_spans(a, b, u, v));
        }
        // Buffers sized for the degrees: low degrees (every real cubic) keep them small.
        match self.u().degree().max(self.v().degree()) {
            0..=3 => self.partials_sized::<4>(a, b, u, v, order),
            4..=7 => self.partials_sized::<8>(a, b, u, v, order),
            _ => self.partials_sized::<CAP>(a, b, u, v, order),
        }
    }

    /// [`Surface::partials_in_spans`] with buffers of `N > max(p, q)` entries (module docs).
    // The loops fill tables indexed by level and by row or column at once.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn partials_sized<const N: usize>(
        &self,
        a: usize,
        b: usize,
        u: f64,
        v: f64,
        order: usize,
    ) -> Partials {
        let (p, q) = (self.u().degree(), self.v().degree());
        let (ku, kv) = (self.u().knots(), self.v().knots());
        let mut nu = [[0.0; N]; N];
        let mut nv = [[0.0; N]; N];
        basis_functions_of_every_degree(ku, p, a, u, &mut nu);
        basis_functions_of_every_degree(kv, q, b, v, &mut nv);
        // The patch's control points and weights, read once.
        let mut points = [[[0.0; 3]; N]; N];
        let mut weights = [[1.0; N]; N];
        for r in 0..=p {
            for s in 0..=q {
                points[r][s] = self.control_point(a - p + r, b - q + s);
                weights[r][s] = self.weight(a - p + r, b - q + s);
            }
        }
        let origin = points[0][0];
        let (top_u, top_v) = (order.min(p), order.min(q));
        // The hodographs' factors `(p - k + 1) / (t_{i+p-k+1} - t_i)`, once per direction.
        let mut factors_u = [[0.0; N]; MAX_PARTIAL_ORDER + 1];
        for k in 1..=top_u {
            for r in k..=p {
                let i = a - p + r;
                factors_u[k][r] = (p - k + 1) as f64 / (ku[i + p - k + 1] - ku[i]);
            }
        }
        let mut factors_v = [[0.0; N]; MAX_PARTIAL_ORDER + 1];
        for l in 1..=top_v {
            for s in l..=q {
                let j = b - q + s;
                factors_v[l][s] = (q - l + 1) as f64 / (kv[j + q - l + 1] - kv[j]);
            }
        }
        // Squared largest first hodograph points in u and v, for the scales.
        let mut largest = [0.0f64; 2];
        let mut level = [[0.0; 4]; N];
        // Per column s of the patch: the u-hodograph levels k of the column (from the data),
        // summed against N_{·,p-k}(u): column[k][s].
        let mut column = [[[0.0; 4]; N]; MAX_PARTIAL_ORDER + 1];
        for s in 0..=q {
            for r in 0..=p {
                level[r] = local(points[r][s], weights[r][s], origin);
            }
            column[0][s] = contract(&level[..=p], &nu[p][..=p]);
            for k in 1..=top_u {
                for r in (k..=p).rev() {
                    let factor = factors_u[k][r];
                    level[r] = if k == 1 {
                        let h = first_hodograph_point(
                            factor,
                            (points[r][s], weights[r][s]),
                            (points[r - 1][s], weights[r - 1][s]),
                            origin,
                        );
                        largest[0] = largest[0].max(squared(h));
                        h
                    } else {
                        hodograph_difference(factor, level[r], level[r - 1])
                    };
                }
                column[k][s] = contract(&level[k..=p], &nu[p - k][..=p - k]);
            }
        }
        // Per row r of the patch: the v-hodograph levels l >= 1 (from the data), summed
        // against M_{·,q-l}(v): row[l][r].
        let mut row = [[[0.0; 4]; N]; MAX_PARTIAL_ORDER + 1];
        for r in 0..=p {
            for l in 1..=top_v {
                for s in (l..=q).rev() {
                    let factor = factors_v[l][s];
                    level[s] = if l == 1 {
                        let h = first_hodograph_point(
                            factor,
                            (points[r][s], weights[r][s]),
                            (points[r][s - 1], weights[r][s - 1]),
                            origin,
                        );
                        largest[1] = largest[1].max(squared(h));
                        h
                    } else {
                        hodograph_difference(factor, level[s], level[s - 1])
                    };
                }
                row[l][r] = contract(&level[l..=q], &nv[q - l][..=q - l]);
            }
        }
        let mut homogeneous = [[[0.0; 4]; MAX_PARTIAL_ORDER + 1]; MAX_PARTIAL_ORDER + 1];
        for k in 0..=top_u {
            homogeneous[k][0] = contract(&column[k][..=q], &nv[q][..=q]);
        }
        for l in 1..=top_v {
            homogeneous[0][l] = contract(&row[l][..=p], &nu[p][..=p]);
        }
        if order >= 2 && top_u >= 1 && top_v >= 1 {
            // Q^(1,1): v-differences of the u-hodograph columns, already summed in u.
            for s in (1..=q).rev() {
                level[s] = hodograph_difference(factors_v[1][s], column[1][s], column[1][s - 1]);
            }
            homogeneous[1][1] = contract(&level[1..=q], &nv[q - 1][..q]);
        }
        let mut values = rational_partials(&homogeneous, order, self.is_rational());
        values[0][0] = std::array::from_fn(|c| origin[c] + values[0][0][c]);
        let min_weight = if self.is_rational() {
            weights[..=p]
                .iter()
                .flat_map(|row| row[..=q].iter())
                .fold(f64::INFINITY, |m, &w| m.min(w))
        } else {
            1.0
        };
        Partials {
            values,
            scales: largest.map(|s| s.sqrt() / min_weight),
        }
    }
}

/// `(w (d - O), w)`.
#[inline(always)]
fn local(d: Point, w: f64, origin: Point) -> [f64; 4] {
    [
        w * (d[0] - origin[0]),
        w * (d[1] - origin[1]),
        w * (d[2] - origin[2]),
        w,
    ]
}

/// `|x|² + |y|² + |z|²` of a homogeneous point's first three coordinates.
#[inline(always)]
fn squared(h: [f64; 4]) -> f64 {
    h[0] * h[0] + h[1] * h[1] + h[2] * h[2]
}

impl Partials {
    fn with_point(mut self, point: Point) -> Partials {
        self.values[0][0] = point;
        self
    }
}

/// `Σ_r basis[r] · points[r]` (homogeneous, non-negative weights).
#[inline(always)]
fn contract(points: &[[f64; 4]], basis: &[f64]) -> [f64; 4] {
    let mut sum = [0.0; 4];
    for (h, &n) in points.iter().zip(basis) {
        for c in 0..4 {
            sum[c] = multiply_add(n, h[c], sum[c]);
        }
    }
    sum
}

/// `C(k, i)` for `k <= MAX_PARTIAL_ORDER`.
const BINOMIALS: [[f64; MAX_PARTIAL_ORDER + 1]; MAX_PARTIAL_ORDER + 1] =
    [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 2.0, 1.0]];

/// The partials `S^(k,l)`, `k + l <= order`, of `S = X / W` from the homogeneous ones
/// `A^(k,l) = (X, W)^(k,l)` (The NURBS Book A4.4); the point relative to the local origin.
fn rational_partials(
    a: &[[[f64; 4]; MAX_PARTIAL_ORDER + 1]; MAX_PARTIAL_ORDER + 1],
    order: usize,
    rational: bool,
) -> [[Point; MAX_PARTIAL_ORDER + 1]; MAX_PARTIAL_ORDER + 1] {
    let mut s = [[[0.0; 3]; MAX_PARTIAL_ORDER + 1]; MAX_PARTIAL_ORDER + 1];
    let w = a[0][0][3];
    for k in 0..=order {
        for l in 0..=order - k {
            let mut value = [a[k][l][0], a[k][l][1], a[k][l][2]];
            if rational {
                for i in 0..=k {
                    for j in 0..=l {
                        if i == 0 && j == 0 {
                            continue;
                        }
                        let factor = BINOMIALS[k][i] * BINOMIALS[l][j] * a[i][j][3];
                        for (c, x) in value.iter_mut().enumerate() {
                            *x -= factor * s[k - i][l - j][c];
                        }
                    }
                }
                value = value.map(|x| x / w);
            }
            s[k][l] = value;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::KnotForm;
    use crate::surface::SurfaceLimits;

    /// The quarter of a cylinder of radius 1 and height 2: a rational quadratic in `u` (the
    /// arc from `(1, 0)` to `(0, 1)`, weights `1, √2/2, 1`) times a line in `v` (`z` from 0
    /// to 2). Every point is at distance 1 from the `z` axis, `S_v = (0, 0, 2)`, and the
    /// normal `S_u × S_v` points away from the axis.
    fn quarter_cylinder() -> Surface {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let arc = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let points: Vec<Vec<Vec<f64>>> = arc
            .iter()
            .map(|xy| (0..2).map(|k| vec![xy[0], xy[1], 2.0 * k as f64]).collect())
            .collect();
        let weights = vec![vec![1.0, 1.0], vec![w, w], vec![1.0, 1.0]];
        Surface::from_knot_forms(
            (2, 1),
            &points,
            (
                KnotForm::Flat(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]),
                KnotForm::Flat(&[0.0, 0.0, 1.0, 1.0]),
            ),
            Some(&weights),
            &SurfaceLimits::default(),
        )
        .unwrap()
    }

    #[test]
    fn cylinder_points_and_partials() {
        let surface = quarter_cylinder();
        for i in 0..=10 {
            for k in 0..=4 {
                let (u, v) = (i as f64 / 10.0, k as f64 / 4.0);
                let partials = surface.partials(u, v, 2);
                let [x, y, z] = partials.point();
                assert!(((x * x + y * y).sqrt() - 1.0).abs() < 1e-15, "{u} {v}");
                assert!((z - 2.0 * v).abs() < 1e-15);
                assert_eq!(partials.point(), surface.point(u, v));
                let dv = partials.dv();
                assert!(dv[0].abs() < 1e-15 && dv[1].abs() < 1e-15);
                assert!((dv[2] - 2.0).abs() < 1e-15);
                // S_u is tangent to the circle: perpendicular to (x, y).
                let du = partials.du();
                assert!((du[0] * x + du[1] * y).abs() < 1e-14);
                assert_eq!(partials.values[0][2], [0.0; 3]);
                assert!(partials.values[1][1].iter().all(|c| c.abs() < 1e-15));
            }
        }
        // At u = 0: S_u = 2 (w_1 / w_0) (d_1 - d_0) = (0, √2, 0).
        let du = surface.partials(0.0, 0.3, 1).du();
        assert!((du[1] - std::f64::consts::SQRT_2).abs() < 1e-15 && du[0].abs() < 1e-15);
    }
}
