//! The one primitive every knot family solves (docs/method.md §31.1): a degree-`q` spline with
//! local knots `t_0 ..= t_{2q+1}` and control points `d_0 ..= d_q`, evaluated at a fixed `ũ`
//! in the span `[t_q, t_{q+1}]` by de Boor,
//!
//! ```text
//! d_l^[r] = (1 - α_{l,r}) d_{l-1}^[r-1] + α_{l,r} d_l^[r-1],   α_{l,r} = (ũ - t_l) / (t_{l+q+1-r} - t_l),
//! l = q, q-1, …, r,   r = 1 … q,   P = d_q^[q],
//! ```
//!
//! as a function of some of its knots (the unknowns). Rational curves run it on homogeneous
//! points `(w d, w)`. The relevant knots are `t_1 … t_{2q}`; `t_0` and `t_{2q+1}` only bound
//! them. Local knot `m` occurs in `min(m, 2q + 1 - m)` of the ratios.
//!
//! For the solvers the equations `P = p` are written as a polynomial system: `F = D · (X - p W)`
//! (`X`, `W` the homogeneous point), `D` the product of the ratios' denominators that depend
//! on an unknown, each combination of de Boor's triangle taken over the common denominator of
//! its two inputs (the product over its *cone* of ratios). `D > 0` wherever the span is not
//! empty, so `F` has exactly the roots of `P = p` there. When both ends of the span are
//! unknown, `D` would vanish at their collapse `t_q = t_{q+1} = ũ`; they are then replaced by
//! the span length `σ = t_{q+1} - t_q` and the last ratio `λ = α_{q,q} = (ũ - t_q) / σ` (a
//! blow-up of that corner), whose denominator `σ` is divided out.
//!
//! One primitive in one file (about 700 lines, then the unit test that compares the two
//! constructions of its numerator), over 600 on purpose: de Boor with its forward-mode
//! derivatives, the search box and both constructions of the polynomial system share one
//! indexing of the ratios and are checked against each other.

use smallvec::SmallVec;

use super::tensor::{MAX_VARIABLES, Tensor};
use crate::spline::vector::Point;

/// Largest degree per variable at which [`LocalProblem::numerator`] interpolates (the
/// collocation matrices at Chebyshev–Lobatto nodes stay well conditioned: their inverses'
/// norms stay below 100 up to here); above it, Bernstein arithmetic.
pub const INTERPOLATION_DEGREE: usize = 9;

/// `n + 1` Chebyshev–Lobatto nodes on `[0, 1]` (one node, `1/2`, for `n = 0`), computed
/// once per degree.
pub(crate) fn lobatto_nodes(n: usize) -> &'static [f64] {
    static TABLE: std::sync::OnceLock<Vec<Vec<f64>>> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        (0..=INTERPOLATION_DEGREE)
            .map(compute_lobatto_nodes)
            .collect()
    });
    &table[n]
}

/// [`lobatto_nodes`] computed.
fn compute_lobatto_nodes(n: usize) -> Vec<f64> {
    if n == 0 {
        return vec![0.5];
    }
    (0..=n)
        .map(|i| 0.5 * (1.0 - (std::f64::consts::PI * i as f64 / n as f64).cos()))
        .collect()
}

/// The inverse of the Bernstein collocation matrix `V_ij = B_j^n(s_i)` at the Lobatto nodes
/// of degree `n` (row-major), computed once per degree.
pub(crate) fn collocation_inverse(n: usize) -> &'static [f64] {
    static TABLE: std::sync::OnceLock<Vec<Vec<f64>>> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| (0..=INTERPOLATION_DEGREE).map(invert_collocation).collect());
    &table[n]
}

/// Gauss–Jordan inverse of the collocation matrix of degree `n`.
fn invert_collocation(n: usize) -> Vec<f64> {
    let size = n + 1;
    let nodes = compute_lobatto_nodes(n);
    let mut a = vec![0.0; size * size];
    for (i, &s) in nodes.iter().enumerate() {
        for j in 0..size {
            a[i * size + j] =
                super::tensor::binomial(n, j) * s.powi(j as i32) * (1.0 - s).powi((n - j) as i32);
        }
    }
    let mut inverse = vec![0.0; size * size];
    for i in 0..size {
        inverse[i * size + i] = 1.0;
    }
    for column in 0..size {
        let pivot = (column..size)
            .max_by(|&r, &t| {
                a[r * size + column]
                    .abs()
                    .total_cmp(&a[t * size + column].abs())
            })
            .unwrap_or(column);
        for k in 0..size {
            a.swap(column * size + k, pivot * size + k);
            inverse.swap(column * size + k, pivot * size + k);
        }
        let scale = 1.0 / a[column * size + column];
        for k in 0..size {
            a[column * size + k] *= scale;
            inverse[column * size + k] *= scale;
        }
        for row in 0..size {
            if row != column {
                let factor = a[row * size + column];
                for k in 0..size {
                    a[row * size + k] -= factor * a[column * size + k];
                    inverse[row * size + k] -= factor * inverse[column * size + k];
                }
            }
        }
    }
    inverse
}

