//! The server: binds the listener, accepts connections under a cap, serves each with hyper's
//! HTTP/1 connection and the router, and shuts down gracefully.
//!
//! Its own accept loop rather than `axum::serve`, which cannot bound connections: each
//! connection's socket is watched ([`watched_io`]) for the header, idle, body and send
//! timeouts, the registry ([`registry`]) caps the connections open and displaces waiting
//! ones at the cap so that probes always get in, and metrics count connections open and
//! closed by reason.
//!
//! **Probes at the cap.** Kubernetes probes (`deploy/kubernetes/deployment.yaml`) reach the
//! same port as the API; there is no second listener to configure or expose. They get in at
//! the cap because a new connection displaces the one that has waited longest without a
//! request in progress (idle, half-sent head, unread response), and requests in progress
//! can hold only about the concurrency limit's worth of connections — which the cap always
//! exceeds. A client holding thousands of half-open connections thus only displaces its own.
//!
//! **Shutdown.** When `shutdown` completes: readiness turns 503 (`/readyz`, and every new
//! `/v1` request is answered 503 with `Retry-After`), every response from then on says
//! `Connection: close`, and idle connections close after [`watched_io::DRAIN_IDLE_GRACE`].
//! After the drain delay the listener closes; the call returns when every connection has
//! ended — requests in progress finish, bounded by the body and request timeouts.
//!
//! **Accept errors.** Errors of the connection being accepted (reset, aborted) are skipped;
//! any other (`EMFILE`, `ENFILE`: out of file descriptors) pauses accepting for
//! [`ACCEPT_ERROR_BACKOFF`] instead of retrying in a tight loop.

mod connection;
mod registry;
mod service;
mod watched_io;

use std::future::Future;
use std::io;
use std::net::SocketAddr;
use std::pin::pin;
use std::sync::Arc;
use std::task::Poll;
use std::time::Duration;

use axum::Router;
use hyper::server::conn::http1;
use hyper_util::rt::TokioIo;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::watch;
use tokio::time::Instant;

use self::registry::{Registered, Registry};
use self::service::ConnectionService;
use self::watched_io::{Timeouts, WatchedIo};
use super::app_with_state;
use super::metrics::{CloseReason, Metrics};
use super::state::{AppState, Readiness};
use crate::config::Config;

/// Pause after an accept error other than the connection's own (e.g. out of descriptors).
pub const ACCEPT_ERROR_BACKOFF: Duration = Duration::from_millis(50);

/// A bound, not yet serving, HTTP server.
#[derive(Debug)]
pub struct Server {
    listener: TcpListener,
    router: Router,
    readiness: Readiness,
    metrics: Metrics,
    drain_delay: Duration,
    timeouts: Timeouts,
    max_connections: usize,
}

impl Server {
    /// Binds `config.listen` (port 0 picks a free port) and builds the router.
    pub async fn bind(config: &Config) -> io::Result<Server> {
        if config.solve_threads != 0 {
            crate::parallel::set_solve_threads(usize::from(config.solve_threads));
        }
        let listener = TcpListener::bind(config.listen).await?;
        let readiness = Readiness::new();
        let state = AppState::new(config, readiness.clone(), crate::openapi_json().into());
        let metrics = state.metrics.clone();
        let limits = config.connection_limits();
        Ok(Server {
            listener,
            router: app_with_state(config, state),
            readiness,
            metrics,
            drain_delay: config.drain_delay(),
            timeouts: Timeouts::from(limits),
            max_connections: usize::try_from(limits.max_connections).unwrap_or(usize::MAX),
        })
    }

    /// The address actually bound.
    pub fn local_addr(&self) -> io::Result<SocketAddr> {
        self.listener.local_addr()
    }

    /// The readiness flag that shutdown clears.
    pub fn readiness(&self) -> Readiness {
        self.readiness.clone()
    }

    /// Serves until `shutdown` completes, then drains (see the module documentation) and
    /// returns once every connection has ended.
    pub async fn serve_until<F>(self, shutdown: F) -> io::Result<()>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        let registry = Registry::new(self.max_connections);
        let mut http = http1::Builder::new();
        // The watched socket applies the header timeout (hyper's would need a timer, and
        // would also cut idle keep-alive connections at the header timeout).
        http.header_read_timeout(None);
        let shared = Arc::new(Shared {
            http,
            router: self.router,
            readiness: self.readiness.clone(),
            metrics: self.metrics,
            timeouts: self.timeouts,
        });
        // Every connection task holds a receiver; `closed()` completes when all are gone.
        let (all_closed, connection_alive) = watch::channel(());

