//! The validated curve type: degree, control points, knots (either convention) and weights.
//!
//! One concept, kept whole: the type, every rule of its validation with the typed errors that
//! name the field, the conventions and the derived curves (other knots or control points,
//! ends snapped onto the domain); a third of the file is the tests of those rules.

use super::basis::{MAX_DEGREE, basis_functions, find_span};
use super::vector::Point;

/// A parameter outside the domain by at most this fraction of the domain's length is taken as
/// the nearer end ([`Curve::snap_to_domain`]).
pub const DOMAIN_END_SLACK: f64 = 1e-12;

/// A parameter outside the domain by at most this many units of roundoff of the ends'
/// magnitude (`ε · max(|lo|, |hi|)`) is taken as the nearer end, however short the domain
/// ([`Curve::snap_to_domain`]).
pub const DOMAIN_END_ULPS: f64 = 4.0;

/// How the caller wrote the knot vector; answers use the same convention.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KnotConvention {
    /// The full vector `u_0 ..= u_{n+p+1}`: `n + p + 2` values (The NURBS Book, the paper).
    Full,
    /// openNURBS / Rhino: the full vector without its first and last value (`n + p` values).
    Trimmed,
}

impl KnotConvention {
    /// The caller's index of full-vector index `full_index` (`None` for the two end values
    /// that the trimmed convention leaves out).
    pub fn caller_index(self, full_index: usize, full_len: usize) -> Option<usize> {
        match self {
            KnotConvention::Full => Some(full_index),
            KnotConvention::Trimmed if full_index == 0 || full_index + 1 >= full_len => None,
            KnotConvention::Trimmed => Some(full_index - 1),
        }
    }

    /// The full-vector index of the caller's index `caller_index`.
    pub fn full_index(self, caller_index: usize) -> usize {
        match self {
            KnotConvention::Full => caller_index,
            KnotConvention::Trimmed => caller_index + 1,
        }
    }
}

/// Whether control points are planar or spatial.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// `[x, y]`; stored with `z = 0`.
    Two,
    /// `[x, y, z]`.
    Three,
}

impl Dimension {
    /// Number of coordinates: 2 or 3.
    pub fn count(self) -> usize {
        match self {
            Dimension::Two => 2,
            Dimension::Three => 3,
        }
    }
}

/// Size limits applied while validating a curve (the service makes them configurable).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CurveLimits {
    /// Largest accepted degree; at most [`MAX_DEGREE`].
    pub max_degree: usize,
    /// Largest accepted number of control points.
    pub max_control_points: usize,
}

impl Default for CurveLimits {
    fn default() -> Self {
        Self {
            max_degree: MAX_DEGREE,
            max_control_points: 10_000,
        }
    }
}

/// The element of the curve data that broke a rule. Knot indices are in the caller's convention.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveField {
    /// The degree.
    Degree,
    /// The control point list as a whole.
    ControlPoints,
    /// One control point (`coordinate: None`) or one of its coordinates.
    ControlPoint {
        /// Index of the control point.
        index: usize,
        /// Index of the coordinate, when one coordinate is at fault.
        coordinate: Option<usize>,
    },
    /// The knot vector as a whole.
    Knots,
    /// One knot, by the caller's index.
    Knot(usize),
    /// The weight list as a whole.
    Weights,
    /// One weight.
    Weight(usize),
}

