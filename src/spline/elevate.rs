//! Degree elevation (The NURBS Book §5.5, A5.9): the same curve as a spline of higher degree.
//!
//! As A5.9 does, in three steps on the homogeneous points `(w x, w y, w z, w)`:
//!
//! 1. cut the curve into its Bézier pieces (one per knot span of the domain);
//! 2. raise each piece from degree `p` to `q` by repeating the one-step elevation
//!    `B'_i = (i / (k+1)) B_{i−1} + (1 − i / (k+1)) B_i`, `i = 0 … k+1` (degree `k` to `k+1`),
//!    which leaves the piece unchanged;
//! 3. join the pieces with multiplicity `q` at each interior knot (the curve is only known to
//!    be `C⁰` there) and remove each knot again `p − m` times, `m` its original multiplicity:
//!    a spline of degree `p` that is `C^{p−m}` at a knot is one of degree `q` with
//!    multiplicity `m + q − p` there, so these removals are exact (their discrepancy is
//!    rounding). A knot of multiplicity `p + 1`, where the curve jumps, keeps `q + 1`.
//!
//! The answer is clamped over the curve's domain (its knot vector starts and ends with
//! `q + 1` equal values) whatever the input's ends; it has
//! `q + 1 + Σ_knots (m + q − p)` control points.

use super::basis::MAX_DEGREE;
use super::curve::Curve;
use super::remove::{apply_removal, from_homogeneous, knot_run, local_removal};

/// Why a curve's degree cannot be raised.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ElevateError {
    #[error("the new degree {degree} must be greater than the curve's degree {current}")]
    NotHigher { degree: usize, current: usize },
    #[error("degree {degree} exceeds the limit {max}")]
    DegreeTooHigh { degree: usize, max: usize },
    #[error("the elevated curve would have {count} control points, above the limit {max}")]
    TooManyControlPoints { count: usize, max: usize },
}

impl Curve {
    /// The same curve with degree `degree` (module docs). Rules: `degree > p`, at most
    /// `max_degree` (and [`MAX_DEGREE`]); the result at most `max_control_points` points.
    pub fn elevate_degree(
        &self,
        degree: usize,
        max_degree: usize,
        max_control_points: usize,
    ) -> Result<Curve, ElevateError> {
        let p = self.degree();
        if degree <= p {
            return Err(ElevateError::NotHigher { degree, current: p });
        }
        let max = max_degree.min(MAX_DEGREE);
        if degree > max {
            return Err(ElevateError::DegreeTooHigh { degree, max });
        }
        let q = degree;
        let raise = q - p;
        let (lo, hi) = self.domain();
        let knots = self.knots();
        let multiplicity = |u: f64| knot_run(knots, u).1.min(p + 1);
        let mut count = q + 1;
        for run in knots.chunk_by(|a, b| a == b) {
            if lo < run[0] && run[0] < hi {
                count = count.saturating_add(run.len().min(p + 1) + raise);
            }
        }
        if count > max_control_points {
            return Err(ElevateError::TooManyControlPoints {
                count,
                max: max_control_points,
            });
        }
        let mut new_knots: Vec<f64> = vec![lo; q + 1];
        let mut points: Vec<[f64; 4]> = Vec::with_capacity(count + q);
        // A junction waits for the next one's knots before its removals (they reach
        // `q + 1` knots to the right).
        let mut pending: Option<(f64, usize)> = None;
        let rational = self.is_rational();
        for (index, piece) in self.bezier_pieces().enumerate() {
            let elevated = elevate_piece(piece.homogeneous(), raise);
            if index == 0 {
                points.extend_from_slice(&elevated);
            } else {
                let value = piece.domain.0;
                let m = multiplicity(value);
                let jumps = m > p;
                new_knots.extend(std::iter::repeat_n(value, if jumps { q + 1 } else { q }));
                if jumps {
                    points.extend_from_slice(&elevated);
                } else {
                    // The shared end point: the mean of both pieces' (equal up to rounding).
                    if let Some(last) = points.last_mut() {
                        *last = std::array::from_fn(|c| 0.5 * (last[c] + elevated[0][c]));
                    }
                    points.extend_from_slice(&elevated[1..]);
                }
                if let Some((value, removals)) = pending.take() {
                    remove_exactly(q, &mut new_knots, &mut points, value, removals, rational);
                }
                if !jumps && m < p {
                    pending = Some((value, p - m));
                }
            }
        }
        new_knots.extend(std::iter::repeat_n(hi, q + 1));
        if let Some((value, removals)) = pending {
            remove_exactly(q, &mut new_knots, &mut points, value, removals, rational);
        }
        Ok(from_homogeneous(
            q,
            self.dimension(),
            rational,
            new_knots,
            &points,
            self.convention(),
        ))
    }
}

