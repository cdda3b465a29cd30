//! How far a surface edit moves the surface: the largest distance between two surfaces of the
//! same degrees, certified by Bernstein branch and bound on their common knot grid
//! (docs/method.md §43), the surface form of [`crate::shape::max_deviation`].
//!
//! The distinct knots of both surfaces in `u` (and in `v`) cut the compared rectangle into
//! cells on which both surfaces are single (rational) polynomial patches, whatever their knots
//! (a knot edit moves them). A cell whose patch is the same in both surfaces (the same `2p`
//! knots around its span in `u`, `2q` in `v`, and the same `(p + 1)(q + 1)` homogeneous poles)
//! is skipped without any arithmetic. On the others, with local parameters
//! `(σ, τ) ∈ [0, 1]²`, each surface's homogeneous Bézier net comes from blossoming (the rows
//! along `v` once per call, `RowBlossoms`, then the columns along `u`), and the gap
//! `S_old − S_new` is one vector rational Bézier patch `G / W`:
//!
//! * both polynomial: `G = B_old − B_new`, `W = 1` (degrees `(p, q)`);
//! * rational (either), homogeneous `(X, W)`: `G = X_old W_new − X_new W_old` and
//!   `W = W_old W_new` (degrees `(2p, 2q)`, Bernstein products; every `w_k > 0` for positive
//!   weights).
//!
//! With Bernstein coefficients `(g_k, w_k)`, all `w_k > 0`, `G / W = Σ_k λ_k (g_k / w_k)` with
//! `λ_k = B_k w_k / Σ_j B_j w_j >= 0` summing to one: the gap lies in the convex hull of the
//! points `g_k / w_k`, so `|G / W|² <= max_k |g_k|² / w_k²` on the whole cell (the *rational
//! convex hull bound*; `+∞` when some `w_k <= 0`). The corner coefficients are corner values
//! and bound the maximum from below. The cells wait in a queue by their bound; the first is
//! either below `M = best (1 + SURFACE_DEVIATION_RELATIVE_TOLERANCE)` (then so is every other,
//! and the search ends) or split (de Casteljau on all four lanes at once, in the direction
//! where `|g_k|² / w_k²` changes most, at the Greville abscissa of the largest ratio clamped
//! to `[1/4, 3/4]`: the likely maximum then lies near a corner of both parts), its new
//! corners raising `best`. Where a cell is split never changes what is certified. The answer is
//! `sqrt(M)`: never below the true maximum, and within the tolerance of a distance the
//! surfaces really have. Near a maximum the points `g_k / w_k` of a cell of width `h` lie
//! within `O(h²)` of the patch, so the bound tightens like the squared form's did. A search
//! that runs out of its budget ([`MAX_CELLS`] halvings) answers the largest bound left, still
//! an upper bound. Gaps below `1e-13` of the nets' size are rounding and not refined.
//!
//! **Knot edits of a polynomial surface** (the same poles, other knots: the knot method's
//! solutions) take a shorter way ([`knot_edit_cells`]). Each cell's Bézier conversion is a
//! linear map of the `p + 1` poles of its span, the same for every pole column: the matrix
//! `E_c` (Bézier point `r` = `Σ_i E_c[r][i] P_{a-p+i}`) is made once per `u` cell and surface,
//! `F_k` once per `v` cell. A cell whose `v` knots around its span are unchanged sees only the
//! `u` knots move: there `S_old − S_new = Σ_j N_j(v) G_j(u)` with `G_j = C_j,old − C_j,new` the
//! gap of pole column `j`'s curve along `u` (the same `N_j(v) >= 0`, summing to one, in both
//! surfaces), whose Bézier points over `u` cell `c` are `g_j = E_c,old P_j − E_c,new P_j`; so
//! `|S_old − S_new|² <= max_{j, r} |g_jr|²` over the cell's `q + 1` columns bounds the cell
//! before its net is made, and the net is those columns' gaps converted along `v`. Rows
//! likewise where only the `v` knots moved. Where both moved, the gap passes through the
//! surface with the new `u` and the old `v` knots — a `u` move, then a `v` move — and is at most
//! the sum of the two bounds (that cell's net is made from both surfaces' nets). The cells
//! are visited by their bound, largest first; once a bound is within the tolerance of the
//! largest value found, the rest are skipped: their maxima cannot raise the answer by more
//! than the tolerance, so what is certified is unchanged.
//!
//! The earlier form squared the gap (`N = |G|²`, `D = W²`, degrees `(4p, 4q)` for rational
//! cells) and tested the coefficients of `N − M D`; the hull bound needs neither the squares
//! nor the quadrupled degree (docs/performance.md has the measured difference).
//!
//! One file (about 840 lines of code, then its tests) over 600 on purpose: the general cells,
//! the knot edits' cells and the branch and bound share the gap patch and its bounds and
//! certify one answer together. The knot edits' part (`knot_edit_cells`, `KnotAxis` and the
//! line conversions, some 300 lines) is the piece to move into a module of its own next.
use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::constraints::surface_edit_size;
use crate::spline::bernstein::BINOMIAL;
use crate::spline::bezier_of_net;
use crate::surface::Surface;

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

/// One homogeneous coefficient: `(g_x, g_y, g_z, w)`.
type Lanes = [f64; 4];

/// `|g|² / w²`, `+∞` when `w <= 0`.
fn ratio(h: &Lanes) -> f64 {
    if h[3] > 0.0 {
        (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]) / (h[3] * h[3])
    } else {
        f64::INFINITY
    }
}

/// The gap of a cell as a vector rational tensor-product Bézier patch `G / W` on `[0, 1]²`:
/// degrees `(m, n)`, coefficients `(g, w)` row by row (`c[i (n + 1) + j]`, `i` along `σ`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct GapPatch {
    m: usize,
    n: usize,
    c: Vec<Lanes>,
}

