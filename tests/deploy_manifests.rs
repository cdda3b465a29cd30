//! The shipping artefacts (Kubernetes manifests, Dockerfile, .dockerignore) agree with the real service.
//!
//! Every YAML document under `deploy/kubernetes/` is parsed; the container's
//! `KNOTSHAPE_*` environment is turned into a [`Config`] through the real clap
//! parser (each variable is mapped to the option that reads it, so an unknown
//! or misspelt variable fails); the probe paths are requested from the real
//! router served on loopback; and the Docker health check is run as the real
//! binary's `healthcheck` subcommand against that server.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::BTreeMap;
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use clap::{CommandFactory, Parser};
use knotshape::config::Config;
use serde_yaml_ng::Value;

const MANIFEST_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/deploy/kubernetes");
const DOCKERFILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/Dockerfile");
const DOCKERIGNORE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/.dockerignore");

// ------------------------------------------------------------------ loading --

/// One parsed YAML document and the file it came from.
struct Doc {
    file: PathBuf,
    value: Value,
}

impl Doc {
    fn kind(&self) -> &str {
        self.value["kind"].as_str().unwrap_or("")
    }
}

/// Every YAML document of every `*.yaml` / `*.yml` file in `dir`, in file-name order.
fn load_docs(dir: &Path) -> Vec<Doc> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|p| matches!(p.extension().and_then(|e| e.to_str()), Some("yaml" | "yml")))
        .collect();
    files.sort();
    let mut docs = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for de in serde_yaml_ng::Deserializer::from_str(&text) {
            let value = serde::Deserialize::deserialize(de)
                .unwrap_or_else(|e| panic!("{}: invalid YAML: {e}", file.display()));
            if value == Value::Null {
                continue; // an empty document, e.g. after a trailing `---`
            }
            docs.push(Doc {
                file: file.clone(),
                value,
            });
        }
    }
    docs
}

/// The one document of `kind` (fails on none or several).
fn one<'a>(docs: &'a [Doc], kind: &str) -> &'a Doc {
    let found: Vec<&Doc> = docs.iter().filter(|d| d.kind() == kind).collect();
    assert_eq!(
        found.len(),
        1,
        "expected exactly one {kind} in {MANIFEST_DIR}, found {}",
        found.len()
    );
    found[0]
}

/// `value` at a dotted path (`"spec.template.spec"`), failing with the path when absent.
fn at<'a>(value: &'a Value, path: &str) -> &'a Value {
    let mut v = value;
    for key in path.split('.') {
        v = match key.parse::<usize>() {
            Ok(i) => &v[i],
            Err(_) => &v[key],
        };
        assert!(*v != Value::Null, "missing `{path}` (at `{key}`)");
    }
    v
}

fn str_at<'a>(value: &'a Value, path: &str) -> &'a str {
    at(value, path)
        .as_str()
        .unwrap_or_else(|| panic!("`{path}` is not a string"))
}

fn i64_at(value: &Value, path: &str) -> i64 {
    at(value, path)
        .as_i64()
        .unwrap_or_else(|| panic!("`{path}` is not an integer"))
}

fn bool_at(value: &Value, path: &str) -> bool {
    at(value, path)
        .as_bool()
        .unwrap_or_else(|| panic!("`{path}` is not a boolean"))
}

/// A `matchLabels` / `labels` / `selector` mapping as string pairs.
fn labels(value: &Value, path: &str) -> BTreeMap<String, String> {
    let map = at(value, path)
        .as_mapping()
        .unwrap_or_else(|| panic!("`{path}` is not a mapping"));
    assert!(!map.is_empty(), "`{path}` is empty");
    map.iter()
        .map(|(k, v)| {
            let k = k.as_str().unwrap().to_owned();
            let v = match v {
                Value::String(s) => s.clone(),
                other => panic!("label {k} in `{path}` is not a string: {other:?}"),
            };
            (k, v)
        })
        .collect()
}

/// True when every pair of `selector` is in `labels`.
fn selects(selector: &BTreeMap<String, String>, labels: &BTreeMap<String, String>) -> bool {
    selector.iter().all(|(k, v)| labels.get(k) == Some(v))
}

// ------------------------------------------------------------ configuration --

