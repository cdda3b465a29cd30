//! Wire types of the shape requests (membership, solve, regions) and their parsing into the
//! core's edit: methods, sides, regions, the curve (cubic for the knot pairs), constraints and
//! fixed control points.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::CurveBody;
use crate::http::error::{ApiError, FieldError};
use crate::http::pointer::JsonPointer;
use crate::http::wire::constraints::{ConstraintBody, parse_constraints, parse_fixed};
use crate::http::wire::families::{KnotFamily, parse_families};
use crate::http::wire::methods::{Method, Methods};
use crate::shape::family::FamilyChoice;
use crate::shape::{
    ConstraintSet, EditContext, FixedPoles, KnotPair, PoleVariables, ShapeError, ShapeQuery,
    SideChoice,
};
use crate::spline::{Curve, CurveLimits};

/// Which knot next to `t` may move to `t`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("both"))]
pub enum SideRequest {
    /// The knot right of `t`, `u_{m+1}`.
    Right,
    /// The knot left of (or at) `t`, `u_m`.
    Left,
    /// Both, each as its own candidate (right first).
    #[default]
    Both,
}

impl From<SideRequest> for SideChoice {
    fn from(side: SideRequest) -> Self {
        match side {
            SideRequest::Right => SideChoice::Right,
            SideRequest::Left => SideChoice::Left,
            SideRequest::Both => SideChoice::Both,
        }
    }
}

/// The side of a candidate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("left"))]
pub enum CandidateSide {
    /// The knot right of `t` moved to `t`.
    Right,
    /// The knot left of (or at) `t` moved to `t`.
    Left,
}

impl CandidateSide {
    /// The name on the wire (as serde writes it).
    pub fn wire_name(self) -> &'static str {
        match self {
            CandidateSide::Right => "right",
            CandidateSide::Left => "left",
        }
    }
}

impl From<crate::shape::Side> for CandidateSide {
    fn from(side: crate::shape::Side) -> Self {
        match side {
            crate::shape::Side::Right => CandidateSide::Right,
            crate::shape::Side::Left => CandidateSide::Left,
        }
    }
}

/// A region `Ω_r`: the targets one knot pair reaches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("omega2"))]
pub enum Region {
    /// `(a, b) = (v_{j-1}, v_j)` move (paper §3.1).
    Omega1,
    /// `(b, c) = (v_j, v_{j+1})` move (paper §3.1).
    Omega2,
    /// `(c, e) = (v_{j+1}, v_{j+2})` move (paper §3.1).
    Omega3,
    /// `(a, c) = (v_{j-1}, v_{j+1})` move (paper §3.2.1).
    Omega4,
    /// `(a, e) = (v_{j-1}, v_{j+2})` move (paper §3.2.2).
    Omega5,
    /// `(b, e) = (v_j, v_{j+2})` move (paper §3.2.3).
    Omega6,
}

impl Region {
    /// The name on the wire (as serde writes it).
    pub fn wire_name(self) -> &'static str {
        match self {
            Region::Omega1 => "omega1",
            Region::Omega2 => "omega2",
            Region::Omega3 => "omega3",
            Region::Omega4 => "omega4",
            Region::Omega5 => "omega5",
            Region::Omega6 => "omega6",
        }
    }
}

impl From<Region> for KnotPair {
    fn from(region: Region) -> Self {
        match region {
            Region::Omega1 => KnotPair::Omega1,
            Region::Omega2 => KnotPair::Omega2,
            Region::Omega3 => KnotPair::Omega3,
            Region::Omega4 => KnotPair::Omega4,
            Region::Omega5 => KnotPair::Omega5,
            Region::Omega6 => KnotPair::Omega6,
        }
    }
}

impl From<KnotPair> for Region {
    fn from(pair: KnotPair) -> Self {
        match pair {
            KnotPair::Omega1 => Region::Omega1,
            KnotPair::Omega2 => Region::Omega2,
            KnotPair::Omega3 => Region::Omega3,
            KnotPair::Omega4 => Region::Omega4,
            KnotPair::Omega5 => Region::Omega5,
            KnotPair::Omega6 => Region::Omega6,
        }
    }
}

fn keep_domain_default() -> bool {
    true
}

