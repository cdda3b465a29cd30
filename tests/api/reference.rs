//! An independent reference: de Boor's algorithm on homogeneous points, written for the tests
//! (it shares no code with the service).

use serde_json::{Value, json};

use crate::helpers::{numbers, points};

/// A curve as plain test data, always with the full knot vector.
#[derive(Debug, Clone)]
pub struct ReferenceCurve {
    pub degree: usize,
    pub points: Vec<Vec<f64>>,
    pub knots: Vec<f64>,
    pub weights: Option<Vec<f64>>,
}

impl ReferenceCurve {
    /// Reads a curve object (full or trimmed knots).
    pub fn from_json(curve: &Value) -> Self {
        let degree = curve["degree"].as_u64().unwrap() as usize;
        let points = points(&curve["control_points"]);
        let mut knots = numbers(&curve["knots"]);
        if knots.len() + 2 == points.len() + degree + 1 {
            knots.insert(0, knots[0]);
            knots.push(knots[knots.len() - 1]);
        }
        assert_eq!(knots.len(), points.len() + degree + 1);
        let weights = curve.get("weights").filter(|w| !w.is_null()).map(numbers);
        ReferenceCurve {
            degree,
            points,
            knots,
            weights,
        }
    }

    /// The curve object with full (`trimmed = false`) or trimmed knots.
    pub fn to_json(&self, trimmed: bool) -> Value {
        let knots = if trimmed {
            self.knots[1..self.knots.len() - 1].to_vec()
        } else {
            self.knots.clone()
        };
        let mut curve = json!({
            "degree": self.degree,
            "control_points": self.points,
            "knots": knots,
        });
        if let Some(weights) = &self.weights {
            curve["weights"] = json!(weights);
        }
        curve
    }

    /// The same curve with another full knot vector.
    pub fn with_knots(&self, knots: Vec<f64>) -> Self {
        ReferenceCurve {
            knots,
            ..self.clone()
        }
    }

    /// `[u_p, u_{n+1}]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.points.len()])
    }

    /// `s(t)` by de Boor's algorithm; at the right end of the domain, the limit from the left.
    pub fn point(&self, t: f64) -> Vec<f64> {
        let p = self.degree;
        let n = self.points.len() - 1;
        let u = &self.knots;
        let mut k = p;
        for span in p..=n {
            if u[span] < u[span + 1] && u[span] <= t {
                k = span;
            }
        }
        let dim = self.points[0].len();
        let weight = |i: usize| self.weights.as_ref().map_or(1.0, |w| w[i]);
        let mut d: Vec<Vec<f64>> = (0..=p)
            .map(|i| {
                let index = k - p + i;
                let w = weight(index);
                let mut h: Vec<f64> = self.points[index].iter().map(|c| c * w).collect();
                h.push(w);
                h
            })
            .collect();
        for r in 1..=p {
            for i in (r..=p).rev() {
                let lo = u[k - p + i];
                let hi = u[i + 1 + k - r];
                let alpha = (t - lo) / (hi - lo);
                let previous = d[i - 1].clone();
                for (value, before) in d[i].iter_mut().zip(previous) {
                    *value = (1.0 - alpha) * before + alpha * *value;
                }
            }
        }
        let w = d[p][dim];
        d[p][..dim].iter().map(|c| c / w).collect()
    }
}

/// Euclidean distance.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// A small deterministic generator (no external randomness, so failures reproduce).
pub struct Lcg(pub u64);

impl Lcg {
    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi]`.
    pub fn between(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// The 2D clamped cubic of MATH.md's worked examples (8 control points).
pub fn cubic_2d() -> ReferenceCurve {
    ReferenceCurve {
        degree: 3,
        points: vec![
            vec![0.0, 0.0],
            vec![1.0, 3.0],
            vec![3.0, 4.0],
            vec![5.0, 3.5],
            vec![6.0, 1.0],
            vec![8.0, 0.0],
            vec![9.0, 2.0],
            vec![10.0, 4.0],
        ],
        knots: vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.35, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0],
        weights: None,
    }
}

/// A 3D rational clamped cubic with a double interior knot.
pub fn rational_3d() -> ReferenceCurve {
    ReferenceCurve {
        degree: 3,
        points: vec![
            vec![0.0, 0.0, 0.0],
            vec![1.0, 2.0, 1.0],
            vec![3.0, 4.0, 0.5],
            vec![5.0, 3.5, 2.0],
            vec![6.0, 1.0, 1.0],
            vec![7.0, 0.0, -1.0],
            vec![9.0, 2.0, 0.0],
        ],
        knots: vec![0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0],
        weights: Some(vec![1.0, 0.5, 2.0, 1.0, 1.5, 0.8, 1.0]),
    }
}
