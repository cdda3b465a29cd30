//! A dense linear solve (Gaussian elimination with partial pivoting on the full matrix),
//! written here so that the banded solvers of `knotshape::spline` are checked against an
//! independent computation.

/// Solves `a x = b` for a dense `n × n` matrix (rows of `a`) and `columns` right-hand sides
/// (rows of `b`, `b[i][c]`). `None` when a pivot vanishes.
pub fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<Vec<f64>>) -> Option<Vec<Vec<f64>>> {
    let n = a.len();
    for k in 0..n {
        let pivot = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
        if a[pivot][k] == 0.0 {
            return None;
        }
        a.swap(k, pivot);
        b.swap(k, pivot);
        let (above, below) = a.split_at_mut(k + 1);
        let (rhs_above, rhs_below) = b.split_at_mut(k + 1);
        let (pivot_row, pivot_rhs) = (&above[k], &rhs_above[k]);
        for (row, rhs) in below.iter_mut().zip(rhs_below.iter_mut()) {
            let factor = row[k] / pivot_row[k];
            for (value, &source) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                *value -= factor * source;
            }
            for (value, &source) in rhs.iter_mut().zip(pivot_rhs) {
                *value -= factor * source;
            }
        }
    }
    for i in (0..n).rev() {
        for c in 0..b[i].len() {
            let mut value = b[i][c];
            for j in i + 1..n {
                value -= a[i][j] * b[j][c];
            }
            b[i][c] = value / a[i][i];
        }
    }
    Some(b)
}
