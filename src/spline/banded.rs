//! Banded linear systems: LU without pivoting for the collocation matrices of interpolation,
//! Cholesky for the normal equations of least squares, and a bordered form (a banded block
//! plus a few border unknowns, by the Schur complement) for the cyclic systems of closed
//! curves. Work and memory are `O(n · w²)` and `O(n · w)` for `n` unknowns and bandwidth `w`;
//! no dense `n × n` matrix is ever formed.
//!
//! Written here rather than taken from a crate: the well-kept Rust linear-algebra crates
//! (nalgebra, faer) have no banded LU or Cholesky, and the systems are small-bandwidth ones
//! whose structure (total positivity, positive definiteness) makes pivoting unnecessary.

/// A pivot is refused as zero when its magnitude is at most this fraction of the largest
/// entry of its original row: the system is then singular to working precision.
pub const PIVOT_FLOOR: f64 = 1e-14;

/// A square matrix whose row `i` holds non-zeros only in columns `i - lower ..= i + upper`.
#[derive(Debug, Clone)]
pub struct BandedMatrix {
    size: usize,
    lower: usize,
    upper: usize,
    /// Row-major: row `i` at `i · width`, column `j` at offset `j + lower - i`.
    entries: Vec<f64>,
    /// The largest magnitude of each row as assembled (for the pivot test).
    row_scale: Vec<f64>,
    factored: bool,
}

/// The system has no unique solution to working precision: pivot `row` vanished.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("the linear system is singular to working precision (pivot {row})")]
pub struct SingularSystem {
    /// The row whose pivot vanished.
    pub row: usize,
}

impl BandedMatrix {
    /// A zero `size × size` matrix with `lower` sub- and `upper` super-diagonals.
    pub fn zeros(size: usize, lower: usize, upper: usize) -> Self {
        let width = lower + upper + 1;
        BandedMatrix {
            size,
            lower,
            upper,
            entries: vec![0.0; size * width],
            row_scale: vec![0.0; size],
            factored: false,
        }
    }

    /// The number of rows (and columns).
    pub fn size(&self) -> usize {
        self.size
    }

    fn width(&self) -> usize {
        self.lower + self.upper + 1
    }

    /// Whether `(row, column)` lies inside the band.
    pub fn in_band(&self, row: usize, column: usize) -> bool {
        column + self.lower >= row && column <= row + self.upper && column < self.size
    }

    fn offset(&self, row: usize, column: usize) -> usize {
        debug_assert!(
            self.in_band(row, column),
            "({row}, {column}) outside the band"
        );
        row * self.width() + column + self.lower - row
    }

    /// Adds `value` to entry `(row, column)`, which must lie inside the band.
    pub fn add(&mut self, row: usize, column: usize, value: f64) {
        let at = self.offset(row, column);
        self.entries[at] += value;
    }

    /// Entry `(row, column)` (0 outside the band).
    pub fn get(&self, row: usize, column: usize) -> f64 {
        if self.in_band(row, column) {
            self.entries[self.offset(row, column)]
        } else {
            0.0
        }
    }

    /// Factors in place into `L U` (unit lower `L`) by Gaussian elimination without pivoting,
    /// which keeps the band (no fill-in outside it).
    ///
    /// Precondition for stability: a totally positive matrix (B-spline collocation matrices
    /// with Schoenberg–Whitney parameters are; de Boor & Pinkus 1977) or a diagonally
    /// dominant one. A pivot at most [`PIVOT_FLOOR`] times its row's largest entry is refused.
    pub fn factor_lu(&mut self) -> Result<(), SingularSystem> {
        self.record_row_scales();
        let n = self.size;
        for k in 0..n {
            let pivot = self.get(k, k);
            if pivot.is_nan() || pivot.abs() <= PIVOT_FLOOR * self.row_scale[k] {
                return Err(SingularSystem { row: k });
            }
            let last_row = (k + self.lower).min(n - 1);
            let last_column = (k + self.upper).min(n - 1);
            for i in k + 1..=last_row {
                let at = self.offset(i, k);
                let factor = self.entries[at] / pivot;
                self.entries[at] = factor;
                if factor == 0.0 {
                    continue;
                }
                for j in k + 1..=last_column {
                    let source = self.entries[self.offset(k, j)];
                    let target = self.offset(i, j);
                    self.entries[target] -= factor * source;
                }
            }
        }
        self.factored = true;
        Ok(())
    }

    fn record_row_scales(&mut self) {
        let width = self.width();
        for (scale, row) in self.row_scale.iter_mut().zip(self.entries.chunks(width)) {
            *scale = row.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        }
    }

