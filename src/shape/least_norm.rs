//! The least-norm solution of a small dense linear system `A x = c` whose rows may be
//! dependent: Householder QR with column pivoting of `Aᵀ`, a complete orthogonal
//! decomposition as in LAPACK's `xGELSY`.
//!
//! With `Aᵀ P = Q R` (`P` a permutation of the rows of `A`, `R` upper triangular), the
//! conditions read `Rᵀ (Qᵀ x) = Pᵀ c`. Rows whose pivot falls below [`RANK_TOLERANCE`] depend
//! on earlier ones and are dropped; the first `r` equations are solved by forward substitution
//! for `y = Qᵀ x` with the remaining components of `y` zero, and `x = Q y` is the least-norm
//! solution of the independent rows. Whether the dropped rows hold too is for the caller to
//! check (the edit re-evaluates every condition on the new curve).
//!
//! Hand-written rather than taken from a linear-algebra crate: the systems are tiny (a few rows
//! per constraint, a few columns per control point under them), the edit needs the rank and
//! the row order of the pivoting, and the whole solve is about sixty lines; the tests check it
//! against nalgebra's SVD pseudo-inverse.

/// Rows are scaled to unit length first; a row whose part outside the span of the rows chosen
/// before it is shorter than this counts as dependent on them.
pub const RANK_TOLERANCE: f64 = 1e-10;

/// A dense system: `rows` rows of `columns` coefficients (row-major), and `rhs_count`
/// right-hand sides per row (row-major), solved for all of them at once.
#[derive(Debug, Clone)]
pub struct DenseSystem {
    rows: usize,
    columns: usize,
    rhs_count: usize,
    matrix: Vec<f64>,
    rhs: Vec<f64>,
}

/// The solution: `columns × rhs_count` values (row-major) and the rank found.
#[derive(Debug, Clone, PartialEq)]
pub struct LeastNormSolution {
    /// `x[j * rhs_count + k]`: unknown `j` for right-hand side `k`.
    pub x: Vec<f64>,
    /// The number of independent rows.
    pub rank: usize,
}

impl DenseSystem {
    /// A zero system of the given size.
    pub fn zeros(rows: usize, columns: usize, rhs_count: usize) -> DenseSystem {
        DenseSystem {
            rows,
            columns,
            rhs_count,
            matrix: vec![0.0; rows * columns],
            rhs: vec![0.0; rows * rhs_count],
        }
    }

    /// The coefficient at `(row, column)`.
    pub fn coefficient_mut(&mut self, row: usize, column: usize) -> &mut f64 {
        &mut self.matrix[row * self.columns + column]
    }

    /// Right-hand side `k` of `row`.
    pub fn rhs_mut(&mut self, row: usize, k: usize) -> &mut f64 {
        &mut self.rhs[row * self.rhs_count + k]
    }

