//! Test harness: starts the real server on `127.0.0.1:0` and talks to it over HTTP.

use std::sync::Once;
use std::time::Duration;

use knotshape::config::{Config, LogFormat};
use knotshape::http::Server;
use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::sync::oneshot;
use tokio::task::JoinHandle;

/// Logs are silent unless `TEST_LOG` is set (then at its value as the filter, or `debug`).
fn init_logs_once() {
    static INIT: Once = Once::new();
    INIT.call_once(|| {
        if let Ok(filter) = std::env::var("TEST_LOG") {
            let filter = if filter.is_empty() || filter == "1" || filter == "true" {
                "debug".to_owned()
            } else {
                filter
            };
            knotshape::telemetry::init_subscriber(LogFormat::Human, &filter, std::io::stdout)
                .expect("install the test log subscriber");
        }
    });
}

/// A running server and a client for it.
pub struct TestApp {
    /// `http://127.0.0.1:<port>`.
    pub address: String,
    /// `127.0.0.1:<port>`.
    pub socket: std::net::SocketAddr,
    pub client: reqwest::Client,
    shutdown: Option<oneshot::Sender<()>>,
    server: Option<JoinHandle<std::io::Result<()>>>,
}

/// A server with the default configuration (but an ephemeral port).
pub async fn spawn_app() -> TestApp {
    spawn_app_with(|_| {}).await
}

/// A server whose configuration `configure` adjusts.
pub async fn spawn_app_with(configure: impl FnOnce(&mut Config)) -> TestApp {
    init_logs_once();
    let mut config = Config {
        listen: "127.0.0.1:0".parse().unwrap(),
        ..Config::default()
    };
    configure(&mut config);
    let server = Server::bind(&config).await.expect("bind 127.0.0.1:0");
    let socket = server.local_addr().unwrap();
    let (shutdown, signal) = oneshot::channel::<()>();
    let handle = tokio::spawn(server.serve_until(async move {
        let _ = signal.await;
    }));
    TestApp {
        address: format!("http://{socket}"),
        socket,
        client: reqwest::Client::builder()
            .timeout(Duration::from_secs(20))
            .build()
            .unwrap(),
        shutdown: Some(shutdown),
        server: Some(handle),
    }
}

impl TestApp {
    /// POSTs `body` as JSON to `path`.
    pub async fn post(&self, path: &str, body: &Value) -> reqwest::Response {
        self.client
            .post(format!("{}{path}", self.address))
            .json(body)
            .send()
            .await
            .expect("send request")
    }

    /// POSTs `body` as JSON and returns status and parsed body.
    pub async fn post_json(&self, path: &str, body: &Value) -> (u16, Value) {
        let response = self.post(path, body).await;
        let status = response.status().as_u16();
        let body = response.json::<Value>().await.expect("a JSON body");
        (status, body)
    }

    /// GET `path`.
    pub async fn get(&self, path: &str) -> reqwest::Response {
        self.client
            .get(format!("{}{path}", self.address))
            .send()
            .await
            .expect("send request")
    }

    /// Asks the server to shut down gracefully.
    pub fn trigger_shutdown(&mut self) {
        if let Some(shutdown) = self.shutdown.take() {
            let _ = shutdown.send(());
        }
    }

    /// Waits (bounded) for the server task to finish after [`TestApp::trigger_shutdown`].
    pub async fn stopped(&mut self) -> std::io::Result<()> {
        let handle = self.server.take().expect("server still owned");
        tokio::time::timeout(Duration::from_secs(10), handle)
            .await
            .expect("server stops within 10 s")
            .expect("server task did not panic")
    }

    /// The value of an un-labelled metric, read from `/metrics`.
    pub async fn metric(&self, name: &str) -> Option<f64> {
        let text = self.get("/metrics").await.text().await.unwrap();
        text.lines()
            .find_map(|line| line.strip_prefix(&format!("{name} ")))
            .and_then(|value| value.trim().parse().ok())
    }

    /// Starts a POST whose body is only partly sent, so the request stays in flight until
    /// [`SlowRequest::finish`].
    pub async fn start_slow_post(&self, path: &str, body: &Value) -> SlowRequest {
        let body = serde_json::to_vec(body).unwrap();
        let split = body.len() / 2;
        let mut stream = TcpStream::connect(self.socket).await.unwrap();
        let head = format!(
            "POST {path} HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
            self.socket,
            body.len()
        );
        stream.write_all(head.as_bytes()).await.unwrap();
        stream.write_all(&body[..split]).await.unwrap();
        stream.flush().await.unwrap();
        SlowRequest {
            stream,
            rest: body[split..].to_vec(),
        }
    }

