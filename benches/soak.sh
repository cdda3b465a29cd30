#!/usr/bin/env bash
# Soak test of the release build on loopback: $DURATION seconds (default 600)
# of mixed traffic from benches/soak/generator.rs to every endpoint of the server's own
# OpenAPI document (good requests, malformed JSON, invalid curves, wrong types,
# too-large bodies, unknown paths and methods), plus slow clients (half-open
# request heads, bodies trickling slower than the body timeout), at a bounded
# rate ($RATE requests/s). Prints the server's RSS and the request count every
# 10 s, then the counts by class, the server's own connection metrics, and
# passes (exit 0) only when the server made no error of its own (no 5xx except
# 503 shedding with Retry-After, no reset, every answer the expected one, every
# slow client closed in time), its RSS grew by less than 10 % after a 60 s
# warm-up (median of the last minute against the median of the first minute
# after the warm-up), and it exits 0 on SIGTERM at the end.
#
# Usage: bash benches/soak.sh
# Environment: DURATION (s, default 600; at most 3600), RATE (requests/s,
#   default 400), BIN (server binary, default target/release/knotshape, built
#   by this script unless BIN is set).
# The server gets the default configuration (settings from the caller's
# environment are dropped), with logs off; traffic goes to 127.0.0.1 only.
set -euo pipefail

cd "$(dirname "$0")/.."

DURATION="${DURATION:-600}"
RATE="${RATE:-400}"
for v in DURATION RATE; do
    if ! [[ "${!v}" =~ ^[1-9][0-9]*$ ]]; then
        echo "soak.sh: $v must be a positive integer, got '${!v}'" >&2
        exit 2
    fi
done
if (( DURATION > 3600 )); then
    echo "soak.sh: DURATION <= 3600 keeps the run bounded" >&2
    exit 2
fi

log() { echo "soak.sh: $*" >&2; }

log "building the release binary and the load generator"
if [[ -z "${BIN:-}" ]]; then
    cargo build --release --locked --bin knotshape >&2
    BIN="target/release/knotshape"
fi
cargo build --release --locked --example soak >&2
GENERATOR="target/release/examples/soak"

workdir="$(mktemp -d)"
server_pid=""
# shellcheck disable=SC2317  # called from the EXIT trap
cleanup() {
    if [[ -n "$server_pid" ]] && kill -0 "$server_pid" 2>/dev/null; then
        kill -KILL "$server_pid" 2>/dev/null || true
        wait "$server_pid" 2>/dev/null || true
    fi
    rm -rf "$workdir"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

port="$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()')"
base="http://127.0.0.1:$port"
unset_inherited=()
for name in $(compgen -e); do
    if [[ "$name" == KNOTSHAPE_* ]]; then unset_inherited+=(-u "$name"); fi
done
log "starting $BIN on 127.0.0.1:$port"
env "${unset_inherited[@]}" KNOTSHAPE_LISTEN="127.0.0.1:$port" KNOTSHAPE_LOG=off \
    "$BIN" >"$workdir/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do
    if curl -fsS -m 1 -o /dev/null "$base/healthz" 2>/dev/null; then break; fi
    sleep 0.1
done
curl -fsS -m 1 -o /dev/null "$base/healthz" || { log "/healthz not up after 10 s"; exit 1; }

echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown); $(nproc) cores shared by server and generator; load average $(cut -d' ' -f1-3 /proc/loadavg)"
status=0
SOAK_URL="$base" SOAK_SERVER_PID="$server_pid" SOAK_DURATION_SECS="$DURATION" SOAK_RATE="$RATE" \
    "$GENERATOR" || status=$?

echo
echo "server metrics at the end (connections, and answers by status class):"
curl -fsS -m 5 "$base/metrics" >"$workdir/metrics" || { log "GET /metrics failed"; status=1; }
grep -E '^knotshape_http_connections' "$workdir/metrics" || true
awk '/^knotshape_http_requests_total\{/ {
        match($0, /status="[0-9]+"/); s = substr($0, RSTART + 8, 1) "xx"
        if ($0 ~ /status="503"/) s = "503"
        n[s] += $NF
    }
    END { for (s in n) printf "  answers %s: %d\n", s, n[s] }' "$workdir/metrics" | sort

kill -TERM "$server_pid"
exit_code=0
wait "$server_pid" || exit_code=$?
server_pid=""
echo "server exit status after SIGTERM: $exit_code"
if (( exit_code != 0 )); then status=1; fi
if (( status != 0 )); then log "FAILED"; fi
exit "$status"