/// A rule broken by raw curve data; [`CurveError::field`] names the offending element.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurveError {
    #[error("degree must be at least 1")]
    DegreeTooLow,
    #[error("degree {degree} exceeds the limit {max}")]
    DegreeTooHigh { degree: usize, max: usize },
    #[error("{count} control points given, a degree-{degree} curve needs at least {needed}")]
    TooFewControlPoints {
        count: usize,
        degree: usize,
        needed: usize,
    },
    #[error("{count} control points exceed the limit {max}")]
    TooManyControlPoints { count: usize, max: usize },
    #[error("control point 0 has {len} coordinates; control points have 2 (planar) or 3 (spatial)")]
    UnsupportedDimension { len: usize },
    #[error("control point {index} has {len} coordinates; all must have {expected}, as the first")]
    WrongDimension {
        index: usize,
        len: usize,
        expected: usize,
    },
    #[error("control point {index} coordinate {coordinate} is not a finite number")]
    NonFiniteCoordinate { index: usize, coordinate: usize },
    #[error(
        "{count} knots given; expected {full} (full vector) or {trimmed} (without the two end values)"
    )]
    WrongKnotCount {
        count: usize,
        full: usize,
        trimmed: usize,
    },
    #[error("knot {index} is not a finite number")]
    NonFiniteKnot { index: usize },
    #[error("knots must be non-decreasing: knot {index} is smaller than knot {}", index - 1)]
    DecreasingKnot { index: usize },
    #[error(
        "knot value at index {index} is repeated {multiplicity} times; at most {max} allowed (degree + 1, or degree + 2 at the ends of a full vector)"
    )]
    KnotMultiplicityTooHigh {
        index: usize,
        multiplicity: usize,
        max: usize,
    },
    #[error("the curve's domain [u_p, u_(n+1)] is empty: the knots there are all equal")]
    EmptyDomain,
    #[error("{count} weights given; expected one per control point ({expected})")]
    WrongWeightCount { count: usize, expected: usize },
    #[error("weight {index} is not a finite number")]
    NonFiniteWeight { index: usize },
    #[error("weight {index} must be greater than 0")]
    NonPositiveWeight { index: usize },
}

impl CurveError {
    /// The element of the input that is at fault.
    pub fn field(&self) -> CurveField {
        match *self {
            CurveError::DegreeTooLow | CurveError::DegreeTooHigh { .. } => CurveField::Degree,
            CurveError::TooFewControlPoints { .. } | CurveError::TooManyControlPoints { .. } => {
                CurveField::ControlPoints
            }
            CurveError::UnsupportedDimension { .. } => CurveField::ControlPoint {
                index: 0,
                coordinate: None,
            },
            CurveError::WrongDimension { index, .. } => CurveField::ControlPoint {
                index,
                coordinate: None,
            },
            CurveError::NonFiniteCoordinate { index, coordinate } => CurveField::ControlPoint {
                index,
                coordinate: Some(coordinate),
            },
            CurveError::WrongKnotCount { .. } | CurveError::EmptyDomain => CurveField::Knots,
            CurveError::NonFiniteKnot { index }
            | CurveError::DecreasingKnot { index }
            | CurveError::KnotMultiplicityTooHigh { index, .. } => CurveField::Knot(index),
            CurveError::WrongWeightCount { .. } => CurveField::Weights,
            CurveError::NonFiniteWeight { index } | CurveError::NonPositiveWeight { index } => {
                CurveField::Weight(index)
            }
        }
    }
}

/// A B-spline or NURBS curve whose data obey every rule; built only by [`Curve::new`] (or
/// derived from another valid curve), so the rest of the core never sees invalid data.
///
/// Invariants: `1 <= p <= MAX_DEGREE`, `n + 1 >= p + 1` control points of one dimension,
/// a finite non-decreasing full knot vector of `n + p + 2` values with `u_p < u_{n+1}`,
/// finite positive weights when rational.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    degree: usize,
    dimension: Dimension,
    control_points: Vec<Point>,
    weights: Option<Vec<f64>>,
    /// `(w x, w y, w z, w)` per control point; `w = 1` when non-rational.
    homogeneous: Vec<[f64; 4]>,
    knots: Vec<f64>,
    convention: KnotConvention,
}

