//! `POST /v1/surfaces/tessellate`: a triangle mesh certified within a tolerance of the
//! surface, as JSON or binary glTF.

use axum::Extension;
use axum::extract::State;
use axum::http::header::CONTENT_TYPE;
use axum::response::{IntoResponse, Response};

use super::compute;
use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::wire::surface_mesh::{MeshFormat, TessellateRequest, TessellateResponse};
use crate::interchange::gltf::{GLTF_BINARY, to_glb};
use crate::surface::TessellationError;

/// Work estimated per control point of the surface (the cells of a fine mesh), in point
/// evaluations: a mesh of many triangles runs on the blocking pool.
const WORK_PER_CONTROL_POINT: usize = 64;

/// Mesh a surface.
///
/// A triangle mesh within `tolerance` of the surface both ways, certified by a bound on the
/// Bézier nets of its cells (docs/method.md), crack-free, with normals per vertex; as JSON, or
/// with `format: "gltf"` as binary glTF (`model/gltf-binary`).
#[utoipa::path(
    post,
    path = "/v1/surfaces/tessellate",
    operation_id = "surface_tessellate",
    tag = "surfaces",
    request_body = TessellateRequest,
    responses(
        (status = 200, description = "The mesh: JSON (the default), or with `format: \"gltf\"` binary glTF 2.0 of the same mesh", content(
            (TessellateResponse = "application/json"),
            (Vec<u8> = "model/gltf-binary"),
        )),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`): a tolerance below the floor, a mesh over the configured `max_triangles`, a surface that jumps", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn tessellate(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<TessellateRequest>,
) -> Result<Response, ApiError> {
    let (limits, surface_limits) = (state.limits, state.surface_limits);
    let poles: usize = request.surface.control_points.iter().map(Vec::len).sum();
    let work = poles.saturating_mul(WORK_PER_CONTROL_POINT);
    let format = request.format;
    let mesh = compute(admission, work, move || {
        let surface = request.surface.parse(&surface_limits, "/surface")?;
        if request.tolerance.is_nan() || request.tolerance <= 0.0 {
            return Err(ApiError::invalid(
                "/tolerance",
                "`tolerance` must be greater than 0",
            ));
        }
        surface
            .tessellate(request.tolerance, limits.max_triangles)
            .map_err(|error| match error {
                TessellationError::Discontinuous { direction, .. } => ApiError::invalid(
                    JsonPointer::from("/surface").push(format!("knots_{}", direction.name())),
                    error.to_string(),
                ),
                _ => ApiError::invalid("/tolerance", error.to_string()),
            })
    })
    .await?;
    Ok(match format {
        MeshFormat::Json => ApiJson(TessellateResponse::from_core(mesh)).into_response(),
        MeshFormat::Gltf => ([(CONTENT_TYPE, GLTF_BINARY)], to_glb(&mesh)).into_response(),
    })
}
