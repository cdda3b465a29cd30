//! Typed service configuration: command-line flags, `KNOTSHAPE_*` environment variables, defaults.
//!
//! Every field has a default that just runs (`Config::default()` equals parsing no arguments),
//! so `cargo run --release` serves on `127.0.0.1:8080`.

use std::fmt;
use std::net::SocketAddr;
use std::str::FromStr;
use std::time::Duration;

use clap::{Parser, ValueEnum};

/// Most worker threads a configuration may ask for.
pub const MAX_WORKER_THREADS: u16 = 1024;

/// Longest connection timeout a configuration may set, in milliseconds (one hour).
pub const MAX_CONNECTION_TIMEOUT_MS: u64 = 3_600_000;

/// Most open connections a configuration may allow.
pub const MAX_CONNECTIONS: u32 = 1_048_576;

/// Service configuration. Each flag can also be set by the environment variable named in its
/// help text; a flag wins over the variable.
#[derive(Debug, Clone, PartialEq, Parser)]
#[command(name = "knotshape", version, about)]
pub struct Config {
    /// Address and port to listen on (`0.0.0.0:8080` to serve outside the host).
    #[arg(
        long,
        env = "KNOTSHAPE_LISTEN",
        default_value = "127.0.0.1:8080",
        global = true
    )]
    pub listen: SocketAddr,

    /// API key required as `Authorization: Bearer <key>` on every `/v1` route (none: open).
    #[arg(long, env = "KNOTSHAPE_API_KEY", hide_env_values = true, global = true)]
    pub api_key: Option<ApiKey>,

    /// Origins allowed by CORS, comma-separated (e.g. `https://cad.example.com`); none: CORS off.
    #[arg(
        long = "cors-allow-origin",
        env = "KNOTSHAPE_CORS_ALLOW_ORIGINS",
        value_delimiter = ',',
        global = true
    )]
    pub cors_allow_origins: Vec<String>,

    /// Largest accepted request body in bytes (larger: 413).
    #[arg(long, env = "KNOTSHAPE_MAX_BODY_BYTES", default_value_t = Limits::DEFAULT.max_body_bytes, global = true)]
    pub max_body_bytes: usize,

    /// Largest number of control points per curve (more: 422).
    #[arg(long, env = "KNOTSHAPE_MAX_CONTROL_POINTS", default_value_t = Limits::DEFAULT.max_control_points, global = true)]
    pub max_control_points: usize,

    /// Largest number of `parameters`, or of `samples`, per evaluate request (more: 422).
    #[arg(long, env = "KNOTSHAPE_MAX_PARAMETERS", default_value_t = Limits::DEFAULT.max_parameters, global = true)]
    pub max_parameters: usize,

    /// Highest derivative order per evaluate request (higher: 422).
    #[arg(long, env = "KNOTSHAPE_MAX_DERIVATIVE_ORDER", default_value_t = Limits::DEFAULT.max_derivative_order, global = true)]
    pub max_derivative_order: usize,

    /// Largest number of vertices of one region polygon (`/v1/shape/regions`); values below
    /// 128 act as 128.
    #[arg(long, env = "KNOTSHAPE_MAX_POLYGON_VERTICES", default_value_t = Limits::DEFAULT.max_polygon_vertices, global = true)]
    pub max_polygon_vertices: usize,

    /// Largest file text accepted by `/v1/curves/import`, in bytes (larger: 422). The request
    /// body holding it must also fit `max_body_bytes`.
    #[arg(long, env = "KNOTSHAPE_MAX_FILE_BYTES", default_value_t = Limits::DEFAULT.max_file_bytes, global = true)]
    pub max_file_bytes: usize,

    /// Largest number of entities (STEP instances, DXF entities) in an imported file, and of
    /// curves in an exported one (more: 422).
    #[arg(long, env = "KNOTSHAPE_MAX_FILE_ENTITIES", default_value_t = Limits::DEFAULT.max_file_entities, global = true)]
    pub max_file_entities: usize,
    /// Largest number of `points` per interpolate or approximate request (more: 422).
    #[arg(long, env = "KNOTSHAPE_MAX_FIT_POINTS", default_value_t = Limits::DEFAULT.max_fit_points, global = true)]
    pub max_fit_points: usize,

    /// Largest number of control points per surface, rows × points per row (more: 422).
    #[arg(long, env = "KNOTSHAPE_MAX_SURFACE_CONTROL_POINTS", default_value_t = Limits::DEFAULT.max_surface_control_points, global = true)]
    pub max_surface_control_points: usize,

    /// Largest number of triangles in one `/v1/surfaces/tessellate` answer (more needed: 422).
    #[arg(long, env = "KNOTSHAPE_MAX_TRIANGLES", default_value_t = Limits::DEFAULT.max_triangles, global = true)]
    pub max_triangles: usize,

    /// Time a request may take, in milliseconds, before it is answered with 503.
    #[arg(
        long,
        env = "KNOTSHAPE_REQUEST_TIMEOUT_MS",
        default_value_t = 10_000,
        global = true
    )]
    pub request_timeout_ms: u64,

    /// Largest number of `/v1` requests served at once; more are shed with 503 + `Retry-After`.
    #[arg(
        long,
        env = "KNOTSHAPE_CONCURRENCY_LIMIT",
        default_value_t = 64,
        global = true
    )]
    pub concurrency_limit: usize,

    /// Seconds sent in `Retry-After` with a 503.
    #[arg(
        long,
        env = "KNOTSHAPE_RETRY_AFTER_SECS",
        default_value_t = 1,
        global = true
    )]
    pub retry_after_secs: u64,

    /// On shutdown, milliseconds between readiness turning 503 and the listener closing
    /// (lets a load balancer notice); in-flight requests always finish.
    #[arg(
        long,
        env = "KNOTSHAPE_DRAIN_DELAY_MS",
        default_value_t = 0,
        global = true
    )]
    pub drain_delay_ms: u64,

    /// Milliseconds a client has to send a complete request head: from accepting the
    /// connection, or from the first byte of a later request on a kept-alive connection.
    /// Slower: the connection is closed.
    #[arg(
        long,
        env = "KNOTSHAPE_HEADER_TIMEOUT_MS",
        default_value_t = ConnectionLimits::DEFAULT.header_timeout_ms,
        value_parser = clap::value_parser!(u64).range(1..=MAX_CONNECTION_TIMEOUT_MS),
        global = true
    )]
    pub header_timeout_ms: u64,

    /// Milliseconds a kept-alive connection may wait, idle, for its next request before it is
    /// closed.
    #[arg(
        long,
        env = "KNOTSHAPE_IDLE_TIMEOUT_MS",
        default_value_t = ConnectionLimits::DEFAULT.idle_timeout_ms,
        value_parser = clap::value_parser!(u64).range(1..=MAX_CONNECTION_TIMEOUT_MS),
        global = true
    )]
    pub idle_timeout_ms: u64,

    /// Milliseconds a request body may take to arrive after its head (slower: 408 and the
    /// connection is closed), and a response may stay stuck because the client does not read
    /// it (then the connection is closed). Keep it below the request timeout.
    #[arg(
        long,
        env = "KNOTSHAPE_BODY_TIMEOUT_MS",
        default_value_t = ConnectionLimits::DEFAULT.body_timeout_ms,
        value_parser = clap::value_parser!(u64).range(1..=MAX_CONNECTION_TIMEOUT_MS),
        global = true
    )]
    pub body_timeout_ms: u64,

    /// Most connections open at once. At the cap, a new connection displaces the one that
    /// has waited longest without a request in progress, or is closed at once if every
    /// connection is serving a request. Values below the concurrency limit + 16 act as that.
    #[arg(
        long,
        env = "KNOTSHAPE_MAX_CONNECTIONS",
        default_value_t = ConnectionLimits::DEFAULT.max_connections,
        value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_CONNECTIONS)),
        global = true
    )]
    pub max_connections: u32,

    /// Worker threads of the async runtime that serves requests; 0: one per CPU available to
    /// the process (its cgroup's CPU limit included). Large computations run on a separate
    /// blocking pool either way.
    #[arg(
        long,
        env = "KNOTSHAPE_WORKER_THREADS",
        default_value_t = 0,
        value_parser = clap::value_parser!(u16).range(0..=MAX_WORKER_THREADS as i64),
        global = true
    )]
    pub worker_threads: u16,

    /// Threads one request's solve may use (a knot family's pairs and triples, the
    /// deviations of many solutions): 0 = every core, 1 = the request's own thread only (best
    /// where the cores are busy otherwise, e.g. a browser on the same small machine).
    #[arg(
        long,
        env = "KNOTSHAPE_SOLVE_THREADS",
        default_value_t = 0,
        value_parser = clap::value_parser!(u16).range(0..=MAX_WORKER_THREADS as i64),
        global = true
    )]
    pub solve_threads: u16,

    /// Log format: `human` or `json`.
    #[arg(long, env = "KNOTSHAPE_LOG_FORMAT", value_enum, default_value_t = LogFormat::Human, global = true)]
    pub log_format: LogFormat,

    /// Log filter in `tracing` syntax, e.g. `info` or `knotshape=debug,tower_http=info`.
    #[arg(long, env = "KNOTSHAPE_LOG", default_value = "info", global = true)]
    pub log_filter: String,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            listen: SocketAddr::from(([127, 0, 0, 1], 8080)),
            api_key: None,
            cors_allow_origins: Vec::new(),
            max_body_bytes: Limits::DEFAULT.max_body_bytes,
            max_control_points: Limits::DEFAULT.max_control_points,
            max_parameters: Limits::DEFAULT.max_parameters,
            max_derivative_order: Limits::DEFAULT.max_derivative_order,
            max_polygon_vertices: Limits::DEFAULT.max_polygon_vertices,
            max_file_bytes: Limits::DEFAULT.max_file_bytes,
            max_file_entities: Limits::DEFAULT.max_file_entities,
            max_fit_points: Limits::DEFAULT.max_fit_points,
            max_surface_control_points: Limits::DEFAULT.max_surface_control_points,
            max_triangles: Limits::DEFAULT.max_triangles,
            request_timeout_ms: 10_000,
            concurrency_limit: 64,
            retry_after_secs: 1,
            drain_delay_ms: 0,
            header_timeout_ms: ConnectionLimits::DEFAULT.header_timeout_ms,
            idle_timeout_ms: ConnectionLimits::DEFAULT.idle_timeout_ms,
            body_timeout_ms: ConnectionLimits::DEFAULT.body_timeout_ms,
            max_connections: ConnectionLimits::DEFAULT.max_connections,
            worker_threads: 0,
            solve_threads: 0,
            log_format: LogFormat::Human,
            log_filter: "info".to_owned(),
        }
    }
}

