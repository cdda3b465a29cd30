//! The envelope of the family of curves made by moving a run of equal knots (docs/method.md §2).
//!
//! Moving the run `u_i = … = u_{i+m-1}` (multiplicity `m`, `1 <= m <= p - 1`) together to
//! `τ ∈ [u_{i-1}, u_{i+m}]` gives curves `s(u; τ)` whose envelope is the B-spline of degree
//! `p - m` with the same control points and weights over `u` without the run; the family
//! touches it at `u = τ` (Juhász & Hoffmann, Theorem 1, generalised).

use super::curve::Curve;

/// A maximal run of equal interior knots and the interval its value may take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KnotRun {
    /// Full-vector index of the run's first knot, `i`.
    pub start: usize,
    /// Number of equal knots `m`.
    pub multiplicity: usize,
    /// `[u_{i-1}, u_{i+m}]`: the values the run may move to keeping the knots ordered.
    pub range: (f64, f64),
}

/// Why a knot index cannot be moved as an envelope run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EnvelopeError {
    /// The index does not name a knot.
    #[error("knot index {index} is out of range: the knot vector has {len} values")]
    IndexOutOfRange { index: usize, len: usize },
    /// The run touches the domain's end knots `u_p` or `u_{n+1}`; moving it would move the domain.
    #[error(
        "knot {index} is not an interior knot: its run of equal values reaches the domain's end knots"
    )]
    NotInterior { index: usize },
    /// The run is too long for an envelope of degree `>= 1`.
    #[error(
        "knot {index} has multiplicity {multiplicity}; an envelope needs at most degree - 1 = {max}"
    )]
    MultiplicityTooHigh {
        index: usize,
        multiplicity: usize,
        max: usize,
    },
}

impl Curve {
    /// The maximal run of equal knots holding the caller's knot index `index`.
    ///
    /// The run must lie among the interior knots `u_{p+1} ..= u_n` (so the domain stays put)
    /// and have multiplicity `m <= p - 1`.
    pub fn knot_run(&self, index: usize) -> Result<KnotRun, EnvelopeError> {
        let caller_len = self.knots_in_convention().len();
        if index >= caller_len {
            return Err(EnvelopeError::IndexOutOfRange {
                index,
                len: caller_len,
            });
        }
        let knots = self.knots();
        let p = self.degree();
        let n = self.control_points().len() - 1;
        let full = self.convention().full_index(index);
        let value = knots[full];
        let mut start = full;
        while start > 0 && knots[start - 1] == value {
            start -= 1;
        }
        let mut end = full;
        while end + 1 < knots.len() && knots[end + 1] == value {
            end += 1;
        }
        if start <= p || end > n {
            return Err(EnvelopeError::NotInterior { index });
        }
        let multiplicity = end - start + 1;
        if multiplicity + 1 > p {
            return Err(EnvelopeError::MultiplicityTooHigh {
                index,
                multiplicity,
                max: p - 1,
            });
        }
        Ok(KnotRun {
            start,
            multiplicity,
            range: (knots[start - 1], knots[end + 1]),
        })
    }

    /// The envelope of moving `run`: degree `p - m`, same control points and weights, the knot
    /// vector without the run. Its full knot vector can hold `p - m + 2` equal values at a
    /// clamped end (the theorem's exact vector; the extra end knot has no effect).
    ///
    /// Its domain reaches beyond the curve's. When the run moves onto the domain's right end
    /// (`τ = u_{n+1}`), the moved curve there is the limit from the left, and so is the contact
    /// point: the envelope's own value at `τ` (span on the right) can differ where `τ` merges
    /// with the end knots and the envelope has a corner or a jump.
    pub fn envelope(&self, run: &KnotRun) -> Curve {
        let knots: Vec<f64> = self
            .knots()
            .iter()
            .enumerate()
            .filter(|(l, _)| *l < run.start || *l >= run.start + run.multiplicity)
            .map(|(_, &u)| u)
            .collect();
        Curve::from_valid_parts(
            self.degree() - run.multiplicity,
            self.dimension(),
            self.control_points().to_vec(),
            self.weights().map(<[f64]>::to_vec),
            knots,
            self.convention(),
        )
    }