/// A picked curve point `s(parameter)` and the target it should move to.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
              "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]},
    "parameter": 0.42,
    "target": [4.746666666666666, 3.3233333333333333],
    "side": "both",
    "regions": ["omega1", "omega2", "omega3", "omega4", "omega5", "omega6"],
    "keep_domain": true
}))]
pub struct ShapeRequest {
    /// The curve: degree 2 or more when `methods` holds `knots` (the default), any degree
    /// otherwise.
    pub curve: CurveBody,
    /// The picked parameter `t`, inside the domain; one outside it by at most `1e-12` of the
    /// domain's length (or 4 units of roundoff of the ends) is taken as the nearer end.
    #[schema(example = 0.42)]
    pub parameter: f64,
    /// The target point `p` (same dimension as the control points).
    #[schema(example = json!([4.746666666666666, 3.3233333333333333]))]
    pub target: Vec<f64>,
    /// Which knot next to `t` moves to `t` (default `both`).
    #[serde(default)]
    pub side: SideRequest,
    /// A cubic's envelope pairs to try (default all six); no repeats.
    #[serde(default)]
    pub regions: Option<Vec<Region>>,
    /// The knot families to try (default: every family that applies — `envelope` on degree
    /// ≥ 3, `direct` on degree ≥ 2, `triples` on 3D curves); no repeats. `triples` on a 2D
    /// curve is answered with the family not applicable (three knots, two equations).
    #[serde(default)]
    #[schema(value_type = Option<Vec<KnotFamily>>, example = json!(["envelope", "direct"]))]
    pub knot_families: Option<Vec<String>>,
    /// Drop solutions that move the ends of the curve's domain (default `true`).
    #[serde(default = "keep_domain_default")]
    #[schema(default = true, example = true)]
    pub keep_domain: bool,
    /// Solve only: when no solution reaches the target, answer `nearest`, the reachable point
    /// closest to it (default `false`). Membership ignores it.
    #[serde(default)]
    #[schema(example = false)]
    pub nearest: bool,
    /// The ways to move the point (default `["knots"]`): `knots` (the knot pairs, cubic
    /// curves), `control_points` (the least-norm move of the free poles) and `weights` (two
    /// weights of the poles active at `t`); their solutions are ranked together.
    #[serde(default)]
    #[schema(value_type = Option<Vec<Method>>, example = json!(["knots", "control_points"]))]
    pub methods: Option<Vec<String>>,
    /// Conditions every solution keeps (at most 32; order irrelevant): pins and prescribed
    /// values of the point and first two derivatives, kept tangent directions. Solutions that
    /// break one are left out and counted in `excluded`.
    #[serde(default)]
    #[schema(example = json!([{"parameter": 0.0, "order": 0}, {"parameter": 0.8, "order": 1, "direction_only": true}]))]
    pub constraints: Option<Vec<ConstraintBody>>,
    /// Indices of control points no solution may move (the weight method: whose weights it
    /// may not change); no repeats.
    #[serde(default)]
    #[schema(example = json!([0, 7]))]
    pub fixed_control_points: Option<Vec<usize>>,
    /// Solve only: give each solution the `svg_path` of its new curve (planar non-rational
    /// curves of degree <= 3), so that a drag can draw its preview without another request
    /// (default `false`).
    #[serde(default)]
    #[schema(example = false)]
    pub svg_paths: bool,
}

/// A picked parameter whose regions' boundaries are wanted.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
              "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]},
    "parameter": 0.42,
    "side": "left",
    "regions": ["omega2", "omega4"],
    "tolerance": 0.01
}))]
pub struct RegionsRequest {
    /// The curve: degree 2 or more when `methods` holds `knots` (the default), any degree
    /// otherwise.
    pub curve: CurveBody,
    /// The picked parameter `t`, inside the domain; one outside it by at most `1e-12` of the
    /// domain's length (or 4 units of roundoff of the ends) is taken as the nearer end.
    #[schema(example = 0.42)]
    pub parameter: f64,
    /// Which knot next to `t` moves to `t` (default `both`).
    #[serde(default)]
    pub side: SideRequest,
    /// A cubic's envelope pairs to draw (default all six); no repeats.
    #[serde(default)]
    pub regions: Option<Vec<Region>>,
    /// The knot families whose regions to draw (as in solve).
    #[serde(default)]
    #[schema(value_type = Option<Vec<KnotFamily>>, example = json!(["envelope", "direct"]))]
    pub knot_families: Option<Vec<String>>,
    /// As in solve (default `true`): a drawn region holds only targets that solve reaches
    /// with the same request, so pairs whose knots the rule freezes are not drawn.
    #[serde(default = "keep_domain_default")]
    #[schema(default = true, example = true)]
    pub keep_domain: bool,
    /// The methods whose reachable sets to draw (default `["knots"]`): `knots` (the regions
    /// of the candidates), `weights` (each weight pair's quadrilateral, in
    /// `weight_regions`); `control_points` reaches every target and draws nothing.
    #[serde(default)]
    #[schema(value_type = Option<Vec<Method>>, example = json!(["knots", "weights"]))]
    pub methods: Option<Vec<String>>,
    /// As in solve, checked the same way. Only the regions of the pairs (knot or weight)
    /// whose edits surely keep every constraint are drawn: the edit leaves the curve alone
    /// where the constraint is (a point at an end of the changed part, or outside it; a
    /// derivative outside it) and the constraint holds on the current curve.
    #[serde(default)]
    #[schema(example = json!([{"parameter": 0.0, "order": 0}]))]
    pub constraints: Option<Vec<ConstraintBody>>,
    /// As in solve: the weight pairs of these control points are not drawn.
    #[serde(default)]
    #[schema(example = json!([0]))]
    pub fixed_control_points: Option<Vec<usize>>,
    /// Largest distance, in curve coordinates, between the true boundary and the polygon
    /// (> 0; default 1/1000 of the control triangle's longest edge). Refinement also stops at
    /// the configured vertex limit (then `tolerance_met` is false).
    #[serde(default)]
    #[schema(example = 0.01)]
    pub tolerance: Option<f64>,
    /// A target point (same dimension as the control points), drawn in the SVG picture
    /// (`Accept: image/svg+xml`); checked but otherwise unused by the JSON answer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = json!([4.746666666666666, 3.3233333333333333]))]
    pub target: Option<Vec<f64>>,
}

