//! Prometheus metrics of the HTTP edge: requests by matched route, method and status, a latency
//! histogram, the number of requests in flight, open connections and connection closes by
//! reason.
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

/// Why a connection ended (the `reason` label of `knotshape_http_connections_closed_total`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CloseReason {
    /// The client closed it, or a response said `Connection: close`.
    Completed,
    /// The request head did not arrive in time.
    HeaderTimeout,
    /// Idle between requests for longer than the idle timeout.
    IdleTimeout,
    /// The request body did not arrive in time (answered with 408).
    BodyTimeout,
    /// The client did not read its response in time.
    SendTimeout,
    /// Displaced at the connection cap by a new connection.
    Evicted,
    /// Refused at once: the cap was reached and every connection was serving a request.
    OverCapacity,
    /// Closed while idle during shutdown.
    Shutdown,
    /// A protocol or socket error.
    Error,
}

impl CloseReason {
    /// Every reason, in the order of their counters.
    pub const ALL: [CloseReason; 9] = [
        CloseReason::Completed,
        CloseReason::HeaderTimeout,
        CloseReason::IdleTimeout,
        CloseReason::BodyTimeout,
        CloseReason::SendTimeout,
        CloseReason::Evicted,
        CloseReason::OverCapacity,
        CloseReason::Shutdown,
        CloseReason::Error,
    ];

    /// The label value.
    pub fn label(self) -> &'static str {
        match self {
            CloseReason::Completed => "completed",
            CloseReason::HeaderTimeout => "header_timeout",
            CloseReason::IdleTimeout => "idle_timeout",
            CloseReason::BodyTimeout => "body_timeout",
            CloseReason::SendTimeout => "send_timeout",
            CloseReason::Evicted => "evicted",
            CloseReason::OverCapacity => "over_capacity",
            CloseReason::Shutdown => "shutdown",
            CloseReason::Error => "error",
        }
    }
}

/// Labels of the connection-close counter.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct CloseLabels {
    reason: &'static str,
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
    connections_open: Gauge,
    /// One counter per [`CloseReason::ALL`] entry, created up front so that counting a close
    /// needs no lookup.
    connections_closed: [Counter; CloseReason::ALL.len()],
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
        let connections_open = Gauge::default();
        registry.register(
            "http_connections_open",
            "TCP connections open now",
            connections_open.clone(),
        );
        let closed = Family::<CloseLabels, Counter>::default();
        registry.register(
            "http_connections_closed",
            "TCP connections ended (or refused at the cap), by reason",
            closed.clone(),
        );
        let connections_closed = CloseReason::ALL.map(|reason| {
            closed
                .get_or_create(&CloseLabels {
                    reason: reason.label(),
                })
                .clone()
        });
        Metrics {
            inner: Arc::new(MetricsInner {
                registry,
                requests,
                latency,
                in_flight,
                connections_open,
                connections_closed,
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

    /// Counts a connection as open; the guard counts it as closed when dropped.
    pub fn open_connection(&self) -> OpenConnectionGuard {
        self.inner.connections_open.inc();
        OpenConnectionGuard {
            gauge: self.inner.connections_open.clone(),
        }
    }

    /// Counts a connection that ended (or was refused) for `reason`.
    pub fn record_close(&self, reason: CloseReason) {
        let index = CloseReason::ALL
            .iter()
            .position(|r| *r == reason)
            .unwrap_or(CloseReason::ALL.len() - 1);
        self.inner.connections_closed[index].inc();
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

/// Decrements the open-connections gauge when dropped.
#[derive(Debug)]
pub struct OpenConnectionGuard {
    gauge: Gauge,
}

impl Drop for OpenConnectionGuard {
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

    #[test]
    fn connections_are_counted_open_and_closed_by_reason() {
        let metrics = Metrics::new();
        let text = metrics.encode();
        for reason in CloseReason::ALL {
            let line = format!(
                r#"knotshape_http_connections_closed_total{{reason="{}"}} 0"#,
                reason.label()
            );
            assert!(text.contains(&line), "{line} missing from\n{text}");
        }
        let first = metrics.open_connection();
        let second = metrics.open_connection();
        assert!(
            metrics
                .encode()
                .contains("knotshape_http_connections_open 2")
        );
        drop(first);
        metrics.record_close(CloseReason::HeaderTimeout);
        metrics.record_close(CloseReason::HeaderTimeout);
        metrics.record_close(CloseReason::OverCapacity);
        let text = metrics.encode();
        assert!(text.contains("knotshape_http_connections_open 1"));
        assert!(
            text.contains(r#"knotshape_http_connections_closed_total{reason="header_timeout"} 2"#)
        );
        assert!(
            text.contains(r#"knotshape_http_connections_closed_total{reason="over_capacity"} 1"#)
        );
        assert!(text.contains(r#"knotshape_http_connections_closed_total{reason="completed"} 0"#));
        drop(second);
    }
}
