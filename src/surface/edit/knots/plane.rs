//! The plane condition of the mixed moves (docs/method.md §46): for a fixed value `c` of the
//! single direction's unknown knot, the pair's `q = 2` problem reaches only the plane of its
//! three poles `D_0(c), D_1(c), D_2(c)`, so `c` solves
//!
//! ```text
//! g(c) = det[ X_k(c) − p W_k(c) ]_{k = 0, 1, 2} = 0,
//! ```
//!
//! `(X_k, W_k)` the homogeneous poles times the common product `D_B(c) > 0` of the ratio
//! denominators holding the knot: a polynomial of degree `3 n_c`. Its Bernstein form (by
//! interpolation at Chebyshev–Lobatto nodes, or by exact products above degree 9) is
//! isolated by certified subdivision and each root refined by Newton's method.

use crate::shape::family::isolate::{IsolationOptions, isolate};
use crate::shape::family::local::{
    INTERPOLATION_DEGREE, LocalProblem, SearchBox, collocation_inverse, lobatto_nodes,
};
use crate::shape::family::roots::SEARCH_MARGIN;
use crate::shape::family::tensor::Tensor;

/// The roots `c` (knot values) of the plane condition `g` of the rows `rows` (poles already
/// shifted by the target) for the unknown local knot `m` of `B`, by certified isolation of
/// its Bernstein form; `budget` boxes at most.
pub(crate) fn plane_roots(rows: &[LocalProblem], m: usize, budget: &mut usize) -> Vec<f64> {
    let Some(search) = rows[0].search_box(&[m], SEARCH_MARGIN, 0.0) else {
        return Vec::new();
    };
    if search.admissible[0].1 <= search.admissible[0].0 {
        return Vec::new();
    }
    let det = plane_polynomial(rows, &search, m)
        .filter(|det| det.coefficients.iter().all(|c| c.is_finite()))
        .unwrap_or_else(|| plane_polynomial_by_products(rows, &search));
    let largest = det.coefficients.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if largest == 0.0 || !largest.is_finite() {
        // Identically zero: the three rows stay in one plane with the target (a planar
        // net); the one-direction families serve that case.
        return Vec::new();
    }
    let options = IsolationOptions {
        max_boxes: (*budget).min(2048),
        ..IsolationOptions::default()
    };
    let isolation = isolate(&det, 1, options, &|_, _| false);
    *budget = budget.saturating_sub(isolation.boxes);
    let (lo, hi) = search.admissible[0];
    let slope = det.derivative(0);
    isolation
        .roots
        .iter()
        .map(|root| {
            let s = newton(&det, &slope, root.point[0]);
            rows[0].knots_at(&search, [s, 0.0, 0.0])[m].clamp(lo, hi)
        })
        .collect()
}

/// Newton's method on the univariate polynomial `f` (derivative `slope`) from `start`, kept
/// in the unit interval; a step that does not lower `|f|` ends it (the isolating box's
/// centre is only within the box's width of the root).
fn newton(f: &Tensor, slope: &Tensor, start: f64) -> f64 {
    let value = |s: f64| {
        let mut out = [0.0];
        f.evaluate([s, 0.0, 0.0], &mut out);
        out[0]
    };
    let (mut s, mut fs) = (start, value(start));
    for _ in 0..NEWTON_STEPS {
        let mut d = [0.0];
        slope.evaluate([s, 0.0, 0.0], &mut d);
        if d[0] == 0.0 || fs == 0.0 {
            break;
        }
        let next = (s - fs / d[0]).clamp(0.0, 1.0);
        let fn_ = value(next);
        if fn_.is_nan() || fn_.abs() >= fs.abs() {
            break;
        }
        (s, fs) = (next, fn_);
    }
    s
}

/// Newton steps at most on the plane condition.
const NEWTON_STEPS: usize = 40;

/// The plane condition's polynomial `D_B³ · g` on the unit interval of `search` (ordinary
/// Bernstein basis) by interpolation: its values at the Chebyshev–Lobatto nodes of its
/// degree `3 n_c` (`n_c` the ratios of `B`'s de Boor triangle holding knot `m`, `D_B` the
/// product of their denominators), converted by the inverse collocation matrix; `None` when
/// the degree exceeds [`INTERPOLATION_DEGREE`].
pub(crate) fn plane_polynomial(
    rows: &[LocalProblem],
    search: &SearchBox,
    m: usize,
) -> Option<Tensor> {
    let q = rows[0].degree;
    let ratios: Vec<(usize, usize)> = (1..=q)
        .flat_map(|r| (r..=q).map(move |l| (l, l + q + 1 - r)))
        .filter(|&(lo, hi)| lo == m || hi == m)
        .collect();
    let degree = 3 * ratios.len();
    if degree > INTERPOLATION_DEGREE {
        return None;
    }
    let nodes = lobatto_nodes(degree);
    let inverse = collocation_inverse(degree);
    let values: Vec<f64> = nodes
        .iter()
        .map(|&s| {
            let knots = rows[0].knots_at(search, [s, 0.0, 0.0]);
            let d: f64 = ratios
                .iter()
                .map(|&(lo, hi)| knots[hi] - knots[lo])
                .product();
            let h: Vec<[f64; 4]> = rows.iter().map(|r| r.homogeneous_point(&knots)).collect();
            d * d * d * determinant(&h)
        })
        .collect();
    let size = degree + 1;
    let coefficients = (0..size)
        .map(|i| (0..size).map(|j| inverse[i * size + j] * values[j]).sum())
        .collect();
    Some(Tensor {
        degrees: [degree, 0, 0],
        components: 1,
        coefficients,
    })
}

