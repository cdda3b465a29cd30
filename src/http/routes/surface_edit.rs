//! `POST /v1/surfaces/shape/solve` and `/v1/surfaces/shape/regions`: the surface edit
//! (control points and weights under constraints; docs/method.md §41–§44) over the wire. Each
//! handler validates its request ([`parse_surface_edit`]), calls the core
//! ([`crate::surface::edit`]) and converts the answer.

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::surface::SurfaceBody;
use crate::http::wire::surface_edit::{
    SurfaceNearestBody, SurfaceRegionsRequest, SurfaceRegionsResponse, SurfaceShapeRequest,
    SurfaceSolveResponse,
};
use crate::http::wire::surface_edit_parse::{
    SurfaceEditFields, exclusion_body, parse_surface_edit, region_body, solution_body,
    solution_is_finite,
};
use crate::surface::edit::{
    SurfaceEditContext, SurfaceEditOptions, SurfaceEditRequest, surface_edit, surface_regions,
};

/// Point evaluations (roughly) the edit costs for `surface` with `constraints` rows: the net,
/// the control-point system (cubic in its rows, times the poles per row), the weight triples
/// of the active poles and the deviation's patches; large requests go to the blocking pool.
fn edit_work(surface: &SurfaceBody, constraints: usize) -> usize {
    let active = surface
        .degree_u
        .clamp(1, 16)
        .saturating_add(1)
        .saturating_mul(surface.degree_v.clamp(1, 16).saturating_add(1));
    let poles: usize = surface.control_points.iter().map(Vec::len).sum();
    let rows = 1 + 2 * constraints.min(64);
    poles
        .saturating_add(rows.pow(3).saturating_mul(active))
        .saturating_add(active.pow(3) / 6)
        .saturating_add(active.saturating_mul(200))
}

/// Move a surface point onto a target.
///
/// Every way the requested `methods` move `S(parameter)` onto `target`: the least-norm move
/// of the free control points, and new weights of three poles active there; each meets every
/// constraint and keeps the fixed poles, and all are sorted by the certified largest distance
/// between the old and the new surface. An unreachable target is a normal answer
/// (`reachable: false`, with `nearest` when asked).
#[utoipa::path(
    post,
    path = "/v1/surfaces/shape/solve",
    operation_id = "surface_shape_solve",
    tag = "surfaces",
    request_body = SurfaceShapeRequest,
    responses(
        (status = 200, description = "Solutions (possibly none)", body = SurfaceSolveResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn solve(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<SurfaceShapeRequest>,
) -> Result<ApiJson<SurfaceSolveResponse>, ApiError> {
    let surface_limits = state.surface_limits;
    let work = edit_work(
        &request.surface,
        request.constraints.as_ref().map_or(0, Vec::len),
    );
    compute(admission, work, move || {
        let mut errors = Vec::new();
        let target = parse_target(&request.target, &mut errors);
        let fields = SurfaceEditFields {
            surface: &request.surface,
            parameter: request.parameter,
            methods: request.methods.as_deref(),
            constraints: request.constraints.as_deref(),
            fixed: request.fixed_control_points.as_deref(),
            keep_boundary: request.keep_boundary,
        };
        let parsed = parse_surface_edit(&fields, &surface_limits, &mut errors);
        let (Some(parsed), Some(target), true) = (parsed, target, errors.is_empty()) else {
            return Err(ApiError::Invalid(errors));
        };
        let outcome = surface_edit(&SurfaceEditRequest {
            surface: &parsed.surface,
            parameter: parsed.parameter,
            target,
            methods: &parsed.methods,
            constraints: &parsed.constraints,
            fixed: &parsed.fixed,
            options: SurfaceEditOptions {
                nearest: request.nearest,
                keep_domain: request.keep_domain,
            },
        });
        let solutions: Vec<_> = outcome.solutions.iter().map(solution_body).collect();
        let nearest = outcome.nearest.as_ref().map(|nearest| SurfaceNearestBody {
            point: nearest.point,
            distance: nearest.distance,
            solutions: nearest.solutions.iter().map(solution_body).collect(),
        });
        let finite = solutions.iter().all(solution_is_finite)
            && nearest.as_ref().is_none_or(|n| {
                n.distance.is_finite() && n.solutions.iter().all(solution_is_finite)
            });
        if !finite {
            return Err(ApiError::non_finite_result());
        }
        Ok(ApiJson(SurfaceSolveResponse {
            reachable: !solutions.is_empty(),
            solutions,
            nearest,
            excluded: outcome.excluded.iter().map(exclusion_body).collect(),
        }))
    })
    .await
}

/// What the surface-edit methods reach, for drawing.
///
/// Per requested method at `S(parameter)`: the control-point move reaches every target (when
/// a free pole acts there); the weights reach the tetrahedra of each triple of poles active
/// there with the point `s₀` of the others (cut near their faces by the weight bounds).
#[utoipa::path(
    post,
    path = "/v1/surfaces/shape/regions",
    operation_id = "surface_shape_regions",
    tag = "surfaces",
    request_body = SurfaceRegionsRequest,
    responses(
        (status = 200, description = "The methods' reachable sets", body = SurfaceRegionsResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn regions(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<SurfaceRegionsRequest>,
) -> Result<ApiJson<SurfaceRegionsResponse>, ApiError> {
    let surface_limits = state.surface_limits;
    let work = edit_work(&request.surface, 0);
    compute(admission, work, move || {
        let mut errors = Vec::new();
        let fields = SurfaceEditFields {
            surface: &request.surface,
            parameter: request.parameter,
            methods: request.methods.as_deref(),
            constraints: None,
            fixed: request.fixed_control_points.as_deref(),
            keep_boundary: request.keep_boundary,
        };
        let parsed = parse_surface_edit(&fields, &surface_limits, &mut errors);
        let (Some(parsed), true) = (parsed, errors.is_empty()) else {
            return Err(ApiError::Invalid(errors));
        };
        let context = SurfaceEditContext {
            surface: &parsed.surface,
            parameter: parsed.parameter,
            constraints: &parsed.constraints,
            fixed: &parsed.fixed,
            keep_domain: request.keep_domain,
        };
        let point = parsed.surface.point(parsed.parameter.0, parsed.parameter.1);
        let methods: Vec<_> = surface_regions(&context, &parsed.methods)
            .iter()
            .map(|(kind, reachable)| region_body(*kind, reachable))
            .collect();
        let finite = point.iter().all(|x| x.is_finite())
            && methods
                .iter()
                .flat_map(|m| m.tetrahedra.iter().flatten())
                .all(|t| t.tetrahedron.iter().flatten().all(|x| x.is_finite()));
        if !finite {
            return Err(ApiError::non_finite_result());
        }
        Ok(ApiJson(SurfaceRegionsResponse { point, methods }))
    })
    .await
}

/// `target`: three finite coordinates.
fn parse_target(target: &[f64], errors: &mut Vec<FieldError>) -> Option<[f64; 3]> {
    if target.len() != 3 {
        errors.push(FieldError::new(
            "/target",
            format!(
                "the target is a 3D point [x, y, z], not {} coordinates",
                target.len()
            ),
        ));
        return None;
    }
    if let Some(c) = target.iter().position(|x| !x.is_finite()) {
        errors.push(FieldError::new(
            JsonPointer::from("/target").push(c),
            "the target's coordinates must be finite numbers",
        ));
        return None;
    }
    Some([target[0], target[1], target[2]])
}
