//! Certified root isolation for a square polynomial system `F: [0, 1]^N → R^N`, `N ≤ 3`, given
//! in tensor Bernstein form ([`super::tensor`]): subdivision with two tests per box
//! (docs/method.md §31.3).
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
//! where no test can succeed) and the boxes left when the budget runs out are returned as
//! uncertified candidates; the caller verifies every root independently either way.

use super::tensor::{MAX_VARIABLES, Tensor};

/// A coefficient within `ZERO_MARGIN` times its component's largest coefficient (on the
/// whole box) of zero counts as either sign: the construction's rounding.
pub const ZERO_MARGIN: f64 = 1e-12;

/// Where a box is cut, as a fraction of its width: off the middle (and exact in binary), so
/// that roots at simple values (a planted solution, a symmetric system) do not fall on a cut,
/// where no box could certify them.
const CUT: f64 = 0.4921875;

/// Simplified Newton steps at most inside a certified box.
const NEWTON_STEPS: usize = 60;

/// Limits of one isolation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsolationOptions {
    /// Boxes examined at most (time bound).
    pub max_boxes: usize,
    /// A box narrower than this in every variable (unit-box coordinates) is not cut again.
    pub min_width: f64,
    /// Uncertified candidates returned at most (the best by `|F(c)|` when more are left).
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
pub fn isolate(system: &Tensor, variables: usize, options: IsolationOptions) -> Isolation {
    debug_assert_eq!(system.components, variables);
    debug_assert!((1..=MAX_VARIABLES).contains(&variables));
    let n = variables;
    let margin: Vec<f64> = (0..n)
        .map(|i| ZERO_MARGIN * system.magnitude(i))
        .collect();
    let mut isolation = Isolation::default();
    let mut candidates: Vec<(f64, IsolatedRoot)> = Vec::new();
    let mut stack = vec![Cell {
        lo: [0.0; MAX_VARIABLES],
        width: [1.0, 1.0, 1.0].map(|w: f64| w),
        system: system.clone(),
    }];
    while let Some(cell) = stack.pop() {
        if isolation.boxes >= options.max_boxes {
            isolation.exhausted = true;
            let residual = centre_residual(&cell, n);
            candidates.push((residual, uncertified(&cell)));
            continue;
        }
        isolation.boxes += 1;
        if excluded(&cell.system, n, &margin) {
            continue;
        }
        match krawczyk(&cell.system, n, &margin) {
            Test::NoRoot => continue,
            Test::UniqueRoot { y } => {
                let local = newton_in_cell(&cell.system, n, &y);
                let mut point = [0.0; MAX_VARIABLES];
                for k in 0..n {
                    point[k] = cell.lo[k] + local[k] * cell.width[k];
                }
                isolation.roots.push(IsolatedRoot {
                    point,
                    certified: true,
                });
                continue;
            }
            Test::Undecided => {}
        }
        // Halve across the widest side whose variable F depends on.
        let split = (0..n)
            .filter(|&k| cell.system.degrees[k] > 0 && cell.width[k] > options.min_width)
            .max_by(|&a, &b| cell.width[a].total_cmp(&cell.width[b]));
        let Some(k) = split else {
            let residual = centre_residual(&cell, n);
            candidates.push((residual, uncertified(&cell)));
            continue;
        };
        let (left, right) = cell.system.split(k, CUT);
        let (mut left_width, mut right_width) = (cell.width, cell.width);
        left_width[k] *= CUT;
        right_width[k] *= 1.0 - CUT;
        let mut right_lo = cell.lo;
        right_lo[k] += left_width[k];
        stack.push(Cell {
            lo: right_lo,
            width: right_width,
            system: right,
        });
        stack.push(Cell {
            lo: cell.lo,
            width: left_width,
            system: left,
        });
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
    candidates.truncate(options.max_candidates);
    isolation
        .roots
        .extend(candidates.into_iter().map(|(_, root)| root));
    isolation
}

/// The box centre as an uncertified candidate.
fn uncertified(cell: &Cell) -> IsolatedRoot {
    let mut point = [0.0; MAX_VARIABLES];
    for k in 0..MAX_VARIABLES {
        point[k] = cell.lo[k] + 0.5 * cell.width[k];
    }
    IsolatedRoot {
        point,
        certified: false,
    }
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
    /// `K ⊂ int X`, with the preconditioner `Y`.
    UniqueRoot { y: [[f64; MAX_VARIABLES]; MAX_VARIABLES] },
    /// Neither.
    Undecided,
}

/// Krawczyk's test on the cell's own unit box (module docs).
fn krawczyk(system: &Tensor, n: usize, margin: &[f64]) -> Test {
    // [J]_{ik}: the range of ∂F_i/∂s_k, widened by the coefficients' rounding.
    let mut jacobian = [[Interval { lo: 0.0, hi: 0.0 }; MAX_VARIABLES]; MAX_VARIABLES];
    for k in 0..n {
        let derivative = system.derivative(k);
        let slack = 2.0 * system.degrees[k] as f64;
        for (i, row) in jacobian.iter_mut().enumerate().take(n) {
            let (lo, hi) = derivative.range(i);
            row[k] = Interval {
                lo: lo - slack * margin[i],
                hi: hi + slack * margin[i],
            };
        }
    }
    let mut middle = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
    for i in 0..n {
        for k in 0..n {
            middle[i][k] = 0.5 * (jacobian[i][k].lo + jacobian[i][k].hi);
        }
    }
    let Some(y) = invert(&middle, n) else {
        return Test::Undecided;
    };
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
        Test::UniqueRoot { y }
    } else {
        Test::Undecided
    }
}

