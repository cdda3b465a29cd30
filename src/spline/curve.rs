//! The validated curve type: degree, control points, knots (either convention) and weights.

use super::basis::{MAX_DEGREE, find_span};
use super::vector::Point;

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
    #[error("control point {index} has {len} coordinates; all must have {expected} (2 or 3)")]
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
        "knot value at index {index} is repeated {multiplicity} times; at most degree + 1 = {max} allowed"
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
    /// times; a non-empty domain `u_p < u_{n+1}`.
    pub fn new(
        degree: usize,
        control_points: &[Vec<f64>],
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
        let expected = control_points[0].len();
        let dimension = match expected {
            2 => Dimension::Two,
            3 => Dimension::Three,
            _ => {
                return Err(CurveError::WrongDimension {
                    index: 0,
                    len: expected,
                    expected: 2,
                });
            }
        };
        let mut points = Vec::with_capacity(count);
        for (index, raw) in control_points.iter().enumerate() {
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
        check_knot_values(knots, degree)?;
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
    /// needs: finite, non-decreasing values and a non-empty domain; a knot-moving edit may
    /// legitimately reach multiplicity `p + 2` at a clamped end, where it has no effect.
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

    /// The span `m` with `u_m <= t < u_{m+1}` (last non-empty span at the right end).
    pub fn span(&self, t: f64) -> usize {
        find_span(&self.knots, self.degree, t)
    }
}

/// Checks finiteness, monotonicity and multiplicity of the caller's knots (caller's indices).
fn check_knot_values(knots: &[f64], degree: usize) -> Result<(), CurveError> {
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
        if multiplicity > degree + 1 {
            return Err(CurveError::KnotMultiplicityTooHigh {
                index,
                multiplicity,
                max: degree + 1,
            });
        }
    }
    Ok(())
}
