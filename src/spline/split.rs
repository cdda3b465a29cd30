//! Splitting a curve at parameters into clamped pieces that together are the curve.
//!
//! Each split parameter, and each end of the domain, is inserted until its multiplicity is at
//! least `p` (Boehm; The NURBS Book A5.4, on the homogeneous points): the curve then passes
//! through a control point there, `s(ū) = P_{r−p}` for the run of `ū` ending at index `r`.
//! The piece on `[a, b]` keeps the points from `P_{r_a − p}` to the one before `b`'s run and
//! the knots strictly between `a` and `b`, with `p + 1` copies of `a` and of `b` at its ends
//! (a clamped end: the first knot never affects the curve on its domain).

use super::curve::Curve;
use super::remove::knot_run;

/// Why a curve cannot be split.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SplitError {
    #[error("parameter {index} is not a finite number")]
    NonFinite { index: usize },
    #[error(
        "parameter {value} does not lie strictly inside the domain [{}, {}] (a split at an end would give an empty piece)",
        domain.0, domain.1
    )]
    NotInside {
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
    #[error("{count} split parameters exceed the limit of {max}")]
    TooMany { count: usize, max: usize },
}

impl SplitError {
    /// The position in the caller's list of the parameter at fault, when one is.
    pub fn index(&self) -> Option<usize> {
        match *self {
            SplitError::NonFinite { index } | SplitError::NotInside { index, .. } => Some(index),
            SplitError::TooMany { .. } => None,
        }
    }
}

impl Curve {
    /// The clamped pieces between the split parameters (any order; repeats count once), in
    /// order of parameter (module docs). Each piece has the degree, dimension, weights and
    /// knot convention of the curve; its domain is `[a, b]` for consecutive split values.
    /// Rules: parameters finite and strictly inside the domain, at most `max_parameters`.
    pub fn split_at(
        &self,
        parameters: &[f64],
        max_parameters: usize,
    ) -> Result<Vec<Curve>, SplitError> {
        if parameters.len() > max_parameters {
            return Err(SplitError::TooMany {
                count: parameters.len(),
                max: max_parameters,
            });
        }
        let (lo, hi) = self.domain();
        let mut values = Vec::with_capacity(parameters.len() + 2);
        for (index, &value) in parameters.iter().enumerate() {
            if !value.is_finite() {
                return Err(SplitError::NonFinite { index });
            }
            if !(lo < value && value < hi) {
                return Err(SplitError::NotInside {
                    index,
                    value,
                    domain: (lo, hi),
                });
            }
            values.push(value);
        }
        values.sort_by(f64::total_cmp);
        values.dedup();
        let p = self.degree();
        let knots = self.knots();
        // Raise every cut (ends included) to multiplicity p, counting the ends' runs within
        // u_0 ..= u_p and u_{n+1} ..= u_{n+p+1} only.
        let mut inserted = Vec::new();
        let n = self.control_points().len() - 1;
        let at_start = knots[..=p].iter().filter(|&&u| u == lo).count();
        let at_end = knots[n + 1..].iter().filter(|&&u| u == hi).count();
        inserted.extend(std::iter::repeat_n(lo, p.saturating_sub(at_start)));
        for &value in &values {
            let (_, existing) = knot_run(knots, value);
            inserted.extend(std::iter::repeat_n(value, p.saturating_sub(existing)));
        }
        inserted.extend(std::iter::repeat_n(hi, p.saturating_sub(at_end)));
        let refined = self.refined(&inserted);
        let full = refined.knots();
        let homogeneous = refined.homogeneous();
        let mut cuts = Vec::with_capacity(values.len() + 2);
        cuts.push(lo);
        cuts.extend_from_slice(&values);
        cuts.push(hi);
        let mut pieces = Vec::with_capacity(cuts.len() - 1);
        for window in cuts.windows(2) {
            let (a, b) = (window[0], window[1]);
            // The first point is the one the curve passes through at `a` (from the right):
            // `P_{r−p}`, `r` the last index of `a`'s run; the last is the one before `b`'s
            // run (the curve's left limit at `b`).
            let first = knot_run(full, a).0 - p;
            let last = full.partition_point(|&u| u < b) - 1;
            let mut piece_knots = vec![a; p + 1];
            piece_knots.extend(full.iter().copied().filter(|&u| a < u && u < b));
            piece_knots.extend(std::iter::repeat_n(b, p + 1));
            let points = &homogeneous[first..=last];
            debug_assert_eq!(piece_knots.len(), points.len() + p + 1);
            pieces.push(refined.with_homogeneous(piece_knots, points));
        }
        Ok(pieces)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn a_bezier_piece_splits_by_de_casteljau() {
        let curve = Curve::new(
            3,
            &[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]],
            &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            None,
            &CurveLimits::default(),
        )
        .unwrap();
        let pieces = curve.split_at(&[0.5], 10).unwrap();
        assert_eq!(pieces.len(), 2);
        let left = pieces[0].control_points();
        // De Casteljau at 1/2: (0,0), (0.5,1), (1.25,1.5), (2,1.5).
        let expected = [[0.0, 0.0], [0.5, 1.0], [1.25, 1.5], [2.0, 1.5]];
        for (point, want) in left.iter().zip(expected) {
            assert!((point[0] - want[0]).abs() < 1e-15 && (point[1] - want[1]).abs() < 1e-15);
        }
        assert_eq!(pieces[1].domain(), (0.5, 1.0));
        assert!(matches!(
            curve.split_at(&[1.0], 10),
            Err(SplitError::NotInside { index: 0, .. })
        ));
    }
}
