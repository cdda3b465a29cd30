//! The cells of a mesh: rectangles of the parameter domain inside one knot-span patch, each
//! with its Bézier net, and the bounds that certify how far the surface over a cell is from
//! the triangles over it (docs/method.md, "Meshes within a tolerance").
//!
//! On a cell with local parameters `(s, t) ∈ [0, 1]²` let `B` be the bilinear interpolant of
//! the surface's four corner points (`B = P00 (1−s)(1−t) + P10 s (1−t) + P01 (1−s) t +
//! P11 s t`). The mesh over the cell is the image of a triangulation of the square under the
//! map `L` that interpolates `S` linearly on each triangle. Then `|S − L| <= |S − B| + |B −
//! L_B| + |L_B − L|` everywhere (`L_B` interpolating `B` at the same vertices), and:
//!
//! * `|S − B| <= ε₁`: non-rational, `S − B` is a polynomial of bidegree `(p, q)` whose
//!   Bernstein coefficients are `d_ij − B(i/p, j/q)` (a bilinear function elevated); rational,
//!   `S − B = (X − W B) / W` and `X − W B` is a polynomial of bidegree `(p + 1, q + 1)`, so
//!   `ε₁ = max |coefficient of X − W B| / min (weight coefficient)` (positive weights).
//!   Sharper when the cell bends gently: `S − B` (or `X − W B`) vanishes at the corners, and
//!   bilinear interpolation of a function `f` on the unit square errs by at most
//!   `(max |f_ss| + max |f_tt|) / 8` (linear interpolation in `s`, then in `t`, each within
//!   `h² max |f''| / 8`, the second not enlarging the first's error); for a Bézier patch
//!   `max |f_ss| <= p (p − 1) max |Δ²_s d|` over its coefficients. So `ε₁` is the smaller of the
//!   two (a quadratic's coefficient bound is twice the second-difference one).
//! * `|B − L_B| <= |T| · max_e |Δs_e Δt_e| / 4` with `T = P00 − P10 − P01 + P11` the twist:
//!   `B − L_B = T (st − L(st))`, and `st − L(st)` is a quadratic with an indefinite Hessian,
//!   so its extremes over a triangle lie on the edges, where it is `−τ(1−τ) Δs Δt`. For the
//!   two triangles of a diagonal that is `|T| / 4`; for a fan from the centre, `|T| / 16`.
//! * `|L_B − L| <= max` over the cell's vertices of `|S − B|` there: `0` at the corners, and
//!   measured at the centre and the vertices of finer neighbours on the edges.
//! * Rounding: a vertex is the surface at a parameter rounded to a double, its net corner the
//!   surface at the exact fraction of the cell; they differ by at most
//!   `|∂S/∂s| · 2 ε |u| / (u₁ − u₀)` (and likewise in `v`), with `|∂S/∂s| <= p max |Δ_s P|
//!   (w_max / w_min)²`: negligible except on spans a few units of roundoff wide, where a cell
//!   whose bound it breaks cannot be certified.
//!
//! Since `L` maps the triangulation onto the mesh and `S` the square onto the surface, every
//! point of either is within that bound of a point of the other (Hausdorff distance).
//!
//! Any one triangle of a cell, whatever its vertices, also has a bound of its own, by the
//! surface's second partials along its edges: [`triangle`].

pub(crate) mod triangle;

use super::surface::Surface;
use crate::spline::bernstein::BINOMIAL;
use crate::spline::vector::{distance, norm, sub};
use crate::spline::{CAP, Point};

/// A rectangle of a patch and its Bézier net.
#[derive(Debug, Clone)]
pub(crate) struct Cell {
    /// `[u0, u1]` and `[v0, v1]`.
    pub(crate) u: (f64, f64),
    pub(crate) v: (f64, f64),
    /// Homogeneous Bézier points, `(p + 1)(q + 1)`, row by row (`r` along `u`).
    pub(crate) net: Vec<[f64; 4]>,
}

