//! Connection limits over real sockets: half-open heads and idle connections are closed
//! within the configured time, a trickling body gets 408, an unread response is cut, and
//! thousands of half-open connections neither starve the probes nor a solve, under the cap
//! and beyond it.

use std::time::{Duration, Instant};

use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use crate::helpers::{TestApp, assert_problem, spawn_app_with};
use crate::reference::cubic_2d;

/// Short timeouts, so that each test takes well under a second of waiting.
const HEADER_MS: u64 = 300;
const IDLE_MS: u64 = 700;
const BODY_MS: u64 = 300;

/// Slack on top of a timeout for the server to notice (timer granularity, a busy machine).
const SLACK: Duration = Duration::from_millis(1_500);

async fn app_with_short_timeouts() -> TestApp {
    spawn_app_with(|config| {
        config.header_timeout_ms = HEADER_MS;
        config.idle_timeout_ms = IDLE_MS;
        config.body_timeout_ms = BODY_MS;
    })
    .await
}

/// Reads until the server closes the connection (EOF or reset); returns what arrived and
/// when the connection ended, measured from `start`.
async fn read_until_closed(stream: &mut TcpStream, start: Instant) -> (Vec<u8>, Duration) {
    let mut received = Vec::new();
    let mut chunk = [0u8; 4096];
    let deadline = Duration::from_secs(10);
    loop {
        match tokio::time::timeout(deadline, stream.read(&mut chunk)).await {
            Ok(Ok(0)) | Ok(Err(_)) => return (received, start.elapsed()),
            Ok(Ok(n)) => received.extend_from_slice(&chunk[..n]),
            Err(_) => panic!("the server kept the connection open for 10 s"),
        }
    }
}

/// Reads one response with a `Content-Length` body off a kept-alive connection.
async fn read_one_response(stream: &mut TcpStream) -> (u16, Vec<u8>) {
    let mut received = Vec::new();
    let mut chunk = [0u8; 4096];
    loop {
        let n = tokio::time::timeout(Duration::from_secs(5), stream.read(&mut chunk))
            .await
            .expect("a response within 5 s")
            .unwrap();
        assert!(n > 0, "closed before a whole response");
        received.extend_from_slice(&chunk[..n]);
        let text = String::from_utf8_lossy(&received).into_owned();
        if let Some((head, body)) = text.split_once("\r\n\r\n") {
            let length: usize = head
                .lines()
                .find_map(|line| {
                    let (name, value) = line.split_once(':')?;
                    name.eq_ignore_ascii_case("content-length")
                        .then(|| value.trim().parse().unwrap())
                })
                .expect("a Content-Length");
            if body.len() >= length {
                let status = head.split(' ').nth(1).unwrap().parse().unwrap();
                return (status, body.as_bytes().to_vec());
            }
        }
    }
}

/// The value of `name` (with its labels, as written) in `/metrics`.
async fn metric(app: &TestApp, name: &str) -> f64 {
    let text = app.get("/metrics").await.text().await.unwrap();
    text.lines()
        .find_map(|line| line.strip_prefix(name)?.strip_prefix(' '))
        .and_then(|value| value.trim().parse().ok())
        .unwrap_or_else(|| panic!("{name} not in /metrics:\n{text}"))
}

fn closed(reason: &str) -> String {
    format!("knotshape_http_connections_closed_total{{reason=\"{reason}\"}}")
}

