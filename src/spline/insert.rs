//! Knot insertion (Boehm; The NURBS Book A5.1, many knots at once by A5.4): the same curve
//! over a finer knot vector, and the knots that make a curve editable around a parameter.

use super::curve::Curve;

/// Knots the cubic knot-pair method needs strictly inside the domain on each side of the
/// picked parameter `t` (in `(lo, t]` and in `(t, hi)`): then both sides' spans `j` satisfy
/// `2 <= j <= n`, and every knot a pair may move (`u_{j-1} ..= u_{j+3}`) is an interior knot,
/// so no pair is dropped for moving an end of the domain.
pub const EDITING_KNOTS_EACH_SIDE: usize = 3;

/// Default spacing of the knots inserted around a parameter, as a fraction of the domain's
/// length (closer to `t` where an end of the domain is nearer).
pub const EDITING_KNOT_SPACING: f64 = 0.125;

/// Why knots cannot be inserted. `index` is the value's position in the caller's list.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InsertError {
    /// A value is NaN or infinite.
    #[error("knot value {index} is not a finite number")]
    NonFinite { index: usize },
    /// A value lies outside the domain (beyond the slack of [`Curve::snap_to_domain`]).
    #[error("knot value {value} lies outside the domain [{}, {}]", domain.0, domain.1)]
    OutsideDomain {
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
    /// Inserting a value (this many times, counting repeats in the list) would give it a
    /// multiplicity above the degree.
    #[error(
        "inserting {value} would give it multiplicity {multiplicity}; at most the degree {degree} is allowed"
    )]
    MultiplicityTooHigh {
        index: usize,
        value: f64,
        multiplicity: usize,
        degree: usize,
    },
    /// The refined curve would have more control points than allowed.
    #[error("the refined curve would have {count} control points, above the limit {max}")]
    TooManyControlPoints { count: usize, max: usize },
    /// No knot can be placed between `t` and the nearer end of the domain: the point there
    /// is an end of the curve, which the knot-pair method cannot move without moving the
    /// domain.
    #[error(
        "parameter {value} is too close to an end of the domain [{}, {}] to place knots between them (the end point of a curve cannot move without moving its domain)",
        domain.0, domain.1
    )]
    NoRoomAtDomainEnd { value: f64, domain: (f64, f64) },
    /// The spacing of the knots to insert around `t` is not a finite number `> 0`.
    #[error("the spacing must be a finite number greater than 0")]
    InvalidSpacing,
}

impl InsertError {
    /// The position in the caller's list of the value at fault, when one value is.
    pub fn index(&self) -> Option<usize> {
        match *self {
            InsertError::NonFinite { index }
            | InsertError::OutsideDomain { index, .. }
            | InsertError::MultiplicityTooHigh { index, .. } => Some(index),
            InsertError::TooManyControlPoints { .. }
            | InsertError::NoRoomAtDomainEnd { .. }
            | InsertError::InvalidSpacing => None,
        }
    }
}

impl Curve {
    /// The same curve with the knot values `values` inserted (a value may repeat to raise its
    /// multiplicity), in the same knot convention. A periodic curve takes any finite value
    /// (reduced into its period; `k_m` is `k_0`) and stays periodic: the value is inserted
    /// into every period.
    ///
    /// Each value is snapped onto the domain ([`Curve::snap_to_domain`]) and must then lie
    /// in `[lo, hi]`; its multiplicity in the full knot vector after insertion must stay at
    /// most the degree `p` (an interior knot of multiplicity `p` is a corner; an end of a
    /// clamped curve already has `p + 1`). The result has `n + 1 + values.len()` control
    /// points, at most `max_control_points`.
    pub fn insert_knots(
        &self,
        values: &[f64],
        max_control_points: usize,
    ) -> Result<Curve, InsertError> {
        let sorted = self.checked_insertions(values)?;
        let count = self.caller_control_points().len() + sorted.len();
        if count > max_control_points {
            return Err(InsertError::TooManyControlPoints {
                count,
                max: max_control_points,
            });
        }
        Ok(self.refined(&sorted))
    }

