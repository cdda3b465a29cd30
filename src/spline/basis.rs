//! B-spline basis functions and their derivatives on one knot span (The NURBS Book, A2.1–A2.3).
//!
//! All routines work on the *full* knot vector `u_0 ..= u_{n+p+1}` of a degree-`p` spline and
//! use fixed-size stack buffers, so they never allocate.

/// Largest degree the evaluator's fixed-size buffers hold; [`crate::spline::CurveLimits`]
/// cannot allow more.
pub const MAX_DEGREE: usize = 15;

/// Capacity of the per-span buffers: `MAX_DEGREE + 1` basis functions.
pub(crate) const CAP: usize = MAX_DEGREE + 1;

/// The span index `m` with `u_m <= t < u_{m+1}` and `p <= m <= n` (The NURBS Book, A2.1).
///
/// `n + 1` is the number of control points, so `knots.len() == n + p + 2`. For
/// `t >= u_{n+1}` it returns the last non-empty span, so that the right end of the domain is
/// evaluated as the limit from the left. Precondition: `u_p < u_{n+1}` (non-empty domain);
/// `t < u_p` gives `p` (the first span, extrapolated).
pub(crate) fn find_span(knots: &[f64], degree: usize, t: f64) -> usize {
    let n = knots.len() - degree - 2;
    if t >= knots[n + 1] {
        let mut m = n;
        while m > degree && knots[m] >= knots[n + 1] {
            m -= 1;
        }
        return m;
    }
    degree + knots[degree + 1..=n + 1].partition_point(|&u| u <= t)
}