/// The [`Config`] the binary builds from these environment variables, parsed
/// by the real clap definition: each `KNOTSHAPE_*` variable becomes the
/// command-line option whose `env` it is (flags and env are the same option),
/// so nothing here depends on the test process's own environment. A
/// `KNOTSHAPE_*` variable that no option reads is an error: it would be
/// silently ignored in production.
fn config_from_env(vars: &[(String, String)]) -> Config {
    let cmd = Config::command();
    let mut argv = vec!["knotshape".to_owned()];
    for (name, value) in vars {
        if !name.starts_with("KNOTSHAPE_") {
            continue;
        }
        let arg = cmd
            .get_arguments()
            .find(|a| a.get_env().is_some_and(|e| e == name.as_str()))
            .unwrap_or_else(|| panic!("{name} is set, but no Config option reads it"));
        let long = arg
            .get_long()
            .unwrap_or_else(|| panic!("the option read from {name} has no long flag"));
        if arg.get_action().takes_values() {
            argv.push(format!("--{long}={value}"));
        } else if matches!(value.as_str(), "1" | "true" | "yes" | "on") {
            argv.push(format!("--{long}"));
        }
    }
    Config::try_parse_from(&argv)
        .unwrap_or_else(|e| panic!("Config rejects {argv:?} (from {vars:?}): {e}"))
}

/// The longest time from SIGTERM to exit: the drain delay (readiness 503,
/// listener still open), then the slowest in-flight request, which the
/// request timeout bounds.
/// The longest shutdown: the drain delay, then a connection accepted just before the listener
/// closed may take the header timeout to send its head, the request timeout to be answered and
/// the body timeout (the send stall) to take its answer.
fn drain_timeout(config: &Config) -> Duration {
    let connections = config.connection_limits();
    config.drain_delay()
        + connections.header_timeout()
        + config.request_timeout()
        + connections.body_timeout()
}

// ---------------------------------------------------------------- Dockerfile --

/// The Dockerfile's logical lines (continuations joined, comments dropped).
fn dockerfile_instructions() -> Vec<(String, String)> {
    let text = std::fs::read_to_string(DOCKERFILE).unwrap();
    let mut out = Vec::new();
    let mut current = String::new();
    for line in text.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with('#') || (current.is_empty() && trimmed.is_empty()) {
            continue;
        }
        if let Some(head) = trimmed.strip_suffix('\\') {
            current.push_str(head);
            current.push(' ');
            continue;
        }
        current.push_str(trimmed);
        let (op, rest) = current
            .split_once(char::is_whitespace)
            .unwrap_or((&current, ""));
        out.push((op.to_ascii_uppercase(), rest.trim().to_owned()));
        current.clear();
    }
    out
}

/// The instructions of the last stage (the image that ships).
fn runtime_stage(instructions: &[(String, String)]) -> &[(String, String)] {
    let last_from = instructions
        .iter()
        .rposition(|(op, _)| op == "FROM")
        .expect("Dockerfile has no FROM");
    &instructions[last_from..]
}

/// `["a", "b"]` (exec form) as a list of strings; fails on shell form.
fn exec_form(what: &str, json: &str) -> Vec<String> {
    serde_json::from_str(json)
        .unwrap_or_else(|e| panic!("{what} must be exec form (a JSON array), got `{json}`: {e}"))
}

/// `ENV A=1 B="2"` pairs of the runtime stage.
fn dockerfile_env(stage: &[(String, String)]) -> Vec<(String, String)> {
    let mut vars = Vec::new();
    for (_, rest) in stage.iter().filter(|(op, _)| op == "ENV") {
        for token in rest.split_whitespace() {
            let (k, v) = token
                .split_once('=')
                .unwrap_or_else(|| panic!("ENV must use KEY=VALUE pairs, got `{rest}`"));
            vars.push((k.to_owned(), v.trim_matches('"').to_owned()));
        }
    }
    vars
}

// --------------------------------------------------------------- the server --

/// The real router, served on an ephemeral loopback port.
async fn spawn_app(config: &Config) -> SocketAddr {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let app = knotshape::app(config);
    tokio::spawn(async move {
        axum::serve(listener, app).await.unwrap();
    });
    addr
}

async fn get_status(addr: SocketAddr, path: &str) -> u16 {
    let client = reqwest::Client::builder()
        .timeout(Duration::from_secs(5))
        .build()
        .unwrap();
    client
        .get(format!("http://{addr}{path}"))
        .send()
        .await
        .unwrap_or_else(|e| panic!("GET {path}: {e}"))
        .status()
        .as_u16()
}

