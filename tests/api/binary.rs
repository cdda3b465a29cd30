//! The real binary as a child process. SIGTERM under load: every request a client sent is
//! answered (200, or 503 with `Retry-After` once draining) or was refused before it was sent
//! (the listener closed); none is cut mid-way; the process exits 0. Out of file descriptors:
//! accepting pauses instead of spinning, and resumes once descriptors are free.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use serde_json::Value;

/// Clients, each with its own kept-alive connection.
const CLIENTS: usize = 8;

/// Load before the signal.
const LOAD_BEFORE_SIGNAL: Duration = Duration::from_millis(400);

/// The drain delay given to the server: new connections are still accepted (and answered 503).
const DRAIN_DELAY_MS: u64 = 300;

#[derive(Default)]
struct Counts {
    sent: AtomicU64,
    ok: AtomicU64,
    shed: AtomicU64,
    refused: AtomicU64,
    other: AtomicU64,
}

/// The server's log lines, as they arrive.
type Log = Arc<std::sync::Mutex<Vec<String>>>;

/// Starts the binary on a free port and returns it with its address, read from its log, and
/// the log; with `open_files`, under that limit of file descriptors (`ulimit -n`).
fn start_server(open_files: Option<u32>) -> (Child, String, Log) {
    let binary = env!("CARGO_BIN_EXE_knotshape");
    let mut command = match open_files {
        None => Command::new(binary),
        Some(limit) => {
            let mut shell = Command::new("sh");
            shell
                .arg("-c")
                .arg(format!("ulimit -n {limit} && exec \"$0\""))
                .arg(binary);
            shell
        }
    };
    let mut child = command
        .env_clear()
        .env("KNOTSHAPE_LISTEN", "127.0.0.1:0")
        .env("KNOTSHAPE_LOG_FORMAT", "json")
        .env(
            "KNOTSHAPE_LOG",
            "knotshape=info,knotshape::http::middleware=warn",
        )
        .env("KNOTSHAPE_DRAIN_DELAY_MS", DRAIN_DELAY_MS.to_string())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .expect("start the binary");
    let stdout = child.stdout.take().unwrap();
    let mut lines = BufReader::new(stdout).lines();
    let address = loop {
        let line = lines.next().expect("the server logs its address").unwrap();
        let Ok(entry) = serde_json::from_str::<Value>(&line) else {
            continue;
        };
        if let Some(address) = entry["address"].as_str() {
            break address.to_owned();
        }
    };
    // Keep reading the log so that the server never blocks on a full pipe.
    let log = Log::default();
    let collected = log.clone();
    std::thread::spawn(move || {
        for line in lines.map_while(Result::ok) {
            collected.lock().unwrap().push(line);
        }
    });
    (child, format!("http://{address}"), log)
}

