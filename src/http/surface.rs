//! The wire form of a surface and its one-time conversion into the core's validated
//! [`Surface`] (every broken rule a 422 naming the field by a JSON pointer).

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::curve::WireCoordinates;
use super::error::{ApiError, FieldError};
use super::pointer::JsonPointer;
use crate::spline::{CurveError, KnotForm, Point};
use crate::surface::{Direction, Surface, SurfaceError, SurfaceField, SurfaceLimits};

/// A B-spline or NURBS surface as sent and received:
/// `S(u, v) = Σ_i Σ_j N_i(u) M_j(v) w_ij d_ij / Σ_i Σ_j N_i(u) M_j(v) w_ij`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "degree_u": 3, "degree_v": 2,
    "control_points": [[[0, 0, 0], [0, 1, 0.5], [0, 2, 0]],
                       [[1, 0, 0.2], [1, 1, 1], [1, 2, 0.2]],
                       [[2, 0, 0], [2, 1, 0.5], [2, 2, 0]],
                       [[3, 0, 0], [3, 1, 0.3], [3, 2, 0]]],
    "knots_u": [0, 0, 0, 0, 1, 1, 1, 1],
    "knots_v": [0, 0, 0, 1, 1, 1],
    "weights": [[1, 1, 1], [1, 2, 1], [1, 1, 1], [1, 1, 1]]
}))]
pub struct SurfaceBody {
    /// Degree in `u` (>= 1).
    #[schema(minimum = 1, example = 3)]
    pub degree_u: usize,
    /// Degree in `v` (>= 1).
    #[schema(minimum = 1, example = 2)]
    pub degree_v: usize,
    /// `control_points[i][j]` is `d_ij`: `n_u` rows (`i` along `u`, at least `degree_u + 1`)
    /// of `n_v` points each (`j` along `v`, at least `degree_v + 1`; every row as long as
    /// the first), all 3D. At most the configured `max_surface_control_points` in all.
    #[schema(value_type = Vec<Vec<Vec<f64>>>)]
    pub control_points: Vec<Vec<WireCoordinates>>,
    /// The knots in `u`, in any of the curves' forms, detected as for a curve whose control
    /// points are a column (`n_u` of them): the full vector (`n_u + degree_u + 1` values),
    /// the openNURBS/Rhino vector without its two end values (`n_u + degree_u - 1`), or with
    /// `multiplicities_u` the distinct values. Answers use the same form.
    #[schema(example = json!([0, 0, 0, 0, 1, 1, 1, 1]))]
    pub knots_u: Vec<f64>,
    /// The knots in `v` (as `knots_u`, for a row of `n_v` control points).
    #[schema(example = json!([0, 0, 0, 1, 1, 1]))]
    pub knots_v: Vec<f64>,
    /// How often each of `knots_u` repeats (as a curve's `multiplicities`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicities_u: Option<Vec<usize>>,
    /// How often each of `knots_v` repeats.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicities_v: Option<Vec<usize>>,
    /// Open CASCADE's periodic form in `u` (`Geom_BSplineSurface::IsUPeriodic`), with
    /// `knots_u` and `multiplicities_u` of one period: the first and last multiplicity equal
    /// and at most `degree_u`, the rows not repeated (as many as the sum of all
    /// multiplicities but the last). Any finite `u` is then reduced into the period.
    #[serde(default, skip_serializing_if = "is_false")]
    pub periodic_u: bool,
    /// The periodic form in `v` (as `periodic_u`, for the points of a row).
    #[serde(default, skip_serializing_if = "is_false")]
    pub periodic_v: bool,
    /// Optional weights, `weights[i][j]` for `d_ij` (same shape as `control_points`), all
    /// `> 0`; absent means non-rational.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = json!([[1, 1, 1], [1, 2, 1], [1, 1, 1], [1, 1, 1]]))]
    pub weights: Option<Vec<Vec<f64>>>,
}

fn is_false(value: &bool) -> bool {
    !*value
}

