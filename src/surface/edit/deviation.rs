//! How far a surface edit moves the surface: the largest distance between two surfaces of the
//! same degrees, certified by Bernstein branch and bound on their common knot grid
//! (docs/method.md §43), the surface form of [`crate::shape::max_deviation`].
//!
//! The distinct knots of both surfaces in `u` (and in `v`) cut the compared rectangle into
//! cells on which both surfaces are single (rational) polynomial patches, whatever their knots
//! (a knot edit moves them). On a cell, with local parameters `(σ, τ) ∈ [0, 1]²`, each
//! surface's homogeneous Bézier net comes from blossoming ([`Surface::bezier_net`]), and the
//! squared gap is a ratio `N / D` of tensor-product Bernstein polynomials:
//!
//! * both polynomial: `N = Σ_c (B_old - B_new)_c²` (degrees `(2p, 2q)`), `D = 1`; with equal
//!   knots the difference net is blossomed directly (blossoming is linear), so unchanged
//!   patches give exactly zero;
//! * rational (either), homogeneous `(X, W)`: `N = |X_old W_new - X_new W_old|²` and
//!   `D = (W_old W_new)²` (degrees `(4p, 4q)`, `D > 0`).
//!
//! A Bernstein polynomial lies within the range of its coefficients and its corner
//! coefficients are its corner values. So when every coefficient of `N − M D` is `<= 0`, the
//! squared gap is at most `M` on the cell, and the corner values bound the maximum from
//! below. The cells wait in a queue by `max N / min D`; the first is either proven below
//! `M = best (1 + SURFACE_DEVIATION_RELATIVE_TOLERANCE)` and dropped, or halved (de Casteljau,
//! in the direction where its coefficients change most), its new corners raising `best`. When
//! the queue is empty the answer is `sqrt(M)`: never below the true maximum, and within the
//! tolerance of a distance the surfaces really have. A search that runs out of its budget
//! ([`MAX_CELLS`] halvings) answers the largest `max N / min D` left, still an upper bound.
//! Gaps below `1e-13` of the nets' size are rounding and not refined. A rational cell is first
//! bounded quickly by its degree-`(2p, 2q)` gaps ([`QuickCell`]) and squared only when that
//! bound does not already settle it.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::constraints::surface_edit_size;
use crate::spline::bernstein::{BINOMIAL, halve};
use crate::surface::Surface;
use crate::surface::patches::PatchRect;

/// Relative precision of the squared deviation: when the search converges, the answer `d`
/// satisfies `d² <= (1 + SURFACE_DEVIATION_RELATIVE_TOLERANCE) · best²` for a squared distance
/// `best²` the surfaces have at some parameter pair.
pub const SURFACE_DEVIATION_RELATIVE_TOLERANCE: f64 = 1e-3;

/// Halvings per call at most, which bounds the time whatever the input (the answer is then
/// still an upper bound, only looser).
pub const MAX_CELLS: usize = 2048;

/// Gaps below this fraction of the surface's size are rounding: the search stops refining.
const ZERO_GAP: f64 = 1e-13;

/// Halvings of one cell at most.
const MAX_DEPTH: u32 = 60;

/// A tensor-product Bernstein polynomial: degrees `(m, n)`, coefficients row by row.
#[derive(Debug, Clone)]
struct Poly {
    m: usize,
    n: usize,
    c: Vec<f64>,
}

impl Poly {
    fn max(&self) -> f64 {
        self.c.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
    }

    fn min(&self) -> f64 {
        self.c.iter().fold(f64::INFINITY, |a, &b| a.min(b))
    }

    /// The largest change between neighbouring coefficients along `σ` (`in_u`) or `τ`, times
    /// the degree: how much halving in that direction can tighten the bound.
    fn variation(&self, in_u: bool) -> f64 {
        let (m, n) = (self.m, self.n);
        let mut largest = 0.0f64;
        if in_u {
            for i in 0..m {
                for j in 0..=n {
                    largest = largest
                        .max((self.c[(i + 1) * (n + 1) + j] - self.c[i * (n + 1) + j]).abs());
                }
            }
            largest * m as f64
        } else {
            for i in 0..=m {
                for j in 0..n {
                    largest =
                        largest.max((self.c[i * (n + 1) + j + 1] - self.c[i * (n + 1) + j]).abs());
                }
            }
            largest * n as f64
        }
    }

