//! The wire form of a curve and its one-time conversion into the core's validated [`Curve`].

use serde::{Deserialize, Serialize};
use smallvec::SmallVec;
use utoipa::ToSchema;

use super::error::{ApiError, FieldError};
use super::pointer::JsonPointer;
use crate::spline::{Curve, CurveError, CurveField, CurveLimits, Dimension, Point};

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
    /// Non-decreasing knots: the full vector (`control_points + degree + 1` values) or the
    /// openNURBS/Rhino vector without its two end values (`control_points + degree - 1`),
    /// detected by length. Answers use the same convention.
    #[schema(example = json!([0, 0, 0, 0, 0.5, 1, 1, 1, 1]))]
    pub knots: Vec<f64>,
    /// Optional weights, one per control point, all `> 0`; absent means non-rational.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = json!([1, 1, 2, 1, 1]))]
    pub weights: Option<Vec<f64>>,
}

impl CurveBody {
    /// Validates the wire curve into a core [`Curve`]; errors point below `at`, a pointer such
    /// as `"/curve"` (built only when there is an error).
    pub fn parse(&self, limits: &CurveLimits, at: &str) -> Result<Curve, ApiError> {
        Curve::new(
            self.degree,
            &self.control_points,
            &self.knots,
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
        match self.parse(limits, at) {
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

    /// The wire form of a core curve, knots in the curve's (the caller's) convention.
    pub fn from_curve(curve: &Curve) -> Self {
        let dimension = curve.dimension();
        CurveBody {
            degree: curve.degree(),
            control_points: curve
                .control_points()
                .iter()
                .map(|point| WireCoordinates::from_slice(&point[..dimension.count()]))
                .collect(),
            knots: curve.knots_in_convention().to_vec(),
            weights: curve.weights().map(<[f64]>::to_vec),
        }
    }
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
