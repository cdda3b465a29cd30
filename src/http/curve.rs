//! The wire form of a curve and its one-time conversion into the core's validated [`Curve`].

use serde::{Deserialize, Serialize};
use smallvec::SmallVec;
use utoipa::ToSchema;

use super::error::{ApiError, FieldError};
use super::pointer::JsonPointer;
use crate::spline::{Curve, CurveError, CurveField, CurveLimits, Dimension, KnotForm, Point};

/// A control point as sent: its coordinates, inline up to three (no allocation per point);
/// more (an error the curve's validation names) spill to the heap.
pub type WireCoordinates = SmallVec<[f64; 3]>;

/// A B-spline or NURBS curve as sent and received.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "degree": 3,
    "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]],
    "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1],
    "weights": [1, 1, 2, 1, 1]
}))]
pub struct CurveBody {
    /// Degree `p >= 1` (order `p + 1`); the shape endpoints need 3.
    #[schema(minimum = 1, example = 3)]
    pub degree: usize,
    /// At least `degree + 1` control points, all 2D (`[x, y]`) or all 3D (`[x, y, z]`).
    #[schema(value_type = Vec<Vec<f64>>, example = json!([[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]]))]
    pub control_points: Vec<WireCoordinates>,
    /// Without `multiplicities`: non-decreasing knots, the full vector
    /// (`control_points + degree + 1` values) or the openNURBS/Rhino vector without its two
    /// end values (`control_points + degree - 1`), detected by length. With
    /// `multiplicities`: the distinct values, strictly increasing (STEP, IGES, Open CASCADE).
    /// Answers use the same form.
    #[schema(example = json!([0, 0, 0, 0, 0.5, 1, 1, 1, 1]))]
    pub knots: Vec<f64>,
    /// How often each of `knots` repeats (integers `>= 1`, one per knot): the full vector is
    /// each knot repeated its multiplicity times. They sum to `control_points + degree + 1`;
    /// at most `degree + 1` inside, `degree + 2` at the two ends. Knot indices (in requests
    /// and answers) then refer to that full vector. With `periodic`, see there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = json!([4, 1, 4]))]
    pub multiplicities: Option<Vec<usize>>,
    /// Optional weights, one per control point, all `> 0`; absent means non-rational.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = json!([1, 1, 2, 1, 1]))]
    pub weights: Option<Vec<f64>>,
    /// Open CASCADE's periodic form (`Geom_BSplineCurve` with `Periodic`), with `knots` and
    /// `multiplicities` of one period `T = knots[last] - knots[0]`: the first and last
    /// multiplicity equal and at most `degree`, the control points not repeated (as many as
    /// the sum of all multiplicities but the last, at least `max(degree, 2)`). The curve
    /// repeats with the period: any finite parameter is accepted and reduced into
    /// `[knots[0], knots[last]]` (answers give the reduced one). Taken by evaluate, closest
    /// point, insertion, Bézier pieces, export and the shape endpoints; the others answer 422.
    #[serde(default, skip_serializing_if = "is_false")]
    #[schema(example = false)]
    pub periodic: bool,
}

fn is_false(value: &bool) -> bool {
    !*value
}

impl CurveBody {
    /// Validates the wire curve into a core [`Curve`]; errors point below `at`, a pointer such
    /// as `"/curve"` (built only when there is an error). A periodic curve is refused (422 at
    /// `at/periodic`): an endpoint that takes one says so with
    /// [`CurveBody::parse_allowing_periodic`].
    pub fn parse(&self, limits: &CurveLimits, at: &str) -> Result<Curve, ApiError> {
        let curve = self.parse_allowing_periodic(limits, at)?;
        if curve.is_periodic() {
            return Err(ApiError::invalid(
                JsonPointer::from(at).push("periodic"),
                PERIODIC_NOT_TAKEN,
            ));
        }
        Ok(curve)
    }

    /// [`CurveBody::parse`] for the endpoints that take periodic curves too.
    pub fn parse_allowing_periodic(
        &self,
        limits: &CurveLimits,
        at: &str,
    ) -> Result<Curve, ApiError> {
        let knots = match (&self.multiplicities, self.periodic) {
            (None, false) => KnotForm::Flat(&self.knots),
            (Some(multiplicities), false) => KnotForm::Multiplicities {
                knots: &self.knots,
                multiplicities,
            },
            (Some(multiplicities), true) => KnotForm::Periodic {
                knots: &self.knots,
                multiplicities,
            },
            (None, true) => {
                return Err(ApiError::invalid(
                    JsonPointer::from(at).push("multiplicities"),
                    CurveError::PeriodicNeedsMultiplicities.to_string(),
                ));
            }
        };
        Curve::from_knot_form(
            self.degree,
            &self.control_points,
            knots,
            self.weights.as_deref(),
            limits,
        )
        .map_err(|error| ApiError::Invalid(vec![curve_field_error(&error, &JsonPointer::from(at))]))
    }

    /// [`CurveBody::parse`] for a request that checks more fields: the curve's errors are
    /// added to `errors` (so one answer lists them all), and `None` stands for them.
    pub fn parse_collecting(
        &self,
        limits: &CurveLimits,
        at: &str,
        errors: &mut Vec<FieldError>,
    ) -> Option<Curve> {
        collecting(self.parse(limits, at), at, errors)
    }

