//! A reference NURBS evaluator of any degree, with derivatives, written for the tests (it
//! shares no code with the service): de Boor's algorithm on homogeneous points, derivatives
//! from the derivative curves' control points (The NURBS Book eq. 3.7) and the quotient rule.
//! At a knot the span right of it is used, at the domain's right end the last non-empty one,
//! as the service does.
#![allow(dead_code)]

use knotshape::spline::{Curve, Point};

/// A curve as plain data: degree, control points (`z = 0` in 2D), full knots, weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    pub degree: usize,
    pub points: Vec<Point>,
    pub knots: Vec<f64>,
    pub weights: Vec<f64>,
}

impl Nurbs {
    /// The data of a service curve (read through its accessors only).
    pub fn of(curve: &Curve) -> Nurbs {
        Nurbs {
            degree: curve.degree(),
            points: curve.control_points().to_vec(),
            knots: curve.knots().to_vec(),
            weights: (0..curve.control_points().len())
                .map(|i| curve.weight(i))
                .collect(),
        }
    }

    /// `[u_p, u_{n+1}]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.points.len()])
    }

    /// The homogeneous control points `(w x, w y, w z, w)`.
    fn homogeneous(&self) -> Vec<[f64; 4]> {
        self.points
            .iter()
            .zip(&self.weights)
            .map(|(p, &w)| [w * p[0], w * p[1], w * p[2], w])
            .collect()
    }

    /// `s^(k)(u)` for `k = 0..=order` (`order <= 2` is what the tests need; any works).
    pub fn derivatives(&self, u: f64, order: usize) -> Vec<Point> {
        let (lo, hi) = self.domain();
        // The span: largest m in p..=n with u_m <= u and u_m < u_{m+1}, or the last
        // non-empty one at the right end.
        let p = self.degree;
        let n = self.points.len() - 1;
        let mut span = p;
        for m in p..=n {
            if self.knots[m] < self.knots[m + 1] && (self.knots[m] <= u || u >= hi) {
                span = m;
            }
        }
        assert!(
            u >= lo - 1e-12 && u <= hi + 1e-12,
            "u = {u} outside [{lo}, {hi}]"
        );
        // Homogeneous derivatives A^(k)(u) from the k-th derivative curves.
        let mut control = self.homogeneous();
        let mut knots = self.knots.clone();
        let mut degree = p;
        let mut homogeneous = Vec::with_capacity(order + 1);
        for k in 0..=order {
            if k > p {
                homogeneous.push([0.0; 4]);
                continue;
            }
            // The k-th derivative curve has degree p - k over knots[k..len-k]; span m keeps
            // its interval, now at index m - k.
            homogeneous.push(de_boor(degree, &control, &knots, span - k, u));
            if k < order && degree > 0 {
                let next: Vec<[f64; 4]> = (0..control.len() - 1)
                    .map(|i| {
                        let width = knots[i + degree + 1] - knots[i + 1];
                        if width == 0.0 {
                            [0.0; 4]
                        } else {
                            let f = degree as f64 / width;
                            std::array::from_fn(|c| f * (control[i + 1][c] - control[i][c]))
                        }
                    })
                    .collect();
                control = next;
                knots = knots[1..knots.len() - 1].to_vec();
                degree -= 1;
            }
        }
        // The quotient rule: C = A / w, C' = (A' - w' C) / w, C'' = (A'' - 2 w' C' - w'' C) / w.
        let w = |k: usize| homogeneous[k][3];
        let mut out: Vec<Point> = Vec::with_capacity(order + 1);
        for k in 0..=order {
            let a = homogeneous[k];
            let mut value = [a[0], a[1], a[2]];
            for i in 1..=k {
                let factor = binomial(k, i) * w(i);
                for c in 0..3 {
                    value[c] -= factor * out[k - i][c];
                }
            }
            out.push(value.map(|v| v / w(0)));
        }
        out
    }

    /// `s(u)`.
    pub fn point(&self, u: f64) -> Point {
        self.derivatives(u, 0)[0]
    }
}

fn binomial(k: usize, i: usize) -> f64 {
    (0..i).fold(1.0, |acc, r| acc * (k - r) as f64 / (r + 1) as f64)
}

/// de Boor's algorithm for a degree-`q` spline of homogeneous points over `knots` on span `m`.
fn de_boor(q: usize, points: &[[f64; 4]], knots: &[f64], m: usize, u: f64) -> [f64; 4] {
    let mut d: Vec<[f64; 4]> = (0..=q).map(|r| points[m - q + r]).collect();
    for level in 1..=q {
        for r in (level..=q).rev() {
            let i = m - q + r;
            let denominator = knots[i + q + 1 - level] - knots[i];
            let alpha = if denominator == 0.0 {
                0.0
            } else {
                (u - knots[i]) / denominator
            };
            let previous = d[r - 1];
            for (value, before) in d[r].iter_mut().zip(previous) {
                *value = (1.0 - alpha) * before + alpha * *value;
            }
        }
    }
    d[q]
}
