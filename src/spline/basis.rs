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

/// The non-zero basis functions on span `m` and their derivatives up to order `order <= p`
/// (The NURBS Book, A2.3): `ders[k][r]` is the `k`-th derivative of `N_{m-p+r}^{p+1}` at `t`.
///
/// Derivatives of order above `p` vanish and are not written. Same precondition as
/// [`basis_functions`].
pub(crate) fn basis_derivatives(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    order: usize,
    ders: &mut [[f64; CAP]; CAP],
) {
    let p = degree;
    let order = order.min(p);
    let mut ndu = [[0.0; CAP]; CAP];
    let mut left = [0.0; CAP];
    let mut right = [0.0; CAP];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            // Lower triangle: knot differences; upper triangle: basis functions.
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for r in 0..=p {
        ders[0][r] = ndu[r][p];
    }
    let mut a = [[0.0; CAP]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=order {
            let mut d = 0.0;
            let pk = p - k;
            if r >= k {
                let rk = r - k;
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            // j runs over 1..=j2 with r - k + j >= 0.
            let j1 = if r + 1 >= k { 1 } else { k - r };
            let j2 = if r <= pk + 1 { k - 1 } else { p - r };
            for j in j1..=j2 {
                let rkj = r + j - k;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rkj];
                d += a[s2][j] * ndu[rkj][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
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