impl Curve {
    /// Validates raw curve data (knots in either convention, detected by length).
    ///
    /// Rules, in order: `1 <= degree <= limits.max_degree`; between `degree + 1` and
    /// `limits.max_control_points` control points, all with 2 or all with 3 finite coordinates;
    /// one finite weight `> 0` per control point when weights are given; `n + p + 2` (full) or
    /// `n + p` (trimmed) finite, non-decreasing knots, no value repeated more than `degree + 1`
    /// times (`degree + 2` for a run holding the first or last value of a full vector, whose
    /// end knots have no effect); a non-empty domain `u_p < u_{n+1}`.
    pub fn new(
        degree: usize,
        control_points: &[impl AsRef<[f64]>],
        knots: &[f64],
        weights: Option<&[f64]>,
        limits: &CurveLimits,
    ) -> Result<Curve, CurveError> {
        if degree < 1 {
            return Err(CurveError::DegreeTooLow);
        }
        let max_degree = limits.max_degree.min(MAX_DEGREE);
        if degree > max_degree {
            return Err(CurveError::DegreeTooHigh {
                degree,
                max: max_degree,
            });
        }
        let count = control_points.len();
        if count < degree + 1 {
            return Err(CurveError::TooFewControlPoints {
                count,
                degree,
                needed: degree + 1,
            });
        }
        if count > limits.max_control_points {
            return Err(CurveError::TooManyControlPoints {
                count,
                max: limits.max_control_points,
            });
        }
        let expected = control_points[0].as_ref().len();
        let dimension = match expected {
            2 => Dimension::Two,
            3 => Dimension::Three,
            _ => return Err(CurveError::UnsupportedDimension { len: expected }),
        };
        let mut points = Vec::with_capacity(count);
        for (index, raw) in control_points.iter().enumerate() {
            let raw = raw.as_ref();
            if raw.len() != expected {
                return Err(CurveError::WrongDimension {
                    index,
                    len: raw.len(),
                    expected,
                });
            }
            let mut point = [0.0; 3];
            for (coordinate, &value) in raw.iter().enumerate() {
                if !value.is_finite() {
                    return Err(CurveError::NonFiniteCoordinate { index, coordinate });
                }
                point[coordinate] = value;
            }
            points.push(point);
        }
        if let Some(weights) = weights {
            if weights.len() != count {
                return Err(CurveError::WrongWeightCount {
                    count: weights.len(),
                    expected: count,
                });
            }
            for (index, &w) in weights.iter().enumerate() {
                if !w.is_finite() {
                    return Err(CurveError::NonFiniteWeight { index });
                }
                if w <= 0.0 {
                    return Err(CurveError::NonPositiveWeight { index });
                }
            }
        }
        let full_len = count + degree + 1;
        let convention = if knots.len() == full_len {
            KnotConvention::Full
        } else if knots.len() + 2 == full_len {
            KnotConvention::Trimmed
        } else {
            return Err(CurveError::WrongKnotCount {
                count: knots.len(),
                full: full_len,
                trimmed: full_len - 2,
            });
        };
        check_knot_values(knots, degree, convention)?;
        let full = match convention {
            KnotConvention::Full => knots.to_vec(),
            KnotConvention::Trimmed => {
                let mut full = Vec::with_capacity(full_len);
                full.push(knots[0]);
                full.extend_from_slice(knots);
                full.push(knots[knots.len() - 1]);
                full
            }
        };
        if full[degree] >= full[count] {
            return Err(CurveError::EmptyDomain);
        }
        Ok(Curve::from_valid_parts(
            degree,
            dimension,
            points,
            weights.map(<[f64]>::to_vec),
            full,
            convention,
        ))
    }

