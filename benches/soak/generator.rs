//! Soak load generator for `benches/soak.sh` (`cargo run --release --example soak`): mixed traffic over loopback to every endpoint
//! of the running server's own OpenAPI document, good and bad requests, a few slow clients,
//! for a bounded time and at a bounded rate; prints the server's RSS and the error counts by
//! class every 10 s, and exits 1 when the server made an error of its own (a 5xx other than
//! 503 shedding, a reset, an answer other than the one expected) or its RSS grew by 10 % or
//! more after the warm-up: the median RSS of the last minute against the median of the first
//! minute after the warm-up (medians, because a few concurrent too-large bodies — each
//! buffered up to the limit before the 413 — move single samples by megabytes).
//!
//! The endpoints come from `GET /openapi.json`: every GET operation, and every POST with the
//! example of its request schema as the good body — a new documented endpoint is soaked
//! without a change here. [`BAD_REQUESTS`] lists the bad variants, one line each.
//!
//! One file of some 470 lines: the example is a single binary target, and its parts (endpoint
//! discovery, the request mix, slow clients, the report) are read together.
//!
//! Environment: `SOAK_URL` (e.g. `http://127.0.0.1:8080`), `SOAK_SERVER_PID` (for RSS, from
//! `/proc`), `SOAK_DURATION_SECS` (default 600), `SOAK_RATE` (requests/s, default 400),
//! `SOAK_MAX_BODY_BYTES` (the server's limit, default 1 MiB).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// Time before the RSS baseline is taken.
const WARM_UP: Duration = Duration::from_secs(60);
/// Allowed RSS growth after the warm-up.
const MAX_RSS_GROWTH: f64 = 0.10;
/// Concurrent request loops.
const WORKERS: usize = 16;
/// Clients holding half a request head, each until the server closes it.
const HALF_OPEN_CLIENTS: usize = 8;
/// Clients trickling a body slower than the server allows.
const TRICKLING_CLIENTS: usize = 2;
/// How long past the server's header (10 s) or body (5 s) timeout a slow client waits
/// before it counts the server as not having closed it.
const SLOW_CLIENT_PATIENCE: Duration = Duration::from_secs(20);

/// One kind of bad request: its name, how to make its body from the good one, and the
/// statuses that are right for it.
struct BadRequest {
    name: &'static str,
    body: fn(&Value, usize) -> Vec<u8>,
    expected: &'static [u16],
}

/// The bad variants sent to every POST endpoint.
const BAD_REQUESTS: &[BadRequest] = &[
    BadRequest {
        name: "malformed_json",
        body: |good, _| truncated(good),
        expected: &[400],
    },
    BadRequest {
        name: "invalid_curve",
        body: |good, _| with_degree(good, 0),
        expected: &[400, 422],
    },
    BadRequest {
        name: "wrong_types",
        body: |_, _| br#"{"curve": "not a curve"}"#.to_vec(),
        expected: &[400, 422],
    },
    BadRequest {
        name: "too_large",
        body: |_, max| too_large(max),
        expected: &[413],
    },
];

fn truncated(good: &Value) -> Vec<u8> {
    let text = serde_json::to_vec(good).unwrap();
    text[..text.len() / 2].to_vec()
}

fn with_degree(good: &Value, degree: u64) -> Vec<u8> {
    let mut bad = good.clone();
    bad["curve"]["degree"] = Value::from(degree);
    serde_json::to_vec(&bad).unwrap()
}

fn too_large(max_body_bytes: usize) -> Vec<u8> {
    let mut body = b"{\"pad\": \"".to_vec();
    body.resize(max_body_bytes + 16, b'x');
    body.extend_from_slice(b"\"}");
    body
}

/// One request the workers send.
#[derive(Clone)]
struct Request {
    class: String,
    method: reqwest::Method,
    path: String,
    body: Option<Vec<u8>>,
    expected: Vec<u16>,
}

/// Counts by class (`<request>: <outcome>`), and the server's own errors.
#[derive(Default)]
struct Tally {
    counts: BTreeMap<String, u64>,
    server_errors: u64,
    requests: u64,
}