impl GapPatch {
    /// The rational convex hull bound `max_k |g_k|² / w_k²` of `|G / W|²` on `[0, 1]²`
    /// (module docs; `+∞` when some `w_k <= 0`).
    pub(crate) fn hull_bound(&self) -> f64 {
        self.c.iter().fold(0.0f64, |a, h| a.max(ratio(h)))
    }

    /// The largest `|G / W|²` at the four corners (a corner with `w <= 0` counts 0): values
    /// the patch has.
    fn corner_value(&self) -> f64 {
        let w = self.n + 1;
        [0, self.n, self.m * w, self.m * w + self.n]
            .iter()
            .map(|&k| {
                let r = ratio(&self.c[k]);
                if r.is_finite() { r } else { 0.0 }
            })
            .fold(0.0f64, f64::max)
    }

    /// Whether to halve along `σ` rather than `τ`: the direction with the larger change of
    /// `r_k = |g_k|² / w_k²` between neighbours, times its degree (how much halving in that
    /// direction can tighten the bound); the ratios computed once.
    fn split_in_u(&self) -> (bool, f64) {
        let (m, n) = (self.m, self.n);
        let r: Vec<f64> = self
            .c
            .iter()
            .map(|h| {
                let r = ratio(h);
                if r.is_finite() { r } else { f64::MAX / 4.0 }
            })
            .collect();
        let (mut along_u, mut along_v) = (0.0f64, 0.0f64);
        let mut top = 0;
        for i in 0..=m {
            for j in 0..=n {
                let here = r[i * (n + 1) + j];
                if here > r[top] {
                    top = i * (n + 1) + j;
                }
                if i < m {
                    along_u = along_u.max((r[(i + 1) * (n + 1) + j] - here).abs());
                }
                if j < n {
                    along_v = along_v.max((r[i * (n + 1) + j + 1] - here).abs());
                }
            }
        }
        let in_u = along_u * m as f64 >= along_v * n as f64;
        // At the Greville abscissa of the largest ratio (where the maximum likely is), kept
        // off the ends: the maximum then sits near a corner of both parts, whose corner
        // values raise `best` at once.
        let at = if in_u {
            (top / (n + 1)) as f64 / m as f64
        } else {
            (top % (n + 1)) as f64 / n as f64
        };
        (in_u, at.clamp(0.25, 0.75))
    }

    /// The parts `[0, t]` and `[t, 1]` along `σ` (`in_u`) or `τ`, each again on `[0, 1]²`.
    pub(crate) fn split(&self, in_u: bool, t: f64) -> (GapPatch, GapPatch) {
        let (m, n) = (self.m, self.n);
        let width = n + 1;
        let lerp = |a: &mut Lanes, b: &Lanes| {
            *a = [
                a[0] + t * (b[0] - a[0]),
                a[1] + t * (b[1] - a[1]),
                a[2] + t * (b[2] - a[2]),
                a[3] + t * (b[3] - a[3]),
            ];
        };
        let mut left = self.clone();
        let mut right = self.clone();
        // De Casteljau at t: level `l` gives the left part's point `l` (its first) and the
        // right part's point `len - 1 - l` (its last).
        if in_u {
            // Along σ: whole rows at once.
            let mut rows = self.c.clone();
            for level in 0..=m {
                let last = m - level;
                left.c[level * width..(level + 1) * width].copy_from_slice(&rows[..width]);
                right.c[last * width..(last + 1) * width]
                    .copy_from_slice(&rows[last * width..(last + 1) * width]);
                for k in 0..last {
                    let (low, high) = rows.split_at_mut((k + 1) * width);
                    for (a, b) in low[k * width..].iter_mut().zip(&high[..width]) {
                        lerp(a, b);
                    }
                }
            }
        } else {
            // Along τ: each row on its own, in place in the right part (a point of level
            // `l` at slot `n - l` is no longer blended after that level).
            for ((row, left_row), right_row) in self
                .c
                .chunks_exact(width)
                .zip(left.c.chunks_exact_mut(width))
                .zip(right.c.chunks_exact_mut(width))
            {
                right_row.copy_from_slice(row);
                for (level, left_point) in left_row.iter_mut().enumerate() {
                    let last = n - level;
                    *left_point = right_row[0];
                    for k in 0..last {
                        let next = right_row[k + 1];
                        lerp(&mut right_row[k], &next);
                    }
                }
            }
        }
        (left, right)
    }

    /// `G / W` at `(σ, τ)` (de Casteljau in both directions), for tests.
    #[cfg(test)]
    fn value(&self, s: f64, t: f64) -> Lanes {
        let (m, n) = (self.m, self.n);
        let mut rows: Vec<Lanes> = (0..=m)
            .map(|i| {
                let mut line: Vec<Lanes> = self.c[i * (n + 1)..(i + 1) * (n + 1)].to_vec();
                for level in 1..=n {
                    for k in 0..=n - level {
                        line[k] =
                            std::array::from_fn(|c| (1.0 - t) * line[k][c] + t * line[k + 1][c]);
                    }
                }
                line[0]
            })
            .collect();
        for level in 1..=m {
            for k in 0..=m - level {
                rows[k] = std::array::from_fn(|c| (1.0 - s) * rows[k][c] + s * rows[k + 1][c]);
            }
        }
        rows[0]
    }
}

/// One cell of the search.
struct Cell {
    upper: f64,
    patch: GapPatch,
    depth: u32,
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
    fn new(patch: GapPatch, depth: u32) -> Cell {
        Cell {
            upper: patch.hull_bound(),
            patch,
            depth,
        }
    }
}

