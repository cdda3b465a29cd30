//! Exact partials of a surface, for judging the evaluator's rounding: the tensor product
//! computed in exact rational arithmetic from the curves' exact evaluator
//! (tests/spline_core/exact.rs).
//!
//! `A^(k,l)(u, v) = Σ_i N_i^(k)(u) D_i^(l)(v)`, with `D_i^(l)` the exact homogeneous
//! derivatives of row `i` (a curve along `v` with control points `w_ij d_ij`, weights
//! `w_ij`) and `N_i^(k)` the exact basis derivatives in `u` (each the exact derivative of
//! the scalar curve whose control points are the unit vector `e_i`); then the quotient rule
//! `S^(k,l) = (A^(k,l) - Σ_{(i,j) ≠ (0,0)} C(k,i) C(l,j) W^(i,j) S^(k-i,l-j)) / W`, exactly.
//! Every `f64` of the data and the parameters is taken exactly.
//!
//! The rule ([`scales`]): an error is acceptable when at most `1e-12` of the scale of the
//! value. For the point, the diagonal of the control points' bounding box (or, when larger,
//! `(p + q + 2) ε` of the largest active control point, the rounding of a double near the
//! point, over `1e-12`). For a partial `(k, l)`, the size of what de Boor's hodograph
//! algorithm computes it from: `|Q^(k,l)|`, the largest point of the patch's hodograph net
//! (`k` differences in `u`, `l` in `v`, The NURBS Book eq. 3.17), and for a level beyond the
//! first in a direction also the level below times that difference's largest factor
//! `(p − k + 1) / (u_{i+p−k+1} − u_i)` (the first level in each direction is taken from the
//! data and keeps its own size); for rational surfaces propagated through the quotient rule
//! `M_kl = (|Q^(k,l)|_xyz + |Q^(k,l)|_w |S| + Σ C(k,i) C(l,j) |Q^(i,j)|_w M_{k−i,l−j}) / W`
//! (as the curves' rule, tests/spline_core/exact.rs). Unlike the curves' rule there is no
//! allowance for a textbook algorithm's own error.

use crate::corpus::SurfaceData;
use crate::curve_exact::{Fraction, Input, exact_homogeneous};

/// Allowed error, relative to the scale of each value (module docs).
pub const EXACT_RELATIVE: f64 = 1e-12;

/// The exact values `S^(k,l)`, `k + l <= order`, at `(u, v)`: `values[k][l]`.
pub fn exact_partials(
    surface: &SurfaceData,
    u: f64,
    v: f64,
    order: usize,
) -> Vec<Vec<[Fraction; 3]>> {
    let (p, q) = (surface.degree_u, surface.degree_v);
    let a = span(&surface.knots_u, p, surface.n_u(), u);
    // D_i^(l)(v) of the active rows.
    let rows: Vec<Vec<[Fraction; 4]>> = (a - p..=a)
        .map(|i| {
            let input = Input {
                degree: q,
                knots: surface.knots_v.clone(),
                points: surface.poles[i]
                    .iter()
                    .map(|d| [d[0], d[1], d[2]])
                    .collect(),
                weights: surface.weights.as_ref().map(|w| w[i].clone()),
            };
            exact_homogeneous(&input, v, order)
        })
        .collect();
    // N_i^(k)(u) of the active basis functions.
    let basis: Vec<Vec<Fraction>> = (a - p..=a)
        .map(|i| {
            let mut points = vec![[0.0; 3]; surface.n_u()];
            points[i][0] = 1.0;
            let input = Input {
                degree: p,
                knots: surface.knots_u.clone(),
                points,
                weights: None,
            };
            exact_homogeneous(&input, u, order)
                .into_iter()
                .map(|h| h[0].clone())
                .collect()
        })
        .collect();
    let zero = || Fraction::of(0.0);
    let mut homogeneous: Vec<Vec<[Fraction; 4]>> = Vec::new();
    for k in 0..=order {
        let mut row = Vec::new();
        for l in 0..=order - k {
            let mut sum: [Fraction; 4] = std::array::from_fn(|_| zero());
            for (n, d) in basis.iter().zip(&rows) {
                for c in 0..4 {
                    sum[c] = sum[c].add(&n[k].mul(&d[l][c]));
                }
            }
            row.push(sum);
        }
        homogeneous.push(row);
    }
    let w = homogeneous[0][0][3].clone();
    let mut values: Vec<Vec<[Fraction; 3]>> = Vec::new();
    for k in 0..=order {
        let mut row: Vec<[Fraction; 3]> = Vec::new();
        for l in 0..=order - k {
            let mut value: [Fraction; 3] = std::array::from_fn(|c| homogeneous[k][l][c].clone());
            for i in 0..=k {
                for j in 0..=l {
                    if i == 0 && j == 0 {
                        continue;
                    }
                    let factor =
                        Fraction::of(binomial(k, i) * binomial(l, j)).mul(&homogeneous[i][j][3]);
                    let lower = if i == 0 {
                        &row[l - j]
                    } else {
                        &values[k - i][l - j]
                    };
                    let lower = lower.clone();
                    for c in 0..3 {
                        value[c] = value[c].sub(&factor.mul(&lower[c]));
                    }
                }
            }
            row.push(value.map(|x| x.div(&w)));
        }
        values.push(row);
    }
    values
}