/// The `p + 1` basis functions `N_{m-p}^{p+1}(t) ..= N_m^{p+1}(t)` that are non-zero on span `m`
/// (The NURBS Book, A2.2), written to `out[0..=p]`.
///
/// Precondition: `u_m < u_{m+1}`; then every denominator `u_{m+r+1} - u_{m+1-j+r}` (r < j) is
/// at least `u_{m+1} - u_m > 0`, whatever the multiplicities elsewhere.
pub(crate) fn basis_functions(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    out: &mut [f64; CAP],
) {
    let mut left = [0.0; CAP];
    let mut right = [0.0; CAP];
    out[0] = 1.0;
    for j in 1..=degree {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = out[r] / (right[r + 1] + left[j - r]);
            out[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        out[j] = saved;
    }
}

/// The non-zero basis functions of every degree `j = 0..=p` on span `m`:
/// `out[j][r] = N_{m-j+r}^{j+1}(t)` for `r = 0..=j` (the rows of A2.2's triangle, kept).
///
/// Every term is a product of non-negative factors for `t` in the span, so each value is
/// accurate to a few units in the last place. Same precondition as [`basis_functions`], and
/// `degree < N` (callers pass [`CAP`], or a smaller `N` for low degrees, which keeps the
/// stack buffers small).
#[inline]
pub(crate) fn basis_functions_of_every_degree<const N: usize>(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    out: &mut [[f64; N]; N],
) {
    let mut left = [0.0; N];
    let mut right = [0.0; N];
    out[0][0] = 1.0;
    for j in 1..=degree {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = out[j - 1][r] / (right[r + 1] + left[j - r]);
            out[j][r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        out[j][j] = saved;
    }
}

/// The non-zero basis functions on span `m` and their derivatives up to order `order <= p`
/// (The NURBS Book, A2.3): `ders[k][r]` is the `k`-th derivative of `N_{m-p+r}^{p+1}` at `t`.
///
/// Derivatives of order above `p` vanish and are not written. Same precondition as
/// [`basis_functions`], and `p < N`: the buffers are `N × N` (callers pass [`CAP`], or a
/// smaller `N` for low degrees, which keeps the stack buffers small).
///
/// Unlike the book, the table's lower triangle keeps the *reciprocals* of the knot
/// differences: one division each, and the derivative recurrences multiply.
#[inline]
pub(crate) fn basis_derivatives<const N: usize>(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    order: usize,
    ders: &mut [[f64; N]; N],
) {
    let p = degree;
    let order = order.min(p);
    let mut ndu = [[0.0; N]; N];
    let mut left = [0.0; N];
    let mut right = [0.0; N];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            // Lower triangle: reciprocal knot differences; upper triangle: basis functions.
            ndu[j][r] = 1.0 / (right[r + 1] + left[j - r]);
            let temp = ndu[r][j - 1] * ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for r in 0..=p {
        ders[0][r] = ndu[r][p];
    }
    let mut a = [[0.0; N]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=order {
            let mut d = 0.0;
            let pk = p - k;
            if r >= k {
                let rk = r - k;
                a[s2][0] = a[s1][0] * ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            // j runs over 1..=j2 with r - k + j >= 0.
            let j1 = if r + 1 >= k { 1 } else { k - r };
            let j2 = if r <= pk + 1 { k - 1 } else { p - r };
            for j in j1..=j2 {
                let rkj = r + j - k;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) * ndu[pk + 1][rkj];
                d += a[s2][j] * ndu[rkj][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] * ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for (k, row) in ders.iter_mut().enumerate().take(order + 1).skip(1) {
        for value in row.iter_mut().take(p + 1) {
            *value *= factor;
        }
        factor *= (p - k) as f64;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Known values are exact binary fractions; this only absorbs rounding.
    const TOL: f64 = 1e-14;

    /// The NURBS Book, Examples 2.3 and 2.4: `U = {0,0,0,1,2,3,4,4,5,5,5}`, `p = 2`.
    const KNOTS: [f64; 11] = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 5.0, 5.0, 5.0];

    #[test]
    fn span_search() {
        assert_eq!(find_span(&KNOTS, 2, 0.0), 2);
        assert_eq!(find_span(&KNOTS, 2, 2.5), 4);
        assert_eq!(
            find_span(&KNOTS, 2, 3.0),
            5,
            "a knot uses the span on its right"
        );
        assert_eq!(find_span(&KNOTS, 2, 4.0), 7, "past a double knot");
        assert_eq!(
            find_span(&KNOTS, 2, 5.0),
            7,
            "the right end uses the last non-empty span"
        );
    }

    #[test]
    fn basis_functions_of_the_nurbs_book_example() {
        // N_{2,2}(5/2) = 1/8, N_{3,2}(5/2) = 6/8, N_{4,2}(5/2) = 1/8.
        let mut out = [0.0; CAP];
        basis_functions(&KNOTS, 2, 4, 2.5, &mut out);
        for (value, expected) in out[..3].iter().zip([0.125, 0.75, 0.125]) {
            assert_relative_eq!(*value, expected, epsilon = TOL);
        }
    }

    #[test]
    fn basis_derivatives_of_the_nurbs_book_example() {
        // On [2, 3): N_2 = (3-u)²/2, N_3 = 1 - N_2 - N_4, N_4 = (u-2)²/2.
        let mut ders = [[0.0; CAP]; CAP];
        basis_derivatives(&KNOTS, 2, 4, 2.5, 2, &mut ders);
        let expected = [[0.125, 0.75, 0.125], [-0.5, 0.0, 0.5], [1.0, -2.0, 1.0]];
        for (row, expected_row) in ders.iter().zip(expected) {
            for (value, e) in row[..3].iter().zip(expected_row) {
                assert_relative_eq!(*value, e, epsilon = TOL);
            }
        }
    }

    #[test]
    fn partition_of_unity_and_its_derivatives() {
        // A cubic with a double interior knot and an unclamped start.
        let knots = [-1.0, -0.5, 0.0, 0.0, 0.4, 1.0, 1.0, 1.7, 2.0, 2.0, 2.0, 2.0];
        let p = 3;
        for i in 0..=40 {
            let t = 2.0 * f64::from(i) / 40.0;
            let span = find_span(&knots, p, t);
            let mut ders = [[0.0; CAP]; CAP];
            basis_derivatives(&knots, p, span, t, p, &mut ders);
            let mut values = [0.0; CAP];
            basis_functions(&knots, p, span, t, &mut values);
            let sum: f64 = values[..=p].iter().sum();
            assert_relative_eq!(sum, 1.0, epsilon = TOL);
            for (k, row) in ders.iter().enumerate().take(p + 1) {
                let expected = if k == 0 { 1.0 } else { 0.0 };
                let scale = row[..=p].iter().fold(1.0f64, |m, v| m.max(v.abs()));
                assert_relative_eq!(
                    row[..=p].iter().sum::<f64>(),
                    expected,
                    epsilon = TOL * scale
                );
            }
            for (a, b) in values[..=p].iter().zip(&ders[0][..=p]) {
                assert_relative_eq!(*a, *b, epsilon = TOL);
            }
        }
    }
}