#[tokio::test]
async fn half_open_heads_and_silent_connections_are_closed_at_the_header_timeout() {
    let app = app_with_short_timeouts().await;
    let start = Instant::now();
    let mut silent = TcpStream::connect(app.socket).await.unwrap();
    let mut half_open = TcpStream::connect(app.socket).await.unwrap();
    half_open
        .write_all(b"GET /healthz HTTP/1.1\r\nHost: x\r\nX-Slow: ")
        .await
        .unwrap();
    // A head sent one byte at a time, each in time, but not whole within the timeout.
    let mut trickled = TcpStream::connect(app.socket).await.unwrap();
    let trickle = tokio::spawn(async move {
        for byte in b"GET /healthz HTTP/1.1\r\nHost: x\r\n".iter() {
            if trickled.write_all(&[*byte]).await.is_err() {
                break;
            }
            tokio::time::sleep(Duration::from_millis(40)).await;
        }
        read_until_closed(&mut trickled, start).await
    });
    for stream in [&mut silent, &mut half_open] {
        let (received, after) = read_until_closed(stream, start).await;
        assert!(
            !String::from_utf8_lossy(&received).contains(" 200 "),
            "no answer to half a head"
        );
        let timeout = Duration::from_millis(HEADER_MS);
        assert!(after >= timeout - Duration::from_millis(50), "{after:?}");
        assert!(after < timeout + SLACK, "closed only after {after:?}");
    }
    let (_, after) = trickle.await.unwrap();
    assert!(
        after < Duration::from_millis(HEADER_MS) + SLACK,
        "{after:?}"
    );
    assert!(metric(&app, &closed("header_timeout")).await >= 3.0);
}

#[tokio::test]
async fn an_idle_keep_alive_connection_is_closed_at_the_idle_timeout_not_the_header_timeout() {
    let app = app_with_short_timeouts().await;
    let mut stream = TcpStream::connect(app.socket).await.unwrap();
    let request = b"GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
    stream.write_all(request).await.unwrap();
    assert_eq!(read_one_response(&mut stream).await.0, 200);
    // Longer than the header timeout, shorter than the idle timeout: still open.
    tokio::time::sleep(Duration::from_millis(HEADER_MS + 150)).await;
    stream.write_all(request).await.unwrap();
    assert_eq!(read_one_response(&mut stream).await.0, 200);
    let idle_since = Instant::now();
    let (received, after) = read_until_closed(&mut stream, idle_since).await;
    assert!(received.is_empty());
    let timeout = Duration::from_millis(IDLE_MS);
    assert!(after >= timeout - Duration::from_millis(50), "{after:?}");
    assert!(after < timeout + SLACK, "closed only after {after:?}");
    assert!(metric(&app, &closed("idle_timeout")).await >= 1.0);
}

