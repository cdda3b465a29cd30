//! The service hyper calls for each request of one connection: the router, with the
//! connection's phase kept up to date (head complete, body complete, response complete), a
//! 408 for a body that timed out, and `Connection: close` on every response once draining (so
//! that each client learns it with an answer instead of a closed socket).

use std::convert::Infallible;
use std::future::Future;
use std::pin::Pin;
use std::sync::Arc;
use std::task::{Context, Poll, ready};

use axum::Router;
use axum::body::{Body, Bytes};
use axum::http::{HeaderValue, Request, Response, StatusCode, header};
use axum::response::IntoResponse;
use http_body::{Body as HttpBody, Frame, SizeHint};
use hyper::body::Incoming;
use pin_project_lite::pin_project;
use tower::ServiceExt;
use tower::util::Oneshot;

use super::connection::Connection;
use crate::http::error::Problem;
use crate::http::metrics::CloseReason;
use crate::http::state::Readiness;

/// What the 408 answer says.
const BODY_TIMEOUT_DETAIL: &str =
    "the request body did not arrive within the configured time; the connection is closed";

/// The per-connection service.
#[derive(Debug, Clone)]
pub(super) struct ConnectionService {
    pub(super) router: Router,
    pub(super) connection: Arc<Connection>,
    pub(super) readiness: Readiness,
}

impl hyper::service::Service<Request<Incoming>> for ConnectionService {
    type Response = Response<ResponseBody>;
    type Error = Infallible;
    type Future = ResponseFuture;

    fn call(&self, request: Request<Incoming>) -> ResponseFuture {
        let body_complete = request.body().is_end_stream();
        self.connection.request_started(body_complete);
        let request = if body_complete {
            request.map(Body::new)
        } else {
            let connection = self.connection.clone();
            request.map(|inner| Body::new(RequestBody { inner, connection }))
        };
        ResponseFuture {
            inner: self.router.clone().oneshot(request),
            connection: self.connection.clone(),
            readiness: self.readiness.clone(),
        }
    }
}

pin_project! {
    /// The router's answer, adjusted for the connection.
    pub(super) struct ResponseFuture {
        #[pin]
        inner: Oneshot<Router, Request<Body>>,
        connection: Arc<Connection>,
        readiness: Readiness,
    }
}

impl Future for ResponseFuture {
    type Output = Result<Response<ResponseBody>, Infallible>;

    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        let this = self.project();
        let Ok(mut response) = ready!(this.inner.poll(cx));
        let body_timed_out = this.connection.close_reason() == Some(CloseReason::BodyTimeout);
        if body_timed_out {
            response = Problem::for_status(StatusCode::REQUEST_TIMEOUT, BODY_TIMEOUT_DETAIL)
                .into_response();
        }
        if body_timed_out || !this.readiness.is_ready() || this.connection.close_after_response() {
            response
                .headers_mut()
                .insert(header::CONNECTION, HeaderValue::from_static("close"));
        }
        let connection = this.connection.clone();
        Poll::Ready(Ok(response.map(|inner| ResponseBody { inner, connection })))
    }
}

pin_project! {
    /// A request body that reports when it has been received whole.
    struct RequestBody {
        #[pin]
        inner: Incoming,
        connection: Arc<Connection>,
    }
}

impl HttpBody for RequestBody {
    type Data = Bytes;
    type Error = hyper::Error;

    fn poll_frame(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, hyper::Error>>> {
        let mut this = self.project();
        let frame = ready!(this.inner.as_mut().poll_frame(cx));
        if frame.is_none() || this.inner.is_end_stream() {
            this.connection.body_finished();
        }
        Poll::Ready(frame)
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.inner.size_hint()
    }
}

pin_project! {
    /// A response body that reports, when hyper drops it, that the response is complete.
    pub(super) struct ResponseBody {
        #[pin]
        inner: Body,
        connection: Arc<Connection>,
    }

    impl PinnedDrop for ResponseBody {
        fn drop(this: Pin<&mut Self>) {
            this.connection.response_finished();
        }
    }
}

impl HttpBody for ResponseBody {
    type Data = Bytes;
    type Error = axum::Error;

    fn poll_frame(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, axum::Error>>> {
        self.project().inner.poll_frame(cx)
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.inner.size_hint()
    }
}