/// Whether `old` on its span pair `(a, b)` and `new` on `(a2, b2)` are the same patch: the
/// same knots `t_{a-p+1} ..= t_{a+p}` (and in `v`) and the same homogeneous poles
/// `a-p ..= a` × `b-q ..= b`, all a patch depends on.
fn same_patch(
    old: &Surface,
    new: &Surface,
    (a, b): (usize, usize),
    (a2, b2): (usize, usize),
) -> bool {
    let (p, q) = (old.u().degree(), old.v().degree());
    if old.u().knots()[a + 1 - p..=a + p] != new.u().knots()[a2 + 1 - p..=a2 + p]
        || old.v().knots()[b + 1 - q..=b + q] != new.v().knots()[b2 + 1 - q..=b2 + q]
    {
        return false;
    }
    let (n_old, n_new) = (old.v().count(), new.v().count());
    let (h_old, h_new) = (old.homogeneous(), new.homogeneous());
    (0..=p).all(|r| {
        let (x, y) = ((a - p + r) * n_old + b - q, (a2 - p + r) * n_new + b2 - q);
        h_old[x..=x + q] == h_new[y..=y + q]
    })
}

/// The rows of a surface's patches blossomed along `v` over the search's `v` cells, each
/// computed once per call and shared by every `u` cell above it (a row is pole row `i`,
/// columns `b - q ..= b` of the cell's span `b`), and shared between the two surfaces where
/// the row's poles and the `2q` knots around the span are the same (the rows a weight or a
/// `u`-knot edit leaves alone).
struct RowBlossoms<'a> {
    surface: &'a Surface,
    /// The `v` span of each `v` cell.
    spans: Vec<usize>,
    /// The `v` range of each `v` cell.
    ranges: Vec<(f64, f64)>,
    /// `lanes[(k · rows + i) (q + 1) + s]`.
    lanes: Vec<Lanes>,
    filled: Vec<bool>,
}