/// Raises a Bézier piece's degree `raise` times (module docs, step 2).
fn elevate_piece(points: &[[f64; 4]], raise: usize) -> Vec<[f64; 4]> {
    let mut current = points.to_vec();
    for _ in 0..raise {
        let k = current.len() - 1;
        let mut next = Vec::with_capacity(k + 2);
        for i in 0..=k + 1 {
            let a = i as f64 / (k + 1) as f64;
            let point: [f64; 4] = std::array::from_fn(|c| {
                let before = if i > 0 { current[i - 1][c] } else { 0.0 };
                let here = if i <= k { current[i][c] } else { 0.0 };
                a * before + (1.0 - a) * here
            });
            next.push(point);
        }
        current = next;
    }
    current
}

/// Removes `value` `removals` times from the degree-`q` curve, which is known to allow it
/// exactly (module docs, step 3); stops early if rounding made a removal fail (the curve is
/// then still right, with one more knot).
fn remove_exactly(
    q: usize,
    knots: &mut Vec<f64>,
    points: &mut Vec<[f64; 4]>,
    value: f64,
    removals: usize,
    rational: bool,
) {
    for _ in 0..removals {
        let (r, s) = knot_run(knots, value);
        match local_removal(q, knots, points, r, s, rational) {
            Some(removal) => apply_removal(knots, points, &removal),
            None => return,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn a_line_elevated_to_a_cubic_has_evenly_spaced_points() {
        let line = Curve::new(
            1,
            &[[0.0, 0.0], [3.0, 6.0]],
            &[0.0, 0.0, 1.0, 1.0],
            None,
            &CurveLimits::default(),
        )
        .unwrap();
        let cubic = line.elevate_degree(3, 15, 100).unwrap();
        assert_eq!(cubic.degree(), 3);
        assert_eq!(cubic.knots(), &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
        for (i, point) in cubic.control_points().iter().enumerate() {
            assert!((point[0] - i as f64).abs() < 1e-15);
            assert!((point[1] - 2.0 * i as f64).abs() < 1e-15);
        }
        assert!(matches!(
            line.elevate_degree(1, 15, 100),
            Err(ElevateError::NotHigher { .. })
        ));
        assert!(matches!(
            line.elevate_degree(16, 20, 100),
            Err(ElevateError::DegreeTooHigh { max: 15, .. })
        ));
    }

    #[test]
    fn interior_knots_keep_their_continuity() {
        let curve = Curve::new(
            2,
            &[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [6.0, 1.0]],
            &[0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0],
            None,
            &CurveLimits::default(),
        )
        .unwrap();
        let cubic = curve.elevate_degree(3, 15, 100).unwrap();
        assert_eq!(
            cubic.knots(),
            &[0.0, 0.0, 0.0, 0.0, 0.4, 0.4, 0.7, 0.7, 1.0, 1.0, 1.0, 1.0]
        );
        for i in 0..=50 {
            let t = i as f64 / 50.0;
            let (a, b) = (curve.point(t).unwrap(), cubic.point(t).unwrap());
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 1e-13);
            }
        }
    }
}
