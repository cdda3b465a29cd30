//! Wire types of `POST /v1/surfaces/shape/solve` and `/v1/surfaces/shape/regions`: moving a
//! surface point by control points or weights under constraints (docs/method.md §41–§44).
//! Their validation and the answers' conversion live in [`super::surface_edit_parse`].

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::surface::SurfaceBody;

/// A way to move the picked surface point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("control_points"))]
pub enum SurfaceMethod {
    /// Knots in `u`, `v` or both (not offered yet: a request for it is answered in
    /// `excluded`).
    Knots,
    /// The least-norm move of the free control points that meets the target and every
    /// constraint; without constraints
    /// `Δd_ij = R_ij(u, v) / Σ_kl R_kl(u, v)² · (target − S(u, v))`.
    ControlPoints,
    /// Three weights of the poles active at `(u, v)`, in closed form: reaches targets inside
    /// the tetrahedron of the three poles and the point `s₀` of the others.
    Weights,
}

/// The value a constraint prescribes: one point (order 0) or the two first partials
/// `[S_u, S_v]` (order 1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(untagged)]
#[schema(example = json!([[1, 0, 0.5], [0, 1, 0]]))]
pub enum SurfaceConstraintValue {
    /// Order 0: `[x, y, z]`.
    Point(Vec<f64>),
    /// Order 1: `[[S_u], [S_v]]`, two 3D vectors.
    Partials(Vec<Vec<f64>>),
}

/// A condition every solution keeps at a parameter pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"parameter": [0.2, 0.8], "order": 1}))]
pub struct SurfaceConstraintBody {
    /// `[u, v]` inside the domain (just outside: the nearer end; periodic: reduced into the
    /// period). An order-0 constraint may not sit at the picked `parameter`.
    pub parameter: [f64; 2],
    /// 0: the point; 1: both first partials `S_u` and `S_v` (the tangent plane and the
    /// parametrisation along it).
    #[schema(minimum = 0, maximum = 1, example = 0)]
    pub order: u64,
    /// The value to take: `[x, y, z]` for order 0, `[[S_u], [S_v]]` for order 1; without it
    /// the quantity keeps its current value (a pin).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<SurfaceConstraintValue>,
}

/// Move the surface point `S(parameter)` onto `target`.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 2, "degree_v": 2,
                "control_points": [[[0, 0, 0], [0, 1, 0], [0, 2, 0]],
                                   [[1, 0, 0], [1, 1, 1], [1, 2, 0]],
                                   [[2, 0, 0], [2, 1, 0], [2, 2, 0]]],
                "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1]},
    "parameter": [0.5, 0.5],
    "target": [1, 1, 0.8],
    "methods": ["control_points", "weights"],
    "keep_boundary": true
}))]
pub struct SurfaceShapeRequest {
    /// The surface.
    pub surface: SurfaceBody,
    /// The picked `[u, v]`, inside the domain (as a constraint's `parameter`).
    pub parameter: [f64; 2],
    /// Where `S(u, v)` should go: three finite coordinates.
    #[schema(example = json!([1, 1, 0.8]))]
    pub target: Vec<f64>,
    /// Which methods to use: `"knots"`, `"control_points"`, `"weights"`, each at most once
    /// (default: all). A method this version does not offer is answered in `excluded`.
    #[serde(default)]
    #[schema(example = json!(["control_points", "weights"]))]
    pub methods: Option<Vec<String>>,
    /// Conditions every solution keeps (at most 32).
    #[serde(default)]
    pub constraints: Option<Vec<SurfaceConstraintBody>>,
    /// Control points `[i, j]` (the caller's indices) that no solution moves or reweights.
    #[serde(default)]
    #[schema(example = json!([[0, 0]]))]
    pub fixed_control_points: Option<Vec<[usize; 2]>>,
    /// Keep every control point of the four boundary rows and columns (of each non-periodic
    /// direction), so that faces sharing those edges stay attached (default `false`).
    #[serde(default)]
    pub keep_boundary: bool,
    /// For the knot method: keep the domain (default `false`).
    #[serde(default)]
    pub keep_domain: bool,
    /// When no method reaches the target, answer the nearest point the weights reach with its
    /// solutions (default `false`).
    #[serde(default)]
    pub nearest: bool,
}

