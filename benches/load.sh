#!/usr/bin/env bash
# Load benchmark of the release build on loopback, in one run:
#   GET /healthz and POST /v1/shape/solve (benches/load/solve.json, the first
#   worked example of the shared examples: a cubic, t = 0.42), each at
#   $CONNECTIONS connections, after a $WARMUP s warm-up each, in $ROUNDS
#   alternating rounds of $DURATION s per endpoint (healthz, solve, healthz,
#   ...): this machine's speed drifts by tens of percent within a minute, and
#   alternating spreads the drift over both endpoints instead of letting it
#   fall on one of them.
# Prints each round, then per endpoint requests/s (all requests over all its
# rounds' time), the median of the rounds' p50 and the worst round's p99
# latency and the non-2xx count, then the ratio solve/healthz of requests/s. Fails (exit 1) if any request
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
# Environment: DURATION (s per endpoint and round, default 5), ROUNDS
#   (default 3), WARMUP (s, default 2),
#   CONNECTIONS (default 64), THREADS (wrk threads, default 2),
#   ENFORCE_TARGETS (0/1, default 0), BODY (the solve request, default
#   benches/load/solve.json).
# Traffic goes to 127.0.0.1 only; the server is stopped on exit.
set -euo pipefail

cd "$(dirname "$0")/.."

DURATION="${DURATION:-5}"
ROUNDS="${ROUNDS:-3}"
WARMUP="${WARMUP:-2}"
CONNECTIONS="${CONNECTIONS:-64}"
THREADS="${THREADS:-2}"
ENFORCE_TARGETS="${ENFORCE_TARGETS:-0}"
TARGET_RATIO=0.6
TARGET_SOLVE_P99_MS=5

BODY="${BODY:-benches/load/solve.json}"
LUA="benches/load/wrk.lua"
BIN="target/release/knotshape"

for v in DURATION ROUNDS WARMUP CONNECTIONS THREADS; do
    if ! [[ "${!v}" =~ ^[1-9][0-9]*$ ]]; then
        echo "load.sh: $v must be a positive integer, got '${!v}'" >&2
        exit 2
    fi
done
if (( DURATION > 60 || ROUNDS > 10 || WARMUP > 30 )); then
    echo "load.sh: DURATION <= 60, ROUNDS <= 10 and WARMUP <= 30 keep the run bounded" >&2
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
# run_wrk NAME PATH BODY SECONDS OUT: one wrk run; its summary line goes to OUT.
run_wrk() {
    local name="$1" path="$2" body="$3" seconds="$4" out="$5"
    KNOTSHAPE_BENCH_BODY="$body" timeout $(( seconds + 30 )) \
        wrk -t "$THREADS" -c "$CONNECTIONS" --timeout 2s -s "$LUA" -d "${seconds}s" \
        "$base$path" >"$out" 2>&1
    grep -q '^KNOTSHAPE_RESULT ' "$out" || {
        log "$name: no result from wrk:"; cat "$out" >&2; exit 1
    }
}

# measure NAME PATH [BODY]: one measured round; appends
# "NAME requests duration_us p50_us p99_us non2xx socket_errors" to $workdir/results.
measure() {
    local name="$1" path="$2" body="${3:-}"
    run_wrk "$name" "$path" "$body" "$DURATION" "$workdir/$name.out"
    grep '^KNOTSHAPE_RESULT ' "$workdir/$name.out" | awk -v name="$name" '{
        for (i = 2; i <= NF; i++) { split($i, kv, "="); r[kv[1]] = kv[2] }
        sock = r["connect_errors"] + r["read_errors"] + r["write_errors"] + r["timeouts"]
        printf "%s %d %d %d %d %d %d\n", name, r["requests"], r["duration_us"],
            r["p50_us"], r["p99_us"], r["status_errors"], sock
    }' | tee -a "$workdir/results" | awk '{
        printf "  %-8s %10.1f req/s   p50 %6.3f ms   p99 %6.3f ms\n", $1, $2 / ($3 / 1e6), $4 / 1000, $5 / 1000
    }'
}

echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown); machine: $(nproc) cores, load generator and server share them"
echo "load average before the run: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "wrk: $(wrk --version 2>&1 | head -n1 | cut -d' ' -f1-2); $CONNECTIONS connections, $THREADS threads; $ROUNDS rounds of ${DURATION}s per endpoint, alternating, after ${WARMUP}s warm-up each"

log "warm-up: ${WARMUP}s per endpoint"
run_wrk healthz /healthz "" "$WARMUP" "$workdir/healthz.warmup"
run_wrk solve /v1/shape/solve "$BODY" "$WARMUP" "$workdir/solve.warmup"
for round in $(seq "$ROUNDS"); do
    log "round $round of $ROUNDS: ${DURATION}s per endpoint"
    echo "round $round:"
    measure healthz /healthz
    measure solve /v1/shape/solve "$BODY"
done

echo "load average after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
sort -s -k1,1 "$workdir/results" | awk -v target_ratio="$TARGET_RATIO" -v target_p99="$TARGET_SOLVE_P99_MS" '
    function median(list, count,    sorted, i, j, t) {
        for (i = 1; i <= count; i++) sorted[i] = list[i]
        for (i = 1; i <= count; i++) for (j = i + 1; j <= count; j++)
            if (sorted[j] < sorted[i]) { t = sorted[i]; sorted[i] = sorted[j]; sorted[j] = t }
        return (count % 2) ? sorted[(count + 1) / 2] : (sorted[count / 2] + sorted[count / 2 + 1]) / 2
    }
    {
        name = $1; n[name]++
        requests[name] += $2; duration[name] += $3
        p50[name, n[name]] = $4
        if ($5 > p99[name]) p99[name] = $5
        bad += $6 + $7; status[name] += $6; sock[name] += $7
    }
    END {
        printf "%-20s %12s %10s %10s %8s %8s %10s\n", "endpoint", "req/s", "p50 ms", "p99 ms", "non-2xx", "sock.err", "requests"
        split("healthz solve", names, " ")
        for (k = 1; k <= 2; k++) {
            name = names[k]
            for (i = 1; i <= n[name]; i++) list[i] = p50[name, i]
            rps[name] = requests[name] / (duration[name] / 1e6)
            path = (name == "healthz") ? "GET /healthz" : "POST /v1/shape/solve"
            printf "%-20s %12.1f %10.3f %10.3f %8d %8d %10d\n", path, rps[name],
                median(list, n[name]) / 1000, p99[name] / 1000, status[name], sock[name], requests[name]
        }
        ratio = rps["solve"] / rps["healthz"]
        printf "\nratio solve/healthz (req/s): %.3f   (target >= %s)\n", ratio, target_ratio
        printf "solve p99 (worst round): %.3f ms   (target < %s ms)\n", p99["solve"] / 1000, target_p99
        met = (ratio >= target_ratio && p99["solve"] / 1000 < target_p99)
        printf "targets: %s\n", met ? "met" : "MISSED"
        exit (bad > 0) ? 1 : (met ? 0 : 3)
    }' && status=0 || status=$?

if (( status == 1 )); then
    log "FAILED: some requests were non-2xx or failed on the socket"
    exit 1
fi
if (( status == 3 )) && [[ "$ENFORCE_TARGETS" == 1 ]]; then
    log "FAILED: targets missed (ENFORCE_TARGETS=1)"
    exit 3
fi
exit 0