impl Tally {
    fn count(&mut self, key: String, server_error: bool) {
        *self.counts.entry(key).or_default() += 1;
        self.requests += 1;
        if server_error {
            self.server_errors += 1;
        }
    }
}

type SharedTally = Arc<Mutex<Tally>>;

fn record(tally: &SharedTally, key: String, server_error: bool) {
    tally.lock().unwrap().count(key, server_error);
}

/// The requests to send, from the server's document.
async fn requests_from_document(
    client: &reqwest::Client,
    base: &str,
    max_body: usize,
) -> Vec<Request> {
    let document: Value = client
        .get(format!("{base}/openapi.json"))
        .send()
        .await
        .expect("GET /openapi.json")
        .json()
        .await
        .expect("a JSON document");
    let schemas = &document["components"]["schemas"];
    let mut requests = Vec::new();
    for (path, item) in document["paths"].as_object().expect("paths") {
        if item.get("get").is_some() {
            requests.push(Request {
                class: format!("GET {path}"),
                method: reqwest::Method::GET,
                path: path.clone(),
                body: None,
                expected: vec![200],
            });
        }
        let Some(post) = item.get("post") else {
            continue;
        };
        let reference = post["requestBody"]["content"]["application/json"]["schema"]["$ref"]
            .as_str()
            .unwrap_or_else(|| panic!("POST {path}: no request schema"));
        let name = reference.rsplit('/').next().unwrap();
        let good = schemas[name]
            .get("example")
            .unwrap_or_else(|| panic!("POST {path}: schema {name} has no example to send"))
            .clone();
        requests.push(Request {
            class: format!("POST {path} good"),
            method: reqwest::Method::POST,
            path: path.clone(),
            body: Some(serde_json::to_vec(&good).unwrap()),
            expected: vec![200],
        });
        for bad in BAD_REQUESTS {
            requests.push(Request {
                class: format!("POST {path} {}", bad.name),
                method: reqwest::Method::POST,
                path: path.clone(),
                body: Some((bad.body)(&good, max_body)),
                expected: bad.expected.to_vec(),
            });
        }
    }
    requests.push(Request {
        class: "GET unknown path".to_owned(),
        method: reqwest::Method::GET,
        path: "/v1/no-such-route".to_owned(),
        body: None,
        expected: vec![404],
    });
    requests.push(Request {
        class: "DELETE /healthz".to_owned(),
        method: reqwest::Method::DELETE,
        path: "/healthz".to_owned(),
        body: None,
        expected: vec![405],
    });
    requests
}

/// Sends `request` and records the outcome.
async fn send(client: &reqwest::Client, base: &str, request: &Request, tally: &SharedTally) {
    let mut builder = client.request(request.method.clone(), format!("{base}{}", request.path));
    if let Some(body) = &request.body {
        builder = builder
            .header("content-type", "application/json")
            .body(body.clone());
    }
    match builder.send().await {
        Ok(response) => {
            let status = response.status().as_u16();
            let retry_after = response.headers().contains_key("retry-after");
            let read = response.bytes().await;
            let (outcome, server_error) = match read {
                Err(error) => (format!("body read failed: {error}"), true),
                Ok(_) if request.expected.contains(&status) => (status.to_string(), false),
                // Shedding at the concurrency limit is intended.
                Ok(_) if status == 503 && retry_after => ("503 shed".to_owned(), false),
                Ok(_) => (format!("{status} UNEXPECTED"), true),
            };
            record(tally, format!("{}: {outcome}", request.class), server_error);
        }
        // A too-large body may be refused while it is being sent; that is the server's right.
        Err(_) if request.expected == [413] => record(
            tally,
            format!("{}: closed while sending", request.class),
            false,
        ),
        Err(error) => record(
            tally,
            format!("{}: TRANSPORT ERROR {}", request.class, error_kind(&error)),
            true,
        ),
    }
}

fn error_kind(error: &reqwest::Error) -> &'static str {
    if error.is_timeout() {
        "timeout"
    } else if error.is_connect() {
        "connect"
    } else {
        "reset or closed"
    }
}