/// Simplified Newton `x ← x - Y F(x)` from the centre of a certified box (Krawczyk's
/// contraction makes it converge), kept in the box.
fn newton_in_cell(
    system: &Tensor,
    n: usize,
    y: &[[f64; MAX_VARIABLES]; MAX_VARIABLES],
) -> [f64; MAX_VARIABLES] {
    let mut x = [0.5; MAX_VARIABLES];
    let mut value = [0.0; MAX_VARIABLES];
    for _ in 0..NEWTON_STEPS {
        system.evaluate(x, &mut value);
        let mut largest = 0.0f64;
        let mut next = x;
        for i in 0..n {
            let step: f64 = (0..n).map(|l| y[i][l] * value[l]).sum();
            next[i] = (x[i] - step).clamp(0.0, 1.0);
            largest = largest.max((next[i] - x[i]).abs());
        }
        x = next;
        if largest <= 4.0 * f64::EPSILON {
            break;
        }
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
        let pivot = (column..n).max_by(|&r, &s| a[r][column].abs().total_cmp(&a[s][column].abs()))?;
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
        let found = isolate(&system, 2, IsolationOptions::default());
        let certified: Vec<_> = found.roots.iter().filter(|r| r.certified).collect();
        assert_eq!(certified.len(), 1, "{found:?}");
        assert!((certified[0].point[0] - 0.5).abs() < 1e-14);
        assert!((certified[0].point[1] - 0.5).abs() < 1e-14);
        assert!(!found.exhausted);
    }

    /// A cubic with three roots in [0, 1]: (s - 0.1)(s - 0.5)(s - 0.9).
    #[test]
    fn a_univariate_cubic_has_its_three_roots() {
        let factor = |r: f64| linear(0, -r, 1.0 - r);
        let f = factor(0.1).times(&factor(0.5)).times(&factor(0.9)).unscaled();
        let found = isolate(&f, 1, IsolationOptions::default());
        let mut roots: Vec<f64> = found.roots.iter().map(|r| r.point[0]).collect();
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
        let found = isolate(&system, 3, IsolationOptions::default());
        let near = found.roots.iter().filter(|r| {
            (r.point[0] - 0.2).abs() < 1e-12
                && (r.point[1] - 0.3).abs() < 1e-12
                && (r.point[2] - 0.4).abs() < 1e-12
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
