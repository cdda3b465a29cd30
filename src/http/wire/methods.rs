//! Wire types of the ways to move a point: the `methods` a request asks for, the membership of
//! the control-point move and of the weight pairs, and the `excluded` list of an answer.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::error::{ApiError, FieldError};
use crate::http::pointer::JsonPointer;
use crate::shape::{Exclusion, ExclusionReason, MethodKind, WeightPairMembership};

/// A way to move the picked curve point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("knots"))]
pub enum Method {
    /// The knot-pair method: two knots around the moved one are solved in closed form (cubic
    /// curves).
    Knots,
    /// The least-norm move of the free control points that meets the target and every
    /// constraint; without constraints `Δd_i = R_i(t) / Σ_k R_k(t)² · (target - s(t))`.
    ControlPoints,
    /// Two weights of the poles active at `t` (any pair), in closed form.
    Weights,
}

impl From<MethodKind> for Method {
    fn from(kind: MethodKind) -> Self {
        match kind {
            MethodKind::Knots => Method::Knots,
            MethodKind::ControlPoints => Method::ControlPoints,
            MethodKind::Weights => Method::Weights,
        }
    }
}

/// The methods a request asks for, once validated, in the request's order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Methods {
    /// The requested methods, each once.
    pub kinds: Vec<MethodKind>,
}

impl Methods {
    /// Whether the knot-pair method is requested.
    pub fn knots(&self) -> bool {
        self.kinds.contains(&MethodKind::Knots)
    }

    /// Reads `methods` (default `["knots"]`): each name once, at least one; an unknown name
    /// is a 422 that points at it.
    pub fn parse(names: Option<&[String]>) -> Result<Methods, ApiError> {
        let Some(names) = names else {
            return Ok(Methods {
                kinds: vec![MethodKind::Knots],
            });
        };
        if names.is_empty() {
            return Err(ApiError::invalid(
                "/methods",
                "`methods` must name at least one method (omit it for [\"knots\"])",
            ));
        }
        let mut kinds = Vec::with_capacity(3);
        let mut errors = Vec::new();
        for (index, name) in names.iter().enumerate() {
            let kind = match name.as_str() {
                "knots" => MethodKind::Knots,
                "control_points" => MethodKind::ControlPoints,
                "weights" => MethodKind::Weights,
                other => {
                    errors.push(FieldError::new(
                        JsonPointer::from("/methods").push(index),
                        format!(
                            "unknown method {other:?}: expected \"knots\", \"control_points\" or \"weights\""
                        ),
                    ));
                    continue;
                }
            };
            if kinds.contains(&kind) {
                errors.push(FieldError::new(
                    JsonPointer::from("/methods").push(index),
                    format!("method {name:?} is listed twice"),
                ));
            } else {
                kinds.push(kind);
            }
        }
        if errors.is_empty() {
            Ok(Methods { kinds })
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
    /// Indices of the control points the move would change (without constraints: those
    /// whose basis is non-zero at `parameter`; empty when it gives no move).
    pub changed_control_points: Vec<usize>,
}

/// Whether one pair of poles reaches the target by its weights.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"poles": [3, 5], "contains": true}))]
pub struct WeightPairBody {
    /// The two poles `[k, l]` whose weights change.
    pub poles: [usize; 2],
    /// True exactly when `/v1/shape/solve` gives a weight solution for this pair.
    pub contains: bool,
}

/// The weight pairs' membership.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"contains": true, "pairs": [{"poles": [3, 4], "contains": false}, {"poles": [3, 5], "contains": true}]}))]
pub struct WeightMembershipBody {
    /// Whether some pair reaches the target.
    pub contains: bool,
    /// Every pair of the poles active at `parameter` (those with a non-degenerate triangle).
    pub pairs: Vec<WeightPairBody>,
}

impl WeightMembershipBody {
    /// The wire form of the core's pair membership.
    pub fn from_pairs(pairs: &[WeightPairMembership]) -> Self {
        WeightMembershipBody {
            contains: pairs.iter().any(|p| p.contains),
            pairs: pairs
                .iter()
                .map(|p| WeightPairBody {
                    poles: p.poles,
                    contains: p.contains,
                })
                .collect(),
        }
    }
}

/// Solutions of one method that the constraints or fixed poles ruled out, or why a method
/// has none at all.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "knots", "count": 2, "constraint": 0,
    "reason": "the pinned first derivative at u = 0.6 (constraints[0]) lies inside the affected domain and does not hold"}))]
pub struct ExclusionBody {
    /// The method.
    pub method: Method,
    /// How many solutions were dropped for this reason (1 for a method that could not meet
    /// the constraints at all).
    pub count: usize,
    /// Why, in words.
    pub reason: String,
    /// The position in `constraints` of the constraint it is about, when one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub constraint: Option<usize>,
    /// The fixed control point a dropped solution would change, when that is the reason.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed_control_point: Option<usize>,
}

impl From<&Exclusion> for ExclusionBody {
    fn from(exclusion: &Exclusion) -> Self {
        ExclusionBody {
            method: exclusion.method.into(),
            count: exclusion.count,
            reason: exclusion.reason.to_string(),
            constraint: exclusion.reason.constraint(),
            fixed_control_point: match exclusion.reason {
                ExclusionReason::MovesFixedPole { index } => Some(index),
                _ => None,
            },
        }
    }
}
