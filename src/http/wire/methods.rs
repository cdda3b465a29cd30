//! Wire types of the second release's solve additions: the `methods` a request asks for, the
//! control-point move's membership, and the `nearest` reachable target.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::error::{ApiError, FieldError};
use crate::http::pointer::JsonPointer;

/// A way to move the picked curve point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("knots"))]
pub enum Method {
    /// The knot-pair method: two knots around the moved one are solved in closed form.
    Knots,
    /// The least-squares move of the control points whose basis is non-zero at `t`:
    /// `Δd_i = R_i(t) / Σ_k R_k(t)² · (target - s(t))`.
    ControlPoints,
}

/// The methods a request asks for, once validated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Methods {
    /// The knot-pair method.
    pub knots: bool,
    /// The control-point move.
    pub control_points: bool,
}

impl Methods {
    /// Reads `methods` (default `["knots"]`): each name once, at least one; an unknown name
    /// is a 422 that points at it.
    pub fn parse(names: Option<&[String]>) -> Result<Methods, ApiError> {
        let Some(names) = names else {
            return Ok(Methods {
                knots: true,
                control_points: false,
            });
        };
        if names.is_empty() {
            return Err(ApiError::invalid(
                "/methods",
                "`methods` must name at least one method (omit it for [\"knots\"])",
            ));
        }
        let mut methods = Methods {
            knots: false,
            control_points: false,
        };
        let mut errors = Vec::new();
        for (index, name) in names.iter().enumerate() {
            let slot = match name.as_str() {
                "knots" => &mut methods.knots,
                "control_points" => &mut methods.control_points,
                other => {
                    errors.push(FieldError::new(
                        JsonPointer::from("/methods").push(index),
                        format!(
                            "unknown method {other:?}: expected \"knots\" or \"control_points\""
                        ),
                    ));
                    continue;
                }
            };
            if *slot {
                errors.push(FieldError::new(
                    JsonPointer::from("/methods").push(index),
                    format!("method {name:?} is listed twice"),
                ));
            }
            *slot = true;
        }
        if errors.is_empty() {
            Ok(methods)
        } else {
            Err(ApiError::Invalid(errors))
        }
    }
}

/// Whether the control-point move reaches the target (it always does when it is computable).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"contains": true, "changed_control_points": [2, 3, 4, 5]}))]
pub struct ControlPointMembershipBody {
    /// True exactly when `/v1/shape/solve` with `methods` holding `control_points` gives a
    /// control-point solution.
    pub contains: bool,
    /// Indices of the control points the move would change (those whose basis is non-zero at
    /// `parameter`).
    pub changed_control_points: Vec<usize>,
}