impl Config {
    /// The size limits applied to request data.
    pub fn limits(&self) -> Limits {
        Limits {
            max_body_bytes: self.max_body_bytes,
            max_control_points: self.max_control_points,
            max_parameters: self.max_parameters,
            max_derivative_order: self.max_derivative_order,
            max_polygon_vertices: self.max_polygon_vertices,
            max_file_bytes: self.max_file_bytes,
            max_file_entities: self.max_file_entities,
            max_fit_points: self.max_fit_points,
            max_surface_control_points: self.max_surface_control_points,
            max_triangles: self.max_triangles,
        }
    }

    /// How long one request may take.
    pub fn request_timeout(&self) -> Duration {
        Duration::from_millis(self.request_timeout_ms)
    }

    /// The pause between readiness turning 503 and the listener closing.
    pub fn drain_delay(&self) -> Duration {
        Duration::from_millis(self.drain_delay_ms)
    }

    /// The limits applied to each connection, with the connection cap raised to
    /// [`ConnectionLimits::min_connections`] for this concurrency limit.
    pub fn connection_limits(&self) -> ConnectionLimits {
        let floor = ConnectionLimits::min_connections(self.concurrency_limit);
        ConnectionLimits {
            header_timeout_ms: self.header_timeout_ms,
            idle_timeout_ms: self.idle_timeout_ms,
            body_timeout_ms: self.body_timeout_ms,
            max_connections: self.max_connections.max(floor),
        }
    }
}

