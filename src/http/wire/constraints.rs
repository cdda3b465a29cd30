//! Wire types of the third release's edit conditions: `constraints` and
//! `fixed_control_points` of solve and membership, and their validation into the core's
//! [`ConstraintSet`] and [`FixedPoles`] with JSON pointers.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::error::FieldError;
use crate::http::pointer::JsonPointer;
use crate::shape::{ConstraintField, ConstraintSet, ConstraintSpec, FixedPoles};
use crate::spline::Curve;

/// A condition every solution must keep: the curve point (`order` 0) or its first or second
/// derivative with respect to the parameter (`order` 1, 2) at `parameter`, pinned to its
/// current value or prescribed by `value`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"parameter": 0.8, "order": 1, "direction_only": true}))]
pub struct ConstraintBody {
    /// The parameter `u`, inside the domain (snapped onto an end just outside it, as
    /// `parameter`); at a knot, derivatives are taken from the right (at the domain's right
    /// end, from the left). `order` 0 may not sit at the picked `parameter` itself.
    #[schema(example = 0.8)]
    pub parameter: f64,
    /// 0: the point; 1, 2: the first, second derivative (at most the curve's degree).
    #[schema(minimum = 0, maximum = 2, example = 1)]
    pub order: u64,
    /// The value the quantity must take (same dimension as the control points); without it
    /// the quantity keeps its current value (a pin). With `direction_only`: the direction the
    /// tangent must take (same sense, any length; not the zero vector).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = json!([1.0, 0.5]))]
    pub value: Option<Vec<f64>>,
    /// `order` 1 only: keep (or prescribe) only the tangent's direction and sense, not its
    /// length (default `false`).
    #[serde(default)]
    #[schema(example = false)]
    pub direction_only: bool,
}

/// The JSON pointer of one field of `/constraints`.
fn constraint_pointer(index: Option<usize>, field: ConstraintField) -> JsonPointer {
    let list = JsonPointer::from("/constraints");
    let Some(index) = index else {
        return list;
    };
    let entry = list.push(index);
    match field {
        ConstraintField::List | ConstraintField::Entry => entry,
        ConstraintField::Parameter => entry.push("parameter"),
        ConstraintField::Order => entry.push("order"),
        ConstraintField::Value => entry.push("value"),
        ConstraintField::ValueCoordinate(c) => entry.push("value").push(c),
        ConstraintField::DirectionOnly => entry.push("direction_only"),
    }
}

/// Validates `constraints` for `curve` and the picked parameter `t` (snapped), collecting
/// every malformed entry into `errors` with its pointer.
pub fn parse_constraints(
    curve: &Curve,
    t: f64,
    constraints: Option<&[ConstraintBody]>,
    errors: &mut Vec<FieldError>,
) -> Option<ConstraintSet> {
    let Some(bodies) = constraints else {
        return Some(ConstraintSet::none());
    };
    let specs: Vec<ConstraintSpec> = bodies
        .iter()
        .map(|body| ConstraintSpec {
            parameter: body.parameter,
            order: body.order,
            value: body.value.as_deref(),
            direction_only: body.direction_only,
        })
        .collect();
    match ConstraintSet::new(curve, t, &specs) {
        Ok(set) => Some(set),
        Err(issues) => {
            errors.extend(issues.into_iter().map(|issue| {
                FieldError::new(
                    constraint_pointer(issue.index, issue.field),
                    issue.error.to_string(),
                )
            }));
            None
        }
    }
}

/// Validates `fixed_control_points` for `curve`, collecting errors at
/// `/fixed_control_points/i`.
pub fn parse_fixed(
    curve: &Curve,
    fixed: Option<&[usize]>,
    errors: &mut Vec<FieldError>,
) -> Option<FixedPoles> {
    // The caller's control points (a periodic curve's `N`, each held once).
    let count = curve.caller_control_points().len();
    match FixedPoles::new(count, fixed.unwrap_or(&[])) {
        Ok(fixed) => Some(fixed),
        Err(issues) => {
            errors.extend(issues.into_iter().map(|(position, error)| {
                FieldError::new(
                    JsonPointer::from("/fixed_control_points").push(position),
                    error.to_string(),
                )
            }));
            None
        }
    }
}