/// The regions of the methods at `S(parameter)`, for drawing.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 2, "degree_v": 2,
                "control_points": [[[0, 0, 0], [0, 1, 0], [0, 2, 0]],
                                   [[1, 0, 0], [1, 1, 1], [1, 2, 0]],
                                   [[2, 0, 0], [2, 1, 0], [2, 2, 0]]],
                "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1]},
    "parameter": [0.5, 0.5],
    "methods": ["weights"]
}))]
pub struct SurfaceRegionsRequest {
    /// The surface.
    pub surface: SurfaceBody,
    /// The picked `[u, v]`.
    pub parameter: [f64; 2],
    /// Which methods (default: all).
    #[serde(default)]
    pub methods: Option<Vec<String>>,
    /// Control points `[i, j]` that no solution may change (their triples are left out).
    #[serde(default)]
    pub fixed_control_points: Option<Vec<[usize; 2]>>,
    /// Keep the boundary rows and columns (as in solve).
    #[serde(default)]
    pub keep_boundary: bool,
    /// For the knot method: keep the domain.
    #[serde(default)]
    pub keep_domain: bool,
}

/// One way to move the point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "control_points", "point": [1, 1, 0.8], "residual": 0.0,
    "affected_domain": [[0, 1], [0, 1]], "max_deviation": 0.35, "conditioning": 1.0,
    "changed_control_points": [[1, 1]], "displacement_norm": 0.8,
    "control_points": [[[0, 0, 0], [0, 1, 0], [0, 2, 0]], [[1, 0, 0], [1, 1, 1.8], [1, 2, 0]],
                       [[2, 0, 0], [2, 1, 0], [2, 2, 0]]]}))]
pub struct SurfaceSolutionBody {
    /// The method.
    pub method: SurfaceMethod,
    /// The new surface's point at `parameter`.
    pub point: [f64; 3],
    /// `|point − target|` (within `1e-9` of the surface's size).
    pub residual: f64,
    /// `[[u0, u1], [v0, v1]]`: outside it the new surface equals the old one.
    pub affected_domain: [[f64; 2]; 2],
    /// The largest distance between the old and the new surface, certified by Bernstein
    /// bounds per patch (never below the true maximum, its square within `1e-3` relative of the maximum's).
    pub max_deviation: f64,
    /// How well the solution is determined, in `(0, 1]`: 1 for the control-point move; for
    /// weights `6 V / (e₁ e₂ e₃)` of the tetrahedron's edges from `s₀`. Orders ties.
    pub conditioning: f64,
    /// Control points: the caller's `[i, j]` of the poles that moved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub changed_control_points: Option<Vec<[usize; 2]>>,
    /// Control points: `sqrt(Σ |Δd_ij|²)`, the norm the move minimises.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub displacement_norm: Option<f64>,
    /// Control points: the whole new net, `control_points[i][j]` as sent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control_points: Option<Vec<Vec<[f64; 3]>>>,
    /// Weights: the caller's `[i, j]` of the three poles whose weights changed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub changed_weights: Option<Vec<[usize; 2]>>,
    /// Weights: the tetrahedron `[s₀, d_a, d_b, d_c]` that holds the target.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tetrahedron: Option<[[f64; 3]; 4]>,
    /// Weights: every new weight, `weights[i][j]` as sent (a non-rational surface becomes
    /// rational).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<Vec<f64>>>,
    /// Knots: the family (`iso_u_envelope`, `iso_u_direct`, `iso_u_triples`, the same in `v`,
    /// or `mixed`: knots in both directions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family: Option<String>,
    /// Knots: the knot set, named for people.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<String>,
    /// Knots: the new `u`-knots in the caller's convention, when they changed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub knots_u: Option<Vec<f64>>,
    /// Knots: the new `v`-knots in the caller's convention, when they changed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub knots_v: Option<Vec<f64>>,
    /// Knots: the multiplicities of `knots_u`, when the surface was sent with them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicities_u: Option<Vec<usize>>,
    /// Knots: the multiplicities of `knots_v`, when the surface was sent with them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicities_v: Option<Vec<usize>>,
    /// Knots: indices (caller's convention; the full vector when sent with multiplicities)
    /// of the changed `u`-knots, ascending.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub changed_knots_u: Option<Vec<usize>>,
    /// Knots: the same for `v`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub changed_knots_v: Option<Vec<usize>>,
}