/// One ratio of de Boor's triangle as polynomials: its left factor `t_hi - ũ`, right factor
/// `ũ - t_lo` and denominator (`None` when it is 1).
type RatioFactors = (Tensor, Tensor, Option<Tensor>);

/// The primitive `Π_q(ũ)` of one family at one picked parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct LocalProblem {
    /// The degree `q`.
    pub degree: usize,
    /// `t_0 ..= t_{2q+1}`.
    pub knots: Vec<f64>,
    /// The full-vector index of each local knot.
    pub full_index: Vec<usize>,
    /// Homogeneous control points `(w d, w)`, `q + 1` of them.
    pub poles: Vec<[f64; 4]>,
    /// `ũ`, in `[t_q, t_{q+1}]` with `t_q < t_{q+1}`.
    pub parameter: f64,
}

/// How the unit box of the solver maps to the unknown knots.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchBox {
    /// Local indices of the unknowns, ascending (2 or 3).
    pub unknowns: Vec<usize>,
    /// Per unknown: its variable's bounds (a knot value, or `σ` and `λ` for the span's ends).
    pub bounds: Vec<(f64, f64)>,
    /// Positions (in `unknowns`) of `t_q` and `t_{q+1}` when both are unknown.
    pub blow_up: Option<(usize, usize)>,
    /// Per unknown: its admissible interval of knot values (before the ordering among
    /// unknowns), `[lo, hi]`.
    pub admissible: Vec<(f64, f64)>,
}

/// A knot value as the solver's variables give it (a tensor of degree ≤ 1 per variable).
#[derive(Debug, Clone)]
enum KnotValue {
    Fixed(f64),
    Variable(Tensor),
}

/// A dual number with up to three partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Dual {
    value: f64,
    partial: [f64; MAX_VARIABLES],
}

impl Dual {
    fn constant(value: f64) -> Dual {
        Dual {
            value,
            partial: [0.0; MAX_VARIABLES],
        }
    }
    fn sub(self, o: Dual) -> Dual {
        Dual {
            value: self.value - o.value,
            partial: [0, 1, 2].map(|k| self.partial[k] - o.partial[k]),
        }
    }
    fn mul(self, o: Dual) -> Dual {
        Dual {
            value: self.value * o.value,
            partial: [0, 1, 2].map(|k| self.partial[k] * o.value + self.value * o.partial[k]),
        }
    }
    fn div(self, o: Dual) -> Dual {
        let value = self.value / o.value;
        Dual {
            value,
            partial: [0, 1, 2].map(|k| (self.partial[k] - value * o.partial[k]) / o.value),
        }
    }
    fn lerp(a: Dual, b: Dual, alpha: Dual) -> Dual {
        // a + α (b - a)
        let d = b.sub(a).mul(alpha);
        Dual {
            value: a.value + d.value,
            partial: [0, 1, 2].map(|k| a.partial[k] + d.partial[k]),
        }
    }
}

/// Which way a ratio's numerator forces it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Forced {
    /// `ũ - t_l ≡ 0` (a fixed `t_l = ũ`): `α ≡ 0`.
    Zero,
    /// `t_hi - ũ ≡ 0` (a fixed `t_hi = ũ`): `α ≡ 1`.
    One,
}

impl LocalProblem {
    /// The local index pair `(l, l + q + 1 - r)` of ratio `α_{l,r}`.
    fn ratio_knots(&self, l: usize, r: usize) -> (usize, usize) {
        (l, l + self.degree + 1 - r)
    }