impl<'a> RowBlossoms<'a> {
    fn new(surface: &'a Surface, vs: &[f64]) -> RowBlossoms<'a> {
        let ranges: Vec<(f64, f64)> = vs.windows(2).map(|v| (v[0], v[1])).collect();
        let spans = ranges
            .iter()
            .map(|&(a, b)| surface.v().span(0.5 * (a + b)))
            .collect();
        let rows = surface.u().count() * ranges.len();
        RowBlossoms {
            surface,
            spans,
            lanes: vec![[0.0; 4]; rows * (surface.v().degree() + 1)],
            filled: vec![false; rows],
            ranges,
        }
    }

    fn slot(&self, k: usize, i: usize) -> usize {
        k * self.surface.u().count() + i
    }

    /// The `2q` knots the patches of `v` cell `k` depend on.
    fn window(&self, k: usize) -> &[f64] {
        let (q, b) = (self.surface.v().degree(), self.spans[k]);
        &self.surface.v().knots()[b + 1 - q..=b + q]
    }

    /// The homogeneous poles of row `i` acting on `v` cell `k`.
    fn poles(&self, k: usize, i: usize) -> &[Lanes] {
        let (q, b) = (self.surface.v().degree(), self.spans[k]);
        let first = i * self.surface.v().count() + b - q;
        &self.surface.homogeneous()[first..=first + q]
    }

    /// Row `i` over `v` cell `k`, blossomed, or copied from `other` when `other` has the same
    /// row there.
    fn fill(&mut self, k: usize, i: usize, other: Option<&mut RowBlossoms>) {
        let slot = self.slot(k, i);
        if self.filled[slot] {
            return;
        }
        let q = self.surface.v().degree();
        let out = slot * (q + 1)..(slot + 1) * (q + 1);
        let shared = other.filter(|o| {
            i < o.surface.u().count()
                && o.window(k) == self.window(k)
                && o.poles(k, i) == self.poles(k, i)
        });
        match shared {
            Some(o) => {
                o.fill(k, i, None);
                let from = o.slot(k, i) * (q + 1);
                self.lanes[out].copy_from_slice(&o.lanes[from..from + q + 1]);
            }
            None => {
                let (v0, v1) = self.ranges[k];
                let first = i * self.surface.v().count() + self.spans[k] - q;
                bezier_of_net(
                    q,
                    self.surface.v().knots(),
                    self.spans[k],
                    &self.surface.homogeneous()[first..=first + q],
                    v0,
                    v1,
                    &mut self.lanes[out],
                );
            }
        }
        self.filled[slot] = true;
    }

    /// The homogeneous Bézier net `out[r (q + 1) + s]` over `[u0, u1]` × `v` cell `k` inside
    /// the `u` span `a` (rows `a - p ..= a` filled): each column of the rows blossomed along
    /// `u` (as [`Surface::bezier_net`] does per patch).
    fn net(&self, k: usize, a: usize, u: (f64, f64), work: &mut [Lanes], out: &mut [Lanes]) {
        let (p, q) = (self.surface.u().degree(), self.surface.v().degree());
        let (column, blossoms) = work.split_at_mut(p + 1);
        for s in 0..=q {
            for (r, point) in column.iter_mut().enumerate() {
                *point = self.lanes[self.slot(k, a - p + r) * (q + 1) + s];
            }
            bezier_of_net(p, self.surface.u().knots(), a, column, u.0, u.1, blossoms);
            for r in 0..=p {
                out[r * (q + 1) + s] = blossoms[r];
            }
        }
    }
}

/// The gap `G / W` of two homogeneous Bézier nets of degrees `(p, q)` (module docs): the
/// difference at `(p, q)` when both weights are 1, else `G = X_old W_new − X_new W_old`,
/// `W = W_old W_new` at `(2p, 2q)` by one Bernstein product in the scaled basis
/// `C(p, i) C(q, j) b_ij` (the sum over all pairs of `x_old,ij w_new,kl − x_new,ij w_old,kl`
/// into `(i + k, j + l)` equals `X_old W_new − X_new W_old`, the pairs being symmetric).
pub(crate) fn gap_patch(
    old: &[Lanes],
    new: &[Lanes],
    p: usize,
    q: usize,
    rational: bool,
) -> GapPatch {
    if !rational {
        return GapPatch {
            m: p,
            n: q,
            c: old
                .iter()
                .zip(new)
                .map(|(a, b)| [a[0] - b[0], a[1] - b[1], a[2] - b[2], 1.0])
                .collect(),
        };
    }
    let (m, n) = (2 * p, 2 * q);
    let (width, out_width) = (q + 1, n + 1);
    // Both nets in the scaled basis.
    let (mut a, mut b) = (Vec::with_capacity(old.len()), Vec::with_capacity(new.len()));
    for i in 0..=p {
        for j in 0..=q {
            let f = BINOMIAL[p][i] * BINOMIAL[q][j];
            let (x, y) = (old[i * width + j], new[i * width + j]);
            a.push([x[0] * f, x[1] * f, x[2] * f, x[3] * f]);
            b.push([y[0] * f, y[1] * f, y[2] * f, y[3] * f]);
        }
    }
    let mut c = vec![[0.0; 4]; (m + 1) * out_width];
    for i in 0..=p {
        for j in 0..=q {
            let x = a[i * width + j];
            for k in 0..=p {
                let start = (i + k) * out_width + j;
                let out = &mut c[start..start + width];
                for (o, y) in out.iter_mut().zip(&b[k * width..(k + 1) * width]) {
                    o[0] += x[0] * y[3] - y[0] * x[3];
                    o[1] += x[1] * y[3] - y[1] * x[3];
                    o[2] += x[2] * y[3] - y[2] * x[3];
                    o[3] += x[3] * y[3];
                }
            }
        }
    }
    for i in 0..=m {
        for j in 0..=n {
            let f = BINOMIAL[m][i] * BINOMIAL[n][j];
            let h = &mut c[i * out_width + j];
            *h = [h[0] / f, h[1] / f, h[2] / f, h[3] / f];
        }
    }
    GapPatch { m, n, c }
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
    // The size depends on the poles only, which knot and weight edits keep.
    let size = if old.control_points() == new.control_points() {
        surface_edit_size(old)
    } else {
        surface_edit_size(old).max(surface_edit_size(new))
    };
    let floor = (ZERO_GAP * size).powi(2);
    let knots_only = !rational
        && (old.u().count(), old.v().count()) == (new.u().count(), new.v().count())
        && old.homogeneous() == new.homogeneous();
    let (queue, best) = if knots_only {
        knot_edit_cells(old, new, (&us, &vs), floor)
    } else {
        changed_cells(old, new, (&us, &vs))
    };
    certify(queue, best, floor)
}

/// Every cell where the two surfaces differ, with its gap (module docs), and the largest
/// corner value.
fn changed_cells(
    old: &Surface,
    new: &Surface,
    (us, vs): (&[f64], &[f64]),
) -> (BinaryHeap<Cell>, f64) {
    let (p, q) = (old.u().degree(), old.v().degree());
    let rational = old.is_rational() || new.is_rational();
    let len = (p + 1) * (q + 1);
    let (mut net_old, mut net_new) = (vec![[0.0; 4]; len], vec![[0.0; 4]; len]);
    let mut work = vec![[0.0; 4]; 2 * (p + 1)];
    let (mut rows_old, mut rows_new) = (RowBlossoms::new(old, vs), RowBlossoms::new(new, vs));
    let mut queue = BinaryHeap::new();
    let mut best = 0.0f64;
    for u in us.windows(2) {
        let mu = 0.5 * (u[0] + u[1]);
        let (a_old, a_new) = (old.u().span(mu), new.u().span(mu));
        for k in 0..vs.len() - 1 {
            let spans_old = (a_old, rows_old.spans[k]);
            let spans_new = (a_new, rows_new.spans[k]);
            if same_patch(old, new, spans_old, spans_new) {
                continue;
            }
            for r in 0..=p {
                rows_old.fill(k, a_old - p + r, None);
                rows_new.fill(k, a_new - p + r, Some(&mut rows_old));
            }
            rows_old.net(k, a_old, (u[0], u[1]), &mut work, &mut net_old);
            rows_new.net(k, a_new, (u[0], u[1]), &mut work, &mut net_new);
            if net_old == net_new {
                continue;
            }
            let patch = gap_patch(&net_old, &net_new, p, q, rational);
            best = best.max(patch.corner_value());
            queue.push(Cell::new(patch, 0));
        }
    }
    (queue, best)
}

/// The `(degree + 1)²` matrix of the Bézier conversion of `[x0, x1]` inside span `span` of the
/// full knots `knots`: entry `(r, i)` (row-major) weighs pole `span - degree + i` in Bézier point
/// `r`. Made by [`bezier_of_net`] on unit poles, four at a time in its four lanes (blossoming
/// is affine, so each lane carries one column).
fn conversion_matrix(degree: usize, knots: &[f64], span: usize, (x0, x1): (f64, f64)) -> Vec<f64> {
    let n = degree + 1;
    let mut matrix = vec![0.0; n * n];
    let (mut unit, mut out) = (vec![[0.0; 4]; n], vec![[0.0; 4]; n]);
    for first in (0..n).step_by(4) {
        for (i, point) in unit.iter_mut().enumerate() {
            *point = std::array::from_fn(|lane| if i == first + lane { 1.0 } else { 0.0 });
        }
        bezier_of_net(degree, knots, span, &unit, x0, x1, &mut out);
        for (r, point) in out.iter().enumerate() {
            for (lane, &value) in point.iter().enumerate().take(n - first) {
                matrix[r * n + first + lane] = value;
            }
        }
    }
    matrix
}

/// One direction of a knot edit's cells: the spans of both surfaces over each cell, whether
/// the `2 degree` knots around it moved, and each cell's conversion matrices: the new
/// surface's where they moved, the old surface's there and, on demand
/// ([`KnotAxis::old_matrix`]), wherever a visited cell needs them.
struct KnotAxis<'a> {
    cuts: &'a [f64],
    degree: usize,
    old_knots: &'a [f64],
    spans: Vec<(usize, usize)>,
    moved: Vec<bool>,
    /// Empty until made.
    old: Vec<Vec<f64>>,
    new: Vec<Vec<f64>>,
}