    /// Solves `A x = b` in place for `columns` right-hand sides stored row by row
    /// (`rhs[i · columns + c]`), after [`BandedMatrix::factor_lu`].
    pub fn solve_lu(&self, rhs: &mut [f64], columns: usize) {
        debug_assert!(self.factored);
        debug_assert_eq!(rhs.len(), self.size * columns);
        let n = self.size;
        for i in 0..n {
            let first = i.saturating_sub(self.lower);
            for j in first..i {
                let factor = self.entries[self.offset(i, j)];
                if factor != 0.0 {
                    for c in 0..columns {
                        rhs[i * columns + c] -= factor * rhs[j * columns + c];
                    }
                }
            }
        }
        for i in (0..n).rev() {
            let last = (i + self.upper).min(n - 1);
            for j in i + 1..=last {
                let factor = self.entries[self.offset(i, j)];
                if factor != 0.0 {
                    for c in 0..columns {
                        rhs[i * columns + c] -= factor * rhs[j * columns + c];
                    }
                }
            }
            let pivot = self.entries[self.offset(i, i)];
            for c in 0..columns {
                rhs[i * columns + c] /= pivot;
            }
        }
    }
}

/// A symmetric positive definite matrix with `bandwidth` sub-diagonals, stored as its lower
/// band; factored in place by Cholesky (`A = L Lᵀ`), which keeps the band.
#[derive(Debug, Clone)]
pub struct SymmetricBandedMatrix {
    size: usize,
    bandwidth: usize,
    /// Row `i`, column `j <= i` (`i - j <= bandwidth`) at `i · (bandwidth + 1) + j + bandwidth - i`.
    entries: Vec<f64>,
    factored: bool,
}

impl SymmetricBandedMatrix {
    /// A zero `size × size` matrix of half-bandwidth `bandwidth`.
    pub fn zeros(size: usize, bandwidth: usize) -> Self {
        SymmetricBandedMatrix {
            size,
            bandwidth,
            entries: vec![0.0; size * (bandwidth + 1)],
            factored: false,
        }
    }

    fn offset(&self, row: usize, column: usize) -> usize {
        debug_assert!(column <= row && row - column <= self.bandwidth);
        row * (self.bandwidth + 1) + column + self.bandwidth - row
    }

    /// Adds `value` to entry `(row, column)` with `column <= row` (the lower triangle) inside
    /// the band; the upper triangle is its mirror image.
    pub fn add_lower(&mut self, row: usize, column: usize, value: f64) {
        let at = self.offset(row, column);
        self.entries[at] += value;
    }

    /// Factors in place into `L Lᵀ`. A pivot `L_kk²` at most [`PIVOT_FLOOR`] times the
    /// diagonal entry it comes from (or not positive) is refused.
    pub fn factor_cholesky(&mut self) -> Result<(), SingularSystem> {
        let n = self.size;
        let w = self.bandwidth;
        for k in 0..n {
            let diagonal = self.entries[self.offset(k, k)];
            let first = k.saturating_sub(w);
            let mut pivot = diagonal;
            for j in first..k {
                let l = self.entries[self.offset(k, j)];
                pivot -= l * l;
            }
            if !pivot.is_finite() || pivot <= PIVOT_FLOOR * diagonal.abs() {
                return Err(SingularSystem { row: k });
            }
            let root = pivot.sqrt();
            let at = self.offset(k, k);
            self.entries[at] = root;
            for i in k + 1..=(k + w).min(n - 1) {
                let mut value = self.entries[self.offset(i, k)];
                let first = i.saturating_sub(w);
                for j in first..k {
                    value -= self.entries[self.offset(i, j)] * self.entries[self.offset(k, j)];
                }
                let at = self.offset(i, k);
                self.entries[at] = value / root;
            }
        }
        self.factored = true;
        Ok(())
    }

    /// Solves `A x = b` in place for `columns` right-hand sides stored row by row, after
    /// [`SymmetricBandedMatrix::factor_cholesky`].
    pub fn solve(&self, rhs: &mut [f64], columns: usize) {
        debug_assert!(self.factored);
        let n = self.size;
        let w = self.bandwidth;
        for i in 0..n {
            for j in i.saturating_sub(w)..i {
                let l = self.entries[self.offset(i, j)];
                for c in 0..columns {
                    rhs[i * columns + c] -= l * rhs[j * columns + c];
                }
            }
            let d = self.entries[self.offset(i, i)];
            for c in 0..columns {
                rhs[i * columns + c] /= d;
            }
        }
        for i in (0..n).rev() {
            for j in i + 1..=(i + w).min(n.saturating_sub(1)) {
                let l = self.entries[self.offset(j, i)];
                for c in 0..columns {
                    rhs[i * columns + c] -= l * rhs[j * columns + c];
                }
            }
            let d = self.entries[self.offset(i, i)];
            for c in 0..columns {
                rhs[i * columns + c] /= d;
            }
        }
    }
}