/// Limits of the connections themselves: how long a client may take to send, how long a
/// connection may sit idle, and how many may be open.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ConnectionLimits {
    /// Time to send a complete request head, in milliseconds.
    pub header_timeout_ms: u64,
    /// Time a kept-alive connection may wait for its next request, in milliseconds.
    pub idle_timeout_ms: u64,
    /// Time a request body may take to arrive, and a response may stay unread, in
    /// milliseconds.
    pub body_timeout_ms: u64,
    /// Connections open at once.
    pub max_connections: u32,
}

impl ConnectionLimits {
    /// The defaults: 10 s for a request head (hyper's own default is 30 s, nginx's 60 s), 60 s
    /// of keep-alive idleness (nginx: 75 s), 5 s for a body (below the 10 s request timeout, so
    /// that a slow client gets its 408 before the timeout's 503), 4 096 connections (about
    /// 8 KiB of read buffer each while idle).
    pub const DEFAULT: ConnectionLimits = ConnectionLimits {
        header_timeout_ms: 10_000,
        idle_timeout_ms: 60_000,
        body_timeout_ms: 5_000,
        max_connections: 4_096,
    };

    /// Connections beyond the concurrency limit that the cap always leaves: requests in
    /// progress hold at most `concurrency_limit` connections for long (other requests are
    /// answered at once), so at least this many are always waiting and can be displaced by a
    /// probe.
    pub const PROBE_HEADROOM: u32 = 16;

