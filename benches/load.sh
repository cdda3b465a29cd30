#!/usr/bin/env bash
# Load benchmark of the release build on loopback, in one run:
#   GET /healthz and POST /v1/shape/solve (benches/load/solve.json, the first
#   worked example of the shared examples: a cubic, t = 0.42), each at
#   $CONNECTIONS connections for $DURATION s after a $WARMUP s warm-up.
# Prints requests/s, p50 and p99 latency and the non-2xx count per endpoint,
# then the ratio solve/healthz of requests/s. Fails (exit 1) if any request
# was non-2xx or failed on the socket; with ENFORCE_TARGETS=1 also fails
# (exit 3) when the targets (ratio >= 0.6, solve p99 < 5 ms) are missed.
#
# Load generator: wrk (Debian package, installed by this script if missing):
# a C event loop that adds little CPU of its own next to the server on a
# 2-core machine and installs in seconds (oha would be a few hundred crates to
# compile first). Both share the machine's cores, so the numbers are for
# server + generator on one box; a busy machine skews them (the load average
# is printed before and after).
#
# Usage: bash benches/load.sh
# Environment: DURATION (s, default 10), WARMUP (s, default 2),
#   CONNECTIONS (default 64), THREADS (wrk threads, default 2),
#   ENFORCE_TARGETS (0/1, default 0).
# Traffic goes to 127.0.0.1 only; the server is stopped on exit.
set -euo pipefail

cd "$(dirname "$0")/.."

DURATION="${DURATION:-10}"
WARMUP="${WARMUP:-2}"
CONNECTIONS="${CONNECTIONS:-64}"
THREADS="${THREADS:-2}"
ENFORCE_TARGETS="${ENFORCE_TARGETS:-0}"
TARGET_RATIO=0.6
TARGET_SOLVE_P99_MS=5

BODY="benches/load/solve.json"
LUA="benches/load/wrk.lua"
BIN="target/release/knotshape"

for v in DURATION WARMUP CONNECTIONS THREADS; do
    if ! [[ "${!v}" =~ ^[1-9][0-9]*$ ]]; then
        echo "load.sh: $v must be a positive integer, got '${!v}'" >&2
        exit 2
    fi
done
if (( DURATION > 120 || WARMUP > 30 )); then
    echo "load.sh: DURATION <= 120 and WARMUP <= 30 keep the run bounded" >&2
    exit 2
fi

log() { echo "load.sh: $*" >&2; }

