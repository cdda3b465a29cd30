//! An independent B-spline/NURBS evaluator written from the textbook definitions, sharing no
//! code with `knotshape::spline`: the Cox–de Boor recursion on the full knot vector (0/0 := 0),
//! derivatives by repeated hodographs, rational curves as `Σ N w d / Σ N w`, and central finite
//! differences.

/// A point or vector in 3D (2D curves have `z = 0`).
pub type P3 = [f64; 3];

/// A curve as the textbook writes it: degree `p`, control points `d_0 ..= d_n`, the full knot
/// vector `u_0 ..= u_{n+p+1}` and optional weights.
#[derive(Debug, Clone)]
pub struct Reference {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub points: Vec<P3>,
    pub weights: Option<Vec<f64>>,
}

/// `num / den` with the convention `x / 0 := 0` (the term's basis function vanishes then).
fn ratio(num: f64, den: f64) -> f64 {
    if den == 0.0 { 0.0 } else { num / den }
}

/// `binom(k, i)` by Pascal's triangle.
pub fn binomial(k: usize, i: usize) -> f64 {
    let mut row = vec![1.0f64];
    for _ in 0..k {
        let mut next = vec![1.0; row.len() + 1];
        for j in 1..row.len() {
            next[j] = row[j - 1] + row[j];
        }
        row = next;
    }
    row[i]
}

impl Reference {
    /// The number of control points minus one, `n`.
    fn n(&self) -> usize {
        self.points.len() - 1
    }

    /// The domain `[u_p, u_{n+1}]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.n() + 1])
    }

    /// The weight of control point `i` (1 when non-rational).
    pub fn weight(&self, i: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i])
    }

    /// Index `j` of the degree-0 basis function that is 1 at `t`: `u_j <= t < u_{j+1}`, except
    /// at the right end of the domain, where the last non-empty interval inside the domain is
    /// closed on the right (the curve there is the limit from the left).
    fn indicator(&self, t: f64) -> usize {
        let (_, hi) = self.domain();
        if t == hi {
            return self.left_indicator(t);
        }
        let u = &self.knots;
        (0..u.len() - 1)
            .find(|&j| u[j] <= t && t < u[j + 1])
            .expect("parameter inside the knot vector")
    }

    /// Index `j` of the interval `u_j < t <= u_{j+1}`: the piece whose limit from the left is
    /// taken at `t`.
    fn left_indicator(&self, t: f64) -> usize {
        let u = &self.knots;
        (0..u.len() - 1)
            .find(|&j| u[j] < t && t <= u[j + 1])
            .expect("parameter inside the knot vector")
    }

    /// Every basis function of degree `q` on the full knot vector at `t`:
    /// `N_{j,q}(t)` for `j = 0 .. knots.len() - q - 1`, by the Cox–de Boor recursion
    /// `N_{i,q} = (t - u_i)/(u_{i+q} - u_i) N_{i,q-1} + (u_{i+q+1} - t)/(u_{i+q+1} - u_{i+1}) N_{i+1,q-1}`.
    pub fn basis(&self, q: usize, t: f64) -> Vec<f64> {
        self.basis_from(q, t, self.indicator(t))
    }

    /// The basis functions of degree `q` at `t`, starting the recursion from the degree-0
    /// function `N_{one,0} = 1` (all others 0).
    fn basis_from(&self, q: usize, t: f64, one: usize) -> Vec<f64> {
        let u = &self.knots;
        let mut values: Vec<f64> = (0..u.len() - 1)
            .map(|j| if j == one { 1.0 } else { 0.0 })
            .collect();
        for d in 1..=q {
            values = (0..u.len() - 1 - d)
                .map(|i| {
                    ratio(t - u[i], u[i + d] - u[i]) * values[i]
                        + ratio(u[i + d + 1] - t, u[i + d + 1] - u[i + 1]) * values[i + 1]
                })
                .collect();
        }
        values
    }

    /// The point `Σ N_i w_i d_i / Σ N_i w_i` (the weights are 1 when non-rational).
    pub fn point(&self, t: f64) -> P3 {
        let basis = self.basis(self.degree, t);
        let mut numerator = [0.0; 3];
        let mut denominator = 0.0;
        for (i, d) in self.points.iter().enumerate() {
            let nw = basis[i] * self.weight(i);
            for c in 0..3 {
                numerator[c] += nw * d[c];
            }
            denominator += nw;
        }
        numerator.map(|v| v / denominator)
    }

    /// The hodograph coefficients of the homogeneous curve `A = Σ N_{i,p} (w_i d_i, w_i)`:
    /// level `k` holds the coefficients `Q^(k)_i` of `N_{i+k, p-k}` in `A^(k)`, from
    /// `Q^(k)_i = (p-k+1) (Q^(k-1)_{i+1} - Q^(k-1)_i) / (u_{i+p+1} - u_{i+k})` (The NURBS Book,
    /// eq. 3.8, on the full knot vector; a zero denominator means an empty support).
    pub fn hodographs(&self, order: usize) -> Vec<Vec<[f64; 4]>> {
        let p = self.degree;
        let u = &self.knots;
        let first: Vec<[f64; 4]> = self
            .points
            .iter()
            .enumerate()
            .map(|(i, d)| {
                let w = self.weight(i);
                [w * d[0], w * d[1], w * d[2], w]
            })
            .collect();
        let mut levels = vec![first];
        for k in 1..=order.min(p) {
            let previous = &levels[k - 1];
            let factor = (p - k + 1) as f64;
            let next = (0..previous.len() - 1)
                .map(|i| {
                    let den = u[i + p + 1] - u[i + k];
                    let mut q = [0.0; 4];
                    for c in 0..4 {
                        q[c] = ratio(factor * (previous[i + 1][c] - previous[i][c]), den);
                    }
                    q
                })
                .collect();
            levels.push(next);
        }
        levels
    }

    /// Homogeneous derivatives `A^(k)(t)`, `k = 0..=order` (zero above the degree).
    pub fn homogeneous_derivatives(&self, t: f64, order: usize) -> Vec<[f64; 4]> {
        self.homogeneous_derivatives_from(t, order, self.indicator(t))
    }

    /// [`Self::homogeneous_derivatives`] of the piece on interval `one`.
    fn homogeneous_derivatives_from(&self, t: f64, order: usize, one: usize) -> Vec<[f64; 4]> {
        let p = self.degree;
        let levels = self.hodographs(order);
        (0..=order)
            .map(|k| {
                let mut a = [0.0; 4];
                if k <= p {
                    let basis = self.basis_from(p - k, t, one);
                    for (i, q) in levels[k].iter().enumerate() {
                        for c in 0..4 {
                            a[c] += q[c] * basis[i + k];
                        }
                    }
                }
                a
            })
            .collect()
    }

    /// Curve derivatives `C^(k)(t)`, `k = 0..=order`, from the homogeneous ones by Leibniz's rule
    /// on `A = w C`: `C^(k) = (A^(k) - Σ_{i=1..k} binom(k, i) w^(i) C^(k-i)) / w`.
    pub fn derivatives(&self, t: f64, order: usize) -> Vec<P3> {
        quotients(&self.homogeneous_derivatives(t, order))
    }

    /// [`Self::derivatives`] as the limit from the left at `t`.
    pub fn derivatives_from_left(&self, t: f64, order: usize) -> Vec<P3> {
        quotients(&self.homogeneous_derivatives_from(t, order, self.left_indicator(t)))
    }

    /// Natural size of the `k`-th derivative at `t`: `R (p / w)^k`, with `R` the point scale
    /// and `w` the width of the knot span that holds `t` (each derivative of a B-spline piece
    /// scales like `p / w`). Errors are measured against the larger of this and the value.
    pub fn derivative_scale(&self, t: f64, k: usize) -> f64 {
        let j = self.indicator(t);
        let width = self.knots[j + 1] - self.knots[j];
        self.point_scale() * (self.degree as f64 / width).powi(k as i32)
    }

    /// The largest control-point coordinate magnitude (at least 1): the scale of point errors.
    pub fn point_scale(&self) -> f64 {
        self.points
            .iter()
            .flat_map(|d| d.iter())
            .fold(1.0f64, |m, v| m.max(v.abs()))
    }
}