    /// The values `values` snapped onto the domain and sorted, once every rule of
    /// [`Curve::insert_knots`] but the size limit is checked; the first error in the
    /// caller's order otherwise.
    pub fn checked_insertions(&self, values: &[f64]) -> Result<Vec<f64>, InsertError> {
        let mut snapped = Vec::with_capacity(values.len());
        for (index, &value) in values.iter().enumerate() {
            if !value.is_finite() {
                return Err(InsertError::NonFinite { index });
            }
            let Some(t) = self.snap_to_domain(value) else {
                return Err(InsertError::OutsideDomain {
                    index,
                    value,
                    domain: self.domain(),
                });
            };
            // A periodic curve's `k_m` is its `k_0`, one knot of the periodic form.
            let t = match self.is_periodic() {
                true if t == self.domain().1 => self.domain().0,
                _ => t,
            };
            snapped.push((t, index));
        }
        snapped.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let p = self.degree();
        let knots = self.knots();
        let mut first_error: Option<InsertError> = None;
        for run in snapped.chunk_by(|a, b| a.0 == b.0) {
            let value = run[0].0;
            let existing =
                knots.partition_point(|&u| u <= value) - knots.partition_point(|&u| u < value);
            // Within a run the caller's indices ascend, so the first to cross the degree is
            // the earliest offender of this value.
            if let Some((k, &(_, index))) =
                run.iter().enumerate().find(|(k, _)| existing + k + 1 > p)
            {
                let error = InsertError::MultiplicityTooHigh {
                    index,
                    value,
                    multiplicity: existing + k + 1,
                    degree: p,
                };
                if first_error
                    .as_ref()
                    .and_then(InsertError::index)
                    .is_none_or(|i| index < i)
                {
                    first_error = Some(error);
                }
            }
        }
        match first_error {
            Some(error) => Err(error),
            None => Ok(snapped.into_iter().map(|(t, _)| t).collect()),
        }
    }

    /// The same curve over the full knot vector refined by the sorted values `inserted`
    /// (The NURBS Book A5.4, `RefineKnotVectCurve`, on the homogeneous points
    /// `(w x, w y, w z, w)`; each new point is a convex combination of old ones).
    ///
    /// Preconditions: `inserted` sorted, inside the domain, no multiplicity above the degree
    /// afterwards (as [`Curve::checked_insertions`] makes them).
    pub(crate) fn refined(&self, inserted: &[f64]) -> Curve {
        if inserted.is_empty() {
            return self.clone();
        }
        if let Some(periodicity) = self.periodicity() {
            return super::periodic::refined(self, periodicity, inserted);
        }
        let (knots, homogeneous) =
            refine(self.degree(), self.knots(), self.homogeneous(), inserted);
        let (points, weights) = if self.is_rational() {
            let points = homogeneous
                .iter()
                .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3]])
                .collect();
            (points, Some(homogeneous.iter().map(|h| h[3]).collect()))
        } else {
            (
                homogeneous.iter().map(|h| [h[0], h[1], h[2]]).collect(),
                None,
            )
        };
        Curve::from_valid_parts(
            self.degree(),
            self.dimension(),
            points,
            weights,
            knots,
            self.convention(),
        )
    }

    /// The same curve over its domain with clamped ends (`degree + 1` equal knots at each
    /// end, so the first and last control points are the curve's ends), as an ordinary
    /// curve: a periodic one is cut open at `k_0`. The domain's ends are inserted up to
    /// multiplicity `p` (Boehm), then the control points and knots outside the domain dropped
    /// (the outermost knot of each end run has no effect on the curve in the domain, so it
    /// becomes the end value).
    pub fn clamped(&self) -> Curve {
        let ordinary = self.as_ordinary();
        let p = self.degree();
        let (lo, hi) = self.domain();
        let knots = self.knots();
        let count = |v: f64| knots.iter().filter(|&&u| u == v).count();
        let mut inserted = vec![lo; p.saturating_sub(count(lo))];
        inserted.extend(std::iter::repeat_n(hi, p.saturating_sub(count(hi))));
        let refined = ordinary.refined(&inserted);
        let knots = refined.knots();
        let last_lo = knots.iter().rposition(|&u| u == lo).unwrap_or(p);
        let first_hi = knots
            .iter()
            .position(|&u| u == hi)
            .unwrap_or(knots.len() - p - 1);
        let start = last_lo + 1 - p - 1;
        let end = first_hi + p;
        let mut clamped_knots = knots[start..=end].to_vec();
        clamped_knots[0] = lo;
        let last = clamped_knots.len() - 1;
        clamped_knots[last] = hi;
        let points = refined.control_points()[start..first_hi].to_vec();
        let weights = refined.weights().map(|w| w[start..first_hi].to_vec());
        Curve::from_valid_parts(
            p,
            self.dimension(),
            points,
            weights,
            clamped_knots,
            self.convention(),
        )
    }

    /// The knots to insert so that the cubic knot-pair method can move the point `s(t)`
    /// without moving the curve's domain: [`EDITING_KNOTS_EACH_SIDE`] knots strictly inside
    /// the domain on each side of `t` (in `(lo, t]` and in `(t, hi)`), counting those the
    /// curve has. The missing ones are placed at `t - k h_below` and `t + k h_above`
    /// (`k = 1, 2, …`), `h = spacing` (default [`EDITING_KNOT_SPACING`] `· (hi - lo)`),
    /// shortened near an end so that they stay inside: `h_below = min(h, (t - lo) / (m + 1))`
    /// for `m` missing knots below (likewise above). Sorted; empty when nothing is missing.
    ///
    /// Precondition: `t` in the domain (snap it first). An end of the domain (or a `t` so close
    /// to it that no distinct knot fits between) is refused: the end point of a curve cannot
    /// move without moving its domain.
    pub fn knots_for_editing(&self, t: f64, spacing: Option<f64>) -> Result<Vec<f64>, InsertError> {
        let (lo, hi) = self.domain();
        let h = match spacing {
            None => EDITING_KNOT_SPACING * (hi - lo),
            Some(h) if h.is_finite() && h > 0.0 => h,
            Some(_) => return Err(InsertError::InvalidSpacing),
        };
        let knots = self.knots();
        let below = knots.iter().filter(|&&u| lo < u && u <= t).count();
        let above = knots.iter().filter(|&&u| t < u && u < hi).count();
        let missing_below = EDITING_KNOTS_EACH_SIDE.saturating_sub(below);
        let missing_above = EDITING_KNOTS_EACH_SIDE.saturating_sub(above);
        let no_room = || InsertError::NoRoomAtDomainEnd {
            value: t,
            domain: (lo, hi),
        };
        let mut values = Vec::with_capacity(missing_below + missing_above);
        let h_below = h.min((t - lo) / (missing_below + 1) as f64);
        let mut previous = t;
        for k in 1..=missing_below {
            let value = t - k as f64 * h_below;
            if value <= lo || value >= previous {
                return Err(no_room());
            }
            values.push(value);
            previous = value;
        }
        values.reverse();
        let h_above = h.min((hi - t) / (missing_above + 1) as f64);
        let mut previous = t;
        for k in 1..=missing_above {
            let value = t + k as f64 * h_above;
            if value <= previous || value >= hi {
                return Err(no_room());
            }
            values.push(value);
            previous = value;
        }
        Ok(values)
    }
}