    /// The family member `s(u; τ)`: the curve with every knot of `run` set to `tau`.
    /// `None` when `tau` is outside `run.range`.
    pub fn with_run_moved(&self, run: &KnotRun, tau: f64) -> Option<Curve> {
        if !(run.range.0 <= tau && tau <= run.range.1) {
            return None;
        }
        let mut knots = self.knots().to_vec();
        knots[run.start..run.start + run.multiplicity].fill(tau);
        self.with_full_knots(knots)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    /// A clamped cubic over ten control points with interior runs of multiplicity 1 (index 4),
    /// 2 (indices 5–6) and 3 (indices 7–9), in the full or the trimmed convention.
    fn cubic(trimmed: bool) -> Curve {
        let full = [
            0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 3.0, 3.0, 4.0, 4.0, 4.0, 4.0,
        ];
        let knots = if trimmed { &full[1..13] } else { &full[..] };
        let points: Vec<Vec<f64>> = (0..10)
            .map(|i| vec![f64::from(i), f64::from(i % 3)])
            .collect();
        Curve::new(3, &points, knots, None, &CurveLimits::default()).unwrap()
    }

    #[test]
    fn run_is_found_from_any_of_its_knots() {
        let expected = KnotRun {
            start: 5,
            multiplicity: 2,
            range: (1.0, 3.0),
        };
        assert_eq!(cubic(false).knot_run(5), Ok(expected));
        assert_eq!(cubic(false).knot_run(6), Ok(expected));
        // Trimmed: the caller's index 4 is full index 5; the run is reported in full indices.
        assert_eq!(cubic(true).knot_run(4), Ok(expected));
        let single = KnotRun {
            start: 4,
            multiplicity: 1,
            range: (0.0, 2.0),
        };
        assert_eq!(cubic(false).knot_run(4), Ok(single));
    }

    #[test]
    fn index_out_of_range() {
        assert_eq!(
            cubic(false).knot_run(14),
            Err(EnvelopeError::IndexOutOfRange { index: 14, len: 14 })
        );
        assert_eq!(
            cubic(true).knot_run(12),
            Err(EnvelopeError::IndexOutOfRange { index: 12, len: 12 })
        );
    }

    #[test]
    fn end_knots_are_not_interior() {
        // u_0 ..= u_3 = 0 is the domain's start, u_10 ..= u_13 = 4 its end.
        for index in [0, 3, 10, 13] {
            assert_eq!(
                cubic(false).knot_run(index),
                Err(EnvelopeError::NotInterior { index })
            );
        }
        for index in [0, 2, 9, 11] {
            assert_eq!(
                cubic(true).knot_run(index),
                Err(EnvelopeError::NotInterior { index })
            );
        }
        // Unclamped: a run that reaches u_p also moves the domain.
        let points: Vec<Vec<f64>> = (0..5).map(|i| vec![f64::from(i), 0.0]).collect();
        let knots = [0.0, 1.0, 2.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
        let curve = Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap();
        assert_eq!(
            curve.knot_run(3),
            Err(EnvelopeError::NotInterior { index: 3 })
        );
        assert_eq!(curve.knot_run(4).map(|run| run.start), Ok(4));
    }

    #[test]
    fn multiplicity_must_leave_an_envelope_of_degree_one_or_more() {
        assert_eq!(
            cubic(false).knot_run(8),
            Err(EnvelopeError::MultiplicityTooHigh {
                index: 8,
                multiplicity: 3,
                max: 2
            })
        );
    }

    #[test]
    fn degree_one_curves_have_no_envelope() {
        let points: Vec<Vec<f64>> = (0..3).map(|i| vec![f64::from(i), 0.0]).collect();
        let curve = Curve::new(
            1,
            &points,
            &[0.0, 0.0, 1.0, 2.0, 2.0],
            None,
            &CurveLimits::default(),
        )
        .unwrap();
        assert_eq!(
            curve.knot_run(2),
            Err(EnvelopeError::MultiplicityTooHigh {
                index: 2,
                multiplicity: 1,
                max: 0
            })
        );
    }

    #[test]
    fn moving_outside_the_range_is_refused() {
        let curve = cubic(false);
        let run = curve.knot_run(5).unwrap();
        assert!(curve.with_run_moved(&run, 0.999).is_none());
        assert!(curve.with_run_moved(&run, 3.001).is_none());
        let moved = curve.with_run_moved(&run, 3.0).unwrap();
        assert_eq!(&moved.knots()[4..10], &[1.0, 3.0, 3.0, 3.0, 3.0, 3.0]);
        assert_eq!(curve.envelope(&run).knots().len(), curve.knots().len() - 2);
    }
}