# ---------------------------------------------------------------- tools ---
install_debian_packages() {
    local sudo=()
    if (( EUID != 0 )); then
        if command -v sudo >/dev/null; then sudo=(sudo -n); else
            log "need root (or sudo) to install: $*"; exit 2
        fi
    fi
    log "installing $* from Debian's packages"
    timeout 300 "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    timeout 300 "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

missing=()
command -v wrk >/dev/null || missing+=(wrk)
command -v curl >/dev/null || missing+=(curl)
if (( ${#missing[@]} > 0 )); then
    install_debian_packages "${missing[@]}"
fi

# ---------------------------------------------------------------- build ---
log "building the release binary"
cargo build --release --locked --bin knotshape >&2

# ---------------------------------------------------------------- server --
workdir="$(mktemp -d)"
server_pid=""
# shellcheck disable=SC2317  # called from the EXIT trap
cleanup() {
    if [[ -n "$server_pid" ]] && kill -0 "$server_pid" 2>/dev/null; then
        kill -TERM "$server_pid" 2>/dev/null || true
        for _ in $(seq 50); do
            kill -0 "$server_pid" 2>/dev/null || break
            sleep 0.1
        done
        kill -KILL "$server_pid" 2>/dev/null || true
        wait "$server_pid" 2>/dev/null || true
    fi
    rm -rf "$workdir"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# A free loopback port: bind port 0 and let the kernel choose.
free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()' 2>/dev/null && return
    local p
    for _ in $(seq 100); do
        p=$(( 20000 + RANDOM % 40000 ))
        if ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then echo "$p"; return; fi
    done
    log "no free port found"; exit 2
}
port="$(free_port)"
base="http://127.0.0.1:$port"

# Logs off (the access log would cost more than /healthz itself), and the
# concurrency limit / load shedding well above the benchmark's connections so
# that the numbers measure the handlers, not the 503 path.
server_env=(
    "KNOTSHAPE_LISTEN=127.0.0.1:$port"
    "KNOTSHAPE_LOG=off"
    "KNOTSHAPE_CONCURRENCY_LIMIT=$(( CONNECTIONS * 16 ))"
    "KNOTSHAPE_DRAIN_DELAY_MS=0"
)
# Settings from the caller's environment (an API key, say) would skew or
# break the run: the server gets only the ones above.
unset_inherited=()
for name in $(compgen -e); do
    if [[ "$name" == KNOTSHAPE_* ]]; then unset_inherited+=(-u "$name"); fi
done
log "starting $BIN on 127.0.0.1:$port"
env "${unset_inherited[@]}" "${server_env[@]}" "$BIN" >"$workdir/server.log" 2>&1 &
server_pid=$!

for _ in $(seq 100); do
    if curl -fsS -m 1 -o /dev/null "$base/healthz" 2>/dev/null; then break; fi
    if ! kill -0 "$server_pid" 2>/dev/null; then
        log "the server exited; its output:"; cat "$workdir/server.log" >&2; exit 1
    fi
    sleep 0.1
done
curl -fsS -m 1 -o /dev/null "$base/healthz" || { log "/healthz not up after 10 s"; exit 1; }

# The solve body must be a valid request, or the benchmark measures errors.
code="$(curl -sS -m 5 -o "$workdir/solve.out" -w '%{http_code}' \
    -H 'Content-Type: application/json' --data-binary "@$BODY" "$base/v1/shape/solve")"
if [[ "$code" != 200 ]]; then
    log "POST /v1/shape/solve answered $code:"; cat "$workdir/solve.out" >&2; echo >&2
    exit 1
fi
# ... and one the solver answers with solutions (the target is reachable), so
# the run measures the whole solve, not an early exit.
if ! tr -d ' \n' <"$workdir/solve.out" | grep -q '"reachable":true'; then
    log "POST /v1/shape/solve: the benchmark target is not reachable:"
    cat "$workdir/solve.out" >&2; echo >&2
    exit 1
fi

# ---------------------------------------------------------------- load ----
# run_wrk NAME PATH [BODY]: warm-up, then the measured run; leaves
# "NAME rps p50_ms p99_ms non2xx socket_errors requests" in $workdir/results.
run_wrk() {
    local name="$1" path="$2" body="${3:-}"
    local args=(-t "$THREADS" -c "$CONNECTIONS" --timeout 2s -s "$LUA")
    log "$name: warm-up ${WARMUP}s"
    KNOTSHAPE_BENCH_BODY="$body" timeout $(( WARMUP + 30 )) \
        wrk "${args[@]}" -d "${WARMUP}s" "$base$path" >"$workdir/$name.warmup" 2>&1
    log "$name: ${DURATION}s at $CONNECTIONS connections, $THREADS wrk threads"
    KNOTSHAPE_BENCH_BODY="$body" timeout $(( DURATION + 30 )) \
        wrk "${args[@]}" -d "${DURATION}s" "$base$path" >"$workdir/$name.out" 2>&1
    local line
    line="$(grep '^KNOTSHAPE_RESULT ' "$workdir/$name.out")" || {
        log "$name: no result from wrk:"; cat "$workdir/$name.out" >&2; exit 1
    }
    awk -v name="$name" '{
        for (i = 2; i <= NF; i++) { split($i, kv, "="); r[kv[1]] = kv[2] }
        sock = r["connect_errors"] + r["read_errors"] + r["write_errors"] + r["timeouts"]
        printf "%s %.1f %.3f %.3f %d %d %d\n", name,
            r["requests"] / (r["duration_us"] / 1e6), r["p50_us"] / 1000, r["p99_us"] / 1000,
            r["status_errors"], sock, r["requests"]
    }' <<<"$line" >>"$workdir/results"
}

echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown); machine: $(nproc) cores, load generator and server share them"
echo "load average before the run: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "wrk: $(wrk --version 2>&1 | head -n1 | cut -d' ' -f1-2); $CONNECTIONS connections, $THREADS threads, ${DURATION}s per endpoint after ${WARMUP}s warm-up"

run_wrk healthz /healthz
run_wrk solve /v1/shape/solve "$BODY"

echo "load average after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
awk -v target_ratio="$TARGET_RATIO" -v target_p99="$TARGET_SOLVE_P99_MS" '
    BEGIN { printf "%-18s %12s %10s %10s %8s %8s %10s\n", "endpoint", "req/s", "p50 ms", "p99 ms", "non-2xx", "sock.err", "requests" }
    {
        path = ($1 == "healthz") ? "GET /healthz" : "POST /v1/shape/solve"
        printf "%-18s %12.1f %10.3f %10.3f %8d %8d %10d\n", path, $2, $3, $4, $5, $6, $7
        rps[$1] = $2; p99[$1] = $4; bad += $5 + $6
    }
    END {
        ratio = rps["solve"] / rps["healthz"]
        printf "\nratio solve/healthz (req/s): %.3f   (target >= %s)\n", ratio, target_ratio
        printf "solve p99: %.3f ms            (target < %s ms)\n", p99["solve"], target_p99
        met = (ratio >= target_ratio && p99["solve"] < target_p99)
        printf "targets: %s\n", met ? "met" : "MISSED"
        exit (bad > 0) ? 1 : (met ? 0 : 3)
    }' "$workdir/results" && status=0 || status=$?

if (( status == 1 )); then
    log "FAILED: some requests were non-2xx or failed on the socket"
    exit 1
fi
if (( status == 3 )) && [[ "$ENFORCE_TARGETS" == 1 ]]; then
    log "FAILED: targets missed (ENFORCE_TARGETS=1)"
    exit 3
fi
exit 0
