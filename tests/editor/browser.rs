//! A headless Chromium session for one test: chromedriver started on a free port, Chromium
//! with a fresh profile directory, both ended (and the profile removed) on drop — also when
//! the test panicked and never closed the session. Sessions run side by side, except one
//! started [`Browser::start_alone`] (the drag timings), which waits until it is the only one.

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use fantoccini::{Client, ClientBuilder};
use serde_json::json;
use tokio::sync::{RwLock, RwLockReadGuard, RwLockWriteGuard};

/// Held shared by every session, and alone by a timing session: the test harness runs tests
/// in parallel, and a drag timed beside another test's browser measures that test too.
static SESSIONS: RwLock<()> = RwLock::const_new(());

/// A session's hold on [`SESSIONS`].
enum Hold {
    Shared(#[allow(dead_code)] RwLockReadGuard<'static, ()>),
    Alone(#[allow(dead_code)] RwLockWriteGuard<'static, ()>),
}

/// Debian's Chromium and its WebDriver.
pub const CHROMIUM: &str = "/usr/bin/chromium";
pub const CHROMEDRIVER: &str = "/usr/bin/chromedriver";

/// The browser window's size, in CSS pixels.
pub const WINDOW: (u32, u32) = (1280, 1000);

/// A browser session; chromedriver and the profile go away with it.
pub struct Browser {
    pub client: Client,
    driver: Child,
    profile: PathBuf,
    /// Released when the session ends (after the browser is gone).
    _hold: Hold,
}

impl Browser {
    /// Starts chromedriver and a headless Chromium. Panics, saying how to install them,
    /// when either is missing.
    pub async fn start() -> Browser {
        Browser::launch(Hold::Shared(SESSIONS.read().await)).await
    }

    /// As [`Browser::start`], once no other session is running, and none starts until this
    /// one ends.
    pub async fn start_alone() -> Browser {
        Browser::launch(Hold::Alone(SESSIONS.write().await)).await
    }

    async fn launch(hold: Hold) -> Browser {
        for binary in [CHROMIUM, CHROMEDRIVER] {
            assert!(
                std::path::Path::new(binary).exists(),
                "{binary} is missing: run `bash scripts/test` (it installs Debian's chromium \
                 and chromium-driver packages) or `apt-get install chromium chromium-driver`"
            );
        }
        let port = free_port();
        let driver = Command::new(CHROMEDRIVER)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromedriver");
        let profile = std::env::temp_dir().join(format!(
            "knotshape-editor-test-{}-{port}",
            std::process::id()
        ));
        std::fs::create_dir_all(&profile).unwrap();
        let mut capabilities = serde_json::Map::new();
        capabilities.insert(
            "goog:chromeOptions".to_owned(),
            json!({
                "binary": CHROMIUM,
                "args": [
                    "--headless",
                    "--no-sandbox",
                    "--disable-gpu",
                    // WebGL by SwiftShader (the 3D view): software rendering, trusted local pages.
                    "--enable-unsafe-swiftshader",
                    "--disable-quic",
                    "--no-first-run",
                    "--disable-background-networking",
                    "--disable-component-update",
                    "--disable-sync",
                    "--disable-dev-shm-usage",
                    format!("--window-size={},{}", WINDOW.0, WINDOW.1),
                    format!("--user-data-dir={}", profile.display()),
                ],
            }),
        );
        let connector = hyper_util::client::legacy::connect::HttpConnector::new();
        let url = format!("http://127.0.0.1:{port}");
        let deadline = Instant::now() + Duration::from_secs(20);
        let client = loop {
            match ClientBuilder::new(connector.clone())
                .capabilities(capabilities.clone())
                .connect(&url)
                .await
            {
                Ok(client) => break client,
                Err(error) if Instant::now() < deadline => {
                    let _ = error;
                    tokio::time::sleep(Duration::from_millis(100)).await;
                }
                Err(error) => panic!("no WebDriver session with {CHROMIUM}: {error}"),
            }
        };
        Browser {
            client,
            driver,
            profile,
            _hold: hold,
        }
    }

    /// Ends the session (the browser quits), then chromedriver.
    pub async fn close(mut self) {
        let _ = self.client.clone().close().await;
        let _ = self.driver.kill();
        let _ = self.driver.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.driver.kill();
        let _ = self.driver.wait();
        end_browser(&self.profile);
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

/// Ends the processes of the Chromium that uses `profile` (a directory unique to one
/// session, named in their arguments): when a test panics its session is never closed, and
/// ending chromedriver alone leaves that Chromium running.
fn end_browser(profile: &Path) {
    let directory = profile.display().to_string();
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return;
    };
    let mut ended = Vec::new();
    for entry in entries.flatten() {
        let Some(pid) = entry
            .file_name()
            .to_str()
            .and_then(|name| name.parse::<u32>().ok())
        else {
            continue;
        };
        let Ok(arguments) = std::fs::read(entry.path().join("cmdline")) else {
            continue;
        };
        // Chromium's processes name the profile (`--user-data-dir=…`), its crash handler a
        // directory inside it.
        if arguments.split(|&byte| byte == 0).any(|argument| {
            let argument = String::from_utf8_lossy(argument);
            argument.ends_with(&directory) || argument.contains(&format!("{directory}/"))
        }) {
            let _ = Command::new("kill").arg(pid.to_string()).status();
            ended.push(pid);
        }
    }
    // Gone (or a zombie) before the profile is removed; bounded: two seconds.
    let running = |pid: &u32| {
        std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|stat| {
            stat.rsplit(") ")
                .next()
                .is_some_and(|rest| !rest.starts_with('Z'))
        })
    };
    let deadline = Instant::now() + Duration::from_secs(2);
    while Instant::now() < deadline && ended.iter().any(running) {
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// A TCP port nobody listens on right now.
fn free_port() -> u16 {
    let listener = TcpListener::bind("127.0.0.1:0").expect("bind a free port");
    listener.local_addr().unwrap().port()
}

/// A Chrome DevTools Protocol command sent through chromedriver's `goog/cdp/execute`
/// endpoint (e.g. `Performance.getMetrics`, whose counters split the page's main-thread time
/// into script, style, layout and the rest).
#[derive(Debug)]
struct DevToolsCommand {
    command: String,
    parameters: serde_json::Value,
}

impl fantoccini::wd::WebDriverCompatibleCommand for DevToolsCommand {
    fn endpoint(
        &self,
        base_url: &url::Url,
        session_id: Option<&str>,
    ) -> Result<url::Url, url::ParseError> {
        base_url.join(&format!(
            "session/{}/goog/cdp/execute",
            session_id.unwrap_or_default()
        ))
    }

    fn method_and_body(&self, _request_url: &url::Url) -> (axum::http::Method, Option<String>) {
        let body = json!({ "cmd": self.command, "params": self.parameters });
        (axum::http::Method::POST, Some(body.to_string()))
    }
}

/// Sends the DevTools command `command` with `parameters` and returns its result.
pub async fn devtools(
    client: &Client,
    command: &str,
    parameters: serde_json::Value,
) -> serde_json::Value {
    client
        .issue_cmd(DevToolsCommand {
            command: command.to_owned(),
            parameters,
        })
        .await
        .unwrap_or_else(|error| panic!("DevTools {command}: {error}"))
}
