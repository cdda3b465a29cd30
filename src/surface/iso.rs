//! Iso-curves: the curve `u ↦ S(u, ṽ)` (or `v ↦ S(ũ, v)`) as a curve object, the bridge by
//! which the curves' methods act on a surface (docs/method.md §39).
//!
//! With `v` held at `ṽ`, `S(u, ṽ) = Σ_i N_i(u) W_i D_i / Σ_i N_i(u) W_i` with
//! `W_i = Σ_j M_j(ṽ) w_ij` and `D_i = Σ_j M_j(ṽ) w_ij d_ij / W_i`: the curve over the `u`
//! knots whose control points are the rows (curves along `v`) evaluated at `ṽ`, with their
//! weights. Each `D_i` is computed as de Boor's algorithm computes a point (the basis
//! functions of A2.2 against the row's points moved to a local origin), so the iso-curve is as
//! exact as the surface's evaluation.

use super::surface::{Axis, Direction, Surface};
use crate::spline::{CAP, Curve, Dimension, Point, basis_functions, multiply_add};

impl Surface {
    /// The iso-curve with `fixed` held at `parameter` (in that direction's domain): along `u`
    /// for `fixed = V`, along `v` for `fixed = U` (module docs). It is 3D, rational exactly
    /// when the surface is, and has the free direction's degree and knots in the caller's
    /// convention; a periodic free direction gives the curve cut open over one period, in
    /// the multiplicities form (an ordinary curve, which every curve method takes).
    pub fn iso_curve(&self, fixed: Direction, parameter: f64) -> Curve {
        let held = self.axis(fixed);
        let free = self.axis(fixed.other());
        let degree = held.degree();
        let span = held.span(parameter);
        let mut basis = [0.0; CAP];
        basis_functions(held.knots(), degree, span, parameter, &mut basis);
        let count = free.count();
        let mut points: Vec<Point> = Vec::with_capacity(count);
        let mut weights: Vec<f64> = Vec::with_capacity(count);
        for k in 0..count {
            // The k-th curve across the held direction, at `parameter`.
            let at = |l: usize| match fixed {
                Direction::V => (self.control_point(k, l), self.weight(k, l)),
                Direction::U => (self.control_point(l, k), self.weight(l, k)),
            };
            let origin = at(span - degree).0;
            let mut sum = [0.0; 4];
            for (r, &n) in basis[..=degree].iter().enumerate() {
                let (d, w) = at(span - degree + r);
                for c in 0..3 {
                    sum[c] = multiply_add(n * w, d[c] - origin[c], sum[c]);
                }
                sum[3] = multiply_add(n, w, sum[3]);
            }
            let point = if self.is_rational() {
                std::array::from_fn(|c| origin[c] + sum[c] / sum[3])
            } else {
                std::array::from_fn(|c| origin[c] + sum[c])
            };
            points.push(point);
            weights.push(sum[3]);
        }
        curve_along(free, points, self.is_rational().then_some(weights))
    }
}

/// The ordinary curve over `axis` (a periodic one cut open, in the multiplicities form).
fn curve_along(axis: &Axis, points: Vec<Point>, weights: Option<Vec<f64>>) -> Curve {
    Curve::from_valid_parts(
        axis.degree(),
        Dimension::Three,
        points,
        weights,
        axis.knots().to_vec(),
        axis.convention(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::KnotForm;
    use crate::surface::SurfaceLimits;

    #[test]
    fn iso_curves_are_the_surface_along_their_lines() {
        // A rational bicubic × biquadratic with uneven weights.
        let points: Vec<Vec<[f64; 3]>> = (0..5)
            .map(|i| {
                (0..4)
                    .map(|j| [i as f64, j as f64, ((i * 7 + j * 3) % 5) as f64 * 0.3])
                    .collect()
            })
            .collect();
        let weights: Vec<Vec<f64>> = (0..5)
            .map(|i| (0..4).map(|j| 0.5 + ((i + 2 * j) % 3) as f64).collect())
            .collect();
        let surface = Surface::from_knot_forms(
            (3, 2),
            &points,
            (
                KnotForm::Flat(&[0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0]),
                KnotForm::Flat(&[0.0, 0.0, 0.0, 0.7, 2.0, 2.0, 2.0]),
            ),
            Some(&weights),
            &SurfaceLimits::default(),
        )
        .unwrap();
        for fixed_v in [0.0, 0.35, 0.7, 2.0] {
            let curve = surface.iso_curve(Direction::V, fixed_v);
            assert!(curve.is_rational());
            assert_eq!(curve.domain(), (0.0, 1.0));
            for u in [0.0, 0.2, 0.4, 0.9, 1.0] {
                let (a, b) = (curve.point(u).unwrap(), surface.point(u, fixed_v));
                let gap: f64 = (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max);
                assert!(gap < 1e-14, "v = {fixed_v}, u = {u}: {a:?} vs {b:?}");
            }
        }
        let curve = surface.iso_curve(Direction::U, 0.4);
        assert_eq!(curve.domain(), (0.0, 2.0));
        for v in [0.0, 0.7, 1.3, 2.0] {
            let (a, b) = (curve.point(v).unwrap(), surface.point(0.4, v));
            let gap: f64 = (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max);
            assert!(gap < 1e-14, "v = {v}: {a:?} vs {b:?}");
        }
    }
}
