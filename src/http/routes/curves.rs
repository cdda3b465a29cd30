//! `POST /v1/curves/evaluate` (at given parameters, uniform samples or a certified polyline)
//! and `POST /v1/curves/envelope`.

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::config::Limits;
use crate::http::curve::{CurveBody, point_to_wire};
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::wire::curves::{
    EnvelopeRequest, EnvelopeResponse, EvaluateRequest, EvaluateResponse,
};
use crate::spline::{BatchEvaluator, Curve, CurveLimits, EnvelopeError, Point};

/// Largest number of out-of-domain parameters listed in one 422.
const MAX_LISTED_PARAMETER_ERRORS: usize = 20;

/// Evaluate a curve.
///
/// Points, and derivatives up to `derivatives`, at the given `parameters`, at `samples`
/// uniform parameters over the whole domain, or at the vertices of a polyline within
/// `tolerance` of the curve.
#[utoipa::path(
    post,
    path = "/v1/curves/evaluate",
    tag = "curves",
    request_body = EvaluateRequest,
    responses(
        (status = 200, description = "Points (and derivatives) of the curve", body = EvaluateResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn evaluate(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<EvaluateRequest>,
) -> Result<ApiJson<EvaluateResponse>, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    let points = match (&request.parameters, request.samples, request.tolerance) {
        (Some(parameters), _, _) => parameters.len(),
        (None, Some(samples), _) => samples,
        // A polyline may take up to the limit, each point a split of degree² blends.
        (None, None, Some(_)) => limits
            .max_parameters
            .saturating_mul(request.curve.degree.saturating_add(1)),
        (None, None, None) => 0,
    };
    let orders = request
        .derivatives
        .saturating_add(1)
        .saturating_add(3 * usize::from(request.curvature));
    let work = request.curve.control_points.len() + points.saturating_mul(orders);
    compute(admission, work, move || {
        evaluate_request(&request, &limits, &curve_limits)
    })
    .await
    .map(ApiJson)
}

/// Where the parameters come from, once validated.
enum ParameterSource<'a> {
    Given(&'a [f64]),
    Uniform(usize),
    Polyline(f64),
}

fn evaluate_request(
    request: &EvaluateRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<EvaluateResponse, ApiError> {
    let mut errors = Vec::new();
    let curve =
        request
            .curve
            .parse_collecting_allowing_periodic(curve_limits, "/curve", &mut errors);
    let source = match (&request.parameters, request.samples, request.tolerance) {
        (Some(_), _, Some(_)) | (_, Some(_), Some(_)) => {
            errors.push(FieldError::new(
                "/tolerance",
                "give one of `parameters`, `samples` and `tolerance`, not several",
            ));
            None
        }
        (None, None, Some(tolerance)) if tolerance.is_nan() || tolerance <= 0.0 => {
            errors.push(FieldError::new(
                "/tolerance",
                "`tolerance` must be greater than 0",
            ));
            None
        }
        (None, None, Some(tolerance)) => Some(ParameterSource::Polyline(tolerance)),
        (Some(_), Some(_), None) => {
            errors.push(FieldError::new(
                "/samples",
                "give either `parameters` or `samples`, not both",
            ));
            None
        }
        (None, None, None) => {
            errors.push(FieldError::new(
                "",
                "give one of `parameters` (a list), `samples` (a count) or `tolerance` (a distance)",
            ));
            None
        }
        (Some(parameters), None, None) if parameters.len() > limits.max_parameters => {
            errors.push(FieldError::new(
                "/parameters",
                format!(
                    "{} parameters exceed the limit of {}",
                    parameters.len(),
                    limits.max_parameters
                ),
            ));
            None
        }
        (Some(parameters), None, None) => Some(ParameterSource::Given(parameters)),
        (None, Some(samples), None) if samples < 2 => {
            errors.push(FieldError::new("/samples", "`samples` must be at least 2"));
            None
        }
        (None, Some(samples), None) if samples > limits.max_parameters => {
            errors.push(FieldError::new(
                "/samples",
                format!(
                    "{samples} samples exceed the limit of {}",
                    limits.max_parameters
                ),
            ));
            None
        }
        (None, Some(samples), None) => Some(ParameterSource::Uniform(samples)),
    };
    if request.derivatives > limits.max_derivative_order {
        errors.push(FieldError::new(
            "/derivatives",
            format!(
                "derivative order {} exceeds the limit of {}",
                request.derivatives, limits.max_derivative_order
            ),
        ));
    }
    let (Some(curve), Some(source), true) = (curve, source, errors.is_empty()) else {
        return Err(ApiError::Invalid(errors));
    };
    let parameters: Vec<f64> = match source {
        ParameterSource::Given(parameters) => snapped_into_domain(&curve, parameters)?,
        ParameterSource::Uniform(count) => curve.uniform_parameters(count).collect(),
        ParameterSource::Polyline(tolerance) => curve
            .tessellate(tolerance, limits.max_parameters)
            .map_err(|error| ApiError::invalid("/tolerance", error.to_string()))?,
    };
    let mut response = evaluate_at(&curve, parameters, request.derivatives)?;
    if request.curvature {
        add_curvature(&curve, &mut response)?;
    }
    Ok(response)
}

/// Adds `curvature` (and `curvature_undefined` where the tangent vanishes) at the answer's
/// parameters.
fn add_curvature(curve: &Curve, response: &mut EvaluateResponse) -> Result<(), ApiError> {
    let values = curve.curvatures(&response.parameters).map_err(|error| {
        ApiError::Internal(format!("validated parameters failed to evaluate: {error}"))
    })?;
    let undefined: Vec<usize> = (0..values.len()).filter(|&i| values[i].is_none()).collect();
    response.curvature = Some(values.into_iter().map(|v| v.unwrap_or(0.0)).collect());
    response.curvature_undefined = (!undefined.is_empty()).then_some(undefined);
    Ok(())
}

/// The parameters with those just outside the domain snapped onto its ends
/// ([`Curve::snap_to_domain`]); a 422 listing (up to a bound) every parameter farther out.
fn snapped_into_domain(curve: &Curve, parameters: &[f64]) -> Result<Vec<f64>, ApiError> {
    let snapped: Vec<Option<f64>> = parameters
        .iter()
        .map(|&t| curve.snap_to_domain(t))
        .collect();
    let (lo, hi) = curve.domain();
    let errors: Vec<FieldError> = parameters
        .iter()
        .zip(&snapped)
        .enumerate()
        .filter(|(_, (_, snapped))| snapped.is_none())
        .map(|(index, (t, _))| (index, t))
        .take(MAX_LISTED_PARAMETER_ERRORS)
        .map(|(index, t)| {
            FieldError::new(
                JsonPointer::from("/parameters").push(index),
                format!("parameter {t} lies outside the domain [{lo}, {hi}]"),
            )
        })
        .collect();
    if errors.is_empty() {
        Ok(snapped.into_iter().flatten().collect())
    } else {
        Err(ApiError::Invalid(errors))
    }
}

/// Evaluates validated, in-domain parameters.
fn evaluate_at(
    curve: &Curve,
    parameters: Vec<f64>,
    order: usize,
) -> Result<EvaluateResponse, ApiError> {
    let count = parameters.len();
    let evaluator = BatchEvaluator::new(curve);
    let mut values: Vec<Point> = vec![[0.0; 3]; count * (order + 1)];
    let evaluated = if order == 0 {
        evaluator.points_into(&parameters, &mut values)
    } else {
        evaluator.derivatives_into(&parameters, order, &mut values)
    };
    evaluated.map_err(|error| {
        ApiError::Internal(format!("validated parameters failed to evaluate: {error}"))
    })?;
    if values.iter().flatten().any(|value| !value.is_finite()) {
        return Err(ApiError::invalid(
            "/curve/control_points",
            "the result overflows the range of doubles; scale the control points down",
        ));
    }
    let dimension = curve.dimension();
    let mut rows = values
        .chunks(count.max(1))
        .map(|row| row.iter().map(|&p| point_to_wire(p, dimension)).collect());
    let points = if count == 0 {
        Vec::new()
    } else {
        rows.next().unwrap_or_default()
    };
    let derivatives = (order > 0).then(|| {
        if count == 0 {
            vec![Vec::new(); order]
        } else {
            rows.collect()
        }
    });
    let (lo, hi) = curve.domain();
    Ok(EvaluateResponse {
        domain: [lo, hi],
        parameters,
        points,
        derivatives,
        curvature: None,
        curvature_undefined: None,
    })
}

/// Envelope of moving one knot.
///
/// The family of curves made by moving the run of equal knots that holds `knot_index` has an
/// envelope: the B-spline of degree `p - m` with the same control points and the knot vector
/// without the run (docs/method.md §2).
#[utoipa::path(
    post,
    path = "/v1/curves/envelope",
    tag = "curves",
    request_body = EnvelopeRequest,
    responses(
        (status = 200, description = "The envelope curve", body = EnvelopeResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn envelope(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<EnvelopeRequest>,
) -> Result<ApiJson<EnvelopeResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    let work = request.curve.control_points.len();
    compute(admission, work, move || {
        envelope_request(&request, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn envelope_request(
    request: &EnvelopeRequest,
    curve_limits: &CurveLimits,
) -> Result<EnvelopeResponse, ApiError> {
    let curve = request.curve.parse(curve_limits, "/curve")?;
    let run = curve
        .knot_run(request.knot_index)
        .map_err(|error: EnvelopeError| ApiError::invalid("/knot_index", error.to_string()))?;
    let envelope = curve.envelope(&run);
    let full_len = curve.knots().len();
    let moved_knots = (run.start..run.start + run.multiplicity)
        .filter_map(|full| curve.convention().caller_index(full, full_len))
        .collect();
    Ok(EnvelopeResponse {
        multiplicity: run.multiplicity,
        range: [run.range.0, run.range.1],
        moved_knots,
        envelope: CurveBody::from_curve(&envelope),
    })
}