    /// Whether a ratio is forced to 0 or 1 by a fixed knot at `ũ`, given which knots move.
    fn forced(&self, l: usize, r: usize, moving: &[bool]) -> Option<Forced> {
        let (lo, hi) = self.ratio_knots(l, r);
        let u = self.parameter;
        if !moving[lo] && self.knots[lo] == u {
            Some(Forced::Zero)
        } else if !moving[hi] && self.knots[hi] == u {
            Some(Forced::One)
        } else {
            None
        }
    }

    /// The homogeneous point for the local knots `knots` (de Boor, module docs).
    pub fn homogeneous_point(&self, knots: &[f64]) -> [f64; 4] {
        self.homogeneous_point_with(knots, &[])
    }

    /// De Boor with the ratios `α_{l,r}` listed in `ratios` (as `((l, r), α)`) set to the
    /// given values instead of computed from the knots.
    pub fn homogeneous_point_with(
        &self,
        knots: &[f64],
        ratios: &[((usize, usize), f64)],
    ) -> [f64; 4] {
        let q = self.degree;
        let u = self.parameter;
        let mut d: SmallVec<[[f64; 4]; 16]> = SmallVec::from_slice(&self.poles);
        for r in 1..=q {
            for l in (r..=q).rev() {
                let (lo, hi) = self.ratio_knots(l, r);
                let span = knots[hi] - knots[lo];
                let alpha = match ratios.iter().find(|(at, _)| *at == (l, r)) {
                    Some(&(_, alpha)) => alpha,
                    None if span > 0.0 => (u - knots[lo]) / span,
                    None => 0.0,
                };
                let (before, after) = d.split_at_mut(l);
                let (previous, current) = (&before[l - 1], &mut after[0]);
                for c in 0..4 {
                    current[c] = previous[c] + alpha * (current[c] - previous[c]);
                }
            }
        }
        d[q]
    }

