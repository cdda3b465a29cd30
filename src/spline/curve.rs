//! The validated curve type: degree, control points, knots (a flat vector in either
//! convention, or distinct values with multiplicities, possibly periodic) and weights.
//!
//! One concept, kept whole: the type, every rule of its validation with the typed errors that
//! name the field, the conventions and the derived curves (other knots or control points,
//! ends snapped onto the domain); a third of the file is the tests of those rules.

use super::basis::{MAX_DEGREE, basis_functions, find_span};
use super::periodic::Periodicity;
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
    /// Distinct increasing values with their multiplicities (STEP, IGES, Open CASCADE); the
    /// full vector is those values each repeated its multiplicity times. Knot *indices* in
    /// this form are indices into that full (flat) vector, as in [`KnotConvention::Full`]:
    /// an index names one knot of a run, which a run's distinct value cannot.
    Multiplicities,
}

impl KnotConvention {
    /// The caller's index of full-vector index `full_index` (`None` for the two end values
    /// that the trimmed convention leaves out).
    pub fn caller_index(self, full_index: usize, full_len: usize) -> Option<usize> {
        match self {
            KnotConvention::Full | KnotConvention::Multiplicities => Some(full_index),
            KnotConvention::Trimmed if full_index == 0 || full_index + 1 >= full_len => None,
            KnotConvention::Trimmed => Some(full_index - 1),
        }
    }

    /// The full-vector index of the caller's index `caller_index`.
    pub fn full_index(self, caller_index: usize) -> usize {
        match self {
            KnotConvention::Full | KnotConvention::Multiplicities => caller_index,
            KnotConvention::Trimmed => caller_index + 1,
        }
    }
}

/// Knots as a caller writes them, before validation ([`Curve::from_knot_form`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KnotForm<'a> {
    /// A flat vector: full (`n + p + 2` values) or trimmed (`n + p`), detected by length.
    Flat(&'a [f64]),
    /// Distinct increasing values and their multiplicities, summing to `n + p + 2`.
    Multiplicities {
        /// The distinct values, strictly increasing.
        knots: &'a [f64],
        /// How often each value repeats in the full vector (each `>= 1`).
        multiplicities: &'a [usize],
    },
    /// Open CASCADE's periodic form (`Geom_BSplineCurve` with `Periodic`): the distinct values
    /// `k_0 < … < k_m` of one period `T = k_m - k_0` with multiplicities; the first and the
    /// last multiplicity are equal and at most the degree; the control points are not
    /// repeated: there are `Σ multiplicities - m_m` of them (see [`super::periodic`]).
    Periodic {
        /// The distinct values of one period, strictly increasing.
        knots: &'a [f64],
        /// Their multiplicities.
        multiplicities: &'a [usize],
    },
}

/// A curve's knots in the caller's form, for an answer ([`Curve::caller_knots`]).
#[derive(Debug, Clone, PartialEq)]
pub struct CallerKnots {
    /// The flat vector (full or trimmed), or the distinct values.
    pub knots: Vec<f64>,
    /// The multiplicities, in the multiplicities and the periodic form.
    pub multiplicities: Option<Vec<usize>>,
    /// Whether the form is periodic.
    pub periodic: bool,
}

/// The distinct values of a non-decreasing knot vector and how often each repeats.
pub fn distinct_knots(full: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let mut values: Vec<f64> = Vec::new();
    let mut multiplicities: Vec<usize> = Vec::new();
    for &u in full {
        match (values.last(), multiplicities.last_mut()) {
            (Some(&last), Some(count)) if last == u => *count += 1,
            _ => {
                values.push(u);
                multiplicities.push(1);
            }
        }
    }
    (values, multiplicities)
}

