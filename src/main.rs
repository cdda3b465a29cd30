//! The knotshape binary: `serve` (the default) runs the service, `openapi` prints the OpenAPI
//! document, `healthcheck` probes a running instance's `/healthz` (for container health checks).

use std::io::{Read, Write};
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr, TcpStream};
use std::process::ExitCode;
use std::time::Duration;

use clap::{Parser, Subcommand};
use knotshape::config::Config;
use knotshape::http::{Server, shutdown_signal};
use knotshape::telemetry;

/// mimalloc instead of glibc's malloc, whose `malloc`/`free` cost the server about 2 µs more per
/// solve request than per health check under load (`perf`; docs/performance.md, history, round 4).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// At exit, the longest wait for computations that outlived their (timed-out) requests.
const EXIT_GRACE: Duration = Duration::from_secs(1);

/// Time the health check waits for connecting, writing and reading.
const HEALTHCHECK_TIMEOUT: Duration = Duration::from_secs(3);

#[derive(Debug, Parser)]
#[command(name = "knotshape", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    config: Config,
}

#[derive(Debug, Clone, Copy, Subcommand)]
enum Command {
    /// Run the HTTP service (the default).
    Serve,
    /// Print the OpenAPI document (JSON) to stdout.
    Openapi,
    /// Probe `http://<listen>/healthz`; exit 0 when it answers 200, 1 otherwise.
    Healthcheck,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command.unwrap_or(Command::Serve) {
        Command::Serve => serve(&cli.config),
        Command::Openapi => {
            print!("{}", knotshape::openapi_json());
            ExitCode::SUCCESS
        }
        Command::Healthcheck => healthcheck(cli.config.listen),
    }
}

fn serve(config: &Config) -> ExitCode {
    if let Err(error) =
        telemetry::init_subscriber(config.log_format, &config.log_filter, std::io::stdout)
    {
        eprintln!("knotshape: {error}");
        return ExitCode::FAILURE;
    }
    let mut runtime = tokio::runtime::Builder::new_multi_thread();
    if config.worker_threads > 0 {
        runtime.worker_threads(usize::from(config.worker_threads));
    }
    let runtime = match runtime.enable_all().build() {
        Ok(runtime) => runtime,
        Err(error) => {
            tracing::error!(%error, "cannot start the async runtime");
            return ExitCode::FAILURE;
        }
    };
    let served = runtime.block_on(async {
        let server = Server::bind(config).await?;
        tracing::info!(address = %server.local_addr()?, "knotshape listening");
        server.serve_until(shutdown_signal()).await
    });
    // Every answer is sent by now; computations still on the blocking pool belong to requests
    // that timed out. Exit without waiting long for them.
    runtime.shutdown_timeout(EXIT_GRACE);
    match served {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            tracing::error!(%error, listen = %config.listen, "server failed");
            ExitCode::FAILURE
        }
    }
}

/// GET `/healthz` over plain TCP (no HTTP client in the container image).
fn healthcheck(listen: SocketAddr) -> ExitCode {
    let target = probe_address(listen);
    match probe_healthz(target) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => {
            eprintln!("knotshape healthcheck: {target}/healthz did not answer 200");
            ExitCode::FAILURE
        }
        Err(error) => {
            eprintln!("knotshape healthcheck: {target}: {error}");
            ExitCode::FAILURE
        }
    }
}

/// The address to probe: an unspecified listen address (`0.0.0.0`, `::`) means loopback.
fn probe_address(listen: SocketAddr) -> SocketAddr {
    let ip = match listen.ip() {
        IpAddr::V4(ip) if ip.is_unspecified() => IpAddr::V4(Ipv4Addr::LOCALHOST),
        IpAddr::V6(ip) if ip.is_unspecified() => IpAddr::V6(Ipv6Addr::LOCALHOST),
        ip => ip,
    };
    SocketAddr::new(ip, listen.port())
}

fn probe_healthz(target: SocketAddr) -> std::io::Result<bool> {
    let mut stream = TcpStream::connect_timeout(&target, HEALTHCHECK_TIMEOUT)?;
    stream.set_read_timeout(Some(HEALTHCHECK_TIMEOUT))?;
    stream.set_write_timeout(Some(HEALTHCHECK_TIMEOUT))?;
    write!(
        stream,
        "GET /healthz HTTP/1.1\r\nHost: {target}\r\nConnection: close\r\n\r\n"
    )?;
    let mut status_line = [0u8; 12];
    stream.read_exact(&mut status_line)?;
    Ok(status_line.starts_with(b"HTTP/1.1 200") || status_line.starts_with(b"HTTP/1.0 200"))
}
