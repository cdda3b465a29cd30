#!/usr/bin/env bash
# Instructions per whole request through the router, in-process (no sockets), counted by
# valgrind's callgrind: GET /healthz and POST /v1/shape/solve with the load test's body.
# Unlike times, the counts hardly change with the machine's load, so they show what a change
# to the request path saves even on a busy or shared machine. Valgrind is installed from
# Debian's packages when missing.
#
# Usage: bash benches/instructions.sh [COUNT]   (requests per kind, default 500)
set -euo pipefail
cd "$(dirname "$0")/.."

COUNT="${1:-500}"
if ! [[ "$COUNT" =~ ^[1-9][0-9]*$ ]]; then
    echo "instructions.sh: COUNT must be a positive integer, got '$COUNT'" >&2
    exit 2
fi
if ! command -v valgrind >/dev/null; then
    sudo=()
    if (( EUID != 0 )); then sudo=(sudo -n); fi
    echo "instructions.sh: installing valgrind from Debian's packages" >&2
    timeout 300 "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    timeout 300 "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y -qq --no-install-recommends valgrind >/dev/null
fi

driver="$(cargo bench --bench request_cost --no-run --message-format=json 2>/dev/null \
    | python3 -c 'import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m["target"]["name"] == "request_cost" and m.get("executable"):
        print(m["executable"])')"
[[ -x "$driver" ]] || { echo "instructions.sh: could not build benches/request_cost.rs" >&2; exit 1; }

workdir="$(mktemp -d)"
trap 'rm -rf "$workdir"' EXIT
# instructions KIND N: total instructions of the driver sending N requests of KIND.
instructions() {
    valgrind --tool=callgrind --callgrind-out-file="$workdir/out" "$driver" "$1" "$2" 2>&1 \
        | awk '/Collected :/ { print $NF }'
}
base="$(instructions healthz 0)"
healthz="$(instructions healthz "$COUNT")"
solve="$(instructions solve "$COUNT")"
per_healthz=$(( (healthz - base) / COUNT ))
per_solve=$(( (solve - base) / COUNT ))
echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown); $COUNT requests per kind"
echo "GET /healthz          $per_healthz instructions/request"
echo "POST /v1/shape/solve  $per_solve instructions/request"
awk -v h="$per_healthz" -v s="$per_solve" 'BEGIN { printf "solve/healthz: %.2f\n", s / h }'