/// The book's span of `u`: `i` with `u_i <= u < u_{i+1}`, `p <= i <= n`, and `n` at the right
/// end `u >= u_{n+1}` (The NURBS Book A2.1, which A5.4 is written for: its loop moves the
/// knots equal to an inserted value to the right of it).
fn book_span(knots: &[f64], p: usize, n: usize, u: f64) -> usize {
    if u >= knots[n + 1] {
        return n;
    }
    p + knots[p + 1..=n + 1].partition_point(|&v| v <= u)
}

/// The NURBS Book A5.4 (`RefineKnotVectCurve`): the full knot vector `ū` (`knots` with the
/// sorted values `x` merged in) and the homogeneous control points `Q` over it of the curve
/// with control points `pw` over `knots`. Working backwards from the right, each inserted
/// value `x_j` makes the new points `Q_{ind-1} = α Q_{ind-1} + (1 - α) Q_ind` with
/// `α = (ū_{k+l} - x_j) / (ū_{k+l} - u_{i-p+l})` in `[0, 1]`.
fn refine(p: usize, knots: &[f64], pw: &[[f64; 4]], x: &[f64]) -> (Vec<f64>, Vec<[f64; 4]>) {
    let n = pw.len() - 1;
    let m = n + p + 1;
    let r = x.len() - 1;
    let a = book_span(knots, p, n, x[0]);
    let b = book_span(knots, p, n, x[r]) + 1;
    let mut q = vec![[0.0; 4]; n + r + 2];
    let mut ubar = vec![0.0; m + r + 2];
    q[..=a - p].copy_from_slice(&pw[..=a - p]);
    q[b + r..=n + r + 1].copy_from_slice(&pw[b - 1..=n]);
    ubar[..=a].copy_from_slice(&knots[..=a]);
    ubar[b + p + r + 1..=m + r + 1].copy_from_slice(&knots[b + p..=m]);
    let mut i = b + p - 1;
    let mut k = b + p + r;
    for &value in x.iter().rev() {
        while value <= knots[i] && i > a {
            q[k - p - 1] = pw[i - p - 1];
            ubar[k] = knots[i];
            k -= 1;
            i -= 1;
        }
        q[k - p - 1] = q[k - p];
        for l in 1..=p {
            let ind = k - p + l;
            let numerator = ubar[k + l] - value;
            let denominator = ubar[k + l] - knots[i + l - p];
            if numerator == 0.0 || denominator == 0.0 {
                // α = 0 (a zero denominator only comes with a multiplicity above p).
                q[ind - 1] = q[ind];
            } else {
                let alpha = numerator / denominator;
                let (left, right) = (q[ind - 1], q[ind]);
                q[ind - 1] = std::array::from_fn(|c| alpha * left[c] + (1.0 - alpha) * right[c]);
            }
        }
        ubar[k] = value;
        k -= 1;
    }
    (ubar, q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    fn bezier() -> Curve {
        let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
    }

    #[test]
    fn midpoint_insertion_into_a_cubic_bezier_is_de_casteljaus_split() {
        // Inserting 1/2 three times splits the Bézier at 1/2: the new points are de
        // Casteljau's triangle's sides (computed here by hand).
        let refined = bezier().insert_knots(&[0.5, 0.5, 0.5], 100).unwrap();
        let expected = [
            [0.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [1.25, 1.5, 0.0],
            [2.0, 1.5, 0.0],
            [2.75, 1.5, 0.0],
            [3.5, 1.0, 0.0],
            [4.0, 0.0, 0.0],
        ];
        assert_eq!(refined.control_points(), &expected);
        assert_eq!(
            refined.knots(),
            &[0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0]
        );
    }

    #[test]
    fn values_are_checked_in_the_callers_order() {
        let curve = bezier();
        let outside = curve.insert_knots(&[0.5, 1.5], 100).unwrap_err();
        assert_eq!(outside.index(), Some(1));
        assert!(matches!(
            curve.insert_knots(&[f64::NAN], 100),
            Err(InsertError::NonFinite { index: 0 })
        ));
        let too_many = curve
            .insert_knots(&[0.7, 0.2, 0.2, 0.7, 0.2, 0.2], 100)
            .unwrap_err();
        assert_eq!(
            too_many,
            InsertError::MultiplicityTooHigh {
                index: 5,
                value: 0.2,
                multiplicity: 4,
                degree: 3
            }
        );
        // The clamped end already has multiplicity 4.
        assert_eq!(
            curve.insert_knots(&[1.0], 100).unwrap_err().index(),
            Some(0)
        );
        // Just outside the domain: snapped onto the end... which is full already.
        let snapped = curve.checked_insertions(&[0.5, 1.0 + 1e-13]);
        assert!(matches!(
            snapped,
            Err(InsertError::MultiplicityTooHigh { index: 1, .. })
        ));
        assert_eq!(
            curve
                .checked_insertions(&[-1e-13, 0.5])
                .unwrap_err()
                .index(),
            Some(0)
        );
        let limit = curve.insert_knots(&[0.1, 0.2], 5).unwrap_err();
        assert_eq!(
            limit,
            InsertError::TooManyControlPoints { count: 6, max: 5 }
        );
    }

    #[test]
    fn editing_knots_fill_up_three_on_each_side() {
        let curve = bezier();
        assert_eq!(
            curve.knots_for_editing(0.5, None).unwrap(),
            vec![0.125, 0.25, 0.375, 0.625, 0.75, 0.875]
        );
        // Near the start the knots below crowd between the start and t.
        let near_start = curve.knots_for_editing(0.2, Some(0.1)).unwrap();
        let expected = [0.05, 0.1, 0.15, 0.3, 0.4, 0.5];
        assert_eq!(near_start.len(), expected.len());
        for (value, expected) in near_start.iter().zip(expected) {
            assert!((value - expected).abs() < 1e-15, "{near_start:?}");
        }
        let refined = curve.insert_knots(&[0.1, 0.3, 0.45, 0.55], 100).unwrap();
        assert_eq!(
            refined.knots_for_editing(0.5, None).unwrap(),
            vec![0.625, 0.75]
        );
        assert!(matches!(
            curve.knots_for_editing(0.0, None),
            Err(InsertError::NoRoomAtDomainEnd { .. })
        ));
        assert!(matches!(
            curve.knots_for_editing(1.0, None),
            Err(InsertError::NoRoomAtDomainEnd { .. })
        ));
        assert_eq!(
            curve.knots_for_editing(0.5, Some(0.0)),
            Err(InsertError::InvalidSpacing)
        );
    }
}