/// The validated parts shared by the shape endpoints.
pub struct ParsedShape {
    /// The curve (cubic when the knot pairs are requested).
    pub curve: Curve,
    /// The requested methods.
    pub methods: Methods,
    /// The requested knot pairs, in order, without repeats.
    pub pairs: Vec<KnotPair>,
    /// The requested knot families.
    pub families: FamilyChoice,
}

/// The validated conditions of an edit, which the core's [`EditContext`] borrows.
pub struct ParsedConditions {
    /// The constraints.
    pub constraints: ConstraintSet,
    /// The fixed control points.
    pub fixed: FixedPoles,
    /// The free poles as variables of the control-point system.
    pub variables: PoleVariables,
}

impl ParsedShape {
    /// Checks the methods, then the degree (the knot method needs degree 2 or more: a 422 at
    /// `/curve/degree` that names the methods that take degree 1), then the curve, the
    /// regions and the knot families.
    pub fn parse(
        curve: &CurveBody,
        regions: &Option<Vec<Region>>,
        knot_families: Option<&[String]>,
        methods: Option<&[String]>,
        curve_limits: &CurveLimits,
    ) -> Result<ParsedShape, ApiError> {
        let methods = Methods::parse(methods)?;
        if methods.knots() && curve.degree < 2 {
            return Err(ApiError::invalid(
                "/curve/degree",
                ShapeError::DegreeOne.to_string(),
            ));
        }
        let mut errors = Vec::new();
        let families = parse_families(knot_families, &mut errors);
        let parsed_curve =
            curve.parse_collecting_allowing_periodic(curve_limits, "/curve", &mut errors);
        let pairs = match regions {
            None => KnotPair::ALL.to_vec(),
            Some(regions) => {
                if regions.is_empty() {
                    errors.push(FieldError::new(
                        "/regions",
                        "`regions` must name at least one region (omit it for all six)",
                    ));
                }
                let mut pairs: Vec<KnotPair> = Vec::with_capacity(regions.len().min(6));
                for (index, &region) in regions.iter().enumerate() {
                    let pair = KnotPair::from(region);
                    if pairs.contains(&pair) {
                        errors.push(FieldError::new(
                            JsonPointer::from("/regions").push(index),
                            format!("region {} is listed twice", pair.name()),
                        ));
                        break;
                    }
                    pairs.push(pair);
                }
                pairs
            }
        };
        match parsed_curve {
            Some(curve) if errors.is_empty() => Ok(ParsedShape {
                curve,
                methods,
                pairs,
                families,
            }),
            _ => Err(ApiError::Invalid(errors)),
        }
    }

    /// The core query of these parts (a parameter just outside the domain snapped onto its
    /// end).
    pub fn query(&self, parameter: f64, side: SideRequest, keep_domain: bool) -> ShapeQuery<'_> {
        ShapeQuery {
            curve: &self.curve,
            // Just outside the domain: onto its end; farther out the query's check refuses it.
            parameter: self.curve.snap_to_domain(parameter).unwrap_or(parameter),
            side: side.into(),
            pairs: &self.pairs,
            families: self.families,
            keep_domain,
        }
    }

    /// Validates the constraints (for the snapped picked parameter) and fixed control points,
    /// every malformed entry reported with its pointer.
    pub fn conditions(
        &self,
        parameter: f64,
        constraints: Option<&[ConstraintBody]>,
        fixed_control_points: Option<&[usize]>,
    ) -> Result<ParsedConditions, ApiError> {
        let t = self.curve.snap_to_domain(parameter).unwrap_or(parameter);
        let mut errors = Vec::new();
        let constraints = parse_constraints(&self.curve, t, constraints, &mut errors);
        let fixed = parse_fixed(&self.curve, fixed_control_points, &mut errors);
        match (constraints, fixed) {
            (Some(constraints), Some(fixed)) if errors.is_empty() => {
                let variables = PoleVariables::free_poles(&fixed);
                Ok(ParsedConditions {
                    constraints,
                    fixed,
                    variables,
                })
            }
            _ => Err(ApiError::Invalid(errors)),
        }
    }
}

impl ParsedConditions {
    /// The core's edit context for `query`.
    pub fn context<'a>(&'a self, query: ShapeQuery<'a>) -> EditContext<'a> {
        EditContext {
            query,
            constraints: &self.constraints,
            fixed: &self.fixed,
            variables: &self.variables,
        }
    }
}
