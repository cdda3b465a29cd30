//! The server: binds the listener, hands connections to per-core event loops that serve the
//! router, and shuts down gracefully (readiness turns 503, the optional drain delay passes, the
//! listener closes, in-flight requests finish).
//!
//! # Why one single-threaded event loop per core
//!
//! Each worker thread runs its own single-threaded tokio runtime and serves the connections
//! handed to it; the caller's runtime only accepts and deals connections out in turn. Tokio's
//! work-stealing runtime would wake a sibling worker (a futex call and a context switch)
//! whenever a task wakes itself while running, and every request with a body does: hyper
//! passes the body to the handler through a channel that wakes the connection's own task.
//! Under load that doubled the scheduling cost of a `POST` over a `GET` (`benches/load.sh`,
//! README). Here a connection stays on one loop for its life; computations large enough to
//! stall a loop run on its blocking pool ([`super::routes::compute`]).

use std::future::Future;
use std::io;
use std::net::SocketAddr;
use std::num::NonZeroUsize;
use std::thread;
use std::time::Duration;

use axum::Router;
use axum::serve::Listener;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{mpsc, watch};

use super::app_with_readiness;
use super::state::Readiness;
use crate::config::Config;

/// Pause after an accept error other than a connection's own (say, out of file descriptors)
/// before accepting again.
const ACCEPT_ERROR_PAUSE: Duration = Duration::from_secs(1);

/// A bound, not yet serving, HTTP server.
#[derive(Debug)]
pub struct Server {
    listener: TcpListener,
    router: Router,
    readiness: Readiness,
    drain_delay: Duration,
    worker_threads: usize,
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
            worker_threads: worker_threads(usize::from(config.worker_threads)),
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

    /// The number of worker threads (event loops) that serve connections.
    pub fn worker_threads(&self) -> usize {
        self.worker_threads
    }

    /// Serves until `shutdown` completes, then drains: readiness turns 503, after the drain
    /// delay the listener closes, and the call returns once in-flight requests have finished.
    ///
    /// Starts the worker threads; the calling task accepts connections and hands them to the
    /// workers in turn. Returns the first error of a worker that could not start (it stops the
    /// others).
    pub async fn serve_until<F>(self, shutdown: F) -> io::Result<()>
    where
        F: Future<Output = ()> + Send + 'static,
    {
        let Server {
            listener,
            router,
            readiness,
            drain_delay,
            worker_threads,
        } = self;
        let local_addr = listener.local_addr()?;
        let (stop, stopped) = watch::channel(false);
        let (exited, mut exits) = mpsc::unbounded_channel::<io::Result<()>>();
        let mut workers = Vec::with_capacity(worker_threads);
        for index in 0..worker_threads {
            let (handover, connections) = mpsc::unbounded_channel();
            let worker = EventLoop {
                connections: HandedOver {
                    connections,
                    local_addr,
                },
                router: router.clone(),
                stop: stopped.clone(),
            };
            let exited = exited.clone();
            let spawned = thread::Builder::new()
                .name(format!("knotshape-worker-{index}"))
                .spawn(move || {
                    let _ = exited.send(worker.run());
                });
            if let Err(error) = spawned {
                let _ = stop.send(true);
                return Err(error);
            }
            workers.push(handover);
        }
        drop(exited);

        let mut dealer = Dealer { workers, next: 0 };
        let mut failure = None;
        tokio::pin!(shutdown);
        tokio::select! {
            () = dealer.accept_from(&listener) => {}
            () = &mut shutdown => {}
            Some(exit) = exits.recv() => failure = Some(exit),
        }
        if failure.is_none() {
            readiness.start_draining();
            tracing::info!(
                drain_delay_ms = drain_delay.as_millis() as u64,
                "shutdown requested: readiness is now 503, finishing in-flight requests"
            );
            tokio::select! {
                () = dealer.accept_from(&listener) => {}
                () = tokio::time::sleep(drain_delay) => {}
                Some(exit) = exits.recv() => failure = Some(exit),
            }
        }
        // Close the listener, then let every worker finish its requests and stop.
        drop(listener);
        drop(dealer);
        let _ = stop.send(true);
        let mut result = failure.unwrap_or(Ok(()));
        while let Some(exit) = exits.recv().await {
            if result.is_ok() {
                result = exit;
            }
        }
        if result.is_ok() {
            tracing::info!("all requests finished; server stopped");
        }
        result
    }
}

