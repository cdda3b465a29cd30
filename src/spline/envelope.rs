//! The envelope of the family of curves made by moving a run of equal knots (MATH.md §2).
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
