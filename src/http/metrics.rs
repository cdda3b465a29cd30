//! Prometheus metrics of the HTTP edge: requests by matched route, method and status, a latency
//! histogram, and the number of requests in flight.
//!
//! Labels use the *matched* route (`/v1/curves/evaluate`, or `unmatched`) and a closed set of
//! method names, so no client can blow up the label cardinality.

use std::sync::Arc;
use std::time::Duration;

use axum::http::Method;
use prometheus_client::encoding::EncodeLabelSet;
use prometheus_client::metrics::counter::Counter;
use prometheus_client::metrics::family::Family;
use prometheus_client::metrics::gauge::Gauge;
use prometheus_client::metrics::histogram::{Histogram, exponential_buckets};
use prometheus_client::registry::Registry;

/// Content type of the `/metrics` body (OpenMetrics text, which Prometheus scrapes).
pub const METRICS_CONTENT_TYPE: &str = "application/openmetrics-text; version=1.0.0; charset=utf-8";

/// Route label of requests that matched no route.
pub const UNMATCHED_ROUTE: &str = "unmatched";

/// Labels of one finished request.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
pub struct RequestLabels {
    /// HTTP method (`other` for uncommon ones).
    pub method: &'static str,
    /// The matched route template, or `unmatched`.
    pub route: String,
    /// The response status code.
    pub status: u16,
}

/// Labels of the latency histogram.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
pub struct LatencyLabels {
    /// HTTP method (`other` for uncommon ones).
    pub method: &'static str,
    /// The matched route template, or `unmatched`.
    pub route: String,
}

/// The service's metrics and the registry they are exported from. Cheap to clone.
#[derive(Clone)]
pub struct Metrics {
    inner: Arc<MetricsInner>,
}

struct MetricsInner {
    registry: Registry,
    requests: Family<RequestLabels, Counter>,
    latency: Family<LatencyLabels, Histogram>,
    in_flight: Gauge,
}

impl std::fmt::Debug for Metrics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Metrics").finish_non_exhaustive()
    }
}

impl Default for Metrics {
    fn default() -> Self {
        Self::new()
    }
}

impl Metrics {
    /// A fresh registry with the HTTP metrics (prefix `knotshape`).
    pub fn new() -> Self {
        let mut registry = Registry::with_prefix("knotshape");
        let requests = Family::<RequestLabels, Counter>::default();
        // 0.5 ms .. ~16 s in factors of 2.
        let latency = Family::<LatencyLabels, Histogram>::new_with_constructor(
            (|| Histogram::new(exponential_buckets(0.0005, 2.0, 16))) as fn() -> Histogram,
        );
        let in_flight = Gauge::default();
        registry.register(
            "http_requests",
            "HTTP requests answered, by method, matched route and status",
            requests.clone(),
        );
        registry.register(
            "http_request_duration_seconds",
            "Time from receiving a request to sending its response head, by method and route",
            latency.clone(),
        );
        registry.register(
            "http_requests_in_flight",
            "HTTP requests being served now",
            in_flight.clone(),
        );
        Metrics {
            inner: Arc::new(MetricsInner {
                registry,
                requests,
                latency,
                in_flight,
            }),
        }
    }

    /// Counts a request as started; the guard counts it as finished when dropped.
    pub fn start_request(&self) -> InFlightGuard {
        self.inner.in_flight.inc();
        InFlightGuard {
            gauge: self.inner.in_flight.clone(),
        }
    }

    /// Records a finished request.
    pub fn record(&self, method: &Method, route: &str, status: u16, latency: Duration) {
        let method = method_label(method);
        self.inner
            .requests
            .get_or_create(&RequestLabels {
                method,
                route: route.to_owned(),
                status,
            })
            .inc();
        self.inner
            .latency
            .get_or_create(&LatencyLabels {
                method,
                route: route.to_owned(),
            })
            .observe(latency.as_secs_f64());
    }

    /// The metrics in OpenMetrics text format.
    pub fn encode(&self) -> String {
        let mut text = String::new();
        // Writing into a String cannot fail.
        let _ = prometheus_client::encoding::text::encode(&mut text, &self.inner.registry);
        text
    }
}

/// Decrements the in-flight gauge when dropped (also when the request future is cancelled).
#[derive(Debug)]
pub struct InFlightGuard {
    gauge: Gauge,
}

impl Drop for InFlightGuard {
    fn drop(&mut self) {
        self.gauge.dec();
    }
}

/// A closed set of method labels.
fn method_label(method: &Method) -> &'static str {
    match *method {
        Method::GET => "GET",
        Method::POST => "POST",
        Method::HEAD => "HEAD",
        Method::OPTIONS => "OPTIONS",
        Method::PUT => "PUT",
        Method::DELETE => "DELETE",
        Method::PATCH => "PATCH",
        _ => "other",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_appear_in_the_text_output() {
        let metrics = Metrics::new();
        {
            let _guard = metrics.start_request();
            assert!(
                metrics
                    .encode()
                    .contains("knotshape_http_requests_in_flight 1")
            );
        }
        metrics.record(
            &Method::POST,
            "/v1/curves/evaluate",
            200,
            Duration::from_millis(3),
        );
        metrics.record(
            &Method::from_bytes(b"BREW").unwrap(),
            UNMATCHED_ROUTE,
            405,
            Duration::ZERO,
        );
        let text = metrics.encode();
        assert!(text.contains(
            r#"knotshape_http_requests_total{method="POST",route="/v1/curves/evaluate",status="200"} 1"#
        ));
        assert!(text.contains(r#"method="other",route="unmatched",status="405""#));
        assert!(text.contains("knotshape_http_request_duration_seconds_bucket"));
        assert!(text.contains("knotshape_http_requests_in_flight 0"));
    }
}