/// [`Curve::snap_to_domain`] for any domain `[lo, hi]` (`lo < hi`) of one parameter: `t`
/// itself inside it; the nearer end just outside it (by at most [`DOMAIN_END_SLACK`]
/// `· (hi - lo)` or [`DOMAIN_END_ULPS`] units of roundoff of the ends); with `periodic`,
/// every finite `t` reduced into the period, `lo + (t - lo) mod (hi - lo)`; `None` otherwise.
/// Shared by the curves and by each direction of a surface.
pub fn snap_parameter(t: f64, (lo, hi): (f64, f64), periodic: bool) -> Option<f64> {
    if !t.is_finite() {
        return None;
    }
    if (lo..=hi).contains(&t) {
        return Some(t);
    }
    if periodic {
        let reduced = lo + (t - lo).rem_euclid(hi - lo);
        return reduced.is_finite().then(|| reduced.clamp(lo, hi));
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
    /// One knot, by the caller's index (in the multiplicities forms: of the distinct values).
    Knot(usize),
    /// The multiplicity list as a whole.
    Multiplicities,
    /// One multiplicity.
    Multiplicity(usize),
    /// The periodic flag.
    Periodic,
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
    #[error(
        "{knots} knots but {multiplicities} multiplicities given; give one multiplicity per knot"
    )]
    MultiplicityCountMismatch { knots: usize, multiplicities: usize },
    #[error("knot {index} is not greater than knot {}: with multiplicities the knots are distinct, increasing values", index - 1)]
    KnotNotIncreasing { index: usize },
    #[error("multiplicity {index} is 0; each knot appears at least once")]
    ZeroMultiplicity { index: usize },
    #[error("multiplicity {index} is {multiplicity}; at most {max} allowed here ({rule})")]
    MultiplicityTooHigh {
        index: usize,
        multiplicity: usize,
        max: usize,
        rule: &'static str,
    },
    #[error(
        "the multiplicities sum to {sum}; a curve with {control_points} control points of degree {degree} needs {expected} (control points + degree + 1)"
    )]
    WrongMultiplicitySum {
        sum: usize,
        control_points: usize,
        degree: usize,
        expected: usize,
    },
    #[error("a periodic curve needs knots with `multiplicities` (Open CASCADE's periodic form)")]
    PeriodicNeedsMultiplicities,
    #[error("a periodic curve needs at least two knots (the two ends of one period)")]
    PeriodicTooFewKnots,
    #[error(
        "the first and last multiplicity of a periodic curve must be equal: {first} and {last} given"
    )]
    PeriodicEndsDiffer {
        first: usize,
        last: usize,
        last_index: usize,
    },
    #[error(
        "{count} control points given; a periodic curve with these multiplicities has {expected} (the sum of all multiplicities but the last)"
    )]
    PeriodicControlPointCount { count: usize, expected: usize },
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
            CurveError::WrongKnotCount { .. }
            | CurveError::EmptyDomain
            | CurveError::PeriodicTooFewKnots => CurveField::Knots,
            CurveError::NonFiniteKnot { index }
            | CurveError::DecreasingKnot { index }
            | CurveError::KnotNotIncreasing { index }
            | CurveError::KnotMultiplicityTooHigh { index, .. } => CurveField::Knot(index),
            CurveError::MultiplicityCountMismatch { .. }
            | CurveError::WrongMultiplicitySum { .. }
            | CurveError::PeriodicControlPointCount { .. } => CurveField::Multiplicities,
            CurveError::ZeroMultiplicity { index }
            | CurveError::MultiplicityTooHigh { index, .. } => CurveField::Multiplicity(index),
            CurveError::PeriodicEndsDiffer { last_index, .. } => {
                CurveField::Multiplicity(last_index)
            }
            CurveError::PeriodicNeedsMultiplicities => CurveField::Periodic,
            CurveError::WrongWeightCount { .. } => CurveField::Weights,
            CurveError::NonFiniteWeight { index } | CurveError::NonPositiveWeight { index } => {
                CurveField::Weight(index)
            }
        }
    }
}

