//! Certified root isolation for a square polynomial system `F: [0, 1]^N → R^N`, `N ≤ 3`, given
//! in tensor Bernstein form ([`super::tensor`]): subdivision with two tests per box
//! (docs/method.md §31.4).
//!
//! * **Exclusion**: a component whose Bernstein coefficients on the box all have one sign
//!   (beyond a rounding margin) has no zero there (convex hull property).
//! * **Krawczyk**: with the interval Jacobian `[J]` from the coefficients of the partial
//!   derivatives (their ranges bound the derivatives on the box), `Y = mid([J])⁻¹` and the
//!   box centre `c`, `K = c - Y F(c) + (I - Y [J]) (X - c)`. `K ⊂ int X` proves that `X` holds
//!   exactly one root (and simplified Newton from `c` converges to it); `K ∩ X = ∅` proves it
//!   holds none. Otherwise the box is cut across its widest side (a little off the middle).
//!
//! Boxes narrower than [`IsolationOptions::min_width`] in every variable (at a singular root,
//! where no test can succeed), the boxes left when the budget runs out, and those left in a
//! neighbourhood narrower than [`NEIGHBOURHOOD_WIDTH`] when its own share of the budget
//! ([`NEIGHBOURHOOD_BOXES`]) runs out are returned as uncertified candidates, one per cluster
//! of touching boxes; the caller verifies every root independently either way.
//!
//! One algorithm in one file (about 630 lines, then its unit tests), over 600 on purpose: the
//! loop, its two tests, the preconditioning, the clip that cuts boxes down and the
//! neighbourhoods' budget are read together; split apart they would only call each other.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::tensor::{MAX_VARIABLES, Tensor};

/// A coefficient within `ZERO_MARGIN` times its component's largest coefficient (on the
/// whole box) of zero counts as either sign: the construction's rounding.
pub const ZERO_MARGIN: f64 = 1e-12;

/// Where a box is cut, as a fraction of its width: off the middle (and exact in binary), so
/// that roots at simple values (a planted solution, a symmetric system) do not fall on a cut,
/// where no box could certify them.
const CUT: f64 = 0.4921875;

/// A box at most this wide in every variable (unit-box coordinates) starts a neighbourhood
/// of its own, which may examine at most [`NEIGHBOURHOOD_BOXES`] boxes: the neighbourhood of
/// a root that no test can decide (a near-singular root, whose equations stay within the
/// rounding margin of zero along a sliver of boxes) must not take the whole budget from the
/// roots elsewhere. What is left of it when its share runs out is returned as candidates.
const NEIGHBOURHOOD_WIDTH: f64 = 1e-6;

/// Boxes one neighbourhood ([`NEIGHBOURHOOD_WIDTH`]) may examine at most: a simple root
/// there is certified in a few, two roots a hundredth of the neighbourhood apart in some
/// twenty.
const NEIGHBOURHOOD_BOXES: usize = 64;

/// Krawczyk's test is tried on boxes at most this wide (unit-box coordinates) in every
/// variable: on larger ones the interval Jacobian is too loose for it to succeed.
const KRAWCZYK_WIDTH: f64 = 0.25;

/// Newton steps at most in [`refine`].
const NEWTON_STEPS: usize = 12;

/// Limits of one isolation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsolationOptions {
    /// Boxes examined at most (time bound).
    pub max_boxes: usize,
    /// A box narrower than this in every variable (unit-box coordinates) is not cut again.
    pub min_width: f64,
    /// Uncertified candidates returned at most: one per cluster of touching boxes left
    /// undecided (the box with the smallest `|F(c)|` of each), the best clusters first.
    pub max_candidates: usize,
}

impl Default for IsolationOptions {
    fn default() -> Self {
        IsolationOptions {
            max_boxes: 4096,
            min_width: 1e-10,
            max_candidates: 16,
        }
    }
}

/// A root (or candidate) in unit-box coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsolatedRoot {
    /// The point (`N` coordinates used).
    pub point: [f64; MAX_VARIABLES],
    /// Krawczyk proved a unique root in a box around it.
    pub certified: bool,
}