    /// Assembles a curve from parts that already satisfy the invariants.
    pub(crate) fn from_valid_parts(
        degree: usize,
        dimension: Dimension,
        control_points: Vec<Point>,
        weights: Option<Vec<f64>>,
        knots: Vec<f64>,
        convention: KnotConvention,
    ) -> Curve {
        let homogeneous = control_points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = weights.as_ref().map_or(1.0, |w| w[i]);
                [w * p[0], w * p[1], w * p[2], w]
            })
            .collect();
        Curve {
            degree,
            dimension,
            control_points,
            weights,
            homogeneous,
            knots,
            convention,
        }
    }

    /// The same curve with another full knot vector (same length). Checks only what evaluation
    /// needs: finite, non-decreasing values and a non-empty domain. Unlike [`Curve::new`] it
    /// accepts any multiplicity, e.g. a knot moved onto a clamped end (multiplicity `p + 2`
    /// there, which takes `d_0` or `d_n` out of the curve: the shape solver's `keep_domain`
    /// rejects such edits).
    pub fn with_full_knots(&self, knots: Vec<f64>) -> Option<Curve> {
        let valid = knots.len() == self.knots.len()
            && knots.iter().all(|u| u.is_finite())
            && knots.windows(2).all(|w| w[0] <= w[1])
            && knots[self.degree] < knots[self.control_points.len()];
        valid.then(|| Curve {
            knots,
            ..self.clone()
        })
    }

    /// The same curve with other control points (same count and dimension; `z = 0` for a
    /// planar curve), or `None` when a coordinate is not finite.
    pub fn with_control_points(&self, control_points: Vec<Point>) -> Option<Curve> {
        let valid = control_points.len() == self.control_points.len()
            && control_points.iter().flatten().all(|v| v.is_finite());
        valid.then(|| {
            Curve::from_valid_parts(
                self.degree,
                self.dimension,
                control_points,
                self.weights.clone(),
                self.knots.clone(),
                self.convention,
            )
        })
    }

    /// The basis functions that can be non-zero at `t` (in the domain): the index `i0` of the
    /// first, and `N_{i0}(t) ..= N_{i0+p}(t)` (The NURBS Book, A2.2) in `out[0..=p]`.
    pub fn basis_at(&self, t: f64, out: &mut [f64; MAX_DEGREE + 1]) -> usize {
        let span = self.span(t);
        basis_functions(&self.knots, self.degree, span, t, out);
        span - self.degree
    }

    /// The degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The order `k = p + 1`.
    pub fn order(&self) -> usize {
        self.degree + 1
    }

    /// 2D or 3D.
    pub fn dimension(&self) -> Dimension {
        self.dimension
    }

    /// The control points `d_0 ..= d_n` (`z = 0` for 2D curves).
    pub fn control_points(&self) -> &[Point] {
        &self.control_points
    }

    /// The weights, when the curve is rational.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Weight of control point `i` (1 for a non-rational curve).
    pub fn weight(&self, i: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i])
    }

    /// Whether the curve has weights.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// The homogeneous control points `(w x, w y, w z, w)`.
    pub(crate) fn homogeneous(&self) -> &[[f64; 4]] {
        &self.homogeneous
    }

    /// The full knot vector `u_0 ..= u_{n+p+1}`, whatever the caller's convention.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The knot vector in the caller's convention.
    pub fn knots_in_convention(&self) -> &[f64] {
        match self.convention {
            KnotConvention::Full => &self.knots,
            KnotConvention::Trimmed => &self.knots[1..self.knots.len() - 1],
        }
    }

    /// The caller's knot convention.
    pub fn convention(&self) -> KnotConvention {
        self.convention
    }

    /// The parameter domain `[u_p, u_{n+1}]`.
    pub fn domain(&self) -> (f64, f64) {
        (
            self.knots[self.degree],
            self.knots[self.control_points.len()],
        )
    }

    /// Whether `t` lies in the domain (closed interval).
    pub fn contains_parameter(&self, t: f64) -> bool {
        let (lo, hi) = self.domain();
        t >= lo && t <= hi
    }

    /// `t` itself when it lies in the domain `[lo, hi]`; the nearer end when it lies outside by
    /// at most [`DOMAIN_END_SLACK`] `· (hi - lo)` or [`DOMAIN_END_ULPS`] units of roundoff
    /// `ε · max(|lo|, |hi|)`, whichever is larger; `None` when it lies farther out or is not
    /// finite.
    ///
    /// A client that computes a parameter in floating point (Greville abscissae, a sum of
    /// steps) lands a few units of roundoff past an end; every endpoint that takes parameters
    /// clamps such values instead of refusing them.
    pub fn snap_to_domain(&self, t: f64) -> Option<f64> {
        if !t.is_finite() {
            return None;
        }
        let (lo, hi) = self.domain();
        if (lo..=hi).contains(&t) {
            return Some(t);
        }
        let roundoff = DOMAIN_END_ULPS * f64::EPSILON * lo.abs().max(hi.abs());
        let slack = (DOMAIN_END_SLACK * (hi - lo)).max(roundoff);
        if t < lo && lo - t <= slack {
            Some(lo)
        } else if t > hi && t - hi <= slack {
            Some(hi)
        } else {
            None
        }
    }

    /// The span `m` with `u_m <= t < u_{m+1}` (last non-empty span at the right end).
    pub fn span(&self, t: f64) -> usize {
        find_span(&self.knots, self.degree, t)
    }
}