// ------------------------------------------------------------------ the tests --

struct Container<'a> {
    pod_spec: &'a Value,
    container: &'a Value,
    env: Vec<(String, String)>,
    /// Container port number by name.
    ports: BTreeMap<String, i64>,
}

fn the_container(deployment: &Value) -> Container<'_> {
    let pod_spec = at(deployment, "spec.template.spec");
    let containers = at(pod_spec, "containers").as_sequence().unwrap();
    assert_eq!(containers.len(), 1, "one container per pod");
    let container = &containers[0];
    let env = at(container, "env")
        .as_sequence()
        .unwrap()
        .iter()
        .map(|e| (str_at(e, "name").to_owned(), str_at(e, "value").to_owned()))
        .collect();
    let ports = at(container, "ports")
        .as_sequence()
        .unwrap()
        .iter()
        .map(|p| (str_at(p, "name").to_owned(), i64_at(p, "containerPort")))
        .collect();
    Container {
        pod_spec,
        container,
        env,
        ports,
    }
}

/// A probe's or Service's port: a container port's name (required to be a
/// name, so that renumbering the port cannot leave it behind) resolved to its number.
fn named_port(ports: &BTreeMap<String, i64>, value: &Value, what: &str) -> i64 {
    let name = value
        .as_str()
        .unwrap_or_else(|| panic!("{what} must name the container port, got {value:?}"));
    *ports
        .get(name)
        .unwrap_or_else(|| panic!("{what} names `{name}`, not a container port ({ports:?})"))
}