/// What an isolation found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Isolation {
    /// Certified roots and uncertified candidates, certified first.
    pub roots: Vec<IsolatedRoot>,
    /// Boxes examined.
    pub boxes: usize,
    /// The budget ran out before every box was decided.
    pub exhausted: bool,
}

/// A box of the subdivision: its corner and widths in unit-box coordinates, and `F` on it
/// (Bernstein form over the box as its own unit box).
struct Cell {
    lo: [f64; MAX_VARIABLES],
    width: [f64; MAX_VARIABLES],
    system: Tensor,
    /// The neighbourhood ([`NEIGHBOURHOOD_WIDTH`]) it lies in, an index into the boxes each
    /// has left.
    neighbourhood: Option<usize>,
}

/// A cell ordered by its area (the product of its widths), the largest greatest.
struct ByArea(Cell);

impl ByArea {
    fn area(&self) -> f64 {
        self.0.width.iter().product()
    }
}

impl PartialEq for ByArea {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for ByArea {}

impl PartialOrd for ByArea {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for ByArea {
    fn cmp(&self, other: &Self) -> Ordering {
        self.area().total_cmp(&other.area())
    }
}

/// A box left undecided: its corner, widths and `max_i |F_i(c)|` at its centre.
struct Candidate {
    lo: [f64; MAX_VARIABLES],
    width: [f64; MAX_VARIABLES],
    residual: f64,
}

impl Candidate {
    fn of(cell: &Cell, n: usize) -> Candidate {
        Candidate {
            lo: cell.lo,
            width: cell.width,
            residual: centre_residual(cell, n),
        }
    }
}

/// An interval `[lo, hi]`.
#[derive(Debug, Clone, Copy)]
struct Interval {
    lo: f64,
    hi: f64,
}

impl Interval {
    fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }
}

/// The isolating roots of `system` (components = `variables` = `N`) in the unit box.
/// `outside(lo, width)` says that a box (corner and widths in unit-box coordinates) lies
/// wholly outside the set of interest (the admissible knots): it is dropped untested.
pub fn isolate(
    system: &Tensor,
    variables: usize,
    options: IsolationOptions,
    outside: &dyn Fn([f64; MAX_VARIABLES], [f64; MAX_VARIABLES]) -> bool,
) -> Isolation {
    debug_assert_eq!(system.components, variables);
    debug_assert!((1..=MAX_VARIABLES).contains(&variables));
    let n = variables;
    let margin: Vec<f64> = (0..n).map(|i| ZERO_MARGIN * system.magnitude(i)).collect();
    let mut isolation = Isolation::default();
    let mut candidates: Vec<Candidate> = Vec::new();
    // Boxes each neighbourhood may still examine.
    let mut shares: Vec<usize> = Vec::new();
    // Largest boxes first: the boxes examined do not depend on the order, but when the
    // budget runs out, what is left undecided is then the narrowest boxes (a sliver where a
    // near-collapsed span makes F vanish within rounding along an edge), not the root
    // elsewhere that a depth-first order would have reached after the sliver.
    let mut stack = BinaryHeap::new();
    stack.push(ByArea(Cell {
        lo: [0.0; MAX_VARIABLES],
        width: [1.0, 1.0, 1.0].map(|w: f64| w),
        system: system.clone(),
        neighbourhood: None,
    }));
    while let Some(ByArea(mut cell)) = stack.pop() {
        if isolation.boxes >= options.max_boxes {
            isolation.exhausted = true;
            candidates.push(Candidate::of(&cell, n));
            continue;
        }
        if cell.neighbourhood.is_none() && (0..n).all(|k| cell.width[k] <= NEIGHBOURHOOD_WIDTH) {
            cell.neighbourhood = Some(shares.len());
            shares.push(NEIGHBOURHOOD_BOXES);
        }
        if let Some(share) = cell.neighbourhood.map(|i| &mut shares[i]) {
            if *share == 0 {
                candidates.push(Candidate::of(&cell, n));
                continue;
            }
            *share -= 1;
        }
        isolation.boxes += 1;
        if outside(cell.lo, cell.width) || excluded(&cell.system, n, &margin) {
            continue;
        }
        let jacobian = jacobian_ranges(&cell.system, n, &margin);
        let y = invert(&middle(&jacobian, n), n);
        let small = (0..n).all(|k| cell.width[k] <= KRAWCZYK_WIDTH);
        match y.filter(|_| small).map_or(Test::Undecided, |y| {
            krawczyk(&cell.system, n, &margin, &jacobian, y)
        }) {
            Test::NoRoot => continue,
            Test::UniqueRoot => {
                let mut point = [0.0; MAX_VARIABLES];
                for k in 0..n {
                    point[k] = cell.lo[k] + 0.5 * cell.width[k];
                }
                isolation.roots.push(IsolatedRoot {
                    point,
                    certified: true,
                });
                continue;
            }
            Test::Undecided => {}
        }
        if let Some(y) = &y {
            // Preconditioned by the inverse Jacobian, each component is nearly one variable
            // minus the root's coordinate: its coefficients bound the root far more tightly.
            let (preconditioned, bounds) = precondition(&cell.system, y, n, &margin);
            if excluded(&preconditioned, n, &bounds) {
                continue;
            }
            let Some(interval) = clip(&preconditioned, n, &bounds) else {
                continue;
            };
            if (0..n).all(|k| cell.width[k] > options.min_width) {
                if let Some(reduced) = reduce(&cell, n, &interval) {
                    stack.push(ByArea(reduced));
                    continue;
                }
            }
        }
        // Halve across the widest side whose variable F depends on.
        let split = (0..n)
            .filter(|&k| cell.system.degrees[k] > 0 && cell.width[k] > options.min_width)
            .max_by(|&a, &b| cell.width[a].total_cmp(&cell.width[b]));
        let Some(k) = split else {
            candidates.push(Candidate::of(&cell, n));
            continue;
        };
        let (left, right) = cell.system.split(k, CUT);
        let (mut left_width, mut right_width) = (cell.width, cell.width);
        left_width[k] *= CUT;
        right_width[k] *= 1.0 - CUT;
        let mut right_lo = cell.lo;
        right_lo[k] += left_width[k];
        stack.push(ByArea(Cell {
            lo: right_lo,
            width: right_width,
            system: right,
            neighbourhood: cell.neighbourhood,
        }));
        stack.push(ByArea(Cell {
            lo: cell.lo,
            width: left_width,
            system: left,
            neighbourhood: cell.neighbourhood,
        }));
    }
    isolation
        .roots
        .extend(representatives(&candidates, n, options.max_candidates));
    isolation
}

/// At most `limit` uncertified candidates, one per cluster of touching boxes (the box of the
/// cluster with the smallest `|F(c)|`, at its centre), best first: the boxes left around one
/// root (a near-singular one leaves a sliver of them) stand for it once, so that the
/// candidates reach every place where a root may be.
fn representatives(candidates: &[Candidate], n: usize, limit: usize) -> Vec<IsolatedRoot> {
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let count = candidates.len();
    let mut parent: Vec<usize> = (0..count).collect();
    let slack = |a: &Candidate, b: &Candidate, k: usize| 1e-9 * a.width[k].max(b.width[k]);
    let touch = |a: &Candidate, b: &Candidate| {
        (0..n).all(|k| {
            a.lo[k] <= b.lo[k] + b.width[k] + slack(a, b, k)
                && b.lo[k] <= a.lo[k] + a.width[k] + slack(a, b, k)
        })
    };
    // Union–find of the touching boxes, by a sweep along the first variable.
    let mut order: Vec<usize> = (0..count).collect();
    order.sort_by(|&a, &b| candidates[a].lo[0].total_cmp(&candidates[b].lo[0]));
    for (position, &a) in order.iter().enumerate() {
        let box_a = &candidates[a];
        for &b in &order[position + 1..] {
            let box_b = &candidates[b];
            if box_b.lo[0] > box_a.lo[0] + box_a.width[0] + slack(box_a, box_b, 0) {
                break;
            }
            if touch(box_a, box_b) {
                let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                parent[ra] = rb;
            }
        }
    }
    let mut best: Vec<Option<usize>> = vec![None; count];
    for i in 0..count {
        let r = find(&mut parent, i);
        if best[r].is_none_or(|j| candidates[i].residual < candidates[j].residual) {
            best[r] = Some(i);
        }
    }
    let mut kept: Vec<usize> = best.into_iter().flatten().collect();
    kept.sort_by(|&a, &b| candidates[a].residual.total_cmp(&candidates[b].residual));
    kept.truncate(limit);
    kept.into_iter()
        .map(|i| {
            let c = &candidates[i];
            let mut point = [0.0; MAX_VARIABLES];
            for k in 0..MAX_VARIABLES {
                point[k] = c.lo[k] + 0.5 * c.width[k];
            }
            IsolatedRoot {
                point,
                certified: false,
            }
        })
        .collect()
}

/// `max_i |F_i(c)|` at the box centre (to rank uncertified candidates).
fn centre_residual(cell: &Cell, n: usize) -> f64 {
    let mut value = [0.0; MAX_VARIABLES];
    cell.system.evaluate([0.5; MAX_VARIABLES], &mut value);
    value[..n].iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Whether some component keeps one sign on the box.
fn excluded(system: &Tensor, n: usize, margin: &[f64]) -> bool {
    (0..n).any(|i| {
        let (lo, hi) = system.range(i);
        lo > margin[i] || hi < -margin[i]
    })
}

/// The outcome of Krawczyk's test on a box.
enum Test {
    /// `K ∩ X = ∅`.
    NoRoot,
    /// `K ⊂ int X`.
    UniqueRoot,
    /// Neither.
    Undecided,
}

/// `[J]_{ik}`: the range of `∂F_i/∂s_k` on the cell (from the coefficients of the partial
/// derivatives), widened by the coefficients' rounding.
fn jacobian_ranges(
    system: &Tensor,
    n: usize,
    margin: &[f64],
) -> [[Interval; MAX_VARIABLES]; MAX_VARIABLES] {
    let mut jacobian = [[Interval { lo: 0.0, hi: 0.0 }; MAX_VARIABLES]; MAX_VARIABLES];
    let mut ranges = [(0.0, 0.0); MAX_VARIABLES];
    for k in 0..n {
        system.derivative_ranges(k, &mut ranges);
        let slack = 2.0 * system.degrees[k] as f64;
        for (i, row) in jacobian.iter_mut().enumerate().take(n) {
            let (lo, hi) = ranges[i];
            row[k] = Interval {
                lo: lo - slack * margin[i],
                hi: hi + slack * margin[i],
            };
        }
    }
    jacobian
}

/// The midpoint matrix of an interval matrix.
fn middle(
    jacobian: &[[Interval; MAX_VARIABLES]; MAX_VARIABLES],
    n: usize,
) -> [[f64; MAX_VARIABLES]; MAX_VARIABLES] {
    let mut middle = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
    for i in 0..n {
        for k in 0..n {
            middle[i][k] = 0.5 * (jacobian[i][k].lo + jacobian[i][k].hi);
        }
    }
    middle
}

/// `G = Y F`, coefficient by coefficient (the same roots), with the rounding margins of its
/// components.
fn precondition(
    system: &Tensor,
    y: &[[f64; MAX_VARIABLES]; MAX_VARIABLES],
    n: usize,
    margin: &[f64],
) -> (Tensor, [f64; MAX_VARIABLES]) {
    let mut out = system.clone();
    for (values, original) in out
        .coefficients
        .chunks_exact_mut(n)
        .zip(system.coefficients.chunks_exact(n))
    {
        for i in 0..n {
            values[i] = (0..n).map(|l| y[i][l] * original[l]).sum();
        }
    }
    let mut bounds = [0.0; MAX_VARIABLES];
    for i in 0..n {
        bounds[i] = (0..n).map(|l| y[i][l].abs() * margin[l]).sum::<f64>() * (1.0 + 1e-12);
    }
    (out, bounds)
}

/// Per variable, the part `[a, b]` of the cell's unit interval where every component's
/// control net can cross zero (the convex hull of the points `(j / d, c_j)` of all its
/// coefficients with index `j` along the variable, widened by the margin); `None` when a
/// component's net cannot cross zero anywhere.
fn clip(system: &Tensor, n: usize, margin: &[f64]) -> Option<[(f64, f64); MAX_VARIABLES]> {
    let mut interval = [(0.0f64, 1.0f64); MAX_VARIABLES];
    let e = system.degrees.map(|d| d + 1);
    for k in 0..n {
        let d = system.degrees[k];
        if d == 0 || d >= 64 {
            continue;
        }
        // The coefficients are blocks `[outer][j][inner]`, `j` the index along `k`.
        let inner: usize = e[..k].iter().product::<usize>() * n;
        let outer: usize = e[k + 1..].iter().product();
        for i in 0..n {
            // Lowest and highest coefficient per index along k (plain comparisons: the
            // coefficients are finite).
            let mut low = [f64::INFINITY; 64];
            let mut high = [f64::NEG_INFINITY; 64];
            for o in 0..outer {
                for j in 0..=d {
                    let at = (o * (d + 1) + j) * inner;
                    for &v in system.coefficients[at..at + inner]
                        .iter()
                        .skip(i)
                        .step_by(n)
                    {
                        if v < low[j] {
                            low[j] = v;
                        }
                        if v > high[j] {
                            high[j] = v;
                        }
                    }
                }
            }
            let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
            let x = |j: usize| j as f64 / d as f64;
            for j in 0..=d {
                let (lo, hi) = (low[j] - margin[i], high[j] + margin[i]);
                if lo <= 0.0 && hi >= 0.0 {
                    a = a.min(x(j));
                    b = b.max(x(j));
                }
                // Segments from a point below zero to a point above it cross zero.
                for l in j + 1..=d {
                    let (lo_l, hi_l) = (low[l] - margin[i], high[l] + margin[i]);
                    for (y0, y1) in [(lo, lo_l), (lo, hi_l), (hi, lo_l), (hi, hi_l)] {
                        if (y0 < 0.0 && y1 > 0.0) || (y0 > 0.0 && y1 < 0.0) {
                            let crossing = x(j) + (x(l) - x(j)) * y0 / (y0 - y1);
                            a = a.min(crossing);
                            b = b.max(crossing);
                        }
                    }
                }
            }
            if a > b {
                return None;
            }
            let (lo, hi) = interval[k];
            interval[k] = (lo.max(a.max(0.0)), hi.min(b.min(1.0)));
            if interval[k].0 > interval[k].1 {
                return None;
            }
        }
    }
    Some(interval)
}

/// The cell cut down to `interval` (local coordinates per variable), when that removes at
/// least two fifths of some side; `None` otherwise (the cell is tested and halved instead).
fn reduce(cell: &Cell, n: usize, interval: &[(f64, f64); MAX_VARIABLES]) -> Option<Cell> {
    let worth = (0..n).any(|k| interval[k].1 - interval[k].0 <= 0.6);
    if !worth {
        return None;
    }
    let mut system = cell.system.clone();
    let mut lo = cell.lo;
    let mut width = cell.width;
    for k in 0..n {
        let (a, b) = interval[k];
        if b - a > 0.6 || cell.system.degrees[k] == 0 {
            continue;
        }
        // Widen a little: the cut's rounding must not lose a root on its edge.
        let (a, b) = ((a - 1e-9).max(0.0), (b + 1e-9).min(1.0));
        system = system.part(k, a, b);
        lo[k] += a * width[k];
        width[k] *= b - a;
    }
    Some(Cell {
        lo,
        width,
        system,
        neighbourhood: cell.neighbourhood,
    })
}

/// Krawczyk's test on the cell's own unit box (module docs), with the interval Jacobian and
/// its preconditioner `y`.
fn krawczyk(
    system: &Tensor,
    n: usize,
    margin: &[f64],
    jacobian: &[[Interval; MAX_VARIABLES]; MAX_VARIABLES],
    y: [[f64; MAX_VARIABLES]; MAX_VARIABLES],
) -> Test {
    let mut value = [0.0; MAX_VARIABLES];
    system.evaluate([0.5; MAX_VARIABLES], &mut value);
    let mut inside = true;
    for i in 0..n {
        // c - Y F(c), and the rounding of F(c) through Y.
        let mut step = 0.0;
        let mut rounding = 0.0;
        for l in 0..n {
            step += y[i][l] * value[l];
            rounding += y[i][l].abs() * margin[l];
        }
        let centre = 0.5 - step;
        // (I - Y [J])_{ik} (X - c)_k with (X - c)_k = [-1/2, 1/2]: symmetric, radius half the
        // magnitude of the interval entry.
        let mut radius = rounding;
        for k in 0..n {
            let mut entry = Interval {
                lo: if i == k { 1.0 } else { 0.0 },
                hi: if i == k { 1.0 } else { 0.0 },
            };
            for l in 0..n {
                let (a, b) = (y[i][l] * jacobian[l][k].lo, y[i][l] * jacobian[l][k].hi);
                entry.lo -= a.max(b);
                entry.hi -= a.min(b);
            }
            radius += 0.5 * entry.magnitude();
        }
        // Rounding of the interval arithmetic itself.
        radius = radius * (1.0 + 1e-12) + 1e-15;
        let (lo, hi) = (centre - radius, centre + radius);
        if hi < 0.0 || lo > 1.0 || !lo.is_finite() || !hi.is_finite() {
            if lo.is_finite() && hi.is_finite() {
                return Test::NoRoot;
            }
            return Test::Undecided;
        }
        if !(lo > 0.0 && hi < 1.0) {
            inside = false;
        }
    }
    if inside {
        Test::UniqueRoot
    } else {
        Test::Undecided
    }
}

/// Newton's method on the polynomial system itself from `start` (unit-box coordinates),
/// kept in the unit box; a step that fails to lower the residual ends it. The knot solvers
/// refine on de Boor instead ([`super::roots`]); this serves where the system is all there
/// is (the regions' outlines, the surfaces' curved mixed moves).
pub fn refine(system: &Tensor, n: usize, start: [f64; MAX_VARIABLES]) -> [f64; MAX_VARIABLES] {
    let derivatives: Vec<Tensor> = (0..n).map(|k| system.derivative(k)).collect();
    let size = |v: &[f64; MAX_VARIABLES]| v[..n].iter().map(|x| x * x).sum::<f64>();
    let mut x = start;
    let mut value = [0.0; MAX_VARIABLES];
    system.evaluate(x, &mut value);
    for _ in 0..NEWTON_STEPS {
        let mut jacobian = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
        let mut column = [0.0; MAX_VARIABLES];
        for (k, derivative) in derivatives.iter().enumerate() {
            derivative.evaluate(x, &mut column);
            for i in 0..n {
                jacobian[i][k] = column[i];
            }
        }
        let Some(inverse) = invert(&jacobian, n) else {
            break;
        };
        let mut next = x;
        for i in 0..n {
            let step: f64 = (0..n).map(|l| inverse[i][l] * value[l]).sum();
            next[i] = (x[i] - step).clamp(0.0, 1.0);
        }
        let mut next_value = [0.0; MAX_VARIABLES];
        system.evaluate(next, &mut next_value);
        let (after, before) = (size(&next_value), size(&value));
        if after.is_nan() || after >= before {
            break;
        }
        x = next;
        value = next_value;
    }
    x
}

/// The inverse of the leading `n × n` block of `m` (Gauss–Jordan with partial pivoting);
/// `None` when a pivot is zero or the result is not finite.
pub fn invert(
    m: &[[f64; MAX_VARIABLES]; MAX_VARIABLES],
    n: usize,
) -> Option<[[f64; MAX_VARIABLES]; MAX_VARIABLES]> {
    let mut a = *m;
    let mut inverse = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
    for (i, row) in inverse.iter_mut().enumerate().take(n) {
        row[i] = 1.0;
    }
    for column in 0..n {
        let pivot =
            (column..n).max_by(|&r, &s| a[r][column].abs().total_cmp(&a[s][column].abs()))?;
        if a[pivot][column] == 0.0 {
            return None;
        }
        a.swap(column, pivot);
        inverse.swap(column, pivot);
        let scale = 1.0 / a[column][column];
        for k in 0..n {
            a[column][k] *= scale;
            inverse[column][k] *= scale;
        }
        for row in 0..n {
            if row != column {
                let factor = a[row][column];
                for k in 0..n {
                    a[row][k] -= factor * a[column][k];
                    inverse[row][k] -= factor * inverse[column][k];
                }
            }
        }
    }
    inverse
        .iter()
        .take(n)
        .all(|row| row[..n].iter().all(|v| v.is_finite()))
        .then_some(inverse)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn linear(variable: usize, at0: f64, at1: f64) -> Tensor {
        let mut mask = [false; 3];
        mask[variable] = true;
        Tensor::multi_affine(mask, |s| at0 + s[variable] * (at1 - at0))
    }

    /// x = s0, y = s1 on the unit box; the circle x² + y² = 0.5 meets the line x = y at
    /// (1/2, 1/2) only (the other crossing is outside the box).
    #[test]
    fn a_circle_and_a_line_meet_once_in_the_box() {
        let x = linear(0, 0.0, 1.0);
        let y = linear(1, 0.0, 1.0);
        let circle = x
            .times(&x)
            .plus(&y.times(&y))
            .plus(&Tensor::constant(&[-0.5]));
        let line = x.plus(&y.times(&Tensor::constant(&[-1.0])));
        let system = Tensor::stack(&[circle.unscaled(), line.raised_to([2, 2, 0]).unscaled()]);
        let found = isolate(&system, 2, IsolationOptions::default(), &|_, _| false);
        let certified: Vec<_> = found.roots.iter().filter(|r| r.certified).collect();
        assert_eq!(certified.len(), 1, "{found:?}");
        let root = refine(&system, 2, certified[0].point);
        assert!((root[0] - 0.5).abs() < 1e-14);
        assert!((root[1] - 0.5).abs() < 1e-14);
        assert!(!found.exhausted);
    }

    /// A cubic with three roots in [0, 1]: (s - 0.1)(s - 0.5)(s - 0.9).
    #[test]
    fn a_univariate_cubic_has_its_three_roots() {
        let factor = |r: f64| linear(0, -r, 1.0 - r);
        let f = factor(0.1)
            .times(&factor(0.5))
            .times(&factor(0.9))
            .unscaled();
        let found = isolate(&f, 1, IsolationOptions::default(), &|_, _| false);
        let mut roots: Vec<f64> = found
            .roots
            .iter()
            .map(|r| refine(&f, 1, r.point)[0])
            .collect();
        roots.sort_by(f64::total_cmp);
        assert_eq!(roots.len(), 3, "{found:?}");
        for (root, expected) in roots.iter().zip([0.1, 0.5, 0.9]) {
            assert!((root - expected).abs() < 1e-14, "{root}");
        }
        assert!(found.roots.iter().all(|r| r.certified));
    }

    /// Three planes through (0.2, 0.3, 0.4) and one sphere-like surface: a 3 × 3 system
    /// with a known root.
    #[test]
    fn a_three_variable_system_is_solved() {
        let x = linear(0, 0.0, 1.0);
        let y = linear(1, 0.0, 1.0);
        let z = linear(2, 0.0, 1.0);
        let minus = |v: f64| Tensor::constant(&[-v]);
        // x y - 0.06, y + z² - 0.46, x + y + z - 0.9.
        let f1 = x.times(&y).plus(&minus(0.06)).raised_to([1, 1, 2]);
        let f2 = y.plus(&z.times(&z)).plus(&minus(0.46)).raised_to([1, 1, 2]);
        let f3 = x.plus(&y).plus(&z).plus(&minus(0.9)).raised_to([1, 1, 2]);
        let system = Tensor::stack(&[f1.unscaled(), f2.unscaled(), f3.unscaled()]);
        let found = isolate(&system, 3, IsolationOptions::default(), &|_, _| false);
        let near = found
            .roots
            .iter()
            .map(|r| refine(&system, 3, r.point))
            .filter(|r| {
                (r[0] - 0.2).abs() < 1e-12
                    && (r[1] - 0.3).abs() < 1e-12
                    && (r[2] - 0.4).abs() < 1e-12
            });
        assert_eq!(near.count(), 1, "{found:?}");
    }

    #[test]
    fn inverting_a_singular_matrix_fails() {
        let m = [[1.0, 2.0, 0.0], [2.0, 4.0, 0.0], [0.0, 0.0, 0.0]];
        assert!(invert(&m, 2).is_none());
        let inverse = invert(&[[2.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0; 3]], 2).unwrap();
        assert!((inverse[0][0] - 0.6).abs() < 1e-15 && (inverse[1][0] + 0.2).abs() < 1e-15);
    }
}