        let stop_accepting = {
            let readiness = self.readiness.clone();
            let registry = registry.clone();
            let drain_delay = self.drain_delay;
            async move {
                shutdown.await;
                readiness.start_draining();
                registry.wake_all();
                tracing::info!(
                    drain_delay_ms = drain_delay.as_millis() as u64,
                    "shutdown requested: readiness is now 503, finishing in-flight requests"
                );
                tokio::time::sleep(drain_delay).await;
            }
        };
        let mut stop_accepting = pin!(stop_accepting);
        let start = |stream: TcpStream| {
            let now = Instant::now();
            let Some(registered) = registry.admit(now) else {
                // Dropping the stream closes it at once.
                shared.metrics.record_close(CloseReason::OverCapacity);
                return;
            };
            tokio::spawn(serve_connection(
                stream,
                registered,
                shared.clone(),
                now,
                connection_alive.clone(),
            ));
        };
        loop {
            let accepted = tokio::select! {
                biased;
                () = &mut stop_accepting => break,
                accepted = self.listener.accept() => accepted,
            };
            match accepted {
                Ok((stream, _peer)) => start(stream),
                Err(error) if is_connection_error(&error) => {}
                Err(error) => {
                    tracing::error!(%error, "accept failed; pausing");
                    tokio::time::sleep(ACCEPT_ERROR_BACKOFF).await;
                }
            }
        }
        // Connections the kernel has completed but not yet handed over would be reset when
        // the listener closes, after their clients sent a request: serve them too (503).
        while let Some(Ok((stream, _peer))) = accept_now(&self.listener).await {
            start(stream);
        }
        drop(self.listener);
        drop(connection_alive);
        registry.wake_all();
        all_closed.closed().await;
        tracing::info!("all requests finished; server stopped");
        Ok(())
    }
}

/// What every connection task needs.
struct Shared {
    http: http1::Builder,
    router: Router,
    readiness: Readiness,
    metrics: Metrics,
    timeouts: Timeouts,
}

/// Serves one connection to its end and counts why it ended.
async fn serve_connection(
    stream: TcpStream,
    registered: Registered,
    shared: Arc<Shared>,
    accepted: Instant,
    _alive: watch::Receiver<()>,
) {
    let _open = shared.metrics.open_connection();
    // Each answer is written whole; Nagle's algorithm would only hold back small ones.
    if let Err(error) = stream.set_nodelay(true) {
        tracing::debug!(%error, "could not set TCP_NODELAY");
    }
    let connection = registered.connection.clone();
    let io = WatchedIo::new(
        stream,
        connection.clone(),
        shared.timeouts,
        shared.readiness.clone(),
        accepted,
    );
    let service = ConnectionService {
        router: shared.router.clone(),
        connection: connection.clone(),
        readiness: shared.readiness.clone(),
    };
    let mut served = pin!(shared.http.serve_connection(TokioIo::new(io), service));
    let result = loop {
        tokio::select! {
            biased;
            result = served.as_mut() => break result,
            // Evicted, or draining began: poll again so that the socket sees it.
            () = connection.woken() => {}
        }
    };
    let reason = connection.close_reason().unwrap_or(match &result {
        Ok(()) => CloseReason::Completed,
        Err(error) if error.is_incomplete_message() || error.is_canceled() => {
            CloseReason::Completed
        }
        Err(_) => CloseReason::Error,
    });
    if let Err(error) = &result {
        tracing::debug!(%error, reason = reason.label(), "connection ended");
    }
    shared.metrics.record_close(reason);
    drop(registered);
}

/// The next connection the kernel has completed, without waiting for one.
async fn accept_now(listener: &TcpListener) -> Option<io::Result<(TcpStream, SocketAddr)>> {
    std::future::poll_fn(|cx| match listener.poll_accept(cx) {
        Poll::Ready(accepted) => Poll::Ready(Some(accepted)),
        Poll::Pending => Poll::Ready(None),
    })
    .await
}

/// Errors of the one connection being accepted, after which accepting goes on at once.
fn is_connection_error(error: &io::Error) -> bool {
    matches!(
        error.kind(),
        io::ErrorKind::ConnectionRefused
            | io::ErrorKind::ConnectionAborted
            | io::ErrorKind::ConnectionReset
    )
}

/// Completes on Ctrl-C or, on Unix, SIGTERM.
pub async fn shutdown_signal() {
    let ctrl_c = async {
        if let Err(error) = tokio::signal::ctrl_c().await {
            tracing::error!(%error, "cannot listen for Ctrl-C");
            std::future::pending::<()>().await;
        }
    };
    #[cfg(unix)]
    let terminate = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut signal) => {
                signal.recv().await;
            }
            Err(error) => {
                tracing::error!(%error, "cannot listen for SIGTERM");
                std::future::pending::<()>().await;
            }
        }
    };
    #[cfg(not(unix))]
    let terminate = std::future::pending::<()>();
    tokio::select! {
        () = ctrl_c => {},
        () = terminate => {},
    }
}