#[tokio::test]
async fn a_trickling_body_is_answered_408_and_the_connection_closed() {
    let app = app_with_short_timeouts().await;
    let body = serde_json::to_vec(&json!({
        "curve": cubic_2d().to_json(false),
        "parameters": [0.5],
    }))
    .unwrap();
    let mut stream = TcpStream::connect(app.socket).await.unwrap();
    let head = format!(
        "POST /v1/curves/evaluate HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len()
    );
    let start = Instant::now();
    stream.write_all(head.as_bytes()).await.unwrap();
    let (mut reader, mut writer) = stream.into_split();
    // Every byte in good time after the last, but the whole takes longer than allowed.
    let trickle = tokio::spawn(async move {
        for byte in &body[..40] {
            if writer.write_all(&[*byte]).await.is_err() {
                break;
            }
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
        writer
    });
    let mut received = Vec::new();
    tokio::time::timeout(Duration::from_secs(10), reader.read_to_end(&mut received))
        .await
        .expect("closed within 10 s")
        .ok();
    let after = start.elapsed();
    drop(trickle.await.unwrap());
    assert!(after < Duration::from_millis(BODY_MS) + SLACK, "{after:?}");
    let text = String::from_utf8_lossy(&received);
    let (head, body) = text.split_once("\r\n\r\n").expect("a response");
    assert!(head.starts_with("HTTP/1.1 408"), "{head}");
    assert!(
        head.to_ascii_lowercase().contains("connection: close"),
        "{head}"
    );
    assert!(
        head.to_ascii_lowercase()
            .contains("content-type: application/problem+json"),
        "{head}"
    );
    let body: Value = serde_json::from_str(body).unwrap();
    assert_problem(408, &body, None);
    assert!(metric(&app, &closed("body_timeout")).await >= 1.0);
}

#[tokio::test]
async fn a_client_that_does_not_read_its_response_is_cut_off() {
    let app = spawn_app_with(|config| {
        config.body_timeout_ms = BODY_MS;
        config.max_parameters = 400_000;
    })
    .await;
    // About 16 MB of points: more than the socket buffers hold.
    let body = serde_json::to_vec(&json!({
        "curve": cubic_2d().to_json(false),
        "samples": 400_000,
    }))
    .unwrap();
    let mut stream = TcpStream::connect(app.socket).await.unwrap();
    let head = format!(
        "POST /v1/curves/evaluate HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len()
    );
    stream.write_all(head.as_bytes()).await.unwrap();
    stream.write_all(&body).await.unwrap();
    let mut send_timeouts = 0.0;
    for _ in 0..100 {
        send_timeouts = metric(&app, &closed("send_timeout")).await;
        if send_timeouts >= 1.0 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert_eq!(send_timeouts, 1.0, "the stalled response is cut within 5 s");
    drop(stream);
}

/// Soft limit on open files of this process (Linux), to size the number of connections.
fn open_files_limit() -> usize {
    std::fs::read_to_string("/proc/self/limits")
        .ok()
        .and_then(|limits| {
            let line = limits.lines().find(|l| l.starts_with("Max open files"))?;
            line.split_whitespace().nth(3)?.parse().ok()
        })
        .unwrap_or(1024)
}

/// Half-open connections to hold: 2 000, or fewer if the descriptors (two per connection in
/// this process, client and server side, shared with the other tests) do not allow it.
fn half_open_count() -> usize {
    (open_files_limit().saturating_sub(1_000) / 4).min(2_000)
}

/// Opens `count` connections that each send half a request head.
async fn hold_half_open(app: &TestApp, count: usize) -> Vec<TcpStream> {
    let mut held = Vec::with_capacity(count);
    for _ in 0..count {
        let Ok(mut stream) = TcpStream::connect(app.socket).await else {
            continue;
        };
        // The server may already have displaced it; a failed write is fine.
        let _ = stream
            .write_all(b"POST /v1/shape/solve HTTP/1.1\r\nHost: x\r\n")
            .await;
        held.push(stream);
    }
    held
}

/// `/healthz`, `/metrics` and a solve each answer within `limit`.
async fn probes_and_a_solve_answer_within(app: &TestApp, limit: Duration) {
    for path in ["/healthz", "/metrics", "/readyz"] {
        let start = Instant::now();
        let response = app.get(path).await;
        assert_eq!(response.status(), 200, "{path}");
        assert!(start.elapsed() < limit, "{path} took {:?}", start.elapsed());
    }
    let body: Value = serde_json::from_str(include_str!("../../benches/load/solve.json")).unwrap();
    let start = Instant::now();
    let (status, answer) = app.post_json("/v1/shape/solve", &body).await;
    assert_eq!(status, 200, "{answer}");
    assert!(start.elapsed() < limit, "solve took {:?}", start.elapsed());
}

#[tokio::test]
async fn thousands_of_half_open_connections_under_the_cap_leave_probes_and_solves_prompt() {
    let count = half_open_count();
    assert!(count >= 500, "too few descriptors for the test: {count}");
    let app = spawn_app_with(|config| config.max_connections = 10_000).await;
    let held = hold_half_open(&app, count).await;
    let mut open = 0.0;
    for _ in 0..100 {
        open = metric(&app, "knotshape_http_connections_open").await;
        if open >= count as f64 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert!(open >= count as f64, "{open} of {count} held");
    probes_and_a_solve_answer_within(&app, Duration::from_millis(500)).await;
    drop(held);
}

#[tokio::test]
async fn beyond_the_cap_half_open_connections_are_displaced_and_probes_still_answer() {
    let count = half_open_count();
    // The smallest cap the service allows with a concurrency limit of 4: 20.
    let app = spawn_app_with(|config| {
        config.concurrency_limit = 4;
        config.max_connections = 1;
    })
    .await;
    let held = hold_half_open(&app, count).await;
    probes_and_a_solve_answer_within(&app, Duration::from_millis(500)).await;
    let open = metric(&app, "knotshape_http_connections_open").await;
    assert!(open <= 20.0 + 2.0, "{open} open above a cap of 20");
    let evicted = metric(&app, &closed("evicted")).await;
    assert!(
        evicted >= (count - 20) as f64,
        "{evicted} displaced of {count}"
    );
    drop(held);
}