    /// Sends raw bytes on a fresh connection and reads the whole response.
    pub async fn raw_exchange(&self, request: &[u8]) -> RawResponse {
        let mut stream = TcpStream::connect(self.socket).await.unwrap();
        stream.write_all(request).await.unwrap();
        stream.flush().await.unwrap();
        SlowRequest {
            stream,
            rest: Vec::new(),
        }
        .response()
        .await
    }

    /// Polls until more than `count` requests are in flight (the poll itself is one).
    pub async fn wait_for_in_flight(&self, count: u32) {
        for _ in 0..200 {
            if self
                .metric("knotshape_http_requests_in_flight")
                .await
                .is_some_and(|value| value > f64::from(count))
            {
                return;
            }
            tokio::time::sleep(Duration::from_millis(10)).await;
        }
        panic!("the slow request never reached the server");
    }
}

/// A request whose body is half sent.
pub struct SlowRequest {
    stream: TcpStream,
    rest: Vec<u8>,
}

impl SlowRequest {
    /// Sends the rest of the body and reads the response: status, headers (lower-case
    /// names) and body.
    pub async fn finish(mut self) -> RawResponse {
        self.stream.write_all(&self.rest).await.unwrap();
        self.stream.flush().await.unwrap();
        self.response().await
    }

    /// Reads the response without sending the rest of the body.
    pub async fn response(mut self) -> RawResponse {
        let mut raw = Vec::new();
        tokio::time::timeout(Duration::from_secs(10), self.stream.read_to_end(&mut raw))
            .await
            .expect("response within 10 s")
            .unwrap();
        RawResponse::parse(&raw)
    }
}

/// A response read off a raw socket.
pub struct RawResponse {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: Value,
}

impl RawResponse {
    fn parse(raw: &[u8]) -> RawResponse {
        let text = String::from_utf8_lossy(raw);
        let (head, body) = text.split_once("\r\n\r\n").expect("a complete response");
        let mut lines = head.lines();
        let status = lines
            .next()
            .unwrap()
            .split(' ')
            .nth(1)
            .unwrap()
            .parse()
            .unwrap();
        let headers = lines
            .filter_map(|line| line.split_once(':'))
            .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_owned()))
            .collect();
        RawResponse {
            status,
            headers,
            body: serde_json::from_str(body).expect("a JSON body"),
        }
    }

    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }
}

/// Asserts that `body` is an RFC 9457 problem document with `status`, and, when `pointer` is
/// given, that its `errors` name that pointer. Returns the body.
pub fn assert_problem(status: u16, body: &Value, pointer: Option<&str>) {
    assert_eq!(body["status"].as_u64(), Some(u64::from(status)), "{body}");
    assert!(
        body["type"].as_str().is_some_and(|t| !t.is_empty()),
        "{body}"
    );
    assert!(
        body["title"].as_str().is_some_and(|t| !t.is_empty()),
        "{body}"
    );
    assert!(
        body["detail"].as_str().is_some_and(|t| !t.is_empty()),
        "{body}"
    );
    if let Some(pointer) = pointer {
        let errors = body["errors"].as_array().expect("an `errors` list");
        assert!(
            errors
                .iter()
                .any(|e| e["pointer"] == pointer && e["detail"].is_string()),
            "expected pointer {pointer} in {body}"
        );
    }
}

/// Asserts the response is a problem document (by content type and body) and returns it.
pub async fn expect_problem(
    response: reqwest::Response,
    status: u16,
    pointer: Option<&str>,
) -> Value {
    assert_eq!(response.status().as_u16(), status);
    let content_type = response
        .headers()
        .get("content-type")
        .and_then(|v| v.to_str().ok())
        .unwrap_or_default()
        .to_owned();
    assert_eq!(content_type, "application/problem+json");
    let body: Value = response.json().await.expect("a JSON problem body");
    assert_problem(status, &body, pointer);
    body
}

/// Reads a JSON array of numbers.
pub fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("an array: {value}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// Reads a JSON array of points.
pub fn points(value: &Value) -> Vec<Vec<f64>> {
    value.as_array().unwrap().iter().map(numbers).collect()
}