/// The determinant of the first three coordinates of three homogeneous points.
fn determinant(h: &[[f64; 4]]) -> f64 {
    h[0][0] * (h[1][1] * h[2][2] - h[1][2] * h[2][1])
        - h[0][1] * (h[1][0] * h[2][2] - h[1][2] * h[2][0])
        + h[0][2] * (h[1][0] * h[2][1] - h[1][1] * h[2][0])
}

/// [`plane_polynomial`] by exact Bernstein arithmetic on the rows' numerators (any degree):
/// the determinant of their shifted coordinates, products and sums of polynomials.
pub(crate) fn plane_polynomial_by_products(rows: &[LocalProblem], search: &SearchBox) -> Tensor {
    let r: Vec<[Tensor; 3]> = rows
        .iter()
        .map(|row| {
            let numerator = row.numerator(search).scaled();
            [0, 1, 2].map(|c| {
                let mut weights = [0.0; 4];
                weights[c] = 1.0;
                numerator.combine(&weights)
            })
        })
        .collect();
    let minor = |a: &Tensor, b: &Tensor, c: &Tensor, d: &Tensor| {
        a.times(b).plus(&c.times(d).combine(&[-1.0]))
    };
    r[0][0]
        .times(&minor(&r[1][1], &r[2][2], &r[1][2], &r[2][1]))
        .plus(&r[0][1].times(&minor(&r[1][2], &r[2][0], &r[1][0], &r[2][2])))
        .plus(&r[0][2].times(&minor(&r[1][0], &r[2][1], &r[1][1], &r[2][0])))
        .unscaled()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::KnotForm;
    use crate::surface::SurfaceLimits;
    use crate::surface::edit::knots::iso::iso_curve_along;
    use crate::surface::edit::knots::mixed::{Oriented, direction_problems, rows_of, singles};
    use crate::surface::{Direction, Surface};

    #[test]
    fn the_plane_polynomial_by_interpolation_is_the_one_by_products() {
        let points: Vec<Vec<[f64; 3]>> = (0..7)
            .map(|i| {
                (0..6)
                    .map(|j| {
                        [
                            i as f64,
                            j as f64 + 0.1 * i as f64,
                            ((i * 5 + j * 3) % 4) as f64 * 0.4,
                        ]
                    })
                    .collect()
            })
            .collect();
        let weights: Vec<Vec<f64>> = (0..7)
            .map(|i| {
                (0..6)
                    .map(|j| 0.6 + ((i + 2 * j) % 3) as f64 * 0.5)
                    .collect()
            })
            .collect();
        let surface = Surface::from_knot_forms(
            (3, 2),
            &points,
            (
                KnotForm::Flat(&[0.0, 0.0, 0.0, 0.0, 0.2, 0.45, 0.7, 1.0, 1.0, 1.0, 1.0]),
                KnotForm::Flat(&[0.0, 0.0, 0.0, 0.3, 0.5, 0.8, 1.0, 1.0, 1.0]),
            ),
            Some(&weights),
            &SurfaceLimits::default(),
        )
        .unwrap();
        let (u, v) = (0.52, 0.61);
        let net = Oriented {
            surface: &surface,
            pair: Direction::U,
        };
        let curve_a = iso_curve_along(&surface, Direction::U, u, v);
        let curve_b = iso_curve_along(&surface, Direction::V, u, v);
        let mut compared = 0;
        for a in direction_problems(&curve_a, u, true, true, false) {
            for b in direction_problems(&curve_b, v, true, false, true) {
                let rows = rows_of(net, &a, &b, v, [2.5, 3.1, 0.7]);
                for m in singles(&b.local, &curve_b, true) {
                    let search = rows[0].search_box(&[m], SEARCH_MARGIN, 0.0).unwrap();
                    let by_values = plane_polynomial(&rows, &search, m).unwrap();
                    let by_products = plane_polynomial_by_products(&rows, &search);
                    let scale = by_products
                        .coefficients
                        .iter()
                        .fold(0.0f64, |s, c| s.max(c.abs()));
                    for s in [0.0, 0.13, 0.5, 0.77, 1.0] {
                        let (mut x, mut y) = ([0.0], [0.0]);
                        by_values.evaluate([s, 0.0, 0.0], &mut x);
                        by_products.evaluate([s, 0.0, 0.0], &mut y);
                        assert!(
                            (x[0] - y[0]).abs() <= 1e-12 * scale,
                            "m {m}, s {s}: {x:?} vs {y:?}"
                        );
                    }
                    compared += 1;
                }
            }
        }
        assert!(compared >= 10);
    }
}
