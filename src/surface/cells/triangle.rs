//! The bound of one triangle of a cell, whatever its vertices: how far the surface over the
//! triangle is from the flat triangle through its three surface points (docs/method.md §38,
//! "The bound of a triangle").
//!
//! Let `G` be a `C²` function on the triangle with vertices `x₀, x₁, x₂` (local parameters of
//! the cell, `[0, 1]²`) that vanishes at them, and `M_E = max |D²G[E, E]|` over the cell for a
//! direction `E`. Cut the triangle by segments parallel to one edge `E₀`; the segment at
//! fraction `r` from the opposite vertex is `r E₀` long and ends on the other two edges `E₁`,
//! `E₂` at fraction `r` of each. On the segment `G` is within `r² M_{E₀} / 8` of its chord
//! (linear interpolation of a function of one variable errs by at most `h² max|f''| / 8`,
//! also for vectors), and at the segment's ends, on edges where `G` vanishes at both ends,
//! `|G| <= r (1 − r) M_{E_k} / 2`. So
//!
//! `|G| <= max_r (A r² + C r (1 − r))`, `A = M_{E₀} / 8`, `C = max(M_{E₁}, M_{E₂}) / 2`,
//!
//! which is `A` when `C <= 2A` and `C² / (4 (C − A))` otherwise (at `r = C / (2 (C − A))`);
//! the bound is the least over the three edges as `E₀`. `M_E` is bounded by the convex hull:
//! `D²G[E, E] = a² G_ss + 2ab G_st + b² G_tt` for `E = (a, b)`, whose Bernstein coefficients
//! are those combinations of the coefficients of `G_ss`, `G_st` and `G_tt` elevated to the
//! bidegree of `G`.
//!
//! * Polynomial surface: `G = S − L` with `L` the linear interpolant of the three surface
//!   points, so `D²G = D²S` (one set of second partials per cell).
//! * Rational: `S − L = (X − W L) / W` with `X`, `W` the homogeneous numerator and the weight;
//!   `G = X − W L` is a polynomial of bidegree `(p + 1, q + 1)` vanishing at the vertices
//!   (`L` extended linearly over the cell), and `|S − L| <= |G| / min w` (positive weight
//!   coefficients).
//!
//! A quadratic patch `s² + st + t²` over the triangle `(0, 0), (1, 0), (0, 1)` errs by exactly
//! `1/3` at `(1/3, 1/3)`, and this bound is `1/3` there; the cell's bilinear bound
//! ([`super`]: `ε₁ + |T| / 4`) is `3/4`: the bound sees which diagonal follows the twist.

use super::{Cell, homogeneous_difference};
use crate::spline::Point;
use crate::spline::vector::{norm, sub};

/// The second partials `f_ss`, `f_st`, `f_tt` of a function of bidegree `(m, n)` on the unit
/// square, as Bernstein coefficients of bidegree `(m, n)` (row `r` along `s`).
pub(crate) struct SecondPartials {
    n: usize,
    ss: Vec<Point>,
    st: Vec<Point>,
    tt: Vec<Point>,
}