/// The span `m` holding `t` (the last non-empty one at the domain's end), as the core and the
/// curves' exact evaluator find it.
fn span(knots: &[f64], p: usize, count: usize, t: f64) -> usize {
    let n = count - 1;
    if t >= knots[n + 1] {
        return (p..=n)
            .rev()
            .find(|&m| knots[m] < knots[m + 1])
            .expect("a span");
    }
    (p..=n)
        .find(|&m| knots[m] <= t && t < knots[m + 1])
        .unwrap_or(p)
}

fn binomial(k: usize, i: usize) -> f64 {
    (0..i).fold(1.0, |acc, r| acc * (k - r) as f64 / (r + 1) as f64)
}

fn norm3(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The scales of the rule (module docs) at `(u, v)`: `out[k][l]` for the partial `(k, l)`,
/// the size for the point.
pub fn scales(surface: &SurfaceData, u: f64, v: f64, order: usize) -> Vec<Vec<f64>> {
    let (p, q) = (surface.degree_u, surface.degree_v);
    let a = span(&surface.knots_u, p, surface.n_u(), u);
    let b = span(&surface.knots_v, q, surface.n_v(), v);
    let (ku, kv) = (&surface.knots_u, &surface.knots_v);
    // The homogeneous net of the patch.
    let net: Vec<Vec<[f64; 4]>> = (a - p..=a)
        .map(|i| {
            (b - q..=b)
                .map(|j| {
                    let d = surface.poles[i][j];
                    let w = surface.weight(i, j);
                    [w * d[0], w * d[1], w * d[2], w]
                })
                .collect()
        })
        .collect();
    // raw[k][l] = (largest |Q^(k,l)|_xyz, largest |Q^(k,l)|_w) of the patch; factor_u[k],
    // factor_v[l]: the largest factors of the k-th (l-th) differences.
    let mut raw = vec![vec![(0.0, 0.0); order + 1]; order + 1];
    let mut factor_u = vec![0.0f64; order + 1];
    let mut factor_v = vec![0.0f64; order + 1];
    let mut u_level = net;
    for k in 0..=order.min(p) {
        if k > 0 {
            for r in (k..=p).rev() {
                let i = a - p + r;
                let factor = (p - k + 1) as f64 / (ku[i + p - k + 1] - ku[i]);
                factor_u[k] = factor_u[k].max(factor);
                let (lower, upper) = u_level.split_at_mut(r);
                for (h, before) in upper[0].iter_mut().zip(&lower[r - 1]) {
                    *h = std::array::from_fn(|c| factor * (h[c] - before[c]));
                }
            }
        }
        let mut level = u_level.clone();
        for l in 0..=(order - k).min(q) {
            if l > 0 {
                for row in &mut level[k..=p] {
                    for s in (l..=q).rev() {
                        let j = b - q + s;
                        let factor = (q - l + 1) as f64 / (kv[j + q - l + 1] - kv[j]);
                        factor_v[l] = factor_v[l].max(factor);
                        let before = row[s - 1];
                        row[s] = std::array::from_fn(|c| factor * (row[s][c] - before[c]));
                    }
                }
            }
            let mut largest = (0.0f64, 0.0f64);
            for row in &level[k..=p] {
                for h in &row[l..=q] {
                    largest.0 = largest.0.max(norm3([h[0], h[1], h[2]]));
                    largest.1 = largest.1.max(h[3].abs());
                }
            }
            raw[k][l] = largest;
        }
    }
    // A level beyond the first in a direction is the difference of the level below: its
    // rounding is that level's, times the factor (de Boor's hodographs; the first level is
    // taken from the data and keeps its own size).
    let mut magnitude = raw.clone();
    for total in 2..=order {
        for k in 0..=total {
            let l = total - k;
            let mut m = raw[k][l];
            if k >= 1 {
                let below = magnitude[k - 1][l];
                m.0 = m.0.max(factor_u[k] * below.0);
                m.1 = m.1.max(factor_u[k] * below.1);
            }
            if l >= 1 {
                let below = magnitude[k][l - 1];
                m.0 = m.0.max(factor_v[l] * below.0);
                m.1 = m.1.max(factor_v[l] * below.1);
            }
            magnitude[k][l] = m;
        }
    }
    let rational = surface.weights.is_some();
    let w = if rational {
        evaluate_weight(surface, u, v)
    } else {
        1.0
    };
    let point = norm3(surface.point_f64(u, v));
    // The point: the size, or the rounding of the coordinates' magnitude (the result itself
    // is a double near |S|), whichever is larger.
    let largest_pole = (a - p..=a)
        .flat_map(|i| (b - q..=b).map(move |j| (i, j)))
        .map(|(i, j)| norm3(surface.poles[i][j]))
        .fold(0.0, f64::max);
    let point_floor = (p + q + 2) as f64 * f64::EPSILON * largest_pole / EXACT_RELATIVE;
    let mut out = vec![vec![0.0; order + 1]; order + 1];
    for k in 0..=order {
        for l in 0..=order - k {
            if k == 0 && l == 0 {
                out[0][0] = surface.size().max(point_floor);
                continue;
            }
            let (xyz, weight) = magnitude[k][l];
            out[k][l] = if rational {
                let mut s = xyz + weight * point;
                for i in 0..=k {
                    for j in 0..=l {
                        if (i == 0 && j == 0) || (i == k && j == l) {
                            continue;
                        }
                        s +=
                            binomial(k, i) * binomial(l, j) * magnitude[i][j].1 * out[k - i][l - j];
                    }
                }
                s / w
            } else {
                xyz
            };
        }
    }
    out
}

/// `W(u, v) = Σ N_i M_j w_ij` in `f64` (a scale only).
fn evaluate_weight(surface: &SurfaceData, u: f64, v: f64) -> f64 {
    let nu = basis_f64(&surface.knots_u, surface.degree_u, surface.n_u(), u);
    let nv = basis_f64(&surface.knots_v, surface.degree_v, surface.n_v(), v);
    let mut w = 0.0;
    for &(i, n) in &nu {
        for &(j, m) in &nv {
            w += n * m * surface.weight(i, j);
        }
    }
    w
}

/// The non-zero basis functions at `t` in `f64` (Cox–de Boor's recursion
/// `N_{k,d} = (t - t_k) / (t_{k+d} - t_k) N_{k,d-1} + (t_{k+d+1} - t) / (t_{k+d+1} - t_{k+1})
/// N_{k+1,d-1}`), as `(index, value)`.
pub fn basis_f64(knots: &[f64], p: usize, count: usize, t: f64) -> Vec<(usize, f64)> {
    let m = span(knots, p, count, t);
    let mut values = vec![1.0];
    for d in 1..=p {
        let mut next = vec![0.0; d + 1];
        for (r, &value) in values.iter().enumerate() {
            // values[r] is N_{k,d-1}, k = m - (d - 1) + r: it feeds N_{k,d} and N_{k-1,d},
            // both over the denominator t_{k+d} - t_k.
            let k = m + 1 - d + r;
            let width = knots[k + d] - knots[k];
            if width > 0.0 {
                next[r + 1] += value * (t - knots[k]) / width;
                next[r] += value * (knots[k + d] - t) / width;
            }
        }
        values = next;
    }
    values
        .into_iter()
        .enumerate()
        .map(|(r, value)| (m - p + r, value))
        .collect()
}