/// A square system split into `n_I` interior and `k` border unknowns and equations:
///
/// `[A_II A_IB; A_BI A_BB] [x_I; x_B] = [b_I; b_B]`,
///
/// `A_II` banded (factored without pivoting: the caller chooses it totally positive),
/// the border blocks dense but small. Solved through the Schur complement
/// `S = A_BB − A_BI A_II⁻¹ A_IB` (`k × k`, Gaussian elimination with partial pivoting):
/// `x_B = S⁻¹ (b_B − A_BI A_II⁻¹ b_I)`, `x_I = A_II⁻¹ (b_I − A_IB x_B)`.
/// Work `O(n_I · k · w + k³)`.
#[derive(Debug, Clone)]
pub struct BorderedSystem {
    /// `A_II`.
    pub interior: BandedMatrix,
    /// `A_IB`, row-major `n_I × k`.
    pub interior_border: Vec<f64>,
    /// `A_BI`, row-major `k × n_I`.
    pub border_interior: Vec<f64>,
    /// `A_BB`, row-major `k × k`.
    pub border_border: Vec<f64>,
    border: usize,
}

impl BorderedSystem {
    /// A zero system with `interior` unknowns of bandwidths `lower`/`upper` and `border`
    /// border unknowns.
    pub fn zeros(interior: usize, lower: usize, upper: usize, border: usize) -> Self {
        BorderedSystem {
            interior: BandedMatrix::zeros(interior, lower, upper),
            interior_border: vec![0.0; interior * border],
            border_interior: vec![0.0; border * interior],
            border_border: vec![0.0; border * border],
            border,
        }
    }

    /// Solves for `columns` right-hand sides: `interior_rhs` (`n_I × columns`) and
    /// `border_rhs` (`k × columns`), row-major, overwritten by the solution.
    pub fn solve(
        mut self,
        interior_rhs: &mut [f64],
        border_rhs: &mut [f64],
        columns: usize,
    ) -> Result<(), SingularSystem> {
        let n = self.interior.size();
        let k = self.border;
        self.interior.factor_lu()?;
        // Z = A_II⁻¹ A_IB (n × k) and y = A_II⁻¹ b_I.
        let mut z = std::mem::take(&mut self.interior_border);
        self.interior.solve_lu(&mut z, k);
        self.interior.solve_lu(interior_rhs, columns);
        // S = A_BB − A_BI Z and the reduced right-hand side b_B − A_BI y.
        let mut schur = self.border_border.clone();
        for r in 0..k {
            let row = &self.border_interior[r * n..(r + 1) * n];
            for (i, &a) in row.iter().enumerate() {
                if a == 0.0 {
                    continue;
                }
                for c in 0..k {
                    schur[r * k + c] -= a * z[i * k + c];
                }
                for c in 0..columns {
                    border_rhs[r * columns + c] -= a * interior_rhs[i * columns + c];
                }
            }
        }
        solve_dense(&mut schur, k, border_rhs, columns)
            .map_err(|e| SingularSystem { row: n + e.row })?;
        // x_I = y − Z x_B.
        for i in 0..n {
            for c in 0..columns {
                let mut correction = 0.0;
                for b in 0..k {
                    correction += z[i * k + b] * border_rhs[b * columns + c];
                }
                interior_rhs[i * columns + c] -= correction;
            }
        }
        Ok(())
    }
}

