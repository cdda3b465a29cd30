//! An independent evaluator: the Cox–de Boor recursion for every basis function (not de
//! Boor's triangle, not the code under test) and the tensor product, homogeneous for NURBS.

/// All `n` basis functions of degree `p` on `knots` at `t` by the Cox–de Boor recursion
/// (`0/0 = 0`); at the domain's right end the last non-empty span is taken.
pub fn basis(knots: &[f64], p: usize, t: f64) -> Vec<f64> {
    let n = knots.len() - p - 1;
    let hi = knots[n];
    // Degree 0: the span containing t (the last non-empty one at the right end).
    let mut values: Vec<f64> = (0..knots.len() - 1)
        .map(|i| {
            let inside = knots[i] <= t && t < knots[i + 1];
            let at_end = t == hi && knots[i] < knots[i + 1] && knots[i + 1] == hi;
            if inside || at_end { 1.0 } else { 0.0 }
        })
        .collect();
    if t == hi {
        // Only the last non-empty span ending at hi.
        let last = (0..knots.len() - 1).rfind(|&i| knots[i] < knots[i + 1] && knots[i + 1] == hi);
        for (i, v) in values.iter_mut().enumerate() {
            *v = if Some(i) == last { 1.0 } else { 0.0 };
        }
    }
    for d in 1..=p {
        let next: Vec<f64> = (0..knots.len() - 1 - d)
            .map(|i| {
                let mut v = 0.0;
                let a = knots[i + d] - knots[i];
                if a > 0.0 {
                    v += (t - knots[i]) / a * values[i];
                }
                let b = knots[i + d + 1] - knots[i + 1];
                if b > 0.0 {
                    v += (knots[i + d + 1] - t) / b * values[i + 1];
                }
                v
            })
            .collect();
        values = next;
    }
    values.truncate(n);
    values
}

/// A surface as plain data.
#[derive(Debug, Clone)]
pub struct Net {
    pub degrees: (usize, usize),
    pub knots_u: Vec<f64>,
    pub knots_v: Vec<f64>,
    /// `poles[i][j]`.
    pub poles: Vec<Vec<[f64; 3]>>,
    pub weights: Option<Vec<Vec<f64>>>,
}

impl Net {
    /// `S(u, v)` with the given knot vectors (the net's own when `None`).
    pub fn point_with(&self, knots_u: &[f64], knots_v: &[f64], u: f64, v: f64) -> [f64; 3] {
        let nu = basis(knots_u, self.degrees.0, u);
        let nv = basis(knots_v, self.degrees.1, v);
        let mut sum = [0.0; 4];
        for (i, row) in self.poles.iter().enumerate() {
            for (j, d) in row.iter().enumerate() {
                let w = self.weights.as_ref().map_or(1.0, |w| w[i][j]);
                let b = nu[i] * nv[j] * w;
                for c in 0..3 {
                    sum[c] += b * d[c];
                }
                sum[3] += b;
            }
        }
        [sum[0] / sum[3], sum[1] / sum[3], sum[2] / sum[3]]
    }

    /// The domain `((u_lo, u_hi), (v_lo, v_hi))`.
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        let (pu, pv) = self.degrees;
        let (nu, nv) = (self.poles.len(), self.poles[0].len());
        (
            (self.knots_u[pu], self.knots_u[nu]),
            (self.knots_v[pv], self.knots_v[nv]),
        )
    }

    /// `S(u, v)` with the net's knots.
    pub fn point(&self, u: f64, v: f64) -> [f64; 3] {
        self.point_with(&self.knots_u, &self.knots_v, u, v)
    }

    /// The surface object of this data.
    pub fn surface(&self) -> knotshape::surface::Surface {
        use knotshape::spline::KnotForm;
        knotshape::surface::Surface::from_knot_forms(
            self.degrees,
            &self.poles,
            (KnotForm::Flat(&self.knots_u), KnotForm::Flat(&self.knots_v)),
            self.weights.as_deref(),
            &knotshape::surface::SurfaceLimits::default(),
        )
        .unwrap()
    }
}

/// `|a - b|`.
pub fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// A clamped knot vector of `count` poles, degree `p`, with `interior` knots, on `[0, 1]`.
pub fn clamped(p: usize, interior: &[f64]) -> Vec<f64> {
    let mut knots = vec![0.0; p + 1];
    knots.extend_from_slice(interior);
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    knots
}