    /// The smallest connection cap for a concurrency limit.
    pub fn min_connections(concurrency_limit: usize) -> u32 {
        u32::try_from(concurrency_limit)
            .unwrap_or(u32::MAX)
            .saturating_add(Self::PROBE_HEADROOM)
            .min(MAX_CONNECTIONS)
    }

    /// Time to send a complete request head.
    pub fn header_timeout(&self) -> Duration {
        Duration::from_millis(self.header_timeout_ms)
    }

    /// Time a kept-alive connection may wait for its next request.
    pub fn idle_timeout(&self) -> Duration {
        Duration::from_millis(self.idle_timeout_ms)
    }

    /// Time a request body may take, and a response may stay unread.
    pub fn body_timeout(&self) -> Duration {
        Duration::from_millis(self.body_timeout_ms)
    }
}

impl Default for ConnectionLimits {
    fn default() -> Self {
        ConnectionLimits::DEFAULT
    }
}

/// The size limits that bound the work and the output of one request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Request body size in bytes.
    pub max_body_bytes: usize,
    /// Control points per curve.
    pub max_control_points: usize,
    /// Parameters (or samples) per evaluate request.
    pub max_parameters: usize,
    /// Derivative order per evaluate request.
    pub max_derivative_order: usize,
    /// Vertices per region polygon.
    pub max_polygon_vertices: usize,
    /// Bytes of an imported file's text.
    pub max_file_bytes: usize,
    /// Entities of an imported file, curves of an exported one.
    pub max_file_entities: usize,
    /// Points per interpolate or approximate request.
    pub max_fit_points: usize,
    /// Control points per surface.
    pub max_surface_control_points: usize,
    /// Triangles per tessellation answer.
    pub max_triangles: usize,
}

impl Limits {
    /// The defaults: 1 MiB bodies, 10 000 control points, 10 000 parameters, derivatives up to
    /// order 8, 2 000 vertices per polygon, files of 1 MiB and 100 000 entities, 10 000 points to
    /// fit, 10 000 control points per surface (the largest of 898 real CAD surfaces has 2 002;
    /// a net that large needs about as many bytes as the body limit allows) and 100 000
    /// triangles per mesh (about 10 MB of JSON).
    pub const DEFAULT: Limits = Limits {
        max_body_bytes: 1024 * 1024,
        max_control_points: 10_000,
        max_parameters: 10_000,
        max_derivative_order: 8,
        max_polygon_vertices: 2_000,
        max_file_bytes: 1024 * 1024,
        max_file_entities: 100_000,
        max_fit_points: 10_000,
        max_surface_control_points: 10_000,
        max_triangles: 100_000,
    };
}

impl Default for Limits {
    fn default() -> Self {
        Limits::DEFAULT
    }
}

/// Log output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LogFormat {
    /// Readable lines for a terminal.
    Human,
    /// One JSON object per line, for log collectors.
    Json,
}

/// A non-empty API key; its `Debug` output never shows the key.
#[derive(Clone, PartialEq, Eq)]
pub struct ApiKey(String);

impl ApiKey {
    /// The key's bytes, for a constant-time comparison.
    pub fn as_bytes(&self) -> &[u8] {
        self.0.as_bytes()
    }
}

impl fmt::Debug for ApiKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("ApiKey(<redacted>)")
    }
}

impl FromStr for ApiKey {
    type Err = String;