impl SecondPartials {
    /// The second partials of the function with Bernstein coefficients `net`, `(m + 1)(n + 1)`
    /// of them row by row: differences (`f_ss` has the coefficients `m (m − 1) Δ²_s d`, of
    /// bidegree `(m − 2, n)`, and so on), each elevated back to `(m, n)`.
    pub(crate) fn of(net: &[Point], m: usize, n: usize) -> SecondPartials {
        let at = |r: usize, c: usize| net[r * (n + 1) + c];
        let grid = |rows: usize, cols: usize, f: &dyn Fn(usize, usize) -> Point| -> Vec<Point> {
            (0..rows * cols).map(|k| f(k / cols, k % cols)).collect()
        };
        let zero = || vec![[0.0; 3]; (m + 1) * (n + 1)];
        let ss = if m >= 2 {
            let factor = (m * (m - 1)) as f64;
            let d = grid(m - 1, n + 1, &|r, c| {
                std::array::from_fn(|k| {
                    factor * (at(r + 2, c)[k] - 2.0 * at(r + 1, c)[k] + at(r, c)[k])
                })
            });
            let d = elevate(&d, m - 2, n, true);
            elevate(&d, m - 1, n, true)
        } else {
            zero()
        };
        let st = if m >= 1 && n >= 1 {
            let factor = (m * n) as f64;
            let d = grid(m, n, &|r, c| {
                std::array::from_fn(|k| {
                    factor * (at(r + 1, c + 1)[k] - at(r + 1, c)[k] - at(r, c + 1)[k] + at(r, c)[k])
                })
            });
            let d = elevate(&d, m - 1, n - 1, true);
            elevate(&d, m, n - 1, false)
        } else {
            zero()
        };
        let tt = if n >= 2 {
            let factor = (n * (n - 1)) as f64;
            let d = grid(m + 1, n - 1, &|r, c| {
                std::array::from_fn(|k| {
                    factor * (at(r, c + 2)[k] - 2.0 * at(r, c + 1)[k] + at(r, c)[k])
                })
            });
            let d = elevate(&d, m, n - 2, false);
            elevate(&d, m, n - 1, false)
        } else {
            zero()
        };
        SecondPartials { n, ss, st, tt }
    }

    /// `max |D²f[E, E]|` over the square for `E = (a, b)` (local units), by the convex hull
    /// of the coefficients of `a² f_ss + 2ab f_st + b² f_tt`.
    pub(crate) fn along(&self, [a, b]: [f64; 2]) -> f64 {
        let (aa, ab, bb) = (a * a, 2.0 * a * b, b * b);
        let mut largest = 0.0f64;
        for k in 0..self.ss.len() {
            let (x, y, z) = (self.ss[k], self.st[k], self.tt[k]);
            let v: Point = std::array::from_fn(|c| aa * x[c] + ab * y[c] + bb * z[c]);
            largest = largest.max(norm(v));
        }
        debug_assert!(self.ss.len() % (self.n + 1) == 0);
        largest
    }
}

/// A net of bidegree `(m, n)` (row `r` along `s`) elevated by one in `s` (`in_s`) or in `t`:
/// `c'_i = (i / (k + 1)) c_{i−1} + (1 − i / (k + 1)) c_i` along that direction.
fn elevate(net: &[Point], m: usize, n: usize, in_s: bool) -> Vec<Point> {
    let (rows, cols) = if in_s { (m + 2, n + 1) } else { (m + 1, n + 2) };
    let at = |r: usize, c: usize| net[r * (n + 1) + c];
    let mut out = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        for c in 0..cols {
            let (i, k) = if in_s { (r, m + 1) } else { (c, n + 1) };
            let weight = i as f64 / k as f64;
            let before = |x: usize| if in_s { at(x, c) } else { at(r, x) };
            let value: Point = if i == 0 {
                before(0)
            } else if i == k {
                before(k - 1)
            } else {
                let (lo, hi) = (before(i - 1), before(i));
                std::array::from_fn(|d| weight * lo[d] + (1.0 - weight) * hi[d])
            };
            out.push(value);
        }
    }
    out
}

/// `max_r (A r² + C r (1 − r))` over `r ∈ [0, 1]` (module docs), for `A = m₀ / 8`,
/// `C = m₁ / 2`.
fn sliced(m0: f64, m1: f64) -> f64 {
    let (a, c) = (m0 / 8.0, m1 / 2.0);
    if c <= 2.0 * a {
        a
    } else {
        c * c / (4.0 * (c - a))
    }
}

/// The bound of a function vanishing at the triangle `x` (local parameters) whose second
/// partials are `second` (module docs): the least over the three edges cut along.
pub(crate) fn vanishing_bound(second: &SecondPartials, x: [[f64; 2]; 3]) -> f64 {
    let edge = |i: usize, j: usize| [x[j][0] - x[i][0], x[j][1] - x[i][1]];
    // Edge k is opposite vertex k.
    let m = [
        second.along(edge(1, 2)),
        second.along(edge(2, 0)),
        second.along(edge(0, 1)),
    ];
    (0..3)
        .map(|k| sliced(m[k], m[(k + 1) % 3].max(m[(k + 2) % 3])))
        .fold(f64::INFINITY, f64::min)
}

