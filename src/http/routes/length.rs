//! `POST /v1/curves/length`: arc length, and the parameters at given arc lengths.

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::config::Limits;
use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::state::AppState;
use crate::http::wire::length::{LengthRequest, LengthResponse};
use crate::http::wire::toolkit_parse::{length_error, length_out_of_range};
use crate::spline::{CurveLimits, DOMAIN_END_SLACK};

/// Largest number of out-of-range lengths listed in one 422.
const MAX_LISTED_LENGTH_ERRORS: usize = 20;

/// Arc length.
///
/// The length of the curve over its domain or a range, with relative error at most `1e-10`
/// (adaptive Gauss–Legendre on each knot span), and the parameter at each of `at_lengths`.
#[utoipa::path(
    post,
    path = "/v1/curves/length",
    tag = "curves",
    request_body = LengthRequest,
    responses(
        (status = 200, description = "The arc length", body = LengthResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn length(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<LengthRequest>,
) -> Result<ApiJson<LengthResponse>, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    let degree = request.curve.degree.saturating_add(1);
    // Three 16-point rules per span to start, and about a hundred more per length asked.
    let work = (request.curve.control_points.len().saturating_mul(48)
        + request
            .at_lengths
            .as_ref()
            .map_or(0, Vec::len)
            .saturating_mul(100 * 16))
    .saturating_mul(degree);
    compute(admission, work, move || {
        length_request(&request, &limits, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn length_request(
    request: &LengthRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<LengthResponse, ApiError> {
    let curve = request.curve.parse(curve_limits, "/curve")?;
    if let Some(lengths) = &request.at_lengths {
        if lengths.len() > limits.max_parameters {
            return Err(ApiError::invalid(
                "/at_lengths",
                format!(
                    "{} lengths exceed the limit of {}",
                    lengths.len(),
                    limits.max_parameters
                ),
            ));
        }
    }
    let arc = curve
        .arc_length(request.range.map(|[lo, hi]| (lo, hi)))
        .map_err(|error| length_error(&error))?;
    let length = arc.length();
    let parameters = match &request.at_lengths {
        None => None,
        Some(lengths) => {
            let slack = DOMAIN_END_SLACK * length;
            let errors: Vec<_> = lengths
                .iter()
                .enumerate()
                .filter(|&(_, &l)| !(l.is_finite() && (0.0..=length + slack).contains(&l)))
                .take(MAX_LISTED_LENGTH_ERRORS)
                .map(|(index, &l)| length_out_of_range(index, l, length))
                .collect();
            if !errors.is_empty() {
                return Err(ApiError::Invalid(errors));
            }
            Some(
                lengths
                    .iter()
                    .map(|&l| arc.parameter_at(l.min(length)))
                    .collect(),
            )
        }
    };
    Ok(LengthResponse {
        length,
        error_estimate: arc.error_estimate(),
        parameters,
    })
}
