//! The server: binds the listener, serves the router, and shuts down gracefully (readiness
//! turns 503, the optional drain delay passes, the listener closes, in-flight requests finish).

use axum::serve::ListenerExt;
use std::future::Future;
use std::io;
use std::net::SocketAddr;
use std::time::Duration;

use axum::Router;
use tokio::net::TcpListener;

use super::app_with_readiness;
use super::state::Readiness;
use crate::config::Config;

/// A bound, not yet serving, HTTP server.
#[derive(Debug)]
pub struct Server {
    listener: TcpListener,
    router: Router,
    readiness: Readiness,
    drain_delay: Duration,
}

impl Server {
    /// Binds `config.listen` (port 0 picks a free port) and builds the router.
    pub async fn bind(config: &Config) -> io::Result<Server> {
        let listener = TcpListener::bind(config.listen).await?;
        let readiness = Readiness::new();
        Ok(Server {
            listener,
            router: app_with_readiness(config, readiness.clone()),
            readiness,
            drain_delay: config.drain_delay(),
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

    /// Serves until `shutdown` completes, then drains: readiness turns 503, after the drain
    /// delay the listener closes, and the call returns once in-flight requests have finished.
    pub async fn serve_until<F>(self, shutdown: F) -> io::Result<()>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        let readiness = self.readiness.clone();
        let drain_delay = self.drain_delay;
        // Each answer is written whole; Nagle's algorithm would only hold back small ones.
        let listener = self.listener.tap_io(|stream| {
            if let Err(error) = stream.set_nodelay(true) {
                tracing::debug!(%error, "could not set TCP_NODELAY");
            }
        });
        axum::serve(listener, self.router)
            .with_graceful_shutdown(async move {
                shutdown.await;
                readiness.start_draining();
                tracing::info!(
                    drain_delay_ms = drain_delay.as_millis() as u64,
                    "shutdown requested: readiness is now 503, finishing in-flight requests"
                );
                tokio::time::sleep(drain_delay).await;
            })
            .await?;
        tracing::info!("all requests finished; server stopped");
        Ok(())
    }
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