impl<'a> KnotAxis<'a> {
    fn new(
        cuts: &'a [f64],
        degree: usize,
        (old, new): (&'a [f64], &[f64]),
        span: impl Fn(f64) -> (usize, usize),
    ) -> KnotAxis<'a> {
        let p = degree;
        let cells = cuts.len() - 1;
        let mut axis = KnotAxis {
            cuts,
            degree,
            old_knots: old,
            spans: Vec::with_capacity(cells),
            moved: Vec::with_capacity(cells),
            old: vec![Vec::new(); cells],
            new: vec![Vec::new(); cells],
        };
        for (c, cell) in cuts.windows(2).enumerate() {
            let (a, a2) = span(0.5 * (cell[0] + cell[1]));
            let moved = a != a2 || old[a + 1 - p..=a + p] != new[a2 + 1 - p..=a2 + p];
            axis.spans.push((a, a2));
            axis.moved.push(moved);
            if moved {
                axis.new[c] = conversion_matrix(p, new, a2, (cell[0], cell[1]));
                axis.old_matrix(c);
            }
        }
        axis
    }

    /// The old surface's conversion matrix of cell `c`, made on first use.
    fn old_matrix(&mut self, c: usize) -> &[f64] {
        if self.old[c].is_empty() {
            let range = (self.cuts[c], self.cuts[c + 1]);
            self.old[c] = conversion_matrix(self.degree, self.old_knots, self.spans[c].0, range);
        }
        &self.old[c]
    }
}

/// `out[r] = Σ_i matrix[r][i] · points[i]` (`n = points.len()`), three coordinates.
fn convert(matrix: &[f64], points: &[[f64; 3]], out: &mut [[f64; 3]]) {
    let n = points.len();
    for (r, value) in out.iter_mut().enumerate().take(n) {
        let weights = &matrix[r * n..(r + 1) * n];
        let mut sum = [0.0; 3];
        for (&weight, x) in weights.iter().zip(points) {
            sum[0] += weight * x[0];
            sum[1] += weight * x[1];
            sum[2] += weight * x[2];
        }
        *value = sum;
    }
}

/// [`convert`] of many lines of poles at once: `lines` holds `n` rows of `width` numbers (row
/// `i` the `i`-th pole of every line, coordinates interleaved), `out` gets `n` such rows,
/// `out[r][x] = Σ_i matrix[r][i] · lines[i][x]`. The rows are contiguous, so the inner loop
/// runs over whole rows of numbers (and vectorizes), where converting line by line did not.
fn convert_lines(matrix: &[f64], lines: &[f64], width: usize, out: &mut [f64]) {
    let n = out.len() / width;
    let line = |i: usize| &lines[i * width..(i + 1) * width];
    for (r, out_row) in out.chunks_exact_mut(width).enumerate() {
        let weights = &matrix[r * n..(r + 1) * n];
        if let [w0, w1, w2, w3] = *weights {
            // Cubics (most surfaces): the four terms in one pass over the row.
            let terms = line(0).iter().zip(line(1)).zip(line(2)).zip(line(3));
            for (o, (((x0, x1), x2), x3)) in out_row.iter_mut().zip(terms) {
                *o = w0 * x0 + w1 * x1 + w2 * x2 + w3 * x3;
            }
        } else {
            for (o, &x) in out_row.iter_mut().zip(line(0)) {
                *o = weights[0] * x;
            }
            for (i, &weight) in weights.iter().enumerate().skip(1) {
                for (o, &x) in out_row.iter_mut().zip(line(i)) {
                    *o += weight * x;
                }
            }
        }
    }
}

fn squared(x: &[f64]) -> f64 {
    x[0] * x[0] + x[1] * x[1] + x[2] * x[2]
}

/// The largest `|g|²` of each line in a block of converted gaps (`degree + 1` rows of `lines`
/// points each, [`convert_lines`]'s layout): `largest[l] = max_r |gaps[r][l]|²`.
fn largest_per_line(gaps: &[f64], lines: usize) -> Vec<f64> {
    let mut largest = vec![0.0f64; lines];
    for row in gaps.chunks_exact(3 * lines) {
        for (l, point) in row.chunks_exact(3).enumerate() {
            largest[l] = largest[l].max(squared(point));
        }
    }
    largest
}

