//! Connections are dealt to the worker threads (one event loop each) in turn: every worker
//! serves the connections it is given, and keeps serving them.

use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use crate::helpers::spawn_app_with;

const HEALTHZ_BODY: &[u8] = b"{\"status\":\"ok\"}";

/// Sends `GET /healthz` on a kept-alive connection and reads its whole answer.
async fn healthz_on(stream: &mut TcpStream) -> Vec<u8> {
    stream
        .write_all(b"GET /healthz HTTP/1.1\r\nHost: knotshape\r\n\r\n")
        .await
        .unwrap();
    let mut answer = Vec::new();
    let mut chunk = [0u8; 512];
    while !answer.ends_with(HEALTHZ_BODY) {
        let read = tokio::time::timeout(Duration::from_secs(10), stream.read(&mut chunk))
            .await
            .expect("an answer within 10 s")
            .unwrap();
        assert!(read > 0, "the connection closed early: {answer:?}");
        answer.extend_from_slice(&chunk[..read]);
    }
    answer
}

#[tokio::test]
async fn connections_dealt_to_every_worker_are_served_and_kept_alive() {
    let app = spawn_app_with(|config| config.worker_threads = 3).await;
    // Nine connections: three per worker. Each asks twice on the same connection.
    let mut streams = Vec::new();
    for _ in 0..9 {
        streams.push(TcpStream::connect(app.socket).await.unwrap());
    }
    for _ in 0..2 {
        for stream in &mut streams {
            let answer = healthz_on(stream).await;
            assert!(answer.starts_with(b"HTTP/1.1 200"), "{answer:?}");
        }
    }
}