    fn from_str(key: &str) -> Result<Self, Self::Err> {
        let key = key.trim();
        if key.is_empty() {
            return Err("the API key must not be empty".to_owned());
        }
        if !key.bytes().all(|b| b.is_ascii_graphic()) {
            return Err("the API key must be printable ASCII without spaces".to_owned());
        }
        Ok(ApiKey(key.to_owned()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parsing_no_arguments_gives_the_defaults() {
        let parsed = Config::try_parse_from(["knotshape"]).unwrap();
        // The environment of the test run may set KNOTSHAPE_* variables; compare only when not.
        if std::env::vars().all(|(k, _)| !k.starts_with("KNOTSHAPE_")) {
            assert_eq!(parsed, Config::default());
        }
        assert_eq!(Config::default().listen.to_string(), "127.0.0.1:8080");
    }

    #[test]
    fn flags_override_defaults() {
        let parsed = Config::try_parse_from([
            "knotshape",
            "--listen",
            "0.0.0.0:9000",
            "--api-key",
            "s3cret",
            "--cors-allow-origin",
            "https://a.example,https://b.example",
            "--max-parameters",
            "5",
        ])
        .unwrap();
        assert_eq!(parsed.listen.to_string(), "0.0.0.0:9000");
        assert_eq!(parsed.api_key.as_ref().unwrap().as_bytes(), b"s3cret");
        assert_eq!(parsed.cors_allow_origins.len(), 2);
        assert_eq!(parsed.limits().max_parameters, 5);
        let surfaces = Config::try_parse_from([
            "knotshape",
            "--max-surface-control-points",
            "64",
            "--max-triangles",
            "1000",
        ])
        .unwrap();
        assert_eq!(surfaces.limits().max_surface_control_points, 64);
        assert_eq!(surfaces.limits().max_triangles, 1000);
    }

    #[test]
    fn worker_threads_are_bounded() {
        let parse = |value: &str| Config::try_parse_from(["knotshape", "--worker-threads", value]);
        assert_eq!(parse("3").unwrap().worker_threads, 3);
        assert_eq!(parse("0").unwrap().worker_threads, 0);
        assert!(parse("1025").is_err());
        assert!(parse("-1").is_err());
        let solve = |value: &str| Config::try_parse_from(["knotshape", "--solve-threads", value]);
        assert_eq!(solve("1").unwrap().solve_threads, 1);
        assert_eq!(Config::default().solve_threads, 0);
        assert!(solve("1025").is_err());
    }

    #[test]
    fn connection_timeouts_and_the_cap_are_bounded() {
        for flag in [
            "--header-timeout-ms",
            "--idle-timeout-ms",
            "--body-timeout-ms",
        ] {
            let parse = |value: &str| Config::try_parse_from(["knotshape", flag, value]);
            assert!(parse("1").is_ok(), "{flag} 1");
            assert!(parse("3600000").is_ok(), "{flag} 3600000");
            assert!(parse("0").is_err(), "{flag} 0 would disable the timeout");
            assert!(parse("3600001").is_err(), "{flag} above an hour");
            assert!(parse("-5").is_err(), "{flag} -5");
        }
        let parse = |value: &str| Config::try_parse_from(["knotshape", "--max-connections", value]);
        assert_eq!(parse("5000").unwrap().max_connections, 5000);
        assert!(parse("0").is_err());
        assert!(parse("1048577").is_err());
        let parsed = Config::try_parse_from([
            "knotshape",
            "--header-timeout-ms",
            "250",
            "--idle-timeout-ms",
            "750",
            "--body-timeout-ms",
            "500",
        ])
        .unwrap();
        let limits = parsed.connection_limits();
        assert_eq!(limits.header_timeout(), Duration::from_millis(250));
        assert_eq!(limits.idle_timeout(), Duration::from_millis(750));
        assert_eq!(limits.body_timeout(), Duration::from_millis(500));
    }

    #[test]
    fn the_connection_cap_leaves_room_above_the_concurrency_limit() {
        let config = Config {
            max_connections: 10,
            concurrency_limit: 64,
            ..Config::default()
        };
        assert_eq!(config.connection_limits().max_connections, 64 + 16);
        let config = Config {
            max_connections: 1000,
            ..config
        };
        assert_eq!(config.connection_limits().max_connections, 1000);
        assert_eq!(
            ConnectionLimits::min_connections(usize::MAX),
            MAX_CONNECTIONS
        );
        let defaults = Config::default().connection_limits();
        assert!(defaults.header_timeout() <= Duration::from_secs(10));
        assert!(defaults.idle_timeout() <= Duration::from_secs(60));
        assert!(defaults.body_timeout() < Config::default().request_timeout());
    }

    #[test]
    fn empty_or_spaced_api_keys_are_rejected_and_never_printed() {
        assert!("".parse::<ApiKey>().is_err());
        assert!("a b".parse::<ApiKey>().is_err());
        let key: ApiKey = "topsecret".parse().unwrap();
        assert!(!format!("{key:?}").contains("topsecret"));
    }
}
