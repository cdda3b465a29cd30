//! `POST /v1/surfaces/iso-curve`, `/v1/surfaces/insert-knots` and `/v1/surfaces/split`: the
//! curves a surface is made of, and the same surface written otherwise.

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::http::curve::CurveBody;
use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::surface::SurfaceBody;
use crate::http::wire::surface_toolkit::{
    IsoCurveRequest, IsoCurveResponse, SurfaceInsertKnotsRequest, SurfaceInsertKnotsResponse,
    SurfaceSplitRequest, SurfaceSplitResponse,
};
use crate::surface::{SurfaceInsertError, SurfaceSplitError};

/// Most control points the pieces of one split may have together, in multiples of the
/// configured `max_surface_control_points`.
pub const SPLIT_OUTPUT_FACTOR: usize = 4;

/// The poles of a wire surface (for the work estimates).
fn poles(surface: &SurfaceBody) -> usize {
    surface.control_points.iter().map(Vec::len).sum()
}

/// The iso-curve of a surface.
///
/// The curve `u ↦ S(u, ṽ)` (`fixed: "v"`) or `v ↦ S(ũ, v)` (`fixed: "u"`) as a curve object
/// that every curve endpoint takes.
#[utoipa::path(
    post,
    path = "/v1/surfaces/iso-curve",
    operation_id = "surface_iso_curve",
    tag = "surfaces",
    request_body = IsoCurveRequest,
    responses(
        (status = 200, description = "The iso-curve", body = IsoCurveResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn iso_curve(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<IsoCurveRequest>,
) -> Result<ApiJson<IsoCurveResponse>, ApiError> {
    let surface_limits = state.surface_limits;
    let work = poles(&request.surface).saturating_mul(4);
    compute(admission, work, move || {
        let surface = request.surface.parse(&surface_limits, "/surface")?;
        let fixed = request.fixed.direction();
        let axis = surface.axis(fixed);
        let parameter = axis.snap(request.parameter).ok_or_else(|| {
            let (lo, hi) = axis.domain();
            ApiError::invalid(
                "/parameter",
                format!(
                    "{} = {} lies outside the domain [{lo}, {hi}]",
                    fixed.name(),
                    request.parameter
                ),
            )
        })?;
        Ok(IsoCurveResponse {
            parameter,
            curve: CurveBody::from_curve(&surface.iso_curve(fixed, parameter)),
        })
    })
    .await
    .map(ApiJson)
}

/// Insert knots into a surface.
///
/// The same surface with knots inserted in `u` and/or `v` (Boehm's insertion on every curve
/// along that direction: same shape, more control points).
#[utoipa::path(
    post,
    path = "/v1/surfaces/insert-knots",
    operation_id = "surface_insert_knots",
    tag = "surfaces",
    request_body = SurfaceInsertKnotsRequest,
    responses(
        (status = 200, description = "The refined surface", body = SurfaceInsertKnotsResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn insert_knots(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<SurfaceInsertKnotsRequest>,
) -> Result<ApiJson<SurfaceInsertKnotsResponse>, ApiError> {
    let surface_limits = state.surface_limits;
    let inserted = request.knots_u.len().saturating_add(request.knots_v.len());
    let work = poles(&request.surface).saturating_mul(inserted.saturating_add(1));
    compute(admission, work, move || {
        let surface = request.surface.parse(&surface_limits, "/surface")?;
        let refined = surface
            .insert_knots(
                &request.knots_u,
                &request.knots_v,
                surface_limits.max_control_points,
            )
            .map_err(|error| match &error {
                SurfaceInsertError::Value {
                    direction,
                    error: inner,
                } => {
                    let list = JsonPointer::root().push(format!("knots_{}", direction.name()));
                    let pointer = match inner.index() {
                        Some(index) => list.push(index),
                        None => list,
                    };
                    ApiError::invalid(pointer, error.to_string())
                }
                SurfaceInsertError::TooManyControlPoints { .. } => {
                    ApiError::invalid("/surface/control_points", error.to_string())
                }
            })?;
        Ok(SurfaceInsertKnotsResponse {
            surface: SurfaceBody::from_surface(&refined),
        })
    })
    .await
    .map(ApiJson)
}

/// Split a surface.
///
/// Clamped pieces between the given `u` (or `v`) values, together equal to the surface.
#[utoipa::path(
    post,
    path = "/v1/surfaces/split",
    operation_id = "surface_split",
    tag = "surfaces",
    request_body = SurfaceSplitRequest,
    responses(
        (status = 200, description = "The pieces, in order", body = SurfaceSplitResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn split(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<SurfaceSplitRequest>,
) -> Result<ApiJson<SurfaceSplitResponse>, ApiError> {
    let (limits, surface_limits) = (state.limits, state.surface_limits);
    let work = poles(&request.surface).saturating_mul(request.parameters.len().saturating_add(2));
    compute(admission, work, move || {
        let surface = request.surface.parse(&surface_limits, "/surface")?;
        let pieces = surface
            .split(
                request.fixed.direction(),
                &request.parameters,
                limits.max_parameters,
                surface_limits
                    .max_control_points
                    .saturating_mul(SPLIT_OUTPUT_FACTOR),
            )
            .map_err(|error| match &error {
                SurfaceSplitError::Value(inner) => {
                    let list = JsonPointer::from("/parameters");
                    let pointer = match inner.index() {
                        Some(index) => list.push(index),
                        None => list,
                    };
                    ApiError::invalid(pointer, error.to_string())
                }
                SurfaceSplitError::TooManyControlPoints { .. } => {
                    ApiError::invalid("/parameters", error.to_string())
                }
            })?;
        Ok(SurfaceSplitResponse {
            surfaces: pieces.iter().map(SurfaceBody::from_surface).collect(),
        })
    })
    .await
    .map(ApiJson)
}