    /// The values at the four corners of `[0, 1]²`.
    fn corners(&self) -> [f64; 4] {
        let w = self.n + 1;
        [
            self.c[0],
            self.c[self.n],
            self.c[self.m * w],
            self.c[self.m * w + self.n],
        ]
    }

    /// `self · other` (degrees add), by convolution in the scaled basis
    /// `C(m, i) C(n, j) b_ij`.
    fn times(&self, other: &Poly) -> Poly {
        let (m, n) = (self.m + other.m, self.n + other.n);
        let scaled = |p: &Poly| -> Vec<f64> {
            (0..=p.m)
                .flat_map(|i| (0..=p.n).map(move |j| (i, j)))
                .map(|(i, j)| p.c[i * (p.n + 1) + j] * BINOMIAL[p.m][i] * BINOMIAL[p.n][j])
                .collect()
        };
        let (a, b) = (scaled(self), scaled(other));
        let mut c = vec![0.0; (m + 1) * (n + 1)];
        for i in 0..=self.m {
            for j in 0..=self.n {
                let x = a[i * (self.n + 1) + j];
                if x == 0.0 {
                    continue;
                }
                for k in 0..=other.m {
                    let row = &b[k * (other.n + 1)..(k + 1) * (other.n + 1)];
                    let out = &mut c[(i + k) * (n + 1) + j..(i + k) * (n + 1) + j + other.n + 1];
                    for (o, y) in out.iter_mut().zip(row) {
                        *o += x * y;
                    }
                }
            }
        }
        for i in 0..=m {
            for j in 0..=n {
                c[i * (n + 1) + j] /= BINOMIAL[m][i] * BINOMIAL[n][j];
            }
        }
        Poly { m, n, c }
    }

    fn add_assign(&mut self, other: &Poly, sign: f64) {
        for (a, b) in self.c.iter_mut().zip(&other.c) {
            *a += sign * b;
        }
    }

    /// The halves at `σ = 1/2` (`in_u`) or `τ = 1/2`, each again on `[0, 1]²`.
    fn halves(&self, in_u: bool) -> (Poly, Poly) {
        let (m, n) = (self.m, self.n);
        let mut left = self.clone();
        let mut right = self.clone();
        let len = if in_u { m + 1 } else { n + 1 };
        let (mut line, mut low, mut high) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
        let lines = if in_u { n + 1 } else { m + 1 };
        for o in 0..lines {
            let at = |k: usize| {
                if in_u {
                    k * (n + 1) + o
                } else {
                    o * (n + 1) + k
                }
            };
            for (k, value) in line.iter_mut().enumerate() {
                *value = self.c[at(k)];
            }
            halve(&line, &mut low, &mut high);
            for k in 0..len {
                left.c[at(k)] = low[k];
                right.c[at(k)] = high[k];
            }
        }
        (left, right)
    }
}

/// One cell of the search: the squared gap's numerator and (rational) denominator.
struct Cell {
    upper: f64,
    numerator: Poly,
    denominator: Option<Poly>,
    depth: u32,
    /// A rational cell not yet squared (then `numerator` is empty).
    quick: Option<Box<QuickCell>>,
}

impl PartialEq for Cell {
    fn eq(&self, other: &Self) -> bool {
        self.upper.total_cmp(&other.upper) == Ordering::Equal
    }
}

impl Eq for Cell {}

impl PartialOrd for Cell {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Cell {
    fn cmp(&self, other: &Self) -> Ordering {
        self.upper.total_cmp(&other.upper)
    }
}

impl Cell {
    fn new(numerator: Poly, denominator: Option<Poly>, depth: u32) -> Cell {
        let top = numerator.max().max(0.0);
        let upper = match &denominator {
            None => top,
            Some(d) => {
                let low = d.min();
                if low > 0.0 { top / low } else { f64::INFINITY }
            }
        };
        Cell {
            upper,
            numerator,
            denominator,
            depth,
            quick: None,
        }
    }

    /// Whether every coefficient of `N − bound · D` is `<= 0`, so that `N / D <= bound` on the
    /// whole cell (a tighter test than `max N / min D` where `D` varies).
    fn below(&self, bound: f64) -> bool {
        match &self.denominator {
            None => self.numerator.max() <= bound,
            Some(d) => self
                .numerator
                .c
                .iter()
                .zip(&d.c)
                .all(|(n, d)| n - bound * d <= 0.0),
        }
    }