    /// The curve-space point for the local knots `knots`.
    pub fn point(&self, knots: &[f64]) -> Point {
        let h = self.homogeneous_point(knots);
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    /// The point and its partial derivatives with respect to the knots at local indices
    /// `unknowns` (forward-mode differentiation of de Boor, ratios of the cartesian point).
    pub fn point_and_partials(
        &self,
        knots: &[f64],
        unknowns: &[usize],
    ) -> (Point, [Point; MAX_VARIABLES]) {
        let q = self.degree;
        let u = self.parameter;
        let knot = |m: usize| {
            let mut value = Dual::constant(knots[m]);
            if let Some(k) = unknowns.iter().position(|&i| i == m) {
                value.partial[k] = 1.0;
            }
            value
        };
        let mut d: Vec<[Dual; 4]> = self.poles.iter().map(|p| p.map(Dual::constant)).collect();
        for r in 1..=q {
            for l in (r..=q).rev() {
                let (lo, hi) = self.ratio_knots(l, r);
                let (t_lo, t_hi) = (knot(lo), knot(hi));
                let span = t_hi.sub(t_lo);
                let alpha = if span.value > 0.0 {
                    Dual::constant(u).sub(t_lo).div(span)
                } else {
                    Dual::constant(0.0)
                };
                for c in 0..4 {
                    d[l][c] = Dual::lerp(d[l - 1][c], d[l][c], alpha);
                }
            }
        }
        let h = d[q];
        let mut point = [0.0; 3];
        let mut partials = [[0.0; 3]; MAX_VARIABLES];
        for c in 0..3 {
            let v = h[c].div(h[3]);
            point[c] = v.value;
            for (k, partial) in partials.iter_mut().enumerate() {
                partial[c] = v.partial[k];
            }
        }
        (point, partials)
    }

    /// The search box of the unknowns at local indices `unknowns` (ascending, each in
    /// `1 ..= 2q`), widened by `margin` times each interval's width so that roots on a bound
    /// are inside; `None` when an unknown has no room (its fixed neighbours coincide with
    /// it on both sides).
    ///
    /// An unknown's interval is bounded by the nearest fixed knots on either side, and by `ũ`
    /// for the span's ends (`t_m ≤ ũ` for `m ≤ q`, `t_m ≥ ũ` for `m > q`). When both `t_q`
    /// and `t_{q+1}` are unknown, their variables are `σ ∈ [σ_min, t_hi - t_lo]` and
    /// `λ ∈ [0, 1]` (module docs); `σ_min = collapse · (t_hi - t_lo)` keeps the search off the
    /// collapsed span.
    pub fn search_box(&self, unknowns: &[usize], margin: f64, collapse: f64) -> Option<SearchBox> {
        let q = self.degree;
        let u = self.parameter;
        let moving = |m: usize| unknowns.contains(&m);
        let mut admissible = Vec::with_capacity(unknowns.len());
        for &m in unknowns {
            let below = (0..m).rev().find(|&i| !moving(i))?;
            let above = (m + 1..=2 * q + 1).find(|&i| !moving(i))?;
            let mut lo = self.knots[below];
            let mut hi = self.knots[above];
            if m <= q {
                hi = hi.min(u);
            } else {
                lo = lo.max(u);
            }
            if hi < lo {
                return None;
            }
            admissible.push((lo, hi));
        }
        if admissible.iter().all(|(lo, hi)| hi <= lo) {
            return None;
        }
        let blow_up = match (
            unknowns.iter().position(|&m| m == q),
            unknowns.iter().position(|&m| m == q + 1),
        ) {
            (Some(a), Some(b)) => Some((a, b)),
            _ => None,
        };
        let mut bounds: Vec<(f64, f64)> = admissible
            .iter()
            .map(|&(lo, hi)| {
                let widen = margin * (hi - lo);
                (lo - widen, hi + widen)
            })
            .collect();
        if let Some((a, b)) = blow_up {
            let (a_lo, _) = admissible[a];
            let (_, b_hi) = admissible[b];
            let width = b_hi - a_lo;
            if width <= 0.0 {
                return None;
            }
            bounds[a] = (collapse * width, width * (1.0 + margin));
            bounds[b] = (-margin, 1.0 + margin);
        }
        Some(SearchBox {
            unknowns: unknowns.to_vec(),
            bounds,
            blow_up,
            admissible,
        })
    }

    /// The local knots at unit-box point `s` of `search`.
    pub fn knots_at(&self, search: &SearchBox, s: [f64; MAX_VARIABLES]) -> Vec<f64> {
        let mut knots = self.knots.clone();
        let value = |k: usize| {
            let (lo, hi) = search.bounds[k];
            lo + s[k] * (hi - lo)
        };
        for (k, &m) in search.unknowns.iter().enumerate() {
            knots[m] = value(k);
        }
        if let Some((a, b)) = search.blow_up {
            let (sigma, lambda) = (value(a), value(b));
            knots[search.unknowns[a]] = self.parameter - sigma * lambda;
            knots[search.unknowns[b]] = self.parameter + sigma * (1.0 - lambda);
        }
        knots
    }

    /// [`LocalProblem::knots_at`] into a buffer.
    fn knots_into(&self, search: &SearchBox, s: [f64; MAX_VARIABLES], knots: &mut [f64]) {
        knots.copy_from_slice(&self.knots);
        let value = |k: usize| {
            let (lo, hi) = search.bounds[k];
            lo + s[k] * (hi - lo)
        };
        for (k, &m) in search.unknowns.iter().enumerate() {
            knots[m] = value(k);
        }
        if let Some((a, b)) = search.blow_up {
            let (sigma, lambda) = (value(a), value(b));
            knots[search.unknowns[a]] = self.parameter - sigma * lambda;
            knots[search.unknowns[b]] = self.parameter + sigma * (1.0 - lambda);
        }
    }

    /// Each local knot as a function of the unit box's variables.
    fn knot_values(&self, search: &SearchBox) -> Vec<KnotValue> {
        let u = self.parameter;
        let mut values: Vec<KnotValue> = self.knots.iter().map(|&t| KnotValue::Fixed(t)).collect();
        for (k, &m) in search.unknowns.iter().enumerate() {
            if search.blow_up.is_some_and(|(a, b)| k == a || k == b) {
                continue;
            }
            let (lo, hi) = search.bounds[k];
            let mut mask = [false; MAX_VARIABLES];
            mask[k] = true;
            values[m] = KnotValue::Variable(Tensor::multi_affine(mask, |s| lo + s[k] * (hi - lo)));
        }
        if let Some((a, b)) = search.blow_up {
            let (s_lo, s_hi) = search.bounds[a];
            let (l_lo, l_hi) = search.bounds[b];
            let mut mask = [false; MAX_VARIABLES];
            mask[a] = true;
            mask[b] = true;
            let sigma = move |s: [f64; 3]| s_lo + s[a] * (s_hi - s_lo);
            let lambda = move |s: [f64; 3]| l_lo + s[b] * (l_hi - l_lo);
            values[search.unknowns[a]] =
                KnotValue::Variable(Tensor::multi_affine(mask, |s| u - sigma(s) * lambda(s)));
            values[search.unknowns[b]] = KnotValue::Variable(Tensor::multi_affine(mask, |s| {
                u + sigma(s) * (1.0 - lambda(s))
            }));
        }
        values
    }

    /// The polynomial system `F_i = e_i · (D (X - p W))` on the unit box of `search` (module
    /// docs), `e_i` the rows of `projection` (as many as unknowns), in the ordinary Bernstein
    /// basis. Rational in nothing: every step is a product or sum of polynomials.
    pub fn system(&self, search: &SearchBox, target: Point, projection: &[Point]) -> Tensor {
        let numerator = self.numerator(search);
        let parts: Vec<Tensor> = projection
            .iter()
            .map(|e| {
                numerator.combine(&[
                    e[0],
                    e[1],
                    e[2],
                    -(e[0] * target[0] + e[1] * target[1] + e[2] * target[2]),
                ])
            })
            .collect();
        Tensor::stack(&parts)
    }

    /// The homogeneous point's numerator `D (X, W)` on the unit box of `search` (four
    /// components, ordinary Bernstein basis): by interpolation where its degrees are small
    /// ([`INTERPOLATION_DEGREE`]), else by exact Bernstein arithmetic
    /// ([`LocalProblem::numerator_by_products`]).
    pub fn numerator(&self, search: &SearchBox) -> Tensor {
        self.numerator_by_interpolation(search)
            .unwrap_or_else(|| self.numerator_by_products(search))
    }

    /// The ratios that depend on the unknowns (neither constant nor forced), with the
    /// variables each depends on, and whether it is the blown-up `α_{q,q}`.
    fn moving_ratios(
        &self,
        search: &SearchBox,
    ) -> Vec<((usize, usize), [bool; MAX_VARIABLES], bool)> {
        let q = self.degree;
        let moving: Vec<bool> = (0..=2 * q + 1)
            .map(|m| search.unknowns.contains(&m))
            .collect();
        let blown = search
            .blow_up
            .map(|(a, b)| (search.unknowns[a], search.unknowns[b]));
        let variables_of = |m: usize| {
            let mut mask = [false; MAX_VARIABLES];
            if let Some(k) = search.unknowns.iter().position(|&i| i == m) {
                match search.blow_up {
                    Some((a, b)) if k == a || k == b => {
                        mask[a] = true;
                        mask[b] = true;
                    }
                    _ => mask[k] = true,
                }
            }
            mask
        };
        let mut ratios = Vec::new();
        for r in 1..=q {
            for l in r..=q {
                let (lo, hi) = self.ratio_knots(l, r);
                if blown == Some((lo, hi)) {
                    let mut mask = [false; MAX_VARIABLES];
                    if let Some((_, b)) = search.blow_up {
                        mask[b] = true;
                    }
                    ratios.push(((l, r), mask, true));
                    continue;
                }
                if self.forced(l, r, &moving).is_some() || !(moving[lo] || moving[hi]) {
                    continue;
                }
                let (a, b) = (variables_of(lo), variables_of(hi));
                ratios.push(((l, r), [0, 1, 2].map(|k| a[k] || b[k]), false));
            }
        }
        ratios
    }

    /// [`LocalProblem::numerator`] by interpolation: `D (X, W)` evaluated (normalised de Boor
    /// times the product `D` of the moving ratios' denominators) on the tensor grid of
    /// Chebyshev–Lobatto nodes of its degrees, then converted to Bernstein coefficients by
    /// the inverse collocation matrices; `None` when a degree exceeds
    /// [`INTERPOLATION_DEGREE`].
    pub fn numerator_by_interpolation(&self, search: &SearchBox) -> Option<Tensor> {
        self.numerator_with_ratios(search, &[])
    }

    /// [`LocalProblem::numerator_by_interpolation`] with the ratios in `fixed` (as
    /// `((l, r), α)`) held at the given values: they then depend on nothing, and their
    /// denominators leave `D`.
    pub fn numerator_with_ratios(
        &self,
        search: &SearchBox,
        fixed: &[((usize, usize), f64)],
    ) -> Option<Tensor> {
        let q = self.degree;
        let mut ratios = self.moving_ratios(search);
        ratios.retain(|(at, _, _)| fixed.iter().all(|(f, _)| f != at));
        let mut degrees = [0usize; MAX_VARIABLES];
        for (_, mask, _) in &ratios {
            for k in 0..MAX_VARIABLES {
                degrees[k] += usize::from(mask[k]);
            }
        }
        if degrees.iter().any(|&d| d > INTERPOLATION_DEGREE) {
            return None;
        }
        let nodes: [&[f64]; MAX_VARIABLES] = degrees.map(lobatto_nodes);
        let e = degrees.map(|d| d + 1);
        let mut values = vec![0.0; e[0] * e[1] * e[2] * 4];
        let blown_ratio = ratios.iter().find(|r| r.2).map(|r| r.0);
        let mut knots = self.knots.clone();
        for i2 in 0..e[2] {
            for i1 in 0..e[1] {
                for i0 in 0..e[0] {
                    let s = [nodes[0][i0], nodes[1][i1], nodes[2][i2]];
                    self.knots_into(search, s, &mut knots);
                    let mut overrides: SmallVec<[((usize, usize), f64); 3]> =
                        SmallVec::from_slice(fixed);
                    if let (Some(at), Some((_, b))) = (blown_ratio, search.blow_up) {
                        let (lo, hi) = search.bounds[b];
                        overrides.push((at, lo + s[b] * (hi - lo)));
                    }
                    let h = self.homogeneous_point_with(&knots, &overrides);
                    let mut d = 1.0;
                    for &((l, r), _, blown) in &ratios {
                        if !blown {
                            let (lo, hi) = self.ratio_knots(l, r);
                            d *= knots[hi] - knots[lo];
                        }
                    }
                    let at = ((i2 * e[1] + i1) * e[0] + i0) * 4;
                    for c in 0..4 {
                        values[at + c] = d * h[c];
                    }
                }
            }
        }
        let _ = q;
        // Apply the inverse collocation matrix along each variable.
        for k in 0..MAX_VARIABLES {
            if degrees[k] == 0 {
                continue;
            }
            let inverse = collocation_inverse(degrees[k]);
            let n = e[k];
            let stride = [1, e[0], e[0] * e[1]][k] * 4;
            let mut fiber = [0.0; (INTERPOLATION_DEGREE + 1) * 4];
            let others: [usize; 2] = match k {
                0 => [1, 2],
                1 => [0, 2],
                _ => [0, 1],
            };
            let other_stride = |j: usize| [1, e[0], e[0] * e[1]][j] * 4;
            for j1 in 0..e[others[1]] {
                for j0 in 0..e[others[0]] {
                    let base = j0 * other_stride(others[0]) + j1 * other_stride(others[1]);
                    for i in 0..n {
                        for c in 0..4 {
                            fiber[i * 4 + c] = values[base + i * stride + c];
                        }
                    }
                    for i in 0..n {
                        for c in 0..4 {
                            values[base + i * stride + c] =
                                (0..n).map(|j| inverse[i * n + j] * fiber[j * 4 + c]).sum();
                        }
                    }
                }
            }
        }
        Some(Tensor {
            degrees,
            components: 4,
            coefficients: values,
        })
    }

    /// [`LocalProblem::numerator`] by exact Bernstein arithmetic: de Boor's triangle over
    /// common denominators, every step a product or sum of polynomials.
    pub fn numerator_by_products(&self, search: &SearchBox) -> Tensor {
        let q = self.degree;
        let u = self.parameter;
        let moving: Vec<bool> = (0..=2 * q + 1)
            .map(|m| search.unknowns.contains(&m))
            .collect();
        let values = self.knot_values(search);
        let blown = search
            .blow_up
            .map(|(a, b)| (search.unknowns[a], search.unknowns[b]));
        // Per ratio: (left factor, right factor, denominator) — `None` denominators are 1.
        // Index [l][r].
        let mut factors: Vec<Vec<Option<RatioFactors>>> = vec![vec![None; q + 1]; q + 1];
        let lambda_tensor = |search: &SearchBox, (_, b): (usize, usize)| {
            let (lo, hi) = search.bounds[b];
            let mut mask = [false; MAX_VARIABLES];
            mask[b] = true;
            Tensor::multi_affine(mask, |s| lo + s[b] * (hi - lo))
        };
        for r in 1..=q {
            for l in r..=q {
                let (lo, hi) = self.ratio_knots(l, r);
                let entry = if blown == Some((lo, hi)) {
                    // α_{q,q} = λ exactly; its denominator σ is divided out.
                    let Some(blow) = search.blow_up else {
                        unreachable!("blown is Some only with a blow-up")
                    };
                    let lambda = lambda_tensor(search, blow);
                    let one_minus =
                        Tensor::constant(&[1.0]).plus(&lambda.times(&Tensor::constant(&[-1.0])));
                    (one_minus, lambda, None)
                } else {
                    match self.forced(l, r, &moving) {
                        Some(Forced::Zero) => {
                            (Tensor::constant(&[1.0]), Tensor::constant(&[0.0]), None)
                        }
                        Some(Forced::One) => {
                            (Tensor::constant(&[0.0]), Tensor::constant(&[1.0]), None)
                        }
                        None => match (&values[lo], &values[hi]) {
                            (KnotValue::Fixed(a), KnotValue::Fixed(b)) => {
                                let alpha = if b > a { (u - a) / (b - a) } else { 0.0 };
                                (
                                    Tensor::constant(&[1.0 - alpha]),
                                    Tensor::constant(&[alpha]),
                                    None,
                                )
                            }
                            (t_lo, t_hi) => {
                                let as_tensor = |v: &KnotValue| match v {
                                    KnotValue::Fixed(x) => Tensor::constant(&[*x]),
                                    KnotValue::Variable(t) => t.clone(),
                                };
                                let (t_lo, t_hi) = (as_tensor(t_lo), as_tensor(t_hi));
                                let minus_u = Tensor::constant(&[-u]);
                                let left = t_hi.plus(&minus_u);
                                let right = Tensor::constant(&[u])
                                    .plus(&t_lo.times(&Tensor::constant(&[-1.0])));
                                let denominator =
                                    t_hi.plus(&t_lo.times(&Tensor::constant(&[-1.0])));
                                (left, right, Some(denominator))
                            }
                        },
                    }
                };
                factors[l][r] = Some(entry);
            }
        }
        let factor = |l: usize, r: usize| match &factors[l][r] {
            Some(entry) => entry,
            None => unreachable!("every ratio α_{{l,r}} with r ≤ l ≤ q has factors"),
        };
        // de Boor over common denominators.
        let mut d: Vec<Tensor> = self.poles.iter().map(|p| Tensor::constant(p)).collect();
        for r in 1..=q {
            for l in (r..=q).rev() {
                // d_{l-1}^[r-1] lacks the denominators α_{l, r'} (r' < r) of d_l's cone;
                // d_l^[r-1] lacks α_{l-r+r', r'} of d_{l-1}'s.
                let mut left = d[l - 1].clone();
                let mut right = d[l].clone();
                for r_prime in 1..r {
                    if let Some(den) = &factor(l, r_prime).2 {
                        left = left.times(den);
                    }
                    if let Some(den) = &factor(l - r + r_prime, r_prime).2 {
                        right = right.times(den);
                    }
                }
                let (l_factor, r_factor, _) = factor(l, r);
                d[l] = left.times(l_factor).plus(&right.times(r_factor));
            }
        }
        d.swap_remove(q).unscaled()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic direct problem (q = 3) with uneven knots and weights.
    fn problem() -> LocalProblem {
        LocalProblem {
            degree: 3,
            knots: vec![-1.75, -1.37, -0.88, 0.0, 0.80, 1.47, 2.00, 2.69],
            full_index: (0..8).collect(),
            poles: vec![
                [0.43, 1.61, 0.2, 1.0],
                [0.72 * 2.0, 0.67 * 2.0, -0.1 * 2.0, 2.0],
                [-0.12 * 0.5, 1.18 * 0.5, 0.3 * 0.5, 0.5],
                [-0.53, -0.91, 0.0, 1.0],
            ],
            parameter: 0.431,
        }
    }

    /// The point by the Cox–de Boor basis functions, written out (an independent evaluator).
    fn basis_point(problem: &LocalProblem, knots: &[f64]) -> Point {
        let q = problem.degree;
        let u = problem.parameter;
        // N_{i,0} on the local knots, then the recursion; poles d_i use knots i ..= i + q + 1.
        let count = knots.len() - 1;
        let mut n: Vec<f64> = (0..count)
            .map(|i| {
                if knots[i] <= u && u < knots[i + 1] {
                    1.0
                } else {
                    0.0
                }
            })
            .collect();
        for degree in 1..=q {
            let mut next = vec![0.0; count - degree];
            for i in 0..count - degree {
                let mut v = 0.0;
                if knots[i + degree] > knots[i] {
                    v += (u - knots[i]) / (knots[i + degree] - knots[i]) * n[i];
                }
                if knots[i + degree + 1] > knots[i + 1] {
                    v += (knots[i + degree + 1] - u) / (knots[i + degree + 1] - knots[i + 1])
                        * n[i + 1];
                }
                next[i] = v;
            }
            n = next;
        }
        let mut h = [0.0; 4];
        for (i, pole) in problem.poles.iter().enumerate() {
            for c in 0..4 {
                h[c] += n[i] * pole[c];
            }
        }
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    #[test]
    fn de_boor_agrees_with_the_basis_functions_and_its_partials_with_differences() {
        let problem = problem();
        let knots = problem.knots.clone();
        let a = problem.point(&knots);
        let b = basis_point(&problem, &knots);
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() < 1e-14, "{a:?} {b:?}");
        }
        let unknowns = [2, 4, 6];
        let (_, partials) = problem.point_and_partials(&knots, &unknowns);
        for (k, &m) in unknowns.iter().enumerate() {
            let h = 1e-6;
            let (mut up, mut down) = (knots.clone(), knots.clone());
            up[m] += h;
            down[m] -= h;
            let (pu, pd) = (problem.point(&up), problem.point(&down));
            for c in 0..3 {
                let fd = (pu[c] - pd[c]) / (2.0 * h);
                assert!(
                    (partials[k][c] - fd).abs() < 1e-7,
                    "knot {m}: {} vs {fd}",
                    partials[k][c]
                );
            }
        }
    }

    /// `F = D (P - p)` must vanish exactly where `P = p` and its sign structure must follow
    /// `P - p` times a positive factor: check `F / (P - p)` is one positive scalar for every
    /// component at random points, for plain unknowns and for the span's blown-up pair.
    /// The two constructions of the numerator — interpolation at Lobatto nodes and exact
    /// Bernstein arithmetic over common denominators — agree coefficient by coefficient.
    #[test]
    fn interpolation_and_bernstein_arithmetic_give_the_same_numerator() {
        let problem = problem();
        for unknowns in [
            vec![1, 5],
            vec![3, 4],
            vec![2, 3, 4],
            vec![2, 5, 6],
            vec![1, 6],
            vec![2, 3],
        ] {
            let search = problem.search_box(&unknowns, 1e-9, 1e-4).unwrap();
            let a = problem.numerator_by_interpolation(&search).unwrap();
            let b = problem.numerator_by_products(&search);
            assert_eq!(a.degrees, b.degrees, "{unknowns:?}");
            let scale = b.coefficients.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (x, y) in a.coefficients.iter().zip(&b.coefficients) {
                assert!((x - y).abs() <= 1e-12 * scale, "{unknowns:?}: {x} vs {y}");
            }
        }
    }

    #[test]
    fn the_polynomial_system_is_a_positive_multiple_of_the_equations() {
        let problem = problem();
        let target = [0.303, 0.936, 0.1];
        let rows = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        for unknowns in [
            vec![1, 5],
            vec![3, 4],
            vec![2, 3, 4],
            vec![2, 5, 6],
            vec![1, 6],
        ] {
            let search = problem.search_box(&unknowns, 0.0, 1e-3).unwrap();
            let system = problem.system(&search, target, &rows);
            let mut checked = 0;
            for i in 0..7 {
                for j in 0..7 {
                    let s = [0.05 + 0.15 * i as f64, 0.05 + 0.15 * j as f64, 0.37];
                    let knots = problem.knots_at(&search, s);
                    if knots.windows(2).any(|w| w[0] > w[1]) {
                        continue;
                    }
                    checked += 1;
                    let point = problem.point(&knots);
                    let mut value = [0.0; 3];
                    system.evaluate(s, &mut value);
                    let ratios: Vec<f64> =
                        (0..3).map(|c| value[c] / (point[c] - target[c])).collect();
                    assert!(ratios[0] > 0.0, "{unknowns:?} {s:?}: {ratios:?}");
                    for c in 1..3 {
                        assert!(
                            (ratios[c] - ratios[0]).abs() <= 1e-9 * ratios[0],
                            "{unknowns:?} {s:?}: {ratios:?}"
                        );
                    }
                }
            }
            assert!(checked > 5, "{unknowns:?}: {checked} monotone points");
        }
    }
}
