//! Conversions for the third release's curve toolkit: wire point lists into the core's
//! [`PointSet`], and the core's errors into 422s whose JSON pointers name the field.

use crate::http::curve::{WireCoordinates, curve_field_error, point_from_wire};
use crate::http::error::{ApiError, FieldError};
use crate::http::pointer::JsonPointer;
use crate::spline::{
    ApproximationError, CurveField, Dimension, ElevateError, InterpolationError,
    InterpolationField, LengthError, Point, PointSet, PointsError, PointsField, RemoveError,
    SplitError,
};

/// Validates `points` (at most `max_points`) into a point set; errors point below `/points`.
pub fn parse_points(points: &[WireCoordinates], max_points: usize) -> Result<PointSet, ApiError> {
    PointSet::new(points, max_points).map_err(|error| points_error(&error))
}

/// The 422 of a [`PointsError`].
pub fn points_error(error: &PointsError) -> ApiError {
    let pointer = match error.field() {
        PointsField::Points => JsonPointer::from("/points"),
        PointsField::Point { index, coordinate } => {
            let point = JsonPointer::from("/points").push(index);
            match coordinate {
                Some(coordinate) => point.push(coordinate),
                None => point,
            }
        }
        PointsField::Parameters => JsonPointer::from("/parameters"),
        PointsField::Parameter(index) => JsonPointer::from("/parameters").push(index),
    };
    ApiError::invalid(pointer, error.to_string())
}

/// The end tangents `[start | null, end | null]` in the points' dimension; errors point
/// below `/end_tangents`.
pub fn parse_end_tangents(
    tangents: Option<&[Option<WireCoordinates>]>,
    dimension: Dimension,
) -> Result<[Option<Point>; 2], ApiError> {
    let Some(tangents) = tangents else {
        return Ok([None, None]);
    };
    let at = JsonPointer::from("/end_tangents");
    if tangents.len() != 2 {
        return Err(ApiError::invalid(
            at,
            format!(
                "`end_tangents` has {} entries; it is `[start, end]`, each a vector or null",
                tangents.len()
            ),
        ));
    }
    let mut parsed = [None, None];
    for (index, tangent) in tangents.iter().enumerate() {
        if let Some(coordinates) = tangent {
            let point = point_from_wire(coordinates, dimension, &at.clone().push(index))?;
            parsed[index] = Some(point);
        }
    }
    Ok(parsed)
}

/// The 422 of an [`InterpolationError`]; `parameters_given` says whether the request sent
/// `parameters` (a singular system is then blamed on them, else on the points).
pub fn interpolation_error(error: &InterpolationError, parameters_given: bool) -> ApiError {
    let detail = error.to_string();
    let pointer = match error.field() {
        InterpolationField::Points(field) => {
            if let InterpolationError::Points(points) = error {
                return points_error(points);
            }
            match field {
                PointsField::Parameter(index) => JsonPointer::from("/parameters").push(index),
                _ => JsonPointer::from("/points"),
            }
        }
        InterpolationField::Degree => JsonPointer::from("/degree"),
        InterpolationField::EndTangents => JsonPointer::from("/end_tangents"),
        InterpolationField::Closed => JsonPointer::from("/closed"),
        InterpolationField::Parameters if parameters_given => JsonPointer::from("/parameters"),
        InterpolationField::Parameters => JsonPointer::from("/points"),
        InterpolationField::Knots(field) => match (error, field) {
            (InterpolationError::Knots(curve_error), CurveField::Knot(_) | CurveField::Knots) => {
                // The template curve's knots are the request's `knots`.
                return ApiError::Invalid(vec![curve_field_error(
                    curve_error,
                    &JsonPointer::root(),
                )]);
            }
            (InterpolationError::Knots(_), CurveField::Degree) => JsonPointer::from("/degree"),
            (InterpolationError::Knots(_), _) => JsonPointer::from("/points"),
            _ => JsonPointer::from("/knots"),
        },
    };
    ApiError::invalid(pointer, detail)
}

/// The 422 of an [`ApproximationError`].
pub fn approximation_error(error: &ApproximationError) -> ApiError {
    let pointer = match error {
        ApproximationError::Points(points) => return points_error(points),
        ApproximationError::DegreeTooLow | ApproximationError::DegreeTooHigh { .. } => "/degree",
        ApproximationError::InvalidTolerance
        | ApproximationError::ToleranceBelowFloor { .. }
        | ApproximationError::TooManyControlPoints { .. } => "/tolerance",
        ApproximationError::NonFiniteResult => "/points",
    };
    ApiError::invalid(pointer, error.to_string())
}

/// The 422 of an [`ElevateError`].
pub fn elevate_error(error: &ElevateError) -> ApiError {
    ApiError::invalid("/degree", error.to_string())
}

/// The 422 of a [`RemoveError`].
pub fn remove_error(error: &RemoveError) -> ApiError {
    match error.index() {
        _ if matches!(error, RemoveError::InvalidTolerance) => {
            ApiError::invalid("/tolerance", error.to_string())
        }
        Some(index) => {
            ApiError::invalid(JsonPointer::from("/knots").push(index), error.to_string())
        }
        None => ApiError::invalid("/knots", error.to_string()),
    }
}

/// The 422 of a [`SplitError`].
pub fn split_error(error: &SplitError) -> ApiError {
    let pointer = match error.index() {
        Some(index) => JsonPointer::from("/parameters").push(index),
        None => JsonPointer::from("/parameters"),
    };
    ApiError::invalid(pointer, error.to_string())
}

/// The 422 of a [`LengthError`].
pub fn length_error(error: &LengthError) -> ApiError {
    let pointer = match *error {
        LengthError::NonFiniteRange { index } | LengthError::RangeOutsideDomain { index, .. } => {
            JsonPointer::from("/range").push(index)
        }
        LengthError::ReversedRange { .. } => JsonPointer::from("/range"),
        LengthError::NotConverged { .. } | LengthError::NonFinite => JsonPointer::from("/curve"),
    };
    ApiError::invalid(pointer, error.to_string())
}

/// A field error at `/at_lengths/index`.
pub fn length_out_of_range(index: usize, value: f64, length: f64) -> FieldError {
    FieldError::new(
        JsonPointer::from("/at_lengths").push(index),
        format!("arc length {value} lies outside [0, {length}], the length of the range"),
    )
}