    /// The largest squared gap at the cell's corners.
    fn corner_value(&self) -> f64 {
        let n = self.numerator.corners();
        match &self.denominator {
            None => n.iter().fold(0.0f64, |a, &b| a.max(b)),
            Some(d) => {
                let d = d.corners();
                (0..4).fold(0.0f64, |a, k| a.max(n[k] / d[k]))
            }
        }
    }
}

/// A rational cell before its squared form: the gaps `G_c = X_c,old W_new − X_c,new W_old`
/// and `W = W_old W_new` (degrees `(2p, 2q)`), with the quick upper bound
/// `Σ_c max_k G_c,k² / (min_k W_k)²` of the squared gap `Σ_c G_c² / W²` and its corner values.
struct QuickCell {
    gaps: Vec<Poly>,
    weight: Poly,
    upper: f64,
    corner_value: f64,
}

impl QuickCell {
    fn new(gaps: Vec<Poly>, weight: Poly) -> QuickCell {
        let low = weight.min();
        let top: f64 = gaps
            .iter()
            .map(|g| g.c.iter().fold(0.0f64, |m, x| m.max(x.abs())).powi(2))
            .sum();
        let upper = if low > 0.0 {
            top / (low * low)
        } else {
            f64::INFINITY
        };
        let w = weight.corners();
        let corners: Vec<[f64; 4]> = gaps.iter().map(Poly::corners).collect();
        let corner_value = (0..4).fold(0.0f64, |m, k| {
            let squared: f64 = corners.iter().map(|c| c[k] * c[k]).sum();
            m.max(squared / (w[k] * w[k]))
        });
        QuickCell {
            gaps,
            weight,
            upper,
            corner_value,
        }
    }
}

/// Largest `|S_old(u, v) - S_new(u, v)|` over `rect` intersected with both domains, certified
/// (module docs): never below the true maximum; within a relative
/// [`SURFACE_DEVIATION_RELATIVE_TOLERANCE`]`/2` of an attained distance when the search
/// converges within [`MAX_CELLS`] halvings. Zero for an empty rectangle.
///
/// Precondition: both surfaces have the same degrees (their knots, poles and weights may all
/// differ).
pub fn surface_max_deviation(old: &Surface, new: &Surface, rect: [(f64, f64); 2]) -> f64 {
    let (p, q) = (old.u().degree(), old.v().degree());
    debug_assert_eq!((p, q), (new.u().degree(), new.v().degree()));
    let ranges: Vec<(f64, f64)> = (0..2)
        .map(|d| {
            let (a, b) = (old.domain()[d], new.domain()[d]);
            (rect[d].0.max(a.0).max(b.0), rect[d].1.min(a.1).min(b.1))
        })
        .collect();
    if ranges
        .iter()
        .any(|(lo, hi)| lo.partial_cmp(hi) != Some(Ordering::Less))
    {
        return 0.0;
    }
    let cuts = |old_knots: &[f64], new_knots: &[f64], (lo, hi): (f64, f64)| -> Vec<f64> {
        let mut cuts: Vec<f64> = old_knots
            .iter()
            .chain(new_knots)
            .copied()
            .filter(|&t| lo < t && t < hi)
            .chain([lo, hi])
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        cuts
    };
    let us = cuts(old.u().knots(), new.u().knots(), ranges[0]);
    let vs = cuts(old.v().knots(), new.v().knots(), ranges[1]);
    let rational = old.is_rational() || new.is_rational();
    let same_knots = old.u().knots() == new.u().knots() && old.v().knots() == new.v().knots();
    // Equal knots, both polynomial: the difference surface's own nets.
    let difference = (!rational && same_knots).then(|| {
        let points = old
            .control_points()
            .iter()
            .zip(new.control_points())
            .map(|(a, b)| [a[0] - b[0], a[1] - b[1], a[2] - b[2]])
            .collect();
        Surface::from_valid_parts(old.u().clone(), old.v().clone(), points, None)
    });
    let len = (p + 1) * (q + 1);
    let (mut net_old, mut net_new) = (vec![[0.0; 4]; len], vec![[0.0; 4]; len]);
    let mut queue = BinaryHeap::new();
    let mut quick_cells = Vec::new();
    let mut best = 0.0f64;
    for u in us.windows(2) {
        for v in vs.windows(2) {
            let (mu, mv) = (0.5 * (u[0] + u[1]), 0.5 * (v[0] + v[1]));
            let rect_of = |surface: &Surface| PatchRect {
                spans: (surface.u().span(mu), surface.v().span(mv)),
                u: (u[0], u[1]),
                v: (v[0], v[1]),
            };
            let cell = match &difference {
                Some(difference) => {
                    difference.bezier_net(&rect_of(difference), &mut net_old);
                    if net_old.iter().all(|h| h[..3] == [0.0; 3]) {
                        continue;
                    }
                    let coordinate = |c: usize| Poly {
                        m: p,
                        n: q,
                        c: net_old.iter().map(|h| h[c]).collect(),
                    };
                    Cell::new(sum_of_squares((0..3).map(coordinate)), None, 0)
                }
                None => {
                    old.bezier_net(&rect_of(old), &mut net_old);
                    new.bezier_net(&rect_of(new), &mut net_new);
                    if net_old == net_new {
                        continue;
                    }
                    let lane = |net: &[[f64; 4]], c: usize| Poly {
                        m: p,
                        n: q,
                        c: net.iter().map(|h| h[c]).collect(),
                    };
                    if rational {
                        let (w_old, w_new) = (lane(&net_old, 3), lane(&net_new, 3));
                        let gaps: Vec<Poly> = (0..3)
                            .map(|c| {
                                let mut gap = lane(&net_old, c).times(&w_new);
                                gap.add_assign(&lane(&net_new, c).times(&w_old), -1.0);
                                gap
                            })
                            .collect();
                        let w = w_old.times(&w_new);
                        let quick = QuickCell::new(gaps, w);
                        best = best.max(quick.corner_value);
                        quick_cells.push(quick);
                        continue;
                    } else {
                        let gaps = (0..3).map(|c| {
                            let mut gap = lane(&net_old, c);
                            gap.add_assign(&lane(&net_new, c), -1.0);
                            gap
                        });
                        Cell::new(sum_of_squares(gaps), None, 0)
                    }
                }
            };
            best = best.max(cell.corner_value());
            queue.push(cell);
        }
    }
    // Rational cells wait in their quick form; a cell gets its squared form only when it comes
    // first in the queue and its quick bound does not settle it.
    for quick in quick_cells {
        queue.push(Cell {
            upper: quick.upper,
            numerator: Poly {
                m: 0,
                n: 0,
                c: Vec::new(),
            },
            denominator: None,
            depth: 0,
            quick: Some(Box::new(quick)),
        });
    }
    let floor = (ZERO_GAP * surface_edit_size(old).max(surface_edit_size(new))).powi(2);
    let mut halvings = 0;
    while let Some(mut cell) = queue.pop() {
        let bound = best * (1.0 + SURFACE_DEVIATION_RELATIVE_TOLERANCE);
        if let Some(quick) = cell.quick.take() {
            if quick.upper > bound.max(floor) {
                let numerator = sum_of_squares(quick.gaps.into_iter());
                let denominator = quick.weight.times(&quick.weight);
                queue.push(Cell::new(numerator, Some(denominator), 0));
            }
            continue;
        }
        if cell.upper <= bound.max(floor) || cell.below(bound) {
            // Proven: the squared gap stays within `bound` on this cell.
            continue;
        }
        if halvings >= MAX_CELLS || cell.depth >= MAX_DEPTH {
            // Out of budget: the largest remaining upper bound (the queue's first) stands.
            return cell.upper.max(bound).sqrt();
        }
        halvings += 1;
        let in_u = cell.numerator.variation(true) >= cell.numerator.variation(false);
        let (n_low, n_high) = cell.numerator.halves(in_u);
        let (d_low, d_high) = match &cell.denominator {
            Some(d) => {
                let (low, high) = d.halves(in_u);
                (Some(low), Some(high))
            }
            None => (None, None),
        };
        for child in [
            Cell::new(n_low, d_low, cell.depth + 1),
            Cell::new(n_high, d_high, cell.depth + 1),
        ] {
            best = best.max(child.corner_value());
            queue.push(child);
        }
    }
    // Every cell was proven within the bound of its time, and `best` only grew.
    let answer = best * (1.0 + SURFACE_DEVIATION_RELATIVE_TOLERANCE);
    if best <= floor {
        best.sqrt()
    } else {
        answer.sqrt()
    }
}

/// `Σ_c g_c²` of polynomials of equal degrees.
fn sum_of_squares(gaps: impl Iterator<Item = Poly>) -> Poly {
    let mut total: Option<Poly> = None;
    for gap in gaps {
        let square = gap.times(&gap);
        match &mut total {
            Some(total) => total.add_assign(&square, 1.0),
            None => total = Some(square),
        }
    }
    total.unwrap_or(Poly {
        m: 0,
        n: 0,
        c: vec![0.0],
    })
}
