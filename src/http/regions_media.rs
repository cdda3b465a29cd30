//! Content negotiation of `POST /v1/shape/regions`: JSON (the default) or, when the
//! `Accept` header prefers it, the SVG picture of [`super::regions_svg`].

use axum::http::{HeaderMap, HeaderValue, header};
use axum::response::{IntoResponse, Response};

use super::curve::point_from_wire;
use super::error::ApiError;
use super::extract::ApiJson;
use super::pointer::JsonPointer;
use super::regions_svg::{NonFinite, Picture, SVG, render};
use super::wire::shape_answer::RegionsResponse;
use super::wire::shape_request::RegionsRequest;
use crate::spline::CurveLimits;

/// Whether the `Accept` header prefers the SVG picture over JSON: `image/svg+xml` with a
/// positive quality no lower than any wildcard's and higher than an explicit
/// `application/json`'s. No header, or a tie with `application/json`: JSON.
pub fn prefers_svg(headers: &HeaderMap) -> bool {
    let (mut svg, mut json, mut wildcard) = (0.0_f64, 0.0_f64, 0.0_f64);
    for value in headers.get_all(header::ACCEPT) {
        let Ok(value) = value.to_str() else { continue };
        for range in value.split(',') {
            let mut parts = range.split(';');
            let media = parts.next().unwrap_or_default().trim().to_ascii_lowercase();
            let quality = parts
                .filter_map(|parameter| parameter.trim().strip_prefix("q="))
                .find_map(|q| q.trim().parse::<f64>().ok())
                .filter(|q| q.is_finite())
                .unwrap_or(1.0)
                .clamp(0.0, 1.0);
            match media.as_str() {
                SVG => svg = svg.max(quality),
                "application/json" => json = json.max(quality),
                "*/*" | "application/*" | "image/*" => wildcard = wildcard.max(quality),
                _ => {}
            }
        }
    }
    svg > 0.0 && svg >= wildcard && svg > json
}

/// The regions answer as JSON, or as the SVG picture when `svg` (from [`prefers_svg`]).
/// A `target` is checked in both cases (the curve's dimension, finite: 422 at `/target`).
pub fn respond(
    request: &RegionsRequest,
    regions: RegionsResponse,
    curve_limits: &CurveLimits,
    svg: bool,
) -> Result<Response, ApiError> {
    let curve = request
        .curve
        .parse_allowing_periodic(curve_limits, "/curve")?;
    let target = request
        .target
        .as_deref()
        .map(|target| point_from_wire(target, curve.dimension(), &JsonPointer::from("/target")))
        .transpose()?;
    if !svg {
        return Ok(ApiJson(regions).into_response());
    }
    let parameter = curve
        .snap_to_domain(request.parameter)
        .unwrap_or(request.parameter);
    let picked = curve
        .point(parameter)
        .map_err(|_| ApiError::non_finite_result())?;
    let picture = Picture {
        regions: &regions,
        parameter,
        picked: [picked[0], picked[1]],
        target: target.map(|p| [p[0], p[1]]),
    };
    let text = render(&picture).map_err(|NonFinite| ApiError::non_finite_result())?;
    let mut response = text.into_response();
    response
        .headers_mut()
        .insert(header::CONTENT_TYPE, HeaderValue::from_static(SVG));
    Ok(response)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn accept(value: &str) -> HeaderMap {
        let mut headers = HeaderMap::new();
        headers.insert(header::ACCEPT, HeaderValue::from_str(value).unwrap());
        headers
    }

    #[test]
    fn svg_only_when_asked_for_it() {
        assert!(!prefers_svg(&HeaderMap::new()));
        assert!(prefers_svg(&accept("image/svg+xml")));
        assert!(prefers_svg(&accept("image/svg+xml, */*;q=0.8")));
        assert!(!prefers_svg(&accept("application/json")));
        assert!(!prefers_svg(&accept("*/*")));
        assert!(!prefers_svg(&accept("image/svg+xml, application/json")));
        assert!(prefers_svg(&accept(
            "application/json;q=0.5, image/svg+xml;q=0.9"
        )));
        assert!(!prefers_svg(&accept("image/svg+xml;q=0")));
        assert!(!prefers_svg(&accept("text/html,*/*;q=0.8")));
    }
}