/// One knot family's region: a polygon in the plane of the control points acting.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"family": "iso_u_envelope", "region": "u envelope right: u_7 := ũ; u_5, u_9 (Omega5)",
    "rings": [[[1.0, 2.0, 0.5], [1.5, 2.0, 0.5], [1.2, 2.4, 0.6], [1.0, 2.0, 0.5]]], "folded": false}))]
pub struct SurfaceKnotRegionBody {
    /// The family (`iso_u_envelope`, …).
    pub family: String,
    /// The knot set, named for people.
    pub region: String,
    /// Closed rings (first vertex repeated last): each outer ring, then its holes.
    pub rings: Vec<Vec<[f64; 3]>>,
    /// Whether the set's map folds (the outline then follows fold curves too).
    pub folded: bool,
}

/// Solutions a method dropped, or why it has none.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "weights", "count": 3,
    "reason": "it changes control point [0, 0], which is fixed", "fixed_control_point": [0, 0]}))]
pub struct SurfaceExclusionBody {
    /// The method.
    pub method: SurfaceMethod,
    /// How many solutions were dropped (1 for a method without any).
    pub count: usize,
    /// Why, in words.
    pub reason: String,
    /// The constraint it is about, when one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub constraint: Option<usize>,
    /// The fixed control point a dropped solution would change.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed_control_point: Option<[usize; 2]>,
}

/// The nearest reachable point, when nothing reaches the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"point": [1.2, 1.1, 0.9], "distance": 0.4, "solutions": []}))]
pub struct SurfaceNearestBody {
    /// The point.
    pub point: [f64; 3],
    /// Its distance from the target.
    pub distance: f64,
    /// The solutions reaching it, ranked.
    pub solutions: Vec<SurfaceSolutionBody>,
}

/// Every solution, ranked by `max_deviation` across methods.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"reachable": true, "solutions": [{"method": "control_points",
    "point": [1, 1, 0.8], "residual": 0.0, "affected_domain": [[0, 1], [0, 1]],
    "max_deviation": 0.35, "conditioning": 1.0, "changed_control_points": [[1, 1]],
    "displacement_norm": 0.8}], "excluded": []}))]
pub struct SurfaceSolveResponse {
    /// Whether some solution reaches the target.
    pub reachable: bool,
    /// The solutions, smallest `max_deviation` first (ties: better conditioned first).
    pub solutions: Vec<SurfaceSolutionBody>,
    /// With `nearest` and no solution: the nearest point the weights reach.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nearest: Option<SurfaceNearestBody>,
    /// What was dropped, per method and reason.
    pub excluded: Vec<SurfaceExclusionBody>,
}

/// A weight triple's region: the tetrahedron of its three poles and `s₀`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"poles": [[1, 1], [1, 2], [2, 1]],
    "tetrahedron": [[1, 1, 0.1], [1, 1, 1], [1, 2, 0], [2, 1, 0]]}))]
pub struct TetrahedronBody {
    /// The caller's `[i, j]` of the three poles.
    pub poles: [[usize; 2]; 3],
    /// `[s₀, d_a, d_b, d_c]`.
    pub tetrahedron: [[f64; 3]; 4],
}

/// What one method reaches.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "control_points", "everywhere": true}))]
pub struct SurfaceMethodRegionBody {
    /// The method.
    pub method: SurfaceMethod,
    /// True when it reaches every target (the control-point move).
    pub everywhere: bool,
    /// The weight triples' tetrahedra (the weight bounds cut them further near their faces).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tetrahedra: Option<Vec<TetrahedronBody>>,
    /// The knot families' planar regions (the mixed moves reach solids and are not drawn).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub knot_regions: Option<Vec<SurfaceKnotRegionBody>>,
    /// Why the method reaches nothing, when it does not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// The regions of the requested methods.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"point": [1, 1, 0.25],
    "methods": [{"method": "control_points", "everywhere": true}]}))]
pub struct SurfaceRegionsResponse {
    /// `S(parameter)`.
    pub point: [f64; 3],
    /// One entry per requested method, in the request's order.
    pub methods: Vec<SurfaceMethodRegionBody>,
}