/// One client: requests on its kept-alive connection until the server refuses connections.
async fn client_loop(base: String, counts: Arc<Counts>, index: usize) {
    let client = reqwest::Client::builder()
        .pool_max_idle_per_host(1)
        .timeout(Duration::from_secs(5))
        .build()
        .unwrap();
    let solve: Value = serde_json::from_str(include_str!("../../benches/load/solve.json")).unwrap();
    for round in 0usize.. {
        let request = if (round + index) % 3 == 0 {
            client.get(format!("{base}/healthz"))
        } else {
            client.post(format!("{base}/v1/shape/solve")).json(&solve)
        };
        counts.sent.fetch_add(1, Ordering::SeqCst);
        match request.send().await {
            Ok(response) => {
                let status = response.status().as_u16();
                let retry_after = response.headers().contains_key("retry-after");
                let body = response.bytes().await;
                match (status, retry_after, body) {
                    (200, _, Ok(_)) => counts.ok.fetch_add(1, Ordering::SeqCst),
                    (503, true, Ok(_)) => {
                        counts.shed.fetch_add(1, Ordering::SeqCst);
                        // A client honouring Retry-After would wait; come back shortly.
                        tokio::time::sleep(Duration::from_millis(20)).await;
                        0
                    }
                    (status, _, body) => {
                        eprintln!("unexpected answer: {status} {body:?}");
                        counts.other.fetch_add(1, Ordering::SeqCst)
                    }
                };
            }
            Err(error) if error.is_connect() => {
                counts.refused.fetch_add(1, Ordering::SeqCst);
                return;
            }
            Err(error) => {
                eprintln!("request failed: {error:?}");
                counts.other.fetch_add(1, Ordering::SeqCst);
            }
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sigterm_under_load_answers_every_request_and_exits_0() {
    let (mut child, base, _log) = start_server(None);
    let counts = Arc::new(Counts::default());
    let clients: Vec<_> = (0..CLIENTS)
        .map(|index| tokio::spawn(client_loop(base.clone(), counts.clone(), index)))
        .collect();
    tokio::time::sleep(LOAD_BEFORE_SIGNAL).await;
    let ok_before_signal = counts.ok.load(Ordering::SeqCst);
    let signalled = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(signalled.success());
    let signalled_at = Instant::now();

    for client in clients {
        tokio::time::timeout(Duration::from_secs(10), client)
            .await
            .expect("every client sees the listener close within 10 s")
            .unwrap();
    }
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        assert!(
            signalled_at.elapsed() < Duration::from_secs(10),
            "the server did not exit within 10 s of SIGTERM"
        );
        tokio::time::sleep(Duration::from_millis(20)).await;
    };
    let load = |counter: &AtomicU64| counter.load(Ordering::SeqCst);
    let (sent, ok, shed, refused, other) = (
        load(&counts.sent),
        load(&counts.ok),
        load(&counts.shed),
        load(&counts.refused),
        load(&counts.other),
    );
    eprintln!(
        "sigterm under load: sent {sent}, 200 {ok}, 503 {shed}, refused before sending {refused}, \
         other {other}; exit {status}"
    );
    assert!(status.success(), "exit status {status}");
    assert_eq!(other, 0, "requests cut or answered otherwise");
    assert_eq!(sent, ok + shed + refused, "every request is accounted for");
    assert!(ok_before_signal > 0, "the load reached the server");
    assert!(shed > 0, "requests during the drain delay are answered 503");
    assert_eq!(
        refused, CLIENTS as u64,
        "each client ends at the closed listener"
    );
}

/// User + system CPU time of a process, in clock ticks (1/100 s on Linux).
fn cpu_ticks(pid: u32) -> u64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    // Fields after the command name (which is in parentheses): utime is the 12th, stime the 13th.
    let after_name = &stat[stat.rfind(')').unwrap() + 2..];
    let fields: Vec<&str> = after_name.split_whitespace().collect();
    fields[11].parse::<u64>().unwrap() + fields[12].parse::<u64>().unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn out_of_file_descriptors_accepting_pauses_and_then_resumes() {
    use tokio::io::AsyncWriteExt;

    let (mut child, base, log) = start_server(Some(40));
    let address = base.trim_start_matches("http://").to_owned();
    // More connections than the server has descriptors: the rest wait in the backlog and
    // each accept fails with EMFILE.
    let mut held = Vec::new();
    for _ in 0..60 {
        let mut stream = tokio::net::TcpStream::connect(&address).await.unwrap();
        let _ = stream
            .write_all(b"GET /healthz HTTP/1.1\r\nHost: x\r\n")
            .await;
        held.push(stream);
    }
    tokio::time::sleep(Duration::from_millis(300)).await;
    let before = cpu_ticks(child.id());
    tokio::time::sleep(Duration::from_secs(1)).await;
    let used = cpu_ticks(child.id()) - before;
    assert!(
        used < 30,
        "the server used {used}/100 s of CPU in 1 s while out of descriptors: it spins"
    );
    let accept_errors = log
        .lock()
        .unwrap()
        .iter()
        .filter(|line| line.contains("accept failed"))
        .count();
    // About 1.3 s out of descriptors, 50 ms pauses: some 26 attempts, not thousands.
    assert!(
        (1..=60).contains(&accept_errors),
        "{accept_errors} failed accepts logged"
    );
    drop(held);
    let client = reqwest::Client::new();
    let mut answered = false;
    for _ in 0..20 {
        let probe = client
            .get(format!("{base}/healthz"))
            .timeout(Duration::from_millis(200))
            .send()
            .await;
        if probe.is_ok_and(|response| response.status() == 200) {
            answered = true;
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert!(
        answered,
        "the server accepts again once descriptors are free"
    );
    Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        assert!(started.elapsed() < Duration::from_secs(10), "no exit");
        tokio::time::sleep(Duration::from_millis(20)).await;
    };
    assert!(status.success(), "{status}");
}