/// Holds half a request head until the server closes the connection, again and again.
async fn half_open_client(address: String, until: Instant, tally: SharedTally) {
    while Instant::now() < until {
        let Ok(mut stream) = TcpStream::connect(&address).await else {
            record(
                &tally,
                "slow: half-open head: CONNECT FAILED".to_owned(),
                true,
            );
            tokio::time::sleep(Duration::from_secs(1)).await;
            continue;
        };
        let _ = stream
            .write_all(b"POST /v1/shape/solve HTTP/1.1\r\nHost: soak\r\n")
            .await;
        let outcome = wait_for_close(&mut stream, until).await;
        record(
            &tally,
            format!("slow: half-open head: {outcome}"),
            outcome.ends_with('!'),
        );
    }
}

/// Sends a body one byte per second, slower than the server's body timeout allows.
async fn trickling_client(address: String, until: Instant, tally: SharedTally) {
    while Instant::now() < until {
        let Ok(stream) = TcpStream::connect(&address).await else {
            record(
                &tally,
                "slow: trickling body: CONNECT FAILED".to_owned(),
                true,
            );
            tokio::time::sleep(Duration::from_secs(1)).await;
            continue;
        };
        let (mut reader, mut writer) = stream.into_split();
        let head = "POST /v1/curves/evaluate HTTP/1.1\r\nHost: soak\r\nContent-Type: application/json\r\nContent-Length: 1000\r\n\r\n{";
        let _ = writer.write_all(head.as_bytes()).await;
        let trickle = tokio::spawn(async move {
            for _ in 0..60 {
                tokio::time::sleep(Duration::from_secs(1)).await;
                if writer.write_all(b" ").await.is_err() {
                    break;
                }
            }
        });
        let mut answer = Vec::new();
        let read =
            tokio::time::timeout(SLOW_CLIENT_PATIENCE, reader.read_to_end(&mut answer)).await;
        trickle.abort();
        let outcome = match read {
            Err(_) => "NOT ANSWERED!",
            Ok(_) if answer.starts_with(b"HTTP/1.1 408") => "408",
            // A reset can swallow the 408 when unsent bytes meet the close; the connection
            // was still closed in time.
            Ok(_) if answer.is_empty() => "closed",
            Ok(_) => "OTHER ANSWER!",
        };
        record(
            &tally,
            format!("slow: trickling body: {outcome}"),
            outcome.ends_with('!'),
        );
    }
}

/// Waits until the server closes `stream`; the outcome ends with `!` when it did not in time.
async fn wait_for_close(stream: &mut TcpStream, until: Instant) -> String {
    let mut buffer = [0u8; 1024];
    let patience = SLOW_CLIENT_PATIENCE
        .min(until.saturating_duration_since(Instant::now()) + SLOW_CLIENT_PATIENCE);
    match tokio::time::timeout(patience, stream.read(&mut buffer)).await {
        Ok(Ok(0)) | Ok(Err(_)) => "closed by the server".to_owned(),
        Ok(Ok(_)) => "answered".to_owned(),
        Err(_) => "NOT CLOSED!".to_owned(),
    }
}

/// RSS samples (10 s apart) in a one-minute window.
const RSS_WINDOW: usize = 6;

/// The median of `values` (0 for none).
fn median(values: &[u64]) -> u64 {
    let mut sorted = values.to_vec();
    sorted.sort_unstable();
    sorted.get(sorted.len() / 2).copied().unwrap_or(0)
}

/// The server's resident set size in KiB.
fn rss_kib(pid: &str) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|line| line.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(default)
}