/// The worker threads for a configured count: `0` means one per CPU available to the process.
fn worker_threads(configured: usize) -> usize {
    if configured > 0 {
        configured
    } else {
        thread::available_parallelism().map_or(1, NonZeroUsize::get)
    }
}

/// Accepts connections and deals them to the workers in turn.
struct Dealer {
    workers: Vec<mpsc::UnboundedSender<std::net::TcpStream>>,
    next: usize,
}

impl Dealer {
    /// Accepts until cancelled (by the caller's `select!`).
    async fn accept_from(&mut self, listener: &TcpListener) {
        loop {
            match listener.accept().await {
                Ok((stream, _)) => self.deal(stream),
                Err(error) if is_connection_error(&error) => {}
                Err(error) => {
                    tracing::error!(%error, "accept error");
                    tokio::time::sleep(ACCEPT_ERROR_PAUSE).await;
                }
            }
        }
    }

    fn deal(&mut self, stream: TcpStream) {
        // Each answer is written whole; Nagle's algorithm would only hold back small ones.
        if let Err(error) = stream.set_nodelay(true) {
            tracing::debug!(%error, "could not set TCP_NODELAY");
        }
        // Leaves this thread's event loop; the worker registers it with its own.
        let stream = match stream.into_std() {
            Ok(stream) => stream,
            Err(error) => {
                tracing::debug!(%error, "an accepted connection failed");
                return;
            }
        };
        let worker = &self.workers[self.next];
        self.next = (self.next + 1) % self.workers.len();
        // A failed send drops (closes) the connection; only a worker that has exited fails,
        // and its exit stops the server.
        let _ = worker.send(stream);
    }
}

/// An error of one connection (refused, aborted or reset before it was accepted), not of the
/// listener.
fn is_connection_error(error: &io::Error) -> bool {
    matches!(
        error.kind(),
        io::ErrorKind::ConnectionRefused
            | io::ErrorKind::ConnectionAborted
            | io::ErrorKind::ConnectionReset
    )
}

/// One worker: a single-threaded runtime serving the connections handed to it until `stop`
/// turns true, then finishing their requests.
struct EventLoop {
    connections: HandedOver,
    router: Router,
    stop: watch::Receiver<bool>,
}

impl EventLoop {
    fn run(self) -> io::Result<()> {
        let EventLoop {
            connections,
            router,
            mut stop,
        } = self;
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()?;
        runtime.block_on(async move {
            axum::serve(connections, router)
                .with_graceful_shutdown(async move {
                    let _ = stop.wait_for(|&stop| stop).await;
                })
                .await
        })
    }
}

/// The connections dealt to one worker, as a listener for `axum::serve`. Each stream is
/// registered with the worker's event loop when it is taken.
struct HandedOver {
    connections: mpsc::UnboundedReceiver<std::net::TcpStream>,
    local_addr: SocketAddr,
}

impl Listener for HandedOver {
    type Io = TcpStream;
    type Addr = SocketAddr;

    async fn accept(&mut self) -> (TcpStream, SocketAddr) {
        loop {
            // Closed only when the server stops, and then graceful shutdown ends `serve`.
            let Some(stream) = self.connections.recv().await else {
                std::future::pending::<()>().await;
                continue;
            };
            let moved =
                TcpStream::from_std(stream).and_then(|stream| Ok((stream.peer_addr()?, stream)));
            match moved {
                Ok((peer, stream)) => return (stream, peer),
                Err(error) => tracing::debug!(%error, "a handed-over connection failed"),
            }
        }
    }

    fn local_addr(&self) -> io::Result<SocketAddr> {
        Ok(self.local_addr)
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