impl SurfaceBody {
    /// Validates the wire surface into a core [`Surface`]; errors point below `at` (such as
    /// `"/surface"`).
    pub fn parse(&self, limits: &SurfaceLimits, at: &str) -> Result<Surface, ApiError> {
        let at = JsonPointer::from(at);
        let form = |direction: Direction| -> Result<KnotForm<'_>, ApiError> {
            let (knots, multiplicities, periodic) = match direction {
                Direction::U => (&self.knots_u, &self.multiplicities_u, self.periodic_u),
                Direction::V => (&self.knots_v, &self.multiplicities_v, self.periodic_v),
            };
            match (multiplicities, periodic) {
                (None, false) => Ok(KnotForm::Flat(knots)),
                (Some(multiplicities), false) => Ok(KnotForm::Multiplicities {
                    knots,
                    multiplicities,
                }),
                (Some(multiplicities), true) => Ok(KnotForm::Periodic {
                    knots,
                    multiplicities,
                }),
                (None, true) => Err(ApiError::invalid(
                    at.clone()
                        .push(format!("multiplicities_{}", direction.name())),
                    CurveError::PeriodicNeedsMultiplicities.to_string(),
                )),
            }
        };
        let knots = (form(Direction::U)?, form(Direction::V)?);
        Surface::from_knot_forms(
            (self.degree_u, self.degree_v),
            &self.control_points,
            knots,
            self.weights.as_deref(),
            limits,
        )
        .map_err(|error| ApiError::Invalid(vec![surface_field_error(&error, &at)]))
    }

    /// [`SurfaceBody::parse`] for a request that checks more fields: the surface's errors are
    /// added to `errors`, and `None` stands for them.
    pub fn parse_collecting(
        &self,
        limits: &SurfaceLimits,
        at: &str,
        errors: &mut Vec<FieldError>,
    ) -> Option<Surface> {
        match self.parse(limits, at) {
            Ok(surface) => Some(surface),
            Err(ApiError::Invalid(surface_errors)) => {
                errors.extend(surface_errors);
                None
            }
            Err(other) => {
                errors.push(FieldError::new(at, other.to_string()));
                None
            }
        }
    }

    /// The wire form of a core surface in the caller's form (knots in each direction's
    /// convention, periodic directions in the periodic form).
    pub fn from_surface(surface: &Surface) -> SurfaceBody {
        let (u, v) = (
            surface.caller_knots(Direction::U),
            surface.caller_knots(Direction::V),
        );
        SurfaceBody {
            degree_u: surface.u().degree(),
            degree_v: surface.v().degree(),
            control_points: surface
                .caller_control_points()
                .iter()
                .map(|row| {
                    row.iter()
                        .map(|p: &Point| WireCoordinates::from_slice(p))
                        .collect()
                })
                .collect(),
            knots_u: u.knots,
            knots_v: v.knots,
            multiplicities_u: u.multiplicities,
            multiplicities_v: v.multiplicities,
            periodic_u: u.periodic,
            periodic_v: v.periodic,
            weights: surface.caller_weights(),
        }
    }
}

/// The field error for a core surface error, pointing below `at`.
pub fn surface_field_error(error: &SurfaceError, at: &JsonPointer) -> FieldError {
    let suffixed = |name: &str, direction: Direction| format!("{name}_{}", direction.name());
    let pointer = match error.field() {
        SurfaceField::Degree(direction) => at.clone().push(suffixed("degree", direction)),
        SurfaceField::ControlPoints => at.clone().push("control_points"),
        SurfaceField::Row(row) => at.clone().push("control_points").push(row),
        SurfaceField::ControlPoint {
            row,
            column,
            coordinate,
        } => {
            let point = at.clone().push("control_points").push(row).push(column);
            match coordinate {
                Some(coordinate) => point.push(coordinate),
                None => point,
            }
        }
        SurfaceField::Knots(direction) => at.clone().push(suffixed("knots", direction)),
        SurfaceField::Knot(direction, index) => {
            at.clone().push(suffixed("knots", direction)).push(index)
        }
        SurfaceField::Multiplicities(direction) => {
            at.clone().push(suffixed("multiplicities", direction))
        }
        SurfaceField::Multiplicity(direction, index) => at
            .clone()
            .push(suffixed("multiplicities", direction))
            .push(index),
        SurfaceField::Periodic(direction) => at.clone().push(suffixed("periodic", direction)),
        SurfaceField::Weights => at.clone().push("weights"),
        SurfaceField::WeightRow(row) => at.clone().push("weights").push(row),
        SurfaceField::Weight { row, column } => at.clone().push("weights").push(row).push(column),
    };
    FieldError::new(pointer, error.to_string())
}