/// A B-spline or NURBS curve whose data obey every rule; built only by [`Curve::new`] or
/// [`Curve::from_knot_form`] (or derived from another valid curve), so the rest of the core
/// never sees invalid data.
///
/// Invariants: `1 <= p <= MAX_DEGREE`, `n + 1 >= p + 1` control points of one dimension,
/// a finite non-decreasing full knot vector of `n + p + 2` values with `u_p < u_{n+1}`,
/// finite positive weights when rational.
///
/// A periodic curve is stored cut open at its first knot `k_0` (see [`super::periodic`]): the
/// fields then hold the ordinary curve over one period `[k_0, k_0 + T]`, whose last poles
/// repeat the first ones; `periodic` remembers how to write it in the periodic form again.
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
    periodic: Option<Periodicity>,
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
        Curve::from_knot_form(
            degree,
            control_points,
            KnotForm::Flat(knots),
            weights,
            limits,
        )
    }

    /// Validates raw curve data with knots in any [`KnotForm`].
    ///
    /// The rules of [`Curve::new`] for the degree, control points and weights (a periodic
    /// curve needs only `max(degree, 2)` control points: its first `degree + 1 - m_0` come
    /// again after the last). Then, for the multiplicities form: one multiplicity per knot;
    /// finite, strictly increasing knots; every multiplicity `>= 1`, at most `degree + 1`
    /// inside and `degree + 2` at the two ends (as a full vector's end runs); the sum
    /// `n + p + 2`; a non-empty domain. For the periodic form: at least two knots; finite,
    /// strictly increasing knots; every multiplicity `>= 1`, at most `degree + 1` inside; the
    /// first and last equal and at most `degree`; `Σ m_i - m_last` control points.
    pub fn from_knot_form(
        degree: usize,
        control_points: &[impl AsRef<[f64]>],
        knots: KnotForm<'_>,
        weights: Option<&[f64]>,
        limits: &CurveLimits,
    ) -> Result<Curve, CurveError> {
        let periodic = matches!(knots, KnotForm::Periodic { .. });
        let (dimension, points) = checked_points(degree, control_points, periodic, limits)?;
        if let Some(weights) = weights {
            check_weights(weights, points.len())?;
        }
        let weights = weights.map(<[f64]>::to_vec);
        let count = points.len();
        if let KnotForm::Periodic {
            knots,
            multiplicities,
        } = knots
        {
            check_periodic_knots(knots, multiplicities, degree, count)?;
            return Ok(super::periodic::unwrapped(
                degree,
                dimension,
                points,
                weights,
                knots,
                multiplicities,
            ));
        }
        let valid = validate_knots(degree, count, knots)?;
        Ok(Curve::from_valid_parts(
            degree,
            dimension,
            points,
            weights,
            valid.full,
            valid.convention,
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
            periodic: None,
        }
    }

    /// This curve's data as an ordinary curve (a periodic one cut open at `k_0`).
    pub(crate) fn as_ordinary(&self) -> Curve {
        Curve {
            periodic: None,
            ..self.clone()
        }
    }

    /// The same curve marked periodic (precondition: the data are a periodic curve cut open
    /// at its first knot, as [`super::periodic`] builds them).
    pub(crate) fn into_periodic(mut self, periodicity: Periodicity) -> Curve {
        self.periodic = Some(periodicity);
        self
    }

    /// The same curve with another full knot vector (same length). Checks only what evaluation
    /// needs: finite, non-decreasing values and a non-empty domain. Unlike [`Curve::new`] it
    /// accepts any multiplicity, e.g. a knot moved onto a clamped end (multiplicity `p + 2`
    /// there, which takes `d_0` or `d_n` out of the curve: the shape solver's `keep_domain`
    /// rejects such edits). A periodic curve's result is the ordinary curve over the period
    /// (new knots need not repeat with the period; [`super::PeriodicWindow::wrap`] makes
    /// periodic edits).
    pub fn with_full_knots(&self, knots: Vec<f64>) -> Option<Curve> {
        let valid = knots.len() == self.knots.len()
            && knots.iter().all(|u| u.is_finite())
            && knots.windows(2).all(|w| w[0] <= w[1])
            && knots[self.degree] < knots[self.control_points.len()];
        valid.then(|| Curve {
            knots,
            periodic: None,
            ..self.clone()
        })
    }

    /// The same curve with other control points (same count and dimension; `z = 0` for a
    /// planar curve), or `None` when a coordinate is not finite. A periodic curve's result is
    /// the ordinary curve over the period, as for [`Curve::with_full_knots`].
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

    /// The control points in the caller's form: all of them, or a periodic curve's `N`
    /// (the cut-open curve's last ones repeat them).
    pub fn caller_control_points(&self) -> &[Point] {
        match self.periodic {
            Some(periodicity) => &self.control_points[..periodicity.poles],
            None => &self.control_points,
        }
    }

    /// The weights in the caller's form (see [`Curve::caller_control_points`]).
    pub fn caller_weights(&self) -> Option<&[f64]> {
        let count = self.caller_control_points().len();
        self.weights.as_deref().map(|w| &w[..count])
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

    /// The knot vector in the caller's convention: the flat vector its knot indices refer to
    /// (the full vector for the multiplicities form; [`Curve::caller_knots`] gives the
    /// distinct values and multiplicities an answer carries).
    pub fn knots_in_convention(&self) -> &[f64] {
        match self.convention {
            KnotConvention::Full | KnotConvention::Multiplicities => &self.knots,
            KnotConvention::Trimmed => &self.knots[1..self.knots.len() - 1],
        }
    }

    /// The caller's knot convention.
    pub fn convention(&self) -> KnotConvention {
        self.convention
    }

    /// Whether the caller gave the curve in the periodic form.
    pub fn is_periodic(&self) -> bool {
        self.periodic.is_some()
    }

    /// The periodic layout, for a periodic curve.
    pub(crate) fn periodicity(&self) -> Option<Periodicity> {
        self.periodic
    }

    /// The knots in the caller's form: the flat vector in its convention, or the distinct
    /// values with multiplicities (of one period, for a periodic curve).
    pub fn caller_knots(&self) -> CallerKnots {
        match self.periodic {
            Some(periodicity) => super::periodic::period_knots(self, periodicity),
            None => self.full_knots_in_caller_form(&self.knots),
        }
    }

    /// Another full knot vector of this (non-periodic) curve's length, e.g. a solution's, in
    /// the caller's form. For a periodic curve the vector is taken as the cut-open curve's
    /// and written flat: periodic edits go through [`super::PeriodicWindow`].
    pub fn full_knots_in_caller_form(&self, full: &[f64]) -> CallerKnots {
        match self.convention {
            KnotConvention::Full => CallerKnots {
                knots: full.to_vec(),
                multiplicities: None,
                periodic: false,
            },
            KnotConvention::Trimmed if full.len() >= 2 => CallerKnots {
                knots: full[1..full.len() - 1].to_vec(),
                multiplicities: None,
                periodic: false,
            },
            KnotConvention::Trimmed => CallerKnots {
                knots: full.to_vec(),
                multiplicities: None,
                periodic: false,
            },
            KnotConvention::Multiplicities => {
                let (knots, multiplicities) = distinct_knots(full);
                CallerKnots {
                    knots,
                    multiplicities: Some(multiplicities),
                    periodic: false,
                }
            }
        }
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
    ///
    /// A periodic curve takes every finite parameter: one outside its period `[lo, hi]` is
    /// reduced into it, `lo + (t - lo) mod (hi - lo)` (the curve repeats with the period).
    pub fn snap_to_domain(&self, t: f64) -> Option<f64> {
        snap_parameter(t, self.domain(), self.periodic.is_some())
    }

    /// The span `m` with `u_m <= t < u_{m+1}` (last non-empty span at the right end).
    pub fn span(&self, t: f64) -> usize {
        find_span(&self.knots, self.degree, t)
    }
}

/// A knot vector of one parameter direction that obeys every rule of its form: what a curve
/// or one direction of a surface is built on.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ValidKnots {
    /// The full vector; for the periodic form that of the ordinary spline over one period
    /// (cut open at `k_0`), whose control point `k` is the periodic form's `k mod N`.
    pub(crate) full: Vec<f64>,
    /// The caller's convention (the periodic form writes its knots with multiplicities).
    pub(crate) convention: KnotConvention,
    /// The periodic layout, for the periodic form.
    pub(crate) periodicity: Option<Periodicity>,
}

/// Checks knots in any [`KnotForm`] for a degree-`degree` spline with `count` control points
/// as the caller gives them (the rules of [`Curve::from_knot_form`] for the knots, and a
/// non-empty domain); the degree and the count themselves are the caller's to check.
pub(crate) fn validate_knots(
    degree: usize,
    count: usize,
    knots: KnotForm<'_>,
) -> Result<ValidKnots, CurveError> {
    let (full, convention) = match knots {
        KnotForm::Flat(knots) => flat_knots(knots, degree, count)?,
        KnotForm::Multiplicities {
            knots,
            multiplicities,
        } => (
            expanded_knots(knots, multiplicities, degree, count)?,
            KnotConvention::Multiplicities,
        ),
        KnotForm::Periodic {
            knots,
            multiplicities,
        } => {
            check_periodic_knots(knots, multiplicities, degree, count)?;
            let (full, periodicity) =
                super::periodic::unwrapped_knots(degree, knots, multiplicities);
            return Ok(ValidKnots {
                full,
                convention: KnotConvention::Multiplicities,
                periodicity: Some(periodicity),
            });
        }
    };
    if full[degree] >= full[count] {
        return Err(CurveError::EmptyDomain);
    }
    Ok(ValidKnots {
        full,
        convention,
        periodicity: None,
    })
}

/// The control points as core points, after the rules of [`Curve::from_knot_form`] for the
/// degree and the control points (`periodic`: `max(degree, 2)` points suffice).
fn checked_points(
    degree: usize,
    control_points: &[impl AsRef<[f64]>],
    periodic: bool,
    limits: &CurveLimits,
) -> Result<(Dimension, Vec<Point>), CurveError> {
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
    let needed = if periodic { degree.max(2) } else { degree + 1 };
    if count < needed {
        return Err(CurveError::TooFewControlPoints {
            count,
            degree,
            needed,
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
    Ok((dimension, points))
}

/// One finite weight `> 0` per control point.
fn check_weights(weights: &[f64], count: usize) -> Result<(), CurveError> {
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
    Ok(())
}

/// The full vector of a flat knot vector (full or trimmed, detected by length) and its
/// convention, once [`check_knot_values`] holds.
fn flat_knots(
    knots: &[f64],
    degree: usize,
    count: usize,
) -> Result<(Vec<f64>, KnotConvention), CurveError> {
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
        KnotConvention::Trimmed => {
            let mut full = Vec::with_capacity(full_len);
            full.push(knots[0]);
            full.extend_from_slice(knots);
            full.push(knots[knots.len() - 1]);
            full
        }
        KnotConvention::Full | KnotConvention::Multiplicities => knots.to_vec(),
    };
    Ok((full, convention))
}

/// Checks what the multiplicities form and the periodic form share: one multiplicity per
/// knot, finite strictly increasing knots, every multiplicity `>= 1` and at most
/// `interior_max` inside (`ends_max` at the first and last knot). Returns the sum of the
/// multiplicities (saturating: a huge sum is wrong anyway).
fn check_distinct_knots(
    knots: &[f64],
    multiplicities: &[usize],
    interior_max: usize,
    ends_max: usize,
    ends_rule: &'static str,
) -> Result<usize, CurveError> {
    if knots.len() != multiplicities.len() {
        return Err(CurveError::MultiplicityCountMismatch {
            knots: knots.len(),
            multiplicities: multiplicities.len(),
        });
    }
    let last = knots.len().saturating_sub(1);
    let mut sum: usize = 0;
    for (index, (&u, &multiplicity)) in knots.iter().zip(multiplicities).enumerate() {
        if !u.is_finite() {
            return Err(CurveError::NonFiniteKnot { index });
        }
        if index > 0 && u <= knots[index - 1] {
            return Err(CurveError::KnotNotIncreasing { index });
        }
        if multiplicity == 0 {
            return Err(CurveError::ZeroMultiplicity { index });
        }
        let (max, rule) = if index == 0 || index == last {
            (ends_max, ends_rule)
        } else {
            (interior_max, "degree + 1 inside")
        };
        if multiplicity > max {
            return Err(CurveError::MultiplicityTooHigh {
                index,
                multiplicity,
                max,
                rule,
            });
        }
        sum = sum.saturating_add(multiplicity);
    }
    Ok(sum)
}

/// The full vector of the multiplicities form, once its rules hold (the sum is checked
/// before anything is expanded, so a huge multiplicity allocates nothing).
fn expanded_knots(
    knots: &[f64],
    multiplicities: &[usize],
    degree: usize,
    count: usize,
) -> Result<Vec<f64>, CurveError> {
    let sum = check_distinct_knots(
        knots,
        multiplicities,
        degree + 1,
        degree + 2,
        "degree + 2 at an end, as in a full vector",
    )?;
    let expected = count + degree + 1;
    if sum != expected {
        return Err(CurveError::WrongMultiplicitySum {
            sum,
            control_points: count,
            degree,
            expected,
        });
    }
    let mut full = Vec::with_capacity(expected);
    for (&u, &multiplicity) in knots.iter().zip(multiplicities) {
        full.extend(std::iter::repeat_n(u, multiplicity));
    }
    Ok(full)
}

/// Open CASCADE's rules of the periodic form (see [`KnotForm::Periodic`]).
fn check_periodic_knots(
    knots: &[f64],
    multiplicities: &[usize],
    degree: usize,
    count: usize,
) -> Result<(), CurveError> {
    if knots.len() == multiplicities.len() && knots.len() < 2 {
        return Err(CurveError::PeriodicTooFewKnots);
    }
    let sum = check_distinct_knots(
        knots,
        multiplicities,
        degree + 1,
        degree,
        "at most the degree at the ends of a periodic curve",
    )?;
    let last_index = multiplicities.len() - 1;
    let (first, last) = (multiplicities[0], multiplicities[last_index]);
    if first != last {
        return Err(CurveError::PeriodicEndsDiffer {
            first,
            last,
            last_index,
        });
    }
    let expected = sum - last;
    if count != expected {
        return Err(CurveError::PeriodicControlPointCount { count, expected });
    }
    Ok(())
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