/// What the bounds of a cell need to know beyond its net.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CellBounds {
    /// `ε₁`: the bound of `|S − B|` on the cell.
    pub(crate) bilinear: f64,
    /// `|T|`, the twist of the corners.
    pub(crate) twist: f64,
    /// Second differences of the net along `u` and along `v` (which direction to halve).
    pub(crate) bends: [f64; 2],
    /// How far the surface at a vertex's rounded parameters may be from the net's corner
    /// (module docs): added to every bound of the cell.
    pub(crate) rounding: f64,
}

impl Cell {
    /// The cell's corner point `(i, j) ∈ {0, 1}²` (the net's corner, projected).
    pub(crate) fn corner(&self, i: usize, j: usize, degrees: (usize, usize)) -> Point {
        let (p, q) = degrees;
        let h = self.net[(i * p) * (q + 1) + j * q];
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    /// The bounds of the cell (module docs).
    pub(crate) fn bounds(&self, degrees: (usize, usize), rational: bool) -> CellBounds {
        let (p, q) = degrees;
        let corners = [
            self.corner(0, 0, degrees),
            self.corner(1, 0, degrees),
            self.corner(0, 1, degrees),
            self.corner(1, 1, degrees),
        ];
        let bilinear = |s: f64, t: f64| -> Point {
            std::array::from_fn(|c| {
                corners[0][c] * (1.0 - s) * (1.0 - t)
                    + corners[1][c] * s * (1.0 - t)
                    + corners[2][c] * (1.0 - s) * t
                    + corners[3][c] * s * t
            })
        };
        let twist: Point =
            std::array::from_fn(|c| corners[0][c] - corners[1][c] - corners[2][c] + corners[3][c]);
        let at = |r: usize, s: usize| self.net[r * (q + 1) + s];
        let bilinear_bound = if rational {
            rational_bilinear_bound(&self.net, degrees, &corners)
        } else {
            let mut largest = 0.0f64;
            for r in 0..=p {
                for s in 0..=q {
                    let h = at(r, s);
                    let b = bilinear(r as f64 / p as f64, s as f64 / q as f64);
                    largest = largest.max(distance([h[0], h[1], h[2]], b));
                }
            }
            largest
        };
        let project = |h: [f64; 4]| [h[0] / h[3], h[1] / h[3], h[2] / h[3]];
        let mut bends = [0.0f64; 2];
        let mut steps = [0.0f64; 2];
        for r in 0..=p {
            for s in 0..=q {
                if r < p {
                    steps[0] = steps[0].max(distance(project(at(r + 1, s)), project(at(r, s))));
                }
                if s < q {
                    steps[1] = steps[1].max(distance(project(at(r, s + 1)), project(at(r, s))));
                }
                if r >= 1 && r < p {
                    let d: Point = std::array::from_fn(|c| {
                        project(at(r + 1, s))[c] - 2.0 * project(at(r, s))[c]
                            + project(at(r - 1, s))[c]
                    });
                    bends[0] = bends[0].max(norm(d) * (p * (p - 1)) as f64);
                }
                if s >= 1 && s < q {
                    let d: Point = std::array::from_fn(|c| {
                        project(at(r, s + 1))[c] - 2.0 * project(at(r, s))[c]
                            + project(at(r, s - 1))[c]
                    });
                    bends[1] = bends[1].max(norm(d) * (q * (q - 1)) as f64);
                }
            }
        }
        // How far a vertex at a rounded parameter may be from the net's corner: the local
        // parameter is off by up to two units of roundoff of the parameter over the width, and
        // `|∂S/∂s| <= p max |Δ_s P| (w_max / w_min)²` (the rational hodograph bound).
        let (low, high) = self.net.iter().fold((f64::INFINITY, 0.0f64), |(l, h), x| {
            (l.min(x[3]), h.max(x[3]))
        });
        let spread = if rational { (high / low).powi(2) } else { 1.0 };
        let off = |(lo, hi): (f64, f64)| 2.0 * f64::EPSILON * lo.abs().max(hi.abs()) / (hi - lo);
        let rounding =
            spread * (p as f64 * steps[0] * off(self.u) + q as f64 * steps[1] * off(self.v));
        // The second-difference bound of bilinear interpolation (module docs), sharper than the
        // coefficients' for low degrees' bending (a quadratic's by half).
        let bilinear_bound = if rational {
            bilinear_bound
        } else {
            bilinear_bound.min((bends[0] + bends[1]) / 8.0)
        };
        CellBounds {
            bilinear: bilinear_bound,
            twist: norm(twist),
            bends,
            rounding,
        }
    }

    /// The bilinear interpolant of the cell's corners at local `(s, t)`.
    pub(crate) fn bilinear_at(&self, degrees: (usize, usize), s: f64, t: f64) -> Point {
        let corners = [
            self.corner(0, 0, degrees),
            self.corner(1, 0, degrees),
            self.corner(0, 1, degrees),
            self.corner(1, 1, degrees),
        ];
        std::array::from_fn(|c| {
            corners[0][c] * (1.0 - s) * (1.0 - t)
                + corners[1][c] * s * (1.0 - t)
                + corners[2][c] * (1.0 - s) * t
                + corners[3][c] * s * t
        })
    }

    /// The two halves (or `parts` equal parts) of the cell along `u` (`in_u`) or `v`, by de
    /// Casteljau on each column (or row) of the net.
    pub(crate) fn split(&self, degrees: (usize, usize), in_u: bool, parts: usize) -> Vec<Cell> {
        let (lo, hi) = if in_u { self.u } else { self.v };
        let mut out = Vec::with_capacity(parts);
        let mut rest = self.clone();
        for k in 1..parts {
            let at = lo + (hi - lo) * k as f64 / parts as f64;
            let (rest_lo, _) = if in_u { rest.u } else { rest.v };
            let fraction = (at - rest_lo) / (hi - rest_lo);
            let (left, right) = rest.split_at(degrees, in_u, fraction, at);
            out.push(left);
            rest = right;
        }
        out.push(rest);
        out
    }

    /// The cell cut at local fraction `fraction` of `u` (`in_u`) or `v`, the cut at
    /// parameter `at` (as the caller computed it: it becomes both pieces' common edge).
    fn split_at(
        &self,
        degrees: (usize, usize),
        in_u: bool,
        fraction: f64,
        at: f64,
    ) -> (Cell, Cell) {
        let (p, q) = degrees;
        let mut left = self.clone();
        let mut right = self.clone();
        let (count, lines) = if in_u { (p, q + 1) } else { (q, p + 1) };
        let index = |line: usize, k: usize| {
            if in_u {
                k * (q + 1) + line
            } else {
                line * (q + 1) + k
            }
        };
        let mut row = [[0.0; 4]; CAP];
        for line in 0..lines {
            for (k, slot) in row.iter_mut().enumerate().take(count + 1) {
                *slot = self.net[index(line, k)];
            }
            left.net[index(line, 0)] = row[0];
            right.net[index(line, count)] = row[count];
            for level in 1..=count {
                for i in 0..=count - level {
                    let (a, b) = (row[i], row[i + 1]);
                    row[i] = std::array::from_fn(|c| (1.0 - fraction) * a[c] + fraction * b[c]);
                }
                left.net[index(line, level)] = row[0];
                right.net[index(line, count - level)] = row[count - level];
            }
        }
        if in_u {
            left.u.1 = at;
            right.u.0 = at;
        } else {
            left.v.1 = at;
            right.v.0 = at;
        }
        (left, right)
    }
}

/// `ε₁` of a rational cell: the largest coefficient of `X − W B` (bidegree `(p + 1, q + 1)`)
/// over the smallest weight (module docs).
fn rational_bilinear_bound(net: &[[f64; 4]], (p, q): (usize, usize), corners: &[Point; 4]) -> f64 {
    let (m, n) = (p + 1, q + 1);
    let wide = n + 1;
    let difference = homogeneous_difference(net, (p, q), corners);
    let largest = difference.iter().map(|d| norm(*d)).fold(0.0f64, f64::max);
    // `X − W B` vanishes at the corners, so its bilinear interpolant is 0 and the
    // second-difference bound applies to it as well (module docs).
    let mut second = [0.0f64; 2];
    for k in 0..=m {
        for l in 0..=n {
            let at = |k: usize, l: usize| difference[k * wide + l];
            if k >= 1 && k < m {
                let d: Point =
                    std::array::from_fn(|c| at(k + 1, l)[c] - 2.0 * at(k, l)[c] + at(k - 1, l)[c]);
                second[0] = second[0].max(norm(d));
            }
            if l >= 1 && l < n {
                let d: Point =
                    std::array::from_fn(|c| at(k, l + 1)[c] - 2.0 * at(k, l)[c] + at(k, l - 1)[c]);
                second[1] = second[1].max(norm(d));
            }
        }
    }
    let bending = ((m * (m - 1)) as f64 * second[0] + (n * (n - 1)) as f64 * second[1]) / 8.0;
    let smallest_weight = net.iter().map(|h| h[3]).fold(f64::INFINITY, f64::min);
    largest.min(bending) / smallest_weight
}

/// The Bernstein coefficients, bidegree `(p + 1, q + 1)` row by row, of `X − W B` for a
/// homogeneous net (`X` its weighted points, `W` its weight) and `B` the bilinear function
/// with `corners` at `(0, 0), (1, 0), (0, 1), (1, 1)`: `X · 1` with `1 = (1 − s + s)(1 − t +
/// t)` and `W · B`, `B`'s scaled coefficients being its corners (`C(1, i) C(1, j) = 1`).
pub(crate) fn homogeneous_difference(
    net: &[[f64; 4]],
    (p, q): (usize, usize),
    corners: &[Point; 4],
) -> Vec<Point> {
    let (m, n) = (p + 1, q + 1);
    let wide = n + 1;
    let mut difference = vec![[0.0; 3]; (m + 1) * (n + 1)];
    for r in 0..=p {
        for s in 0..=q {
            let scale = BINOMIAL[p][r] * BINOMIAL[q][s];
            let h = net[r * (q + 1) + s];
            for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let corner = corners[i + 2 * j];
                let slot = &mut difference[(r + i) * wide + s + j];
                for c in 0..3 {
                    slot[c] += scale * (h[c] - h[3] * corner[c]);
                }
            }
        }
    }
    for k in 0..=m {
        for l in 0..=n {
            let scale = BINOMIAL[m][k] * BINOMIAL[n][l];
            for c in difference[k * wide + l].iter_mut() {
                *c /= scale;
            }
        }
    }
    difference
}

impl Surface {
    /// The cell of a patch rectangle, with its net.
    pub(crate) fn cell(&self, rect: &super::patches::PatchRect) -> Cell {
        let (p, q) = (self.u().degree(), self.v().degree());
        let mut net = vec![[0.0; 4]; (p + 1) * (q + 1)];
        self.bezier_net(rect, &mut net);
        Cell {
            u: rect.u,
            v: rect.v,
            net,
        }
    }
}

/// `|S(vertex) − B(vertex)|` for a vertex of a cell: how far the mesh's interpolation of the
/// surface there is from the cell's bilinear interpolant.
pub(crate) fn vertex_gap(
    cell: &Cell,
    degrees: (usize, usize),
    (u, v): (f64, f64),
    point: Point,
) -> f64 {
    let s = (u - cell.u.0) / (cell.u.1 - cell.u.0);
    let t = (v - cell.v.0) / (cell.v.1 - cell.v.0);
    norm(sub(point, cell.bilinear_at(degrees, s, t)))
}
