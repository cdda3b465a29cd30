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
        for i in k + 1..n {
            let factor = a[i][k] / a[k][k];
            for j in k..n {
                a[i][j] -= factor * a[k][j];
            }
            for c in 0..b[i].len() {
                b[i][c] -= factor * b[k][c];
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
