//! `POST /v1/curves/import` and `POST /v1/curves/export`: B-spline curves from and to STEP
//! and DXF files, B-spline surfaces from and to STEP files ([`crate::interchange`]).

use axum::Extension;
use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};

use super::compute;
use crate::config::Limits;
use crate::http::curve::CurveBody;
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::surface::SurfaceBody;
use crate::http::wire::files::{
    ExportRequest, FileFormat, ImportRequest, ImportResponse, ImportedCurveBody,
    ImportedSurfaceBody,
};
use crate::interchange::{self, FileError, FileLimits};
use crate::spline::CurveLimits;
use crate::surface::SurfaceLimits;

/// Import curves from a file.
///
/// Every B-spline curve of a STEP or DXF file and every B-spline surface of a STEP file, each
/// with the entity it came from; the other curve and surface entities are counted in
/// `skipped`. A malformed or truncated file is a 422 as a whole.
#[utoipa::path(
    post,
    path = "/v1/curves/import",
    tag = "curves",
    request_body = ImportRequest,
    responses(
        (status = 200, description = "The file's B-spline curves and surfaces", body = ImportResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "The file is too large, malformed, or a curve or surface in it breaks a rule (see `errors`, at `/data`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn import(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ImportRequest>,
) -> Result<ApiJson<ImportResponse>, ApiError> {
    let limits = file_limits(&state.limits, &state.curve_limits, &state.surface_limits);
    let work = request.data.len();
    compute(admission, work, move || import_request(&request, &limits))
        .await
        .map(ApiJson)
}

/// The file limits of the service's limits.
fn file_limits(
    limits: &Limits,
    curve_limits: &CurveLimits,
    surface_limits: &SurfaceLimits,
) -> FileLimits {
    FileLimits {
        max_bytes: limits.max_file_bytes,
        max_entities: limits.max_file_entities,
        curve_limits: *curve_limits,
        surface_limits: *surface_limits,
    }
}

fn import_request(
    request: &ImportRequest,
    limits: &FileLimits,
) -> Result<ImportResponse, ApiError> {
    let imported = match request.format {
        FileFormat::Step => interchange::step::read(&request.data, limits),
        FileFormat::Dxf => interchange::dxf::read(&request.data, limits),
    }
    .map_err(|error| file_error(&error))?;
    Ok(ImportResponse {
        curves: imported
            .curves
            .into_iter()
            .map(|found| ImportedCurveBody::new(CurveBody::from_curve(&found.curve), found.source))
            .collect(),
        surfaces: imported
            .surfaces
            .into_iter()
            .map(|found| {
                ImportedSurfaceBody::new(SurfaceBody::from_surface(&found.surface), found.source)
            })
            .collect(),
        skipped: imported.skipped,
    })
}

/// The 422 of a file that cannot be read.
fn file_error(error: &FileError) -> ApiError {
    let what = match error {
        FileError::TooLarge { .. } | FileError::TooManyEntities { .. } => "",
        FileError::TooDeep { .. } | FileError::Malformed { .. } => "malformed file: ",
        FileError::InvalidCurve { .. } => "a curve of the file breaks a rule: ",
        FileError::InvalidSurface { .. } => "a surface of the file breaks a rule: ",
    };
    ApiError::invalid("/data", format!("{what}{error}"))
}

/// Export curves and surfaces to a file.
///
/// A STEP file (`model/step`: the curves in a wireframe shape representation that Open
/// CASCADE's `STEPControl_Reader` transfers, with surfaces curves and surfaces in a geometric
/// set of a surface shape representation, numbers in full precision, 2D curves with
/// `z = 0`) or a DXF file (`image/vnd.dxf`, R2000: one `SPLINE` per curve with the full knot
/// vector, `z = 0` for 2D curves, weights for rational curves).
#[utoipa::path(
    post,
    path = "/v1/curves/export",
    tag = "curves",
    request_body = ExportRequest,
    responses(
        (status = 200, description = "The file", content(
            (String = "model/step"),
            (String = "image/vnd.dxf"),
        )),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn export(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ExportRequest>,
) -> Result<Response, ApiError> {
    let (limits, curve_limits, surface_limits) =
        (state.limits, state.curve_limits, state.surface_limits);
    let work = request
        .curves
        .iter()
        .map(|curve| curve.control_points.len())
        .chain(
            request
                .surfaces
                .iter()
                .flat_map(|surface| surface.control_points.iter().map(Vec::len)),
        )
        .fold(0usize, usize::saturating_add);
    compute(admission, work, move || {
        export_request(&request, &limits, &curve_limits, &surface_limits)
    })
    .await
}

fn export_request(
    request: &ExportRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
    surface_limits: &SurfaceLimits,
) -> Result<Response, ApiError> {
    if request.curves.is_empty() && request.surfaces.is_empty() {
        return Err(ApiError::invalid(
            "/curves",
            "give at least one curve or surface",
        ));
    }
    if !request.surfaces.is_empty() && request.format == FileFormat::Dxf {
        return Err(ApiError::invalid(
            "/surfaces",
            "DXF has no B-spline surfaces: export surfaces as STEP",
        ));
    }
    for (field, count) in [
        ("/curves", request.curves.len()),
        ("/surfaces", request.surfaces.len()),
    ] {
        if count > limits.max_file_entities {
            return Err(ApiError::invalid(
                field,
                format!(
                    "{count} {} exceed the limit of {}",
                    &field[1..],
                    limits.max_file_entities
                ),
            ));
        }
    }
    let mut errors: Vec<FieldError> = Vec::new();
    let mut curves = Vec::with_capacity(request.curves.len());
    for (index, body) in request.curves.iter().enumerate() {
        let at = JsonPointer::from("/curves").push(index).to_string();
        if let Some(curve) = body.parse_collecting_allowing_periodic(curve_limits, &at, &mut errors)
        {
            curves.push(curve);
        }
        if errors.len() >= MAX_LISTED_ERRORS {
            break;
        }
    }
    let mut surfaces = Vec::with_capacity(request.surfaces.len());
    for (index, body) in request.surfaces.iter().enumerate() {
        if errors.len() >= MAX_LISTED_ERRORS {
            break;
        }
        let at = JsonPointer::from("/surfaces").push(index).to_string();
        if let Some(surface) = body.parse_collecting(surface_limits, &at, &mut errors) {
            surfaces.push(surface);
        }
    }
    if !errors.is_empty() {
        return Err(ApiError::Invalid(errors));
    }
    let (text, content_type) = match request.format {
        FileFormat::Step => (interchange::step::write(&curves, &surfaces), "model/step"),
        FileFormat::Dxf => (interchange::dxf::write(&curves), "image/vnd.dxf"),
    };
    Ok(([(header::CONTENT_TYPE, content_type)], text).into_response())
}

/// Largest number of curve and surface errors listed in one 422.
const MAX_LISTED_ERRORS: usize = 20;