    /// [`CurveBody::parse_collecting`] for the endpoints that take periodic curves too.
    pub fn parse_collecting_allowing_periodic(
        &self,
        limits: &CurveLimits,
        at: &str,
        errors: &mut Vec<FieldError>,
    ) -> Option<Curve> {
        collecting(self.parse_allowing_periodic(limits, at), at, errors)
    }

    /// The wire form of a core curve in the caller's form: knots in its convention (with
    /// multiplicities, periodic), control points and weights as the caller gave them.
    pub fn from_curve(curve: &Curve) -> Self {
        let dimension = curve.dimension();
        let knots = curve.caller_knots();
        CurveBody {
            degree: curve.degree(),
            control_points: curve
                .caller_control_points()
                .iter()
                .map(|point| WireCoordinates::from_slice(&point[..dimension.count()]))
                .collect(),
            knots: knots.knots,
            multiplicities: knots.multiplicities,
            weights: curve.caller_weights().map(<[f64]>::to_vec),
            periodic: knots.periodic,
        }
    }
}

/// The 422 detail of an endpoint that does not take periodic curves.
pub const PERIODIC_NOT_TAKEN: &str = "this endpoint does not take periodic curves yet (evaluate, closest-point, insert-knots, bezier, export and the shape endpoints do); send the curve in its non-periodic form (Open CASCADE: SetNotPeriodic)";

/// A parse result as in [`CurveBody::parse_collecting`].
fn collecting(
    result: Result<Curve, ApiError>,
    at: &str,
    errors: &mut Vec<FieldError>,
) -> Option<Curve> {
    match result {
        Ok(curve) => Some(curve),
        Err(ApiError::Invalid(curve_errors)) => {
            errors.extend(curve_errors);
            None
        }
        Err(other) => {
            errors.push(FieldError::new(at, other.to_string()));
            None
        }
    }
}

/// A full knot vector of `curve`'s length (e.g. a solution's new knots) in the caller's
/// form: the flat vector in its convention, or the distinct values and their multiplicities.
/// Answers that carry knots of their own (a solution's `knots`) build them with this.
pub fn knots_in_caller_form(curve: &Curve, full: &[f64]) -> (Vec<f64>, Option<Vec<usize>>) {
    let knots = curve.full_knots_in_caller_form(full);
    (knots.knots, knots.multiplicities)
}

/// The field error for a core curve error, pointing below `at`.
pub fn curve_field_error(error: &CurveError, at: &JsonPointer) -> FieldError {
    let pointer = match error.field() {
        CurveField::Degree => at.clone().push("degree"),
        CurveField::ControlPoints => at.clone().push("control_points"),
        CurveField::ControlPoint { index, coordinate } => {
            let point = at.clone().push("control_points").push(index);
            match coordinate {
                Some(coordinate) => point.push(coordinate),
                None => point,
            }
        }
        CurveField::Knots => at.clone().push("knots"),
        CurveField::Knot(index) => at.clone().push("knots").push(index),
        CurveField::Multiplicities => at.clone().push("multiplicities"),
        CurveField::Multiplicity(index) => at.clone().push("multiplicities").push(index),
        CurveField::Periodic => at.clone().push("periodic"),
        CurveField::Weights => at.clone().push("weights"),
        CurveField::Weight(index) => at.clone().push("weights").push(index),
    };
    FieldError::new(pointer, error.to_string())
}

/// A point in an answer: `[x, y]` or `[x, y, z]` (the curve's dimension), stored inline so
/// that answers with many points allocate none per point. In the OpenAPI document it is an
/// array of numbers (`#[schema(value_type = Vec<f64>)]` where it is used).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WirePoint {
    coordinates: Point,
    dimension: Dimension,
}

impl WirePoint {
    /// The coordinates sent: 2 or 3.
    pub fn as_slice(&self) -> &[f64] {
        &self.coordinates[..self.dimension.count()]
    }
}

impl Serialize for WirePoint {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.as_slice())
    }
}

impl<'de> Deserialize<'de> for WirePoint {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let coordinates = Vec::<f64>::deserialize(deserializer)?;
        let dimension = match coordinates.len() {
            2 => Dimension::Two,
            3 => Dimension::Three,
            count => {
                return Err(serde::de::Error::invalid_length(
                    count,
                    &"a point with 2 or 3 coordinates",
                ));
            }
        };
        let mut point = [0.0; 3];
        point[..coordinates.len()].copy_from_slice(&coordinates);
        Ok(WirePoint {
            coordinates: point,
            dimension,
        })
    }
}

/// A core point as `[x, y]` or `[x, y, z]`.
pub fn point_to_wire(point: Point, dimension: Dimension) -> WirePoint {
    WirePoint {
        coordinates: point,
        dimension,
    }
}

/// A wire point (`[x, y]` or `[x, y, z]`, matching `dimension`) as a core point; the pointer
/// names it when its length is wrong or a coordinate is not finite.
pub fn point_from_wire(
    coordinates: &[f64],
    dimension: Dimension,
    at: &JsonPointer,
) -> Result<Point, ApiError> {
    if coordinates.len() != dimension.count() {
        return Err(ApiError::invalid(
            at.clone(),
            format!(
                "the point has {} coordinates; the curve's control points have {}",
                coordinates.len(),
                dimension.count()
            ),
        ));
    }
    let mut point = [0.0; 3];
    for (index, (&value, slot)) in coordinates.iter().zip(point.iter_mut()).enumerate() {
        if !value.is_finite() {
            return Err(ApiError::invalid(
                at.clone().push(index),
                "coordinates must be finite numbers",
            ));
        }
        *slot = value;
    }
    Ok(point)
}