#[test]
fn every_manifest_parses_and_the_kustomization_lists_them_all() {
    let docs = load_docs(Path::new(MANIFEST_DIR));
    for kind in [
        "Deployment",
        "Service",
        "HorizontalPodAutoscaler",
        "PodDisruptionBudget",
    ] {
        let doc = one(&docs, kind);
        assert_eq!(
            str_at(&doc.value, "metadata.name"),
            "knotshape",
            "{}",
            doc.file.display()
        );
    }
    for doc in &docs {
        assert!(
            !str_at(&doc.value, "apiVersion").is_empty(),
            "{}",
            doc.file.display()
        );
    }
    let expected_api = [
        ("Deployment", "apps/v1"),
        ("Service", "v1"),
        ("HorizontalPodAutoscaler", "autoscaling/v2"),
        ("PodDisruptionBudget", "policy/v1"),
    ];
    for (kind, api) in expected_api {
        assert_eq!(str_at(&one(&docs, kind).value, "apiVersion"), api, "{kind}");
    }

    let kustomization = one(&docs, "Kustomization");
    let listed: Vec<&str> = at(&kustomization.value, "resources")
        .as_sequence()
        .unwrap()
        .iter()
        .map(|r| r.as_str().unwrap())
        .collect();
    let mut resource_files: Vec<String> = docs
        .iter()
        .filter(|d| d.kind() != "Kustomization")
        .map(|d| d.file.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    resource_files.sort();
    resource_files.dedup();
    let mut listed_sorted: Vec<String> = listed.iter().map(|s| (*s).to_owned()).collect();
    listed_sorted.sort();
    assert_eq!(
        listed_sorted, resource_files,
        "kustomization.yaml must list every manifest"
    );
}

#[test]
fn container_port_is_the_port_the_service_listens_on_from_the_container_env() {
    let docs = load_docs(Path::new(MANIFEST_DIR));
    let c = the_container(&one(&docs, "Deployment").value);
    let config = config_from_env(&c.env);
    assert!(
        config.listen.ip().is_unspecified(),
        "in a pod the service must listen on all interfaces, not {}",
        config.listen
    );
    let port = i64::from(config.listen.port());
    assert_eq!(c.ports.len(), 1, "one container port: {:?}", c.ports);
    assert_eq!(
        c.ports.values().next().copied(),
        Some(port),
        "containerPort vs KNOTSHAPE_LISTEN"
    );
    for p in at(c.container, "ports").as_sequence().unwrap() {
        assert_eq!(str_at(p, "protocol"), "TCP");
    }
}

#[tokio::test]
async fn probes_hit_real_routes_on_the_container_port() {
    let docs = load_docs(Path::new(MANIFEST_DIR));
    let c = the_container(&one(&docs, "Deployment").value);
    let config = config_from_env(&c.env);
    let addr = spawn_app(&config).await;

    let mut seen = Vec::new();
    for probe in ["livenessProbe", "readinessProbe", "startupProbe"] {
        let Some(spec) = c.container.get(probe) else {
            assert_ne!(probe, "livenessProbe", "a liveness probe is required");
            assert_ne!(probe, "readinessProbe", "a readiness probe is required");
            continue;
        };
        let path = str_at(spec, "httpGet.path");
        let port = named_port(&c.ports, at(spec, "httpGet.port"), probe);
        assert_eq!(
            port,
            i64::from(config.listen.port()),
            "{probe} port vs KNOTSHAPE_LISTEN"
        );
        let status = get_status(addr, path).await;
        assert_eq!(status, 200, "{probe} GET {path} answered {status}");
        seen.push((probe, path.to_owned()));
    }
    // Liveness must not depend on readiness: a draining pod is alive.
    assert!(seen.contains(&("livenessProbe", "/healthz".to_owned())));
    assert!(seen.contains(&("readinessProbe", "/readyz".to_owned())));
}

#[test]
fn service_targets_the_named_container_port_of_the_deployments_pods() {
    let docs = load_docs(Path::new(MANIFEST_DIR));
    let deployment = &one(&docs, "Deployment").value;
    let c = the_container(deployment);
    let config = config_from_env(&c.env);
    let pod_labels = labels(deployment, "spec.template.metadata.labels");
    assert!(
        selects(
            &labels(deployment, "spec.selector.matchLabels"),
            &pod_labels
        ),
        "the Deployment's selector must match its own pod template"
    );

    let service = &one(&docs, "Service").value;
    assert_eq!(str_at(service, "spec.type"), "ClusterIP");
    assert!(
        selects(&labels(service, "spec.selector"), &pod_labels),
        "the Service's selector must select the Deployment's pods"
    );
    let ports = at(service, "spec.ports").as_sequence().unwrap();
    assert_eq!(ports.len(), 1);
    assert_eq!(i64_at(&ports[0], "port"), 80);
    let target = named_port(&c.ports, at(&ports[0], "targetPort"), "Service targetPort");
    assert_eq!(target, i64::from(config.listen.port()));
}

#[test]
fn hpa_and_pdb_cover_the_deployments_pods() {
    let docs = load_docs(Path::new(MANIFEST_DIR));
    let deployment = &one(&docs, "Deployment").value;
    let pod_labels = labels(deployment, "spec.template.metadata.labels");
    let deployment_selector = labels(deployment, "spec.selector.matchLabels");

    let hpa = &one(&docs, "HorizontalPodAutoscaler").value;
    assert_eq!(str_at(hpa, "spec.scaleTargetRef.apiVersion"), "apps/v1");
    assert_eq!(str_at(hpa, "spec.scaleTargetRef.kind"), "Deployment");
    assert_eq!(
        str_at(hpa, "spec.scaleTargetRef.name"),
        str_at(deployment, "metadata.name")
    );
    let min = i64_at(hpa, "spec.minReplicas");
    let max = i64_at(hpa, "spec.maxReplicas");
    assert!(
        min >= 2 && max > min,
        "replicas {min}..{max}: at least 2, room to grow"
    );
    let metrics = at(hpa, "spec.metrics").as_sequence().unwrap();
    assert!(
        metrics
            .iter()
            .any(|m| m["type"].as_str() == Some("Resource")
                && m["resource"]["name"].as_str() == Some("cpu")
                && m["resource"]["target"]["type"].as_str() == Some("Utilization")),
        "the HPA scales on CPU utilisation"
    );
    // Utilisation is measured against the request: it must be set.
    let c = the_container(deployment);
    at(c.container, "resources.requests.cpu");

    let pdb = &one(&docs, "PodDisruptionBudget").value;
    let pdb_selector = labels(pdb, "spec.selector.matchLabels");
    assert!(
        selects(&pdb_selector, &pod_labels),
        "the PDB must select the Deployment's pods"
    );
    assert_eq!(
        pdb_selector, deployment_selector,
        "the PDB must select exactly the Deployment's pods"
    );
    let spec = at(pdb, "spec");
    match (spec.get("minAvailable"), spec.get("maxUnavailable")) {
        (Some(n), None) => assert!(
            n.as_i64().is_some_and(|n| n >= 1 && n < min),
            "minAvailable {n:?} must leave room to evict with {min} replicas"
        ),
        (None, Some(n)) => assert!(n.as_i64().is_some_and(|n| n >= 1 && n < min)),
        other => panic!("the PDB needs exactly one of minAvailable / maxUnavailable: {other:?}"),
    }
}

#[test]
fn pods_run_non_root_read_only_with_limits() {
    let docs = load_docs(Path::new(MANIFEST_DIR));
    let c = the_container(&one(&docs, "Deployment").value);
    let sc = at(c.container, "securityContext");
    assert!(bool_at(sc, "runAsNonRoot"));
    assert!(bool_at(sc, "readOnlyRootFilesystem"));
    assert!(!bool_at(sc, "allowPrivilegeEscalation"));
    let dropped: Vec<&str> = at(sc, "capabilities.drop")
        .as_sequence()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    assert_eq!(dropped, ["ALL"]);
    assert!(sc.get("capabilities").unwrap().get("add").is_none());
    let seccomp = sc
        .get("seccompProfile")
        .or_else(|| c.pod_spec["securityContext"].get("seccompProfile"))
        .expect("a seccomp profile");
    assert_eq!(str_at(seccomp, "type"), "RuntimeDefault");

    let uid = i64_at(sc, "runAsUser");
    assert_ne!(uid, 0);
    assert_eq!(
        i64::from(dockerfile_uid()),
        uid,
        "runAsUser vs the Dockerfile's USER"
    );

    for kind in ["requests", "limits"] {
        for resource in ["cpu", "memory"] {
            at(c.container, &format!("resources.{kind}.{resource}"));
        }
    }
}

#[test]
fn grace_period_outlasts_prestop_plus_the_services_drain() {
    let docs = load_docs(Path::new(MANIFEST_DIR));
    let c = the_container(&one(&docs, "Deployment").value);
    let config = config_from_env(&c.env);
    let drain = drain_timeout(&config);
    let pre_stop = c.container["lifecycle"]["preStop"]["sleep"]["seconds"]
        .as_i64()
        .map_or(Duration::ZERO, |s| {
            Duration::from_secs(s.try_into().unwrap())
        });
    let grace = Duration::from_secs(
        i64_at(c.pod_spec, "terminationGracePeriodSeconds")
            .try_into()
            .unwrap(),
    );
    // The grace period counts from the start of preStop; SIGKILL comes at
    // its end. Keep a few seconds for process exit.
    let margin = Duration::from_secs(5);
    assert!(
        grace >= pre_stop + drain + margin,
        "terminationGracePeriodSeconds {grace:?} < preStop {pre_stop:?} + drain {drain:?} + {margin:?}"
    );
    // The drain must not be skipped either.
    assert!(drain > Duration::ZERO);
}

#[test]
fn dockerfile_listens_and_exposes_the_same_port_as_the_deployment() {
    let instructions = dockerfile_instructions();
    assert!(
        instructions.iter().filter(|(op, _)| op == "FROM").count() >= 2,
        "multi-stage build"
    );
    assert!(
        instructions.iter().any(|(op, rest)| op == "RUN"
            && rest.contains("cargo build")
            && rest.contains("--release")
            && rest.contains("--locked")),
        "the image is built with `cargo build --release --locked`"
    );
    let stage = runtime_stage(&instructions);
    let config = config_from_env(&dockerfile_env(stage));
    assert!(config.listen.ip().is_unspecified());

    let exposed: Vec<u16> = stage
        .iter()
        .filter(|(op, _)| op == "EXPOSE")
        .flat_map(|(_, rest)| rest.split_whitespace())
        .map(|p| p.trim_end_matches("/tcp").parse().unwrap())
        .collect();
    assert_eq!(
        exposed,
        [config.listen.port()],
        "EXPOSE vs KNOTSHAPE_LISTEN"
    );

    let docs = load_docs(Path::new(MANIFEST_DIR));
    let c = the_container(&one(&docs, "Deployment").value);
    assert_eq!(
        config.listen,
        config_from_env(&c.env).listen,
        "the image's and the Deployment's KNOTSHAPE_LISTEN"
    );
}

/// The numeric `USER` of the runtime stage (non-root).
fn dockerfile_uid() -> u32 {
    let instructions = dockerfile_instructions();
    let stage = runtime_stage(&instructions);
    let users: Vec<&String> = stage
        .iter()
        .filter(|(op, _)| op == "USER")
        .map(|(_, rest)| rest)
        .collect();
    let user = users.last().expect("the runtime stage sets USER");
    let uid: u32 =
        user.split(':').next().unwrap().parse().unwrap_or_else(|_| {
            panic!("USER must be numeric (runAsNonRoot checks it), got {user}")
        });
    assert_ne!(uid, 0, "USER must not be root");
    uid
}

#[test]
fn dockerfile_runs_as_numeric_non_root_with_exec_form_entrypoint() {
    assert_ne!(dockerfile_uid(), 0);
    let instructions = dockerfile_instructions();
    let stage = runtime_stage(&instructions);
    let entrypoint = stage
        .iter()
        .rfind(|(op, _)| op == "ENTRYPOINT")
        .expect("ENTRYPOINT");
    let entrypoint = exec_form("ENTRYPOINT", &entrypoint.1);
    assert_eq!(entrypoint.len(), 1, "the entrypoint serves by default");
    let stop = stage
        .iter()
        .rfind(|(op, _)| op == "STOPSIGNAL")
        .map(|(_, s)| s.as_str());
    assert!(
        matches!(stop, None | Some("SIGTERM")),
        "the drain starts on SIGTERM"
    );

    let ignore = std::fs::read_to_string(DOCKERIGNORE).unwrap();
    let patterns: Vec<&str> = ignore
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect();
    for needed in [".git", "**/target"] {
        assert!(
            patterns.contains(&needed),
            ".dockerignore must exclude {needed}"
        );
    }
    for kept in ["src", "Cargo.toml", "Cargo.lock", "*", "*.rs", "*.toml"] {
        assert!(!patterns.contains(&kept), ".dockerignore must keep {kept}");
    }
}

/// The Docker HEALTHCHECK, run for real: the image's command (minus the
/// install path) is this package's binary, pointed at the real router by the
/// image's own KNOTSHAPE_LISTEN with the port swapped for the test server's.
/// It must succeed against a live server and fail when nothing listens.
#[tokio::test]
async fn docker_healthcheck_command_probes_the_running_service() {
    let instructions = dockerfile_instructions();
    let stage = runtime_stage(&instructions);
    let (_, healthcheck) = stage
        .iter()
        .rfind(|(op, _)| op == "HEALTHCHECK")
        .expect("HEALTHCHECK");
    let cmd_json = healthcheck
        .split_once("CMD")
        .map(|(_, json)| json.trim())
        .expect("HEALTHCHECK ... CMD [...]");
    let cmd = exec_form("HEALTHCHECK CMD", cmd_json);
    let entrypoint = stage
        .iter()
        .rfind(|(op, _)| op == "ENTRYPOINT")
        .map(|(_, e)| exec_form("ENTRYPOINT", e))
        .unwrap();
    assert_eq!(
        cmd[0], entrypoint[0],
        "the health check runs the service's own binary"
    );
    assert_eq!(cmd[1..], ["healthcheck"]);

    let image_env = dockerfile_env(stage);
    let image_config = config_from_env(&image_env);
    let addr = spawn_app(&Config::default()).await;
    // The image listens on the unspecified address; the check must reach it.
    let listen = SocketAddr::new(image_config.listen.ip(), addr.port());

    let run = |listen: SocketAddr| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_knotshape"));
        command.args(&cmd[1..]);
        for (k, v) in &image_env {
            command.env(k, v);
        }
        command.env("KNOTSHAPE_LISTEN", listen.to_string());
        tokio::task::spawn_blocking(move || command.output().unwrap())
    };
    let ok = run(listen).await.unwrap();
    assert!(
        ok.status.success(),
        "`knotshape healthcheck` against a live server: {:?}\n{}",
        ok.status,
        String::from_utf8_lossy(&ok.stderr)
    );

    // Nothing listens on a port we just released.
    let closed = {
        let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        l.local_addr().unwrap().port()
    };
    let down = run(SocketAddr::new(image_config.listen.ip(), closed))
        .await
        .unwrap();
    assert!(
        !down.status.success(),
        "`knotshape healthcheck` must fail when nothing listens"
    );
}
