//! `POST /v1/surfaces/evaluate`: points, partials, normals and curvature of a surface.

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::config::Limits;
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::{ApiJson, JsonWithNulls};
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::wire::surfaces::{CurvatureBody, SurfaceEvaluateRequest, SurfaceEvaluateResponse};
use crate::surface::{
    Inward, MAX_PARTIAL_ORDER, NormalKind, Surface, SurfaceLimits, curvature, unit_normal,
};

/// Largest number of out-of-domain parameters listed in one 422.
const MAX_LISTED_PARAMETER_ERRORS: usize = 20;

/// Evaluate a surface.
///
/// Points, partial derivatives up to order 2, unit normals and curvature at the given
/// parameter pairs or on a uniform grid, as exact as de Boor's algorithm.
#[utoipa::path(
    post,
    path = "/v1/surfaces/evaluate",
    operation_id = "surface_evaluate",
    tag = "surfaces",
    request_body = SurfaceEvaluateRequest,
    responses(
        (status = 200, description = "Points (and partials, normals, curvature) of the surface", body = SurfaceEvaluateResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn evaluate(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<SurfaceEvaluateRequest>,
) -> Result<JsonWithNulls<SurfaceEvaluateResponse>, ApiError> {
    let (limits, surface_limits) = (state.limits, state.surface_limits);
    let count = match (&request.parameters, request.samples) {
        (Some(parameters), _) => parameters.len(),
        (None, Some([n_u, n_v])) => n_u.saturating_mul(n_v),
        (None, None) => 0,
    };
    let degree = |d: usize| d.clamp(1, 16).saturating_add(1);
    let per_point = degree(request.surface.degree_u) * degree(request.surface.degree_v) * 3;
    let poles: usize = request.surface.control_points.iter().map(Vec::len).sum();
    let work = poles.saturating_add(count.saturating_mul(per_point));
    compute(admission, work, move || {
        evaluate_request(&request, &limits, &surface_limits)
    })
    .await
    .map(JsonWithNulls)
}

fn evaluate_request(
    request: &SurfaceEvaluateRequest,
    limits: &Limits,
    surface_limits: &SurfaceLimits,
) -> Result<SurfaceEvaluateResponse, ApiError> {
    let mut errors = Vec::new();
    let surface = request
        .surface
        .parse_collecting(surface_limits, "/surface", &mut errors);
    match (&request.parameters, request.samples) {
        (Some(_), Some(_)) => errors.push(FieldError::new(
            "/samples",
            "give either `parameters` or `samples`, not both",
        )),
        (None, None) => errors.push(FieldError::new(
            "",
            "give `parameters` (a list of [u, v]) or `samples` (a grid [n_u, n_v])",
        )),
        (Some(parameters), None) if parameters.len() > limits.max_parameters => {
            errors.push(FieldError::new(
                "/parameters",
                format!(
                    "{} parameter pairs exceed the limit of {}",
                    parameters.len(),
                    limits.max_parameters
                ),
            ));
        }
        (None, Some([n_u, n_v])) => {
            for (index, n) in [n_u, n_v].into_iter().enumerate() {
                if n < 2 {
                    errors.push(FieldError::new(
                        JsonPointer::from("/samples").push(index),
                        "each grid count must be at least 2 (both ends of the domain)",
                    ));
                }
            }
            if n_u.saturating_mul(n_v) > limits.max_parameters {
                errors.push(FieldError::new(
                    "/samples",
                    format!(
                        "a grid of {n_u} × {n_v} points exceeds the limit of {}",
                        limits.max_parameters
                    ),
                ));
            }
        }
        (Some(_), None) => {}
    }
    if request.derivatives > MAX_PARTIAL_ORDER {
        errors.push(FieldError::new(
            "/derivatives",
            format!(
                "derivative order {} is not offered: 0, 1 or {MAX_PARTIAL_ORDER}",
                request.derivatives
            ),
        ));
    }
    let (Some(surface), true) = (surface, errors.is_empty()) else {
        return Err(ApiError::Invalid(errors));
    };
    let parameters = match (&request.parameters, request.samples) {
        (Some(parameters), _) => snapped_into_domain(&surface, parameters)?,
        (None, Some([n_u, n_v])) => grid(&surface, n_u, n_v),
        (None, None) => Vec::new(),
    };
    let response = evaluate_at(&surface, parameters, request);
    if !response_is_finite(&response) {
        return Err(ApiError::invalid(
            "/surface",
            "the result is not finite: the surface's coordinates or weights are too extreme for \
             double precision",
        ));
    }
    Ok(response)
}

/// The parameter pairs with values just outside the domain snapped onto its ends (periodic
/// directions reduced into the period); a 422 listing (up to a bound) every value farther out.
fn snapped_into_domain(
    surface: &Surface,
    parameters: &[[f64; 2]],
) -> Result<Vec<[f64; 2]>, ApiError> {
    let mut snapped = Vec::with_capacity(parameters.len());
    let mut errors = Vec::new();
    for (index, &[u, v]) in parameters.iter().enumerate() {
        let pair = [surface.u().snap(u), surface.v().snap(v)];
        for (coordinate, (value, axis)) in
            [(u, surface.u()), (v, surface.v())].into_iter().enumerate()
        {
            if pair[coordinate].is_none() && errors.len() < MAX_LISTED_PARAMETER_ERRORS {
                let (lo, hi) = axis.domain();
                let name = if coordinate == 0 { "u" } else { "v" };
                errors.push(FieldError::new(
                    JsonPointer::from("/parameters")
                        .push(index)
                        .push(coordinate),
                    format!("{name} = {value} lies outside the domain [{lo}, {hi}]"),
                ));
            }
        }
        if let [Some(u), Some(v)] = pair {
            snapped.push([u, v]);
        }
    }
    if errors.is_empty() {
        Ok(snapped)
    } else {
        Err(ApiError::Invalid(errors))
    }
}

/// The uniform grid, row by row (`u` outer), both ends exact.
fn grid(surface: &Surface, n_u: usize, n_v: usize) -> Vec<[f64; 2]> {
    let spaced = |(lo, hi): (f64, f64), n: usize| -> Vec<f64> {
        let step = (hi - lo) / (n - 1) as f64;
        (0..n)
            .map(|i| if i + 1 == n { hi } else { i as f64 * step + lo })
            .collect()
    };
    let (us, vs) = (
        spaced(surface.u().domain(), n_u),
        spaced(surface.v().domain(), n_v),
    );
    us.iter()
        .flat_map(|&u| vs.iter().map(move |&v| [u, v]))
        .collect()
}

/// Evaluates validated, in-domain parameter pairs.
fn evaluate_at(
    surface: &Surface,
    parameters: Vec<[f64; 2]>,
    request: &SurfaceEvaluateRequest,
) -> SurfaceEvaluateResponse {
    let geometry = request.normals || request.curvature;
    let order = if geometry {
        MAX_PARTIAL_ORDER
    } else {
        request.derivatives
    };
    let count = parameters.len();
    let mut points = Vec::with_capacity(count);
    let mut partials =
        [(); 5].map(|()| Vec::with_capacity(if request.derivatives > 0 { count } else { 0 }));
    let mut normals = Vec::with_capacity(if request.normals { count } else { 0 });
    let mut limit_normals = Vec::new();
    let mut curvatures = Vec::with_capacity(if request.curvature { count } else { 0 });
    let [(u_lo, u_hi), (v_lo, v_hi)] = surface.domain();
    let inward = |t: f64, hi: f64, periodic: bool| {
        if periodic {
            Inward::Up
        } else {
            Inward::of(t, hi)
        }
    };
    for (index, &[u, v]) in parameters.iter().enumerate() {
        let values = surface.partials(u, v, order);
        points.push(values.point());
        if request.derivatives > 0 {
            let v = values.values;
            let wanted = [v[1][0], v[0][1], v[2][0], v[1][1], v[0][2]];
            let take = if request.derivatives >= 2 { 5 } else { 2 };
            for (list, value) in partials.iter_mut().zip(wanted).take(take) {
                list.push(value);
            }
        }
        if geometry {
            let direction = [
                inward(u, u_hi, surface.u().is_periodic()),
                inward(v, v_hi, surface.v().is_periodic()),
            ];
            let normal = unit_normal(&values, direction);
            if request.normals {
                if let Some((_, NormalKind::Limit)) = normal {
                    limit_normals.push(index);
                }
                normals.push(normal.map(|(n, _)| n));
            }
            if request.curvature {
                let found = normal
                    .filter(|&(_, kind)| kind == NormalKind::Regular)
                    .and_then(|(n, _)| curvature(&values, n));
                curvatures.push(found.map(|c| CurvatureBody {
                    gaussian: c.gaussian,
                    mean: c.mean,
                    principal: c.principal,
                    directions: c.directions,
                }));
            }
        }
    }
    let [du, dv, duu, duv, dvv] = partials;
    let first = request.derivatives >= 1;
    let second = request.derivatives >= 2;
    SurfaceEvaluateResponse {
        domain: [[u_lo, u_hi], [v_lo, v_hi]],
        parameters,
        points,
        du: first.then_some(du),
        dv: first.then_some(dv),
        duu: second.then_some(duu),
        duv: second.then_some(duv),
        dvv: second.then_some(dvv),
        normals: request.normals.then_some(normals),
        limit_normals: (!limit_normals.is_empty()).then_some(limit_normals),
        curvature: request.curvature.then_some(curvatures),
    }
}

/// Whether every number of the answer is finite.
fn response_is_finite(response: &SurfaceEvaluateResponse) -> bool {
    let finite = |points: &[[f64; 3]]| points.iter().flatten().all(|x| x.is_finite());
    let lists = [
        &response.du,
        &response.dv,
        &response.duu,
        &response.duv,
        &response.dvv,
    ];
    finite(&response.points)
        && lists.iter().all(|list| list.as_deref().is_none_or(finite))
        && response
            .normals
            .iter()
            .flatten()
            .flatten()
            .all(|n| n.iter().all(|x| x.is_finite()))
        && response.curvature.iter().flatten().flatten().all(|c| {
            c.gaussian.is_finite()
                && c.mean.is_finite()
                && c.principal.iter().all(|x| x.is_finite())
                && c.directions.iter().flatten().all(|x| x.is_finite())
        })
}