/// The cells of a knot edit of a polynomial surface (module docs, "Knot edits"): every cell
/// where knots moved, by its bound, largest first; the gap nets of those that can still raise
/// the answer, and the largest corner value.
fn knot_edit_cells(
    old: &Surface,
    new: &Surface,
    (us, vs): (&[f64], &[f64]),
    floor: f64,
) -> (BinaryHeap<Cell>, f64) {
    let (p, q) = (old.u().degree(), old.v().degree());
    let (rows, columns) = (old.u().count(), old.v().count());
    // The poles row by row along u (`by_rows[i][j]`, for converting columns along u) and
    // column by column along v (`by_columns[j][i]`, for converting rows along v).
    let homogeneous = old.homogeneous();
    let (mut by_rows, mut by_columns) =
        (vec![0.0; 3 * rows * columns], vec![0.0; 3 * rows * columns]);
    for (flat, h) in homogeneous.iter().enumerate() {
        let (i, j) = (flat / columns, flat % columns);
        by_rows[3 * flat..3 * flat + 3].copy_from_slice(&h[..3]);
        by_columns[3 * (j * rows + i)..3 * (j * rows + i) + 3].copy_from_slice(&h[..3]);
    }
    let mut u = KnotAxis::new(us, p, (old.u().knots(), new.u().knots()), |x| {
        (old.u().span(x), new.u().span(x))
    });
    let mut v = KnotAxis::new(vs, q, (old.v().knots(), new.v().knots()), |x| {
        (old.v().span(x), new.v().span(x))
    });
    // Every pole column converted along u over each moved u cell by both surfaces, as
    // `p + 1` rows of `columns` points (`[r][j]`), their gap and each column's largest
    // squared gap point.
    let (width_u, width_v) = (3 * columns, 3 * rows);
    let cells_u = us.len() - 1;
    let (mut column_old, mut column_new) = (vec![Vec::new(); cells_u], vec![Vec::new(); cells_u]);
    let mut column_gaps = vec![Vec::new(); cells_u];
    let mut column_largest = vec![Vec::new(); cells_u];
    for c in (0..cells_u).filter(|&c| u.moved[c]) {
        let (a, a2) = u.spans[c];
        let converted_along_u = |matrix: &[f64], span: usize| -> Vec<f64> {
            let mut out = vec![0.0; (p + 1) * width_u];
            convert_lines(matrix, &by_rows[(span - p) * width_u..], width_u, &mut out);
            out
        };
        let converted_old = converted_along_u(&u.old[c], a);
        let converted_new = converted_along_u(&u.new[c], a2);
        let gaps: Vec<f64> = converted_old
            .iter()
            .zip(&converted_new)
            .map(|(o, n)| o - n)
            .collect();
        column_largest[c] = largest_per_line(&gaps, columns);
        column_gaps[c] = gaps;
        column_old[c] = converted_old;
        column_new[c] = converted_new;
    }
    // Every pole row's gap along v over each moved v cell (`q + 1` rows of `rows` points,
    // `[s][i]`), and each row's largest squared gap point.
    let cells_v = vs.len() - 1;
    let mut row_gaps = vec![Vec::new(); cells_v];
    let mut row_largest = vec![Vec::new(); cells_v];
    let mut scratch = vec![0.0; (q + 1) * width_v];
    for k in (0..cells_v).filter(|&k| v.moved[k]) {
        let (b, b2) = v.spans[k];
        let mut gaps = vec![0.0; (q + 1) * width_v];
        convert_lines(
            &v.old[k],
            &by_columns[(b - q) * width_v..],
            width_v,
            &mut gaps,
        );
        convert_lines(
            &v.new[k],
            &by_columns[(b2 - q) * width_v..],
            width_v,
            &mut scratch,
        );
        for (g, n) in gaps.iter_mut().zip(&scratch) {
            *g -= n;
        }
        row_largest[k] = largest_per_line(&gaps, rows);
        row_gaps[k] = gaps;
    }
    // Every moved cell's bound: through the surface with the new u and the old v knots.
    let mut bounded = Vec::new();
    let largest = |values: &[f64]| values.iter().fold(0.0f64, |m, &x| m.max(x));
    for (c, columns_largest) in column_largest.iter().enumerate() {
        for (k, rows_largest) in row_largest.iter().enumerate() {
            if !(u.moved[c] || v.moved[k]) {
                continue;
            }
            let (b, a2) = (v.spans[k].0, u.spans[c].1);
            let along_u = if u.moved[c] {
                largest(&columns_largest[b - q..=b])
            } else {
                0.0
            };
            let along_v = if v.moved[k] {
                largest(&rows_largest[a2 - p..=a2])
            } else {
                0.0
            };
            // A bound is not negative, so its bits order as its value does.
            bounded.push(((along_u.sqrt() + along_v.sqrt()).powi(2).to_bits(), c, k));
        }
    }
    // Largest first; heapified at once, popped only as far as the search goes.
    let mut bounded = BinaryHeap::from(bounded);
    let mut queue = BinaryHeap::new();
    let mut best = 0.0f64;
    let mut points = vec![[0.0; 3]; p.max(q) + 1];
    let mut converted = vec![[0.0; 3]; p.max(q) + 1];
    let mut other = vec![[0.0; 3]; p.max(q) + 1];
    let point = |from: &[f64], at: usize| -> [f64; 3] { [from[at], from[at + 1], from[at + 2]] };
    while let Some((bits, c, k)) = bounded.pop() {
        let bound = f64::from_bits(bits);
        if bound <= (best * (1.0 + SURFACE_DEVIATION_RELATIVE_TOLERANCE)).max(floor) {
            // Sorted: every cell left is bounded as low.
            break;
        }
        let ((a, _), (b, b2)) = (u.spans[c], v.spans[k]);
        let mut net = vec![[0.0, 0.0, 0.0, 1.0]; (p + 1) * (q + 1)];
        if u.moved[c] {
            // The columns converted along u, then along v: their gaps where the v knots
            // agree, each surface's own where they moved too.
            for r in 0..=p {
                let column = |from: &[f64], b: usize, points: &mut [[f64; 3]]| {
                    for (l, value) in points.iter_mut().enumerate().take(q + 1) {
                        *value = point(from, r * width_u + 3 * (b - q + l));
                    }
                };
                if v.moved[k] {
                    column(&column_old[c], b, &mut points);
                    convert(v.old_matrix(k), &points[..q + 1], &mut converted);
                    column(&column_new[c], b2, &mut points);
                    convert(&v.new[k], &points[..q + 1], &mut other);
                    for (x, y) in converted.iter_mut().zip(&other) {
                        *x = [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
                    }
                } else {
                    column(&column_gaps[c], b, &mut points);
                    convert(v.old_matrix(k), &points[..q + 1], &mut converted);
                }
                for s in 0..=q {
                    let g = converted[s];
                    net[r * (q + 1) + s] = [g[0], g[1], g[2], 1.0];
                }
            }
        } else {
            // The rows' gaps converted along u.
            for s in 0..=q {
                for (m, value) in points.iter_mut().enumerate().take(p + 1) {
                    *value = point(&row_gaps[k], s * width_v + 3 * (a - p + m));
                }
                convert(u.old_matrix(c), &points[..p + 1], &mut converted);
                for r in 0..=p {
                    let g = converted[r];
                    net[r * (q + 1) + s] = [g[0], g[1], g[2], 1.0];
                }
            }
        }
        let patch = GapPatch { m: p, n: q, c: net };
        best = best.max(patch.corner_value());
        queue.push(Cell::new(patch, 0));
    }
    (queue, best)
}

/// The branch and bound over the cells in `queue` (module docs): `sqrt(M)`.
fn certify(mut queue: BinaryHeap<Cell>, mut best: f64, floor: f64) -> f64 {
    let mut halvings = 0;
    while let Some(cell) = queue.pop() {
        let bound = best * (1.0 + SURFACE_DEVIATION_RELATIVE_TOLERANCE);
        if cell.upper <= bound.max(floor) {
            // Proven, and so is every cell behind it in the queue.
            break;
        }
        if halvings >= MAX_CELLS || cell.depth >= MAX_DEPTH {
            // Out of budget: the largest remaining upper bound (the queue's first) stands.
            return cell.upper.max(bound).sqrt();
        }
        halvings += 1;
        let (in_u, at) = cell.patch.split_in_u();
        let (low, high) = cell.patch.split(in_u, at);
        for half in [low, high] {
            best = best.max(half.corner_value());
            queue.push(Cell::new(half, cell.depth + 1));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::KnotForm;
    use crate::surface::SurfaceLimits;
    use proptest::prelude::*;

    /// A random gap patch: degrees `(m, n)`, `g` in `[-1, 1]³`, `w` in `[0.2, 3]`.
    fn patch() -> impl Strategy<Value = GapPatch> {
        (1usize..=6, 1usize..=6).prop_flat_map(|(m, n)| {
            prop::collection::vec(
                (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, 0.2f64..3.0),
                (m + 1) * (n + 1),
            )
            .prop_map(move |c| GapPatch {
                m,
                n,
                c: c.into_iter().map(|(x, y, z, w)| [x, y, z, w]).collect(),
            })
        })
    }

    fn squared(h: Lanes) -> f64 {
        (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]) / (h[3] * h[3])
    }

    proptest! {
        /// The rational convex hull bound holds at every point of a dense grid, and a corner
        /// value is a value.
        #[test]
        fn the_hull_bound_holds_on_a_dense_grid(patch in patch()) {
            let bound = patch.hull_bound();
            let mut largest = 0.0f64;
            for a in 0..=40 {
                for b in 0..=40 {
                    largest = largest.max(squared(patch.value(a as f64 / 40.0, b as f64 / 40.0)));
                }
            }
            prop_assert!(largest <= bound * (1.0 + 1e-12), "{largest} above the bound {bound}");
            prop_assert!(patch.corner_value() <= largest * (1.0 + 1e-12) + 1e-300);
        }

        /// The parts are the patch on each part.
        #[test]
        fn parts_agree_with_the_whole(
            patch in patch(),
            s in 0.0f64..1.0,
            t in 0.0f64..1.0,
            at in 0.25f64..0.75,
        ) {
            for in_u in [true, false] {
                let (low, high) = patch.split(in_u, at);
                let (whole_low, whole_high) = if in_u {
                    (patch.value(at * s, t), patch.value(at + (1.0 - at) * s, t))
                } else {
                    (patch.value(s, at * t), patch.value(s, at + (1.0 - at) * t))
                };
                for (a, b) in [(low.value(s, t), whole_low), (high.value(s, t), whole_high)] {
                    for c in 0..4 {
                        prop_assert!((a[c] - b[c]).abs() <= 1e-12 * (1.0 + b[c].abs()));
                    }
                }
            }
        }

        /// The product form `G / W` of two homogeneous nets is the difference of their
        /// rational patches.
        #[test]
        fn the_gap_patch_is_the_difference(
            (p, q, old, new) in (1usize..=4, 1usize..=4).prop_flat_map(|(p, q)| {
                let net = prop::collection::vec(
                    (-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0, 0.3f64..3.0),
                    (p + 1) * (q + 1),
                );
                (Just(p), Just(q), net.clone(), net)
            }),
            s in 0.0f64..1.0,
            t in 0.0f64..1.0,
        ) {
            let lanes = |net: &[(f64, f64, f64, f64)]| -> Vec<Lanes> {
                net.iter().map(|&(x, y, z, w)| [x * w, y * w, z * w, w]).collect()
            };
            let (old, new) = (lanes(&old), lanes(&new));
            let gap = gap_patch(&old, &new, p, q, true).value(s, t);
            let point = |net: &[Lanes]| {
                let h = GapPatch { m: p, n: q, c: net.to_vec() }.value(s, t);
                [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
            };
            let (a, b) = (point(&old), point(&new));
            for c in 0..3 {
                let expected = a[c] - b[c];
                prop_assert!(
                    (gap[c] / gap[3] - expected).abs() <= 1e-10 * (1.0 + a[c].abs() + b[c].abs()),
                    "{} against {expected}",
                    gap[c] / gap[3]
                );
            }
        }
    }

    /// A bicubic of 6 × 6 poles with uneven knots, weights `weights` (or none).
    fn bicubic(
        poles: &[Vec<[f64; 3]>],
        knots: (&[f64], &[f64]),
        weights: Option<&[Vec<f64>]>,
    ) -> Surface {
        Surface::from_knot_forms(
            (3, 3),
            poles,
            (KnotForm::Flat(knots.0), KnotForm::Flat(knots.1)),
            weights,
            &SurfaceLimits::default(),
        )
        .unwrap()
    }

    /// The largest `|S_a − S_b|` on a 150 × 150 grid of the common domain and a pattern
    /// search from its best point: a distance the surfaces have.
    fn sampled(a: &Surface, b: &Surface) -> f64 {
        let [(u0, u1), (v0, v1)] = a.domain();
        let gap = |u: f64, v: f64| {
            let (u, v) = (u.clamp(u0, u1), v.clamp(v0, v1));
            let (x, y) = (a.point(u, v), b.point(u, v));
            ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
        };
        let n = 150;
        let (mut best, mut at) = (0.0f64, (u0, v0));
        for k in 0..=n {
            for l in 0..=n {
                let (u, v) = (
                    u0 + (u1 - u0) * k as f64 / n as f64,
                    v0 + (v1 - v0) * l as f64 / n as f64,
                );
                if gap(u, v) > best {
                    (best, at) = (gap(u, v), (u, v));
                }
            }
        }
        let mut step = [(u1 - u0) / n as f64, (v1 - v0) / n as f64];
        for _ in 0..80 {
            let mut moved = false;
            for (du, dv) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
                let c = (at.0 + du * step[0], at.1 + dv * step[1]);
                if gap(c.0, c.1) > best {
                    (best, at, moved) = (gap(c.0, c.1), c, true);
                }
            }
            if !moved {
                step = [step[0] / 2.0, step[1] / 2.0];
            }
        }
        best
    }

    fn net() -> impl Strategy<Value = Vec<Vec<[f64; 3]>>> {
        prop::collection::vec(-0.4f64..0.4, 36).prop_map(|h| {
            (0..6)
                .map(|i| {
                    (0..6)
                        .map(|j| {
                            [
                                i as f64 + 0.3 * h[i * 6 + j],
                                j as f64,
                                2.0 * h[(j * 6 + i) % 36],
                            ]
                        })
                        .collect()
                })
                .collect()
        })
    }

    const KNOTS: [f64; 10] = [0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 1.0, 1.0, 1.0, 1.0];

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Against dense sampling: the certified deviation of a weight change, a pole move
        /// and a knot move is at least the sampled maximum and within the tolerance (and the
        /// sample's own shortfall) above it.
        #[test]
        fn the_certified_deviation_brackets_the_sampled_one(
            poles in net(),
            weights in prop::collection::vec(0.5f64..2.0, 36),
            change in prop::collection::vec(0.3f64..3.0, 3),
            moved in prop::collection::vec(-0.5f64..0.5, 3),
            knot in 0.32f64..0.53,
            rational in any::<bool>(),
            kind in 0usize..5,
            v_knot in 0.32f64..0.53,
        ) {
            let weights: Vec<Vec<f64>> =
                (0..6).map(|i| (0..6).map(|j| weights[i * 6 + j]).collect()).collect();
            let old_weights = rational.then_some(weights.as_slice());
            let old = bicubic(&poles, (&KNOTS, &KNOTS), old_weights);
            let new = match kind {
                0 => {
                    // Three weights of neighbouring poles.
                    let mut w = old_weights.map_or(vec![vec![1.0; 6]; 6], |w| w.to_vec());
                    for (k, (i, j)) in [(2, 2), (2, 3), (3, 2)].into_iter().enumerate() {
                        w[i][j] *= change[k];
                    }
                    bicubic(&poles, (&KNOTS, &KNOTS), Some(&w))
                }
                1 => {
                    let mut moved_poles = poles.clone();
                    moved_poles[3][2] = [
                        poles[3][2][0] + moved[0],
                        poles[3][2][1] + moved[1],
                        poles[3][2][2] + moved[2],
                    ];
                    bicubic(&moved_poles, (&KNOTS, &KNOTS), old_weights)
                }
                // Knots only: in u, in v, in both (a knot edit's cells by their bound).
                2 => {
                    let mut knots = KNOTS;
                    knots[4] = knot;
                    bicubic(&poles, (&knots, &KNOTS), old_weights)
                }
                3 => {
                    let mut knots = KNOTS;
                    knots[5] = 0.55 + (v_knot - 0.32) * 1.5;
                    bicubic(&poles, (&KNOTS, &knots), old_weights)
                }
                _ => {
                    let (mut u_knots, mut v_knots) = (KNOTS, KNOTS);
                    u_knots[4] = knot;
                    v_knots[4] = v_knot;
                    bicubic(&poles, (&u_knots, &v_knots), old_weights)
                }
            };
            let bound = surface_max_deviation(&old, &new, old.domain());
            let found = sampled(&old, &new);
            prop_assert!(found <= bound * (1.0 + 1e-9) + 1e-12, "sampled {found} above {bound}");
            prop_assert!(
                bound <= found * (1.0 + SURFACE_DEVIATION_RELATIVE_TOLERANCE) + 1e-9,
                "bound {bound} above the sampled {found}"
            );
        }
    }

    #[test]
    fn equal_surfaces_deviate_nowhere() {
        let poles: Vec<Vec<[f64; 3]>> = (0..6)
            .map(|i| {
                (0..6)
                    .map(|j| [i as f64, j as f64, ((i * j) % 3) as f64])
                    .collect()
            })
            .collect();
        let a = bicubic(&poles, (&KNOTS, &KNOTS), None);
        assert_eq!(surface_max_deviation(&a, &a.clone(), a.domain()), 0.0);
    }
}
