//! What the surface-edit tests share: a brute-force evaluator that knows nothing of the code
//! under test (Cox–de Boor recursion over every basis function, the rational quotient, and
//! the first partials from the derivative recurrence), and a builder of core surfaces from
//! plain data.

#![allow(dead_code)]

use knotshape::spline::KnotForm;
use knotshape::surface::{Surface, SurfaceLimits};

/// A surface as plain data: full knot vectors, `poles[i][j]`, optional weights.
#[derive(Debug, Clone)]
pub struct Plain {
    pub p: usize,
    pub q: usize,
    pub knots_u: Vec<f64>,
    pub knots_v: Vec<f64>,
    pub poles: Vec<Vec<[f64; 3]>>,
    pub weights: Option<Vec<Vec<f64>>>,
}

impl Plain {
    /// The core surface of the same data.
    pub fn surface(&self) -> Surface {
        Surface::from_knot_forms(
            (self.p, self.q),
            &self.poles,
            (KnotForm::Flat(&self.knots_u), KnotForm::Flat(&self.knots_v)),
            self.weights.as_deref(),
            &SurfaceLimits::default(),
        )
        .expect("valid test surface")
    }

    /// The plain data of a core surface (its stored net and full knots).
    pub fn of(surface: &Surface) -> Plain {
        let (n_u, n_v) = (surface.u().count(), surface.v().count());
        Plain {
            p: surface.u().degree(),
            q: surface.v().degree(),
            knots_u: surface.u().knots().to_vec(),
            knots_v: surface.v().knots().to_vec(),
            poles: (0..n_u)
                .map(|i| (0..n_v).map(|j| surface.control_point(i, j)).collect())
                .collect(),
            weights: surface.is_rational().then(|| {
                (0..n_u)
                    .map(|i| (0..n_v).map(|j| surface.weight(i, j)).collect())
                    .collect()
            }),
        }
    }

    fn weight(&self, i: usize, j: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i][j])
    }

    /// `[S, S_u, S_v]` at `(u, v)`: every `N_i(u)`, `M_j(v)` by the recursion (half-open
    /// spans, the last non-empty span closed at the domain's end), then the quotient rule.
    pub fn eval(&self, u: f64, v: f64) -> [[f64; 3]; 3] {
        let (nu, du) = basis_all(&self.knots_u, self.p, u);
        let (nv, dv) = basis_all(&self.knots_v, self.q, v);
        let mut a = [[0.0; 4]; 3];
        for (i, row) in self.poles.iter().enumerate() {
            for (j, pole) in row.iter().enumerate() {
                let w = self.weight(i, j);
                let factors = [nu[i] * nv[j], du[i] * nv[j], nu[i] * dv[j]];
                for (k, f) in factors.iter().enumerate() {
                    for c in 0..3 {
                        a[k][c] += f * w * pole[c];
                    }
                    a[k][3] += f * w;
                }
            }
        }
        let point: [f64; 3] = std::array::from_fn(|c| a[0][c] / a[0][3]);
        let partial = |k: usize| -> [f64; 3] {
            std::array::from_fn(|c| (a[k][c] - point[c] * a[k][3]) / a[0][3])
        };
        [point, partial(1), partial(2)]
    }

    /// `S(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> [f64; 3] {
        self.eval(u, v)[0]
    }

    /// `[[u_lo, u_hi], [v_lo, v_hi]]`.
    pub fn domain(&self) -> [(f64, f64); 2] {
        let n_u = self.poles.len();
        let n_v = self.poles[0].len();
        [
            (self.knots_u[self.p], self.knots_u[n_u]),
            (self.knots_v[self.q], self.knots_v[n_v]),
        ]
    }

    /// The bounding-box diagonal of the net, at least 1.
    pub fn size(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for pole in self.poles.iter().flatten() {
            for c in 0..3 {
                lo[c] = lo[c].min(pole[c]);
                hi[c] = hi[c].max(pole[c]);
            }
        }
        distance(lo, hi).max(1.0)
    }
}

/// Every degree-`p` B-spline function and its derivative at `t` (Cox–de Boor from degree 0;
/// `N'_{i,p} = p (N_{i,p-1} / (t_{i+p} − t_i) − N_{i+1,p-1} / (t_{i+p+1} − t_{i+1}))`).
pub fn basis_all(knots: &[f64], p: usize, t: f64) -> (Vec<f64>, Vec<f64>) {
    let m = knots.len() - 1;
    let n = m - p; // functions of degree p
    let hi = knots[n];
    // Degree 0: the span holding t; at the domain's end the last non-empty one.
    let mut level: Vec<f64> = (0..m)
        .map(|i| {
            let inside = knots[i] <= t && t < knots[i + 1];
            let at_end = t >= hi && knots[i] < knots[i + 1] && knots[i + 1] == hi;
            if inside && t < hi || at_end { 1.0 } else { 0.0 }
        })
        .collect();
    let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
    let mut previous = level.clone();
    for d in 1..=p {
        previous = level.clone();
        level = (0..m - d)
            .map(|i| {
                ratio(t - knots[i], knots[i + d] - knots[i]) * previous[i]
                    + ratio(knots[i + d + 1] - t, knots[i + d + 1] - knots[i + 1]) * previous[i + 1]
            })
            .collect();
    }
    let derivative = (0..n)
        .map(|i| {
            p as f64
                * (ratio(previous[i], knots[i + p] - knots[i])
                    - ratio(previous[i + 1], knots[i + p + 1] - knots[i + 1]))
        })
        .collect();
    level.truncate(n);
    (level, derivative)
}

pub fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The largest `|S_a − S_b|` on an `n × n` grid of `rect` (both ends included).
pub fn sampled_deviation(a: &Plain, b: &Plain, rect: [(f64, f64); 2], n: usize) -> f64 {
    let mut worst = 0.0f64;
    for k in 0..n {
        for l in 0..n {
            let u = rect[0].0 + (rect[0].1 - rect[0].0) * k as f64 / (n - 1) as f64;
            let v = rect[1].0 + (rect[1].1 - rect[1].0) * l as f64 / (n - 1) as f64;
            worst = worst.max(distance(a.point(u, v), b.point(u, v)));
        }
    }
    worst
}