/// Curve derivatives from homogeneous ones by Leibniz's rule on `A = w C`:
/// `C^(k) = (A^(k) - Σ_{i=1..k} binom(k, i) w^(i) C^(k-i)) / w`.
fn quotients(a: &[[f64; 4]]) -> Vec<P3> {
    let order = a.len() - 1;
    let mut c: Vec<P3> = Vec::with_capacity(order + 1);
    for k in 0..=order {
        let mut v = [a[k][0], a[k][1], a[k][2]];
        for i in 1..=k {
            let f = binomial(k, i) * a[i][3];
            for x in 0..3 {
                v[x] -= f * c[k - i][x];
            }
        }
        c.push(v.map(|x| x / a[0][3]));
    }
    c
}

/// The `k`-th central difference quotient of `f` at `t` with step `h`:
/// `Σ_j (-1)^j binom(k, j) f(t + (k/2 - j) h) / h^k`, refined by one Richardson step
/// `(4 D(h/2) - D(h)) / 3` (error `O(h^4)`).
pub fn central_difference(f: &dyn Fn(f64) -> P3, t: f64, k: usize, h: f64) -> P3 {
    let quotient = |h: f64| {
        let mut sum = [0.0; 3];
        for j in 0..=k {
            let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
            let value = f(t + (k as f64 / 2.0 - j as f64) * h);
            for c in 0..3 {
                sum[c] += sign * binomial(k, j) * value[c];
            }
        }
        sum.map(|v| v / h.powi(k as i32))
    };
    let coarse = quotient(h);
    let fine = quotient(h / 2.0);
    [0, 1, 2].map(|c| (4.0 * fine[c] - coarse[c]) / 3.0)
}