    /// The least-norm solution (module docs). Consumes the system (it is factored in place).
    pub fn solve(mut self) -> LeastNormSolution {
        let (m, n, k) = (self.rows, self.columns, self.rhs_count);
        // Unit rows: the rank test compares like with like, whatever the rows' units.
        for row in 0..m {
            let length = self.row(row).iter().map(|v| v * v).sum::<f64>().sqrt();
            if length > 0.0 {
                self.row_mut(row).iter_mut().for_each(|v| *v /= length);
                self.rhs[row * k..(row + 1) * k]
                    .iter_mut()
                    .for_each(|v| *v /= length);
            }
        }
        let steps = m.min(n);
        let mut diagonal = vec![0.0; steps];
        let mut head = vec![0.0; steps];
        let mut beta = vec![0.0; steps];
        let mut rank = 0;
        for step in 0..steps {
            // Pivot: the remaining row with the longest part in components step..n.
            let remaining = |system: &DenseSystem, row: usize| -> f64 {
                system.row(row)[step..].iter().map(|v| v * v).sum::<f64>()
            };
            let (pivot, length_sq) = (step..m).map(|row| (row, remaining(&self, row))).fold(
                (step, -1.0),
                |best, next| {
                    if next.1 > best.1 { next } else { best }
                },
            );
            let length = length_sq.max(0.0).sqrt();
            if length.is_nan() || length <= RANK_TOLERANCE {
                break;
            }
            self.swap_rows(step, pivot);
            // Householder reflection taking row[step..] onto alpha · e_step.
            let x0 = self.row(step)[step];
            let alpha = if x0 > 0.0 { -length } else { length };
            let v0 = x0 - alpha;
            let b = 1.0 / (alpha * (alpha - x0));
            for row in step + 1..m {
                let (pivot_row, other) = self.two_rows(step, row);
                let s = b
                    * (v0 * other[step]
                        + pivot_row[step + 1..]
                            .iter()
                            .zip(&other[step + 1..])
                            .map(|(v, a)| v * a)
                            .sum::<f64>());
                other[step] -= s * v0;
                for (a, v) in other[step + 1..].iter_mut().zip(&pivot_row[step + 1..]) {
                    *a -= s * v;
                }
            }
            diagonal[step] = alpha;
            head[step] = v0;
            beta[step] = b;
            rank = step + 1;
        }
        // Forward substitution: L y = c' for the first `rank` rows, y = 0 beyond.
        let mut y = vec![0.0; n * k];
        for i in 0..rank {
            for r in 0..k {
                let mut sum = self.rhs[i * k + r];
                for j in 0..i {
                    sum -= self.matrix[i * n + j] * y[j * k + r];
                }
                y[i * k + r] = sum / diagonal[i];
            }
        }
        // x = H_0 H_1 ... H_{rank-1} y, the last reflection applied first.
        for step in (0..rank).rev() {
            let v_tail = &self.matrix[step * n + step + 1..(step + 1) * n];
            for r in 0..k {
                let mut s = head[step] * y[step * k + r];
                for (offset, v) in v_tail.iter().enumerate() {
                    s += v * y[(step + 1 + offset) * k + r];
                }
                s *= beta[step];
                y[step * k + r] -= s * head[step];
                for (offset, v) in v_tail.iter().enumerate() {
                    y[(step + 1 + offset) * k + r] -= s * v;
                }
            }
        }
        LeastNormSolution { x: y, rank }
    }

    fn row(&self, row: usize) -> &[f64] {
        &self.matrix[row * self.columns..(row + 1) * self.columns]
    }

    fn row_mut(&mut self, row: usize) -> &mut [f64] {
        &mut self.matrix[row * self.columns..(row + 1) * self.columns]
    }

    /// Row `first` (read) and row `second` (written), `first < second`.
    fn two_rows(&mut self, first: usize, second: usize) -> (&[f64], &mut [f64]) {
        let n = self.columns;
        let (head, tail) = self.matrix.split_at_mut(second * n);
        (&head[first * n..(first + 1) * n], &mut tail[..n])
    }

    fn swap_rows(&mut self, a: usize, b: usize) {
        if a == b {
            return;
        }
        let (n, k) = (self.columns, self.rhs_count);
        for j in 0..n {
            self.matrix.swap(a * n + j, b * n + j);
        }
        for r in 0..k {
            self.rhs.swap(a * k + r, b * k + r);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn system(rows: &[&[f64]], rhs: &[f64]) -> DenseSystem {
        let mut s = DenseSystem::zeros(rows.len(), rows[0].len(), 1);
        for (i, row) in rows.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                *s.coefficient_mut(i, j) = v;
            }
            *s.rhs_mut(i, 0) = rhs[i];
        }
        s
    }

    #[test]
    fn one_row_gives_the_closed_form() {
        // x = a c / |a|²
        let solution = system(&[&[1.0, 2.0, 2.0]], &[3.0]).solve();
        assert_eq!(solution.rank, 1);
        for (x, a) in solution.x.iter().zip([1.0, 2.0, 2.0]) {
            assert!((x - a * 3.0 / 9.0).abs() < 1e-15);
        }
    }

    #[test]
    fn a_repeated_row_is_dropped() {
        let solution = system(&[&[1.0, 1.0], &[2.0, 2.0]], &[1.0, 2.0]).solve();
        assert_eq!(solution.rank, 1);
        assert!((solution.x[0] - 0.5).abs() < 1e-15 && (solution.x[1] - 0.5).abs() < 1e-15);
    }
}