#[tokio::main]
async fn main() -> std::process::ExitCode {
    let base: String = std::env::var("SOAK_URL").expect("SOAK_URL");
    let address = base.trim_start_matches("http://").to_owned();
    let pid = std::env::var("SOAK_SERVER_PID").expect("SOAK_SERVER_PID");
    let duration = Duration::from_secs(env_or("SOAK_DURATION_SECS", 600));
    let rate: u64 = env_or("SOAK_RATE", 400).max(1);
    let max_body = env_or("SOAK_MAX_BODY_BYTES", 1024 * 1024);

    let client = reqwest::Client::builder()
        .timeout(Duration::from_secs(15))
        .pool_max_idle_per_host(WORKERS)
        .build()
        .unwrap();
    let requests = Arc::new(requests_from_document(&client, &base, max_body).await);
    println!(
        "soak: {} request kinds for {:?} at {rate} requests/s:",
        requests.len(),
        duration
    );
    for request in requests.iter() {
        println!("  {}", request.class);
    }
    // A fixed mix: every request kind in turn, good ones three times as often as bad ones.
    let schedule: Arc<Vec<usize>> = Arc::new(
        requests
            .iter()
            .enumerate()
            .flat_map(|(index, request)| {
                let good = request.expected == [200];
                std::iter::repeat_n(index, if good { 3 } else { 1 })
            })
            .collect(),
    );
    let start = Instant::now();
    let until = start + duration;
    let tally = SharedTally::default();

    let mut tasks = Vec::new();
    let per_worker = Duration::from_secs_f64(WORKERS as f64 / rate as f64);
    for worker in 0..WORKERS {
        let (client, base, requests, tally) = (
            client.clone(),
            base.clone(),
            requests.clone(),
            tally.clone(),
        );
        let schedule = schedule.clone();
        tasks.push(tokio::spawn(async move {
            let mut ticks = tokio::time::interval(per_worker);
            ticks.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
            let mut index = worker;
            while Instant::now() < until {
                ticks.tick().await;
                let request = &requests[schedule[index % schedule.len()]];
                send(&client, &base, request, &tally).await;
                index += WORKERS + 1;
            }
        }));
    }
    for _ in 0..HALF_OPEN_CLIENTS {
        tasks.push(tokio::spawn(half_open_client(
            address.clone(),
            until,
            tally.clone(),
        )));
    }
    for _ in 0..TRICKLING_CLIENTS {
        tasks.push(tokio::spawn(trickling_client(
            address.clone(),
            until,
            tally.clone(),
        )));
    }

    // RSS samples after the warm-up, one per 10 s.
    let mut samples: Vec<u64> = Vec::new();
    let mut last_requests = 0;
    while Instant::now() < until {
        tokio::time::sleep(
            Duration::from_secs(10).min(until.saturating_duration_since(Instant::now())),
        )
        .await;
        let Some(rss) = rss_kib(&pid) else {
            println!("soak: the server (pid {pid}) is gone");
            return std::process::ExitCode::FAILURE;
        };
        let elapsed = start.elapsed();
        if elapsed >= WARM_UP {
            samples.push(rss);
        }
        let tally = tally.lock().unwrap();
        println!(
            "soak: {:>4} s  rss {:>7} KiB  requests {:>8} (+{:.0}/s)  server errors {}",
            elapsed.as_secs(),
            rss,
            tally.requests,
            (tally.requests - last_requests) as f64 / 10.0,
            tally.server_errors,
        );
        last_requests = tally.requests;
    }
    for task in tasks {
        let _ = tokio::time::timeout(SLOW_CLIENT_PATIENCE, task).await;
    }
    let tally = tally.lock().unwrap();
    println!("\nsoak: counts by class");
    for (key, count) in &tally.counts {
        println!("  {count:>9}  {key}");
    }
    let window = samples.len().min(RSS_WINDOW);
    let baseline = median(&samples[..window]);
    let end = median(&samples[samples.len() - window..]);
    let peak = samples.iter().copied().max().unwrap_or(0);
    let growth = (end as f64 - baseline as f64) / baseline.max(1) as f64;
    println!(
        "\nsoak: requests {}; server errors {}; median rss of the first minute after warm-up \
         {baseline} KiB, of the last minute {end} KiB (peak {peak} KiB), growth {:+.1} %",
        tally.requests,
        tally.server_errors,
        growth * 100.0
    );
    if tally.server_errors > 0 || growth >= MAX_RSS_GROWTH {
        println!("soak: FAILED");
        return std::process::ExitCode::FAILURE;
    }
    println!("soak: passed");
    std::process::ExitCode::SUCCESS
}