/// The bounds of the triangles of one cell (module docs).
pub(crate) struct TriangleBounds<'a> {
    cell: &'a Cell,
    degrees: (usize, usize),
    /// The second partials of a polynomial surface, or `None` for a rational one.
    polynomial: Option<SecondPartials>,
    smallest_weight: f64,
}

impl<'a> TriangleBounds<'a> {
    pub(crate) fn new(cell: &'a Cell, degrees: (usize, usize), rational: bool) -> Self {
        let (p, q) = degrees;
        let polynomial = (!rational).then(|| {
            let net: Vec<Point> = cell.net.iter().map(|h| [h[0], h[1], h[2]]).collect();
            SecondPartials::of(&net, p, q)
        });
        let smallest_weight = cell.net.iter().map(|h| h[3]).fold(f64::INFINITY, f64::min);
        TriangleBounds {
            cell,
            degrees,
            polynomial,
            smallest_weight,
        }
    }

    /// The bound of `|S − L|` over the triangle with local parameters `x` and surface points
    /// `points` there (`L` interpolating them linearly), rounding aside.
    pub(crate) fn bound(&self, x: [[f64; 2]; 3], points: [Point; 3]) -> f64 {
        if let Some(second) = &self.polynomial {
            return vanishing_bound(second, x);
        }
        // L extended to the cell's corners: L(y) = P₀ + J (y − x₀), J = [P₁ − P₀, P₂ − P₀] K⁻¹
        // with K = [x₁ − x₀, x₂ − x₀].
        let (e1, e2) = (
            [x[1][0] - x[0][0], x[1][1] - x[0][1]],
            [x[2][0] - x[0][0], x[2][1] - x[0][1]],
        );
        let det = e1[0] * e2[1] - e2[0] * e1[1];
        if det == 0.0 || !det.is_finite() {
            return f64::INFINITY;
        }
        let (d1, d2) = (sub(points[1], points[0]), sub(points[2], points[0]));
        let linear = |y: [f64; 2]| -> Point {
            let (dy0, dy1) = (y[0] - x[0][0], y[1] - x[0][1]);
            // K⁻¹ (y − x₀) = (α, β).
            let alpha = (e2[1] * dy0 - e2[0] * dy1) / det;
            let beta = (e1[0] * dy1 - e1[1] * dy0) / det;
            std::array::from_fn(|c| points[0][c] + alpha * d1[c] + beta * d2[c])
        };
        let corners = [
            linear([0.0, 0.0]),
            linear([1.0, 0.0]),
            linear([0.0, 1.0]),
            linear([1.0, 1.0]),
        ];
        let (p, q) = self.degrees;
        let difference = homogeneous_difference(&self.cell.net, self.degrees, &corners);
        let second = SecondPartials::of(&difference, p + 1, q + 1);
        vanishing_bound(&second, x) / self.smallest_weight
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::bernstein::BINOMIAL;

    /// A small deterministic generator (xorshift).
    struct Random(u64);
    impl Random {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The surface of a homogeneous net at `(s, t)`, by the Bernstein sums directly.
    fn evaluate(net: &[[f64; 4]], (p, q): (usize, usize), s: f64, t: f64) -> Point {
        let basis = |n: usize, i: usize, x: f64| {
            BINOMIAL[n][i] * x.powi(i as i32) * (1.0 - x).powi((n - i) as i32)
        };
        let mut h = [0.0; 4];
        for r in 0..=p {
            for c in 0..=q {
                let b = basis(p, r, s) * basis(q, c, t);
                for k in 0..4 {
                    h[k] += b * net[r * (q + 1) + c][k];
                }
            }
        }
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    fn cell_of(net: Vec<[f64; 4]>) -> Cell {
        Cell {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
            net,
        }
    }

    /// The largest `|S − L|` over a dense barycentric grid of the triangle.
    fn sampled(cell: &Cell, degrees: (usize, usize), x: [[f64; 2]; 3]) -> f64 {
        let points = x.map(|y| evaluate(&cell.net, degrees, y[0], y[1]));
        let steps = 40;
        let mut worst = 0.0f64;
        for i in 0..=steps {
            for j in 0..=steps - i {
                let (b, c) = (i as f64 / steps as f64, j as f64 / steps as f64);
                let a = 1.0 - b - c;
                let s = a * x[0][0] + b * x[1][0] + c * x[2][0];
                let t = a * x[0][1] + b * x[1][1] + c * x[2][1];
                let on: Point =
                    std::array::from_fn(|k| a * points[0][k] + b * points[1][k] + c * points[2][k]);
                worst = worst.max(norm(sub(evaluate(&cell.net, degrees, s, t), on)));
            }
        }
        worst
    }

    #[test]
    fn the_quadratic_example_is_exact() {
        // S = (0, 0, s² + st + t²) as a biquadratic net (a polynomial of bidegree (2, 2)).
        let (p, q) = (2, 2);
        let mut net = Vec::new();
        for r in 0..=p {
            for c in 0..=q {
                let (i, j) = (r as f64 / 2.0, c as f64 / 2.0);
                // Blossom of s² (r/2 ones among two s arguments): [r == 2]; of st: i j; of t².
                let z = f64::from(u8::from(r == 2)) + i * j + f64::from(u8::from(c == 2));
                net.push([i, j, z, 1.0]);
            }
        }
        let cell = cell_of(net);
        let bounds = TriangleBounds::new(&cell, (p, q), false);
        let x = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let points = x.map(|y| evaluate(&cell.net, (p, q), y[0], y[1]));
        let bound = bounds.bound(x, points);
        assert!((bound - 1.0 / 3.0).abs() < 1e-12, "{bound}");
        assert!((sampled(&cell, (p, q), x) - 1.0 / 3.0).abs() < 1e-3);
        // The same net as rational (unit weights) meets the same bound.
        let rational = TriangleBounds::new(&cell, (p, q), true);
        assert!((rational.bound(x, points) - 1.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn the_bound_holds_against_dense_sampling() {
        let mut random = Random(0x9e37_79b9_7f4a_7c15);
        let mut tight = 0.0f64;
        for case in 0..400 {
            let degrees = (1 + case % 5, 1 + (case / 5) % 4);
            let (p, q) = degrees;
            let rational = case % 3 == 0;
            let net: Vec<[f64; 4]> = (0..(p + 1) * (q + 1))
                .map(|k| {
                    let (r, c) = (k / (q + 1), k % (q + 1));
                    let w = if rational {
                        0.3 + 2.7 * random.next()
                    } else {
                        1.0
                    };
                    let point = [
                        r as f64 / p as f64 + 0.3 * (random.next() - 0.5),
                        c as f64 / q as f64 + 0.3 * (random.next() - 0.5),
                        random.next() - 0.5,
                    ];
                    [point[0] * w, point[1] * w, point[2] * w, w]
                })
                .collect();
            let cell = cell_of(net);
            let bounds = TriangleBounds::new(&cell, degrees, rational);
            for _ in 0..4 {
                // Vertices anywhere in the square, or at corners and on edges as in a mesh.
                let mut corner = || {
                    let y = [random.next(), random.next()];
                    if random.next() < 0.5 {
                        y.map(|v| (v * 4.0).round() / 4.0)
                    } else {
                        y
                    }
                };
                let x = [corner(), corner(), corner()];
                let area = (x[1][0] - x[0][0]) * (x[2][1] - x[0][1])
                    - (x[2][0] - x[0][0]) * (x[1][1] - x[0][1]);
                if area.abs() < 1e-3 {
                    continue;
                }
                let points = x.map(|y| evaluate(&cell.net, degrees, y[0], y[1]));
                let bound = bounds.bound(x, points);
                let seen = sampled(&cell, degrees, x);
                assert!(
                    seen <= bound * (1.0 + 1e-9) + 1e-12,
                    "case {case}: sampled {seen} over the bound {bound} on {x:?}"
                );
                tight = tight.max(seen / bound);
            }
        }
        // The bound is not vacuous: some triangle comes within 10 % of it.
        assert!(tight > 0.9, "{tight}");
    }
}