/// Checks finiteness, monotonicity and multiplicity of the caller's knots (caller's indices).
///
/// A value may repeat at most `degree + 1` times, except that in the full convention a run
/// holding the first or last value may repeat `degree + 2` times: `u_0` and `u_{n+p+1}` never
/// influence the curve, and the envelope of a clamped curve has exactly such ends.
fn check_knot_values(
    knots: &[f64],
    degree: usize,
    convention: KnotConvention,
) -> Result<(), CurveError> {
    let end_allowance = usize::from(convention == KnotConvention::Full);
    let mut run_start = 0;
    for (index, &u) in knots.iter().enumerate() {
        if !u.is_finite() {
            return Err(CurveError::NonFiniteKnot { index });
        }
        if index > 0 {
            let previous = knots[index - 1];
            if u < previous {
                return Err(CurveError::DecreasingKnot { index });
            }
            if u != previous {
                run_start = index;
            }
        }
        let multiplicity = index - run_start + 1;
        let touches_end = run_start == 0 || knots[index..].iter().all(|&v| v == u);
        let max = degree + 1 + if touches_end { end_allowance } else { 0 };
        if multiplicity > max {
            return Err(CurveError::KnotMultiplicityTooHigh {
                index,
                multiplicity,
                max,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Five planar control points.
    fn points(count: usize) -> Vec<Vec<f64>> {
        (0..count).map(|i| vec![i as f64, (i * i) as f64]).collect()
    }

    /// A clamped quadratic over five control points: the full vector (8 values).
    const FULL: [f64; 8] = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];

    fn build(
        degree: usize,
        points: &[Vec<f64>],
        knots: &[f64],
        weights: Option<&[f64]>,
    ) -> Result<Curve, CurveError> {
        Curve::new(degree, points, knots, weights, &CurveLimits::default())
    }

    /// The field named by the error of invalid data.
    fn field_of(result: Result<Curve, CurveError>) -> CurveField {
        result.expect_err("the data break a rule").field()
    }

    #[test]
    fn both_conventions_give_the_same_full_vector() {
        let full = build(2, &points(5), &FULL, None).unwrap();
        let trimmed = build(2, &points(5), &FULL[1..7], None).unwrap();
        assert_eq!(full.convention(), KnotConvention::Full);
        assert_eq!(trimmed.convention(), KnotConvention::Trimmed);
        assert_eq!(full.knots(), trimmed.knots());
        assert_eq!(trimmed.knots_in_convention(), &FULL[1..7]);
        assert_eq!(full.domain(), (0.0, 3.0));
        assert_eq!(KnotConvention::Trimmed.caller_index(0, 8), None);
        assert_eq!(KnotConvention::Trimmed.caller_index(7, 8), None);
        assert_eq!(KnotConvention::Trimmed.caller_index(3, 8), Some(2));
        assert_eq!(KnotConvention::Trimmed.full_index(2), 3);
    }

    #[test]
    fn degree_must_be_at_least_one() {
        let err = build(0, &points(5), &FULL[..6], None).unwrap_err();
        assert_eq!(err, CurveError::DegreeTooLow);
        assert_eq!(err.field(), CurveField::Degree);
    }

    #[test]
    fn degree_must_respect_the_limit() {
        let limits = CurveLimits {
            max_degree: 2,
            ..CurveLimits::default()
        };
        let err = Curve::new(3, &points(5), &[0.0; 9], None, &limits).unwrap_err();
        assert_eq!(err, CurveError::DegreeTooHigh { degree: 3, max: 2 });
        assert_eq!(err.field(), CurveField::Degree);
        // A configured limit above MAX_DEGREE is capped at MAX_DEGREE.
        let loose = CurveLimits {
            max_degree: 99,
            ..CurveLimits::default()
        };
        let degree = MAX_DEGREE + 1;
        let err = Curve::new(degree, &points(degree + 1), &[0.0; 40], None, &loose).unwrap_err();
        assert_eq!(
            err,
            CurveError::DegreeTooHigh {
                degree,
                max: MAX_DEGREE
            }
        );
    }

    #[test]
    fn control_point_count_must_fit_the_degree_and_the_limit() {
        let few = build(2, &points(2), &[0.0, 0.0, 0.0, 1.0, 1.0], None);
        assert_eq!(field_of(few), CurveField::ControlPoints);
        let limits = CurveLimits {
            max_control_points: 4,
            ..CurveLimits::default()
        };
        let many = Curve::new(2, &points(5), &FULL, None, &limits);
        assert_eq!(field_of(many), CurveField::ControlPoints);
        assert!(Curve::new(2, &points(4), &FULL[1..], None, &limits).is_ok());
    }

    #[test]
    fn control_points_must_all_be_2d_or_all_3d() {
        let mut mixed = points(5);
        mixed[3].push(1.0);
        let err = build(2, &mixed, &FULL, None).unwrap_err();
        assert_eq!(
            err.field(),
            CurveField::ControlPoint {
                index: 3,
                coordinate: None
            }
        );
        assert!(err.to_string().contains("all must have 2"), "{err}");
        for bad_len in [1, 4] {
            let mut first = points(5);
            first[0] = vec![0.0; bad_len];
            let err = build(2, &first, &FULL, None).unwrap_err();
            assert_eq!(
                err.field(),
                CurveField::ControlPoint {
                    index: 0,
                    coordinate: None
                }
            );
            // The message names the dimensions there are, not one the point could not know.
            let message = err.to_string();
            assert!(
                message.contains(&format!("has {bad_len} coordinates")),
                "{message}"
            );
            assert!(message.contains("2 (planar) or 3 (spatial)"), "{message}");
        }
        let spatial: Vec<Vec<f64>> = points(5)
            .into_iter()
            .map(|p| vec![p[0], p[1], 1.0])
            .collect();
        assert_eq!(
            build(2, &spatial, &FULL, None).unwrap().dimension(),
            Dimension::Three
        );
    }

    #[test]
    fn coordinates_must_be_finite() {
        for (index, coordinate, value) in [
            (2, 1, f64::NAN),
            (4, 0, f64::INFINITY),
            (0, 1, f64::NEG_INFINITY),
        ] {
            let mut bad = points(5);
            bad[index][coordinate] = value;
            let field = field_of(build(2, &bad, &FULL, None));
            assert_eq!(
                field,
                CurveField::ControlPoint {
                    index,
                    coordinate: Some(coordinate)
                }
            );
        }
    }

    #[test]
    fn knot_count_must_match_either_convention() {
        let err = build(2, &points(5), &FULL[..7], None).unwrap_err();
        assert_eq!(
            err,
            CurveError::WrongKnotCount {
                count: 7,
                full: 8,
                trimmed: 6
            }
        );
        assert_eq!(err.field(), CurveField::Knots);
        assert_eq!(field_of(build(2, &points(5), &[], None)), CurveField::Knots);
    }

    #[test]
    fn knots_must_be_finite_named_by_the_callers_index() {
        let mut full = FULL;
        full[4] = f64::NAN;
        assert_eq!(
            field_of(build(2, &points(5), &full, None)),
            CurveField::Knot(4)
        );
        let mut trimmed = FULL[1..7].to_vec();
        trimmed[4] = f64::INFINITY;
        assert_eq!(
            field_of(build(2, &points(5), &trimmed, None)),
            CurveField::Knot(4)
        );
    }

    #[test]
    fn knots_must_not_decrease() {
        let full = [0.0, 0.0, 0.0, 2.0, 1.0, 3.0, 3.0, 3.0];
        assert_eq!(
            field_of(build(2, &points(5), &full, None)),
            CurveField::Knot(4)
        );
        let trimmed = [0.0, 0.0, 2.0, 1.0, 3.0, 3.0];
        let err = build(2, &points(5), &trimmed, None).unwrap_err();
        assert_eq!(err, CurveError::DecreasingKnot { index: 3 });
    }

    #[test]
    fn multiplicity_is_at_most_degree_plus_one() {
        // At an end of a full vector degree + 2 values are allowed (u_0 has no effect; the
        // envelope of a clamped curve has such ends), degree + 3 are not.
        assert!(
            build(
                2,
                &points(5),
                &[0.0, 0.0, 0.0, 0.0, 1.0, 3.0, 3.0, 3.0],
                None
            )
            .is_ok()
        );
        let start = [0.0, 0.0, 0.0, 0.0, 0.0, 3.0, 3.0, 3.0];
        assert_eq!(
            field_of(build(2, &points(5), &start, None)),
            CurveField::Knot(4)
        );
        let interior = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 3.0, 3.0];
        let err = build(2, &points(6), &interior, None).unwrap_err();
        assert_eq!(
            err,
            CurveError::KnotMultiplicityTooHigh {
                index: 6,
                multiplicity: 4,
                max: 3
            }
        );
        let trimmed = [0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 3.0];
        assert_eq!(
            field_of(build(2, &points(6), &trimmed, None)),
            CurveField::Knot(5)
        );
        // p + 1 equal interior values are allowed (the curve may jump there).
        assert!(
            build(
                2,
                &points(6),
                &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 3.0, 3.0, 3.0],
                None
            )
            .is_ok()
        );
    }

    #[test]
    fn parameters_just_outside_the_domain_snap_onto_its_ends() {
        let curve = build(2, &points(5), &FULL, None).unwrap();
        let slack = DOMAIN_END_SLACK * 3.0;
        assert_eq!(curve.snap_to_domain(1.5), Some(1.5));
        assert_eq!(curve.snap_to_domain(0.0), Some(0.0));
        assert_eq!(curve.snap_to_domain(-0.5 * slack), Some(0.0));
        assert_eq!(curve.snap_to_domain(3.0 + 0.9 * slack), Some(3.0));
        assert_eq!(curve.snap_to_domain(-2.0 * slack), None);
        assert_eq!(curve.snap_to_domain(3.0 + 2.0 * slack), None);
        assert_eq!(curve.snap_to_domain(f64::NAN), None);
        assert_eq!(curve.snap_to_domain(f64::INFINITY), None);
        // A short domain far from 0: a few units of roundoff still snap.
        let far: Vec<f64> = FULL.iter().map(|u| 1e6 + 1e-9 * u).collect();
        let curve = build(2, &points(5), &far, None).unwrap();
        let (_, hi) = curve.domain();
        let next_up = f64::from_bits(hi.to_bits() + 2);
        assert_eq!(curve.snap_to_domain(next_up), Some(hi));
        assert_eq!(curve.snap_to_domain(hi + 1e-6), None);
    }

    #[test]
    fn domain_must_not_be_empty() {
        let full = [0.0, 0.0, 1.0, 1.0, 2.0, 2.0];
        let err = build(2, &points(3), &full, None).unwrap_err();
        assert_eq!(err, CurveError::EmptyDomain);
        assert_eq!(err.field(), CurveField::Knots);
        assert_eq!(
            field_of(build(2, &points(3), &full[1..5], None)),
            CurveField::Knots
        );
    }

    #[test]
    fn weights_must_be_one_per_control_point() {
        let weights = [1.0; 4];
        let err = build(2, &points(5), &FULL, Some(&weights)).unwrap_err();
        assert_eq!(
            err,
            CurveError::WrongWeightCount {
                count: 4,
                expected: 5
            }
        );
        assert_eq!(err.field(), CurveField::Weights);
    }

    #[test]
    fn weights_must_be_finite() {
        for (index, value) in [(2, f64::NAN), (0, f64::INFINITY)] {
            let mut weights = [1.0; 5];
            weights[index] = value;
            assert_eq!(
                field_of(build(2, &points(5), &FULL, Some(&weights))),
                CurveField::Weight(index)
            );
        }
    }

    #[test]
    fn weights_must_be_positive() {
        for (index, value) in [(3, 0.0), (1, -1.0), (4, -0.0)] {
            let mut weights = [1.0; 5];
            weights[index] = value;
            let err = build(2, &points(5), &FULL, Some(&weights)).unwrap_err();
            assert_eq!(err, CurveError::NonPositiveWeight { index });
            assert_eq!(err.field(), CurveField::Weight(index));
        }
        let rational = build(2, &points(5), &FULL, Some(&[0.5, 1.0, 2.0, 1.0, 0.5])).unwrap();
        assert!(rational.is_rational());
        assert_eq!(rational.weight(2), 2.0);
    }
}