/// Solves the dense `size × size` system `a x = b` (row-major, overwritten) for `columns`
/// right-hand sides by Gaussian elimination with partial pivoting.
pub fn solve_dense(
    a: &mut [f64],
    size: usize,
    rhs: &mut [f64],
    columns: usize,
) -> Result<(), SingularSystem> {
    let scale = a.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    for k in 0..size {
        let (pivot_row, pivot) = (k..size)
            .map(|i| (i, a[i * size + k]))
            .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
            .unwrap_or((k, 0.0));
        if pivot.is_nan() || pivot.abs() <= PIVOT_FLOOR * scale {
            return Err(SingularSystem { row: k });
        }
        if pivot_row != k {
            for c in 0..size {
                a.swap(k * size + c, pivot_row * size + c);
            }
            for c in 0..columns {
                rhs.swap(k * columns + c, pivot_row * columns + c);
            }
        }
        for i in k + 1..size {
            let factor = a[i * size + k] / pivot;
            if factor == 0.0 {
                continue;
            }
            for c in k..size {
                a[i * size + c] -= factor * a[k * size + c];
            }
            for c in 0..columns {
                rhs[i * columns + c] -= factor * rhs[k * columns + c];
            }
        }
    }
    for i in (0..size).rev() {
        for c in 0..columns {
            let mut value = rhs[i * columns + c];
            for j in i + 1..size {
                value -= a[i * size + j] * rhs[j * columns + c];
            }
            rhs[i * columns + c] = value / a[i * size + i];
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dense product `A x` for a banded `A` given by `entry(i, j)`.
    fn multiply(size: usize, entry: impl Fn(usize, usize) -> f64, x: &[f64]) -> Vec<f64> {
        (0..size)
            .map(|i| (0..size).map(|j| entry(i, j) * x[j]).sum())
            .collect()
    }

    #[test]
    fn banded_lu_solves_a_diagonally_dominant_system() {
        let n = 9;
        let entry = |i: usize, j: usize| match i.abs_diff(j) {
            0 => 4.0 + i as f64,
            1 if j > i => 1.0,
            1 | 2 if j < i => -1.5 + 0.1 * j as f64,
            _ => 0.0,
        };
        let mut a = BandedMatrix::zeros(n, 2, 1);
        for i in 0..n {
            for j in 0..n {
                if entry(i, j) != 0.0 {
                    a.add(i, j, entry(i, j));
                }
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64).sin() + 2.0).collect();
        let mut b = multiply(n, entry, &x);
        a.factor_lu().unwrap();
        a.solve_lu(&mut b, 1);
        for (found, expected) in b.iter().zip(&x) {
            assert!((found - expected).abs() < 1e-13, "{found} vs {expected}");
        }
    }

    #[test]
    fn a_vanishing_pivot_is_refused() {
        let mut a = BandedMatrix::zeros(2, 1, 1);
        a.add(0, 0, 1.0);
        a.add(0, 1, 1.0);
        a.add(1, 0, 1.0);
        a.add(1, 1, 1.0);
        assert_eq!(a.factor_lu(), Err(SingularSystem { row: 1 }));
    }

    #[test]
    fn cholesky_solves_a_positive_definite_band() {
        let n = 7;
        let entry = |i: usize, j: usize| match i.abs_diff(j) {
            0 => 6.0,
            1 => -2.0,
            2 => 0.5,
            _ => 0.0,
        };
        let mut a = SymmetricBandedMatrix::zeros(n, 2);
        for i in 0..n {
            for j in i.saturating_sub(2)..=i {
                a.add_lower(i, j, entry(i, j));
            }
        }
        let x: Vec<f64> = (0..2 * n).map(|i| i as f64 * 0.3 - 1.0).collect();
        let mut b = vec![0.0; 2 * n];
        for c in 0..2 {
            let column: Vec<f64> = (0..n).map(|i| x[i * 2 + c]).collect();
            for (i, v) in multiply(n, entry, &column).into_iter().enumerate() {
                b[i * 2 + c] = v;
            }
        }
        a.factor_cholesky().unwrap();
        a.solve(&mut b, 2);
        for (found, expected) in b.iter().zip(&x) {
            assert!((found - expected).abs() < 1e-13);
        }
        let mut indefinite = SymmetricBandedMatrix::zeros(2, 1);
        indefinite.add_lower(0, 0, 1.0);
        indefinite.add_lower(1, 0, 2.0);
        indefinite.add_lower(1, 1, 1.0);
        assert!(indefinite.factor_cholesky().is_err());
    }

    #[test]
    fn a_bordered_cyclic_system_matches_dense_elimination() {
        // A cyclic tridiagonal matrix with corners, as closed curves give: unknown 0 is the
        // border, 1..n the interior.
        let n = 8;
        let entry = |i: usize, j: usize| {
            let d = (i + n - j) % n;
            match d {
                0 => 4.0,
                1 => 1.0 + 0.1 * i as f64,
                d if d == n - 1 => 1.5,
                _ => 0.0,
            }
        };
        let x: Vec<f64> = (0..n).map(|i| 1.0 + (i * i) as f64 * 0.1).collect();
        let b = multiply(n, entry, &x);
        let mut system = BorderedSystem::zeros(n - 1, 1, 1, 1);
        for i in 1..n {
            for j in 1..n {
                if entry(i, j) != 0.0 {
                    system.interior.add(i - 1, j - 1, entry(i, j));
                }
            }
            system.interior_border[i - 1] = entry(i, 0);
            system.border_interior[i - 1] = entry(0, i);
        }
        system.border_border[0] = entry(0, 0);
        let mut interior_rhs = b[1..].to_vec();
        let mut border_rhs = vec![b[0]];
        system.solve(&mut interior_rhs, &mut border_rhs, 1).unwrap();
        assert!((border_rhs[0] - x[0]).abs() < 1e-13);
        for (found, expected) in interior_rhs.iter().zip(&x[1..]) {
            assert!((found - expected).abs() < 1e-13);
        }
        let mut dense: Vec<f64> = (0..n * n).map(|k| entry(k / n, k % n)).collect();
        let mut rhs = b.clone();
        solve_dense(&mut dense, n, &mut rhs, 1).unwrap();
        for (found, expected) in rhs.iter().zip(&x) {
            assert!((found - expected).abs() < 1e-13);
        }
    }
}
