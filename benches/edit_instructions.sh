#!/usr/bin/env bash
# Instructions per call of the edit benchmarks' cases (benches/edit_cost.rs, the `edit` group of
# benches/solve.rs), counted by valgrind's callgrind: the knot pairs alone, the weight pairs
# and all three methods on the first worked example (with and without the certified deviation
# of each solution), and the control-point move under four constraints on a 60-pole cubic.
# Unlike times, the counts hardly change with the machine's load. Valgrind is installed from
# Debian's packages when missing.
#
# Usage: bash benches/edit_instructions.sh [COUNT]   (calls per case, default 1000)
set -euo pipefail
cd "$(dirname "$0")/.."

COUNT="${1:-1000}"
if ! [[ "$COUNT" =~ ^[1-9][0-9]*$ ]]; then
    echo "edit_instructions.sh: COUNT must be a positive integer, got '$COUNT'" >&2
    exit 2
fi
if ! command -v valgrind >/dev/null; then
    sudo=()
    if (( EUID != 0 )); then sudo=(sudo -n); fi
    echo "edit_instructions.sh: installing valgrind from Debian's packages" >&2
    timeout 300 "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    timeout 300 "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y -qq --no-install-recommends valgrind >/dev/null
fi

driver="$(cargo bench --bench edit_cost --no-run --message-format=json 2>/dev/null \
    | python3 -c 'import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m["target"]["name"] == "edit_cost" and m.get("executable"):
        print(m["executable"])')"
[[ -x "$driver" ]] || { echo "edit_instructions.sh: could not build benches/edit_cost.rs" >&2; exit 1; }

workdir="$(mktemp -d)"
trap 'rm -rf "$workdir"' EXIT
instructions() {
    valgrind --tool=callgrind --callgrind-out-file="$workdir/out" "$driver" "$1" "$2" 2>&1 \
        | awk '/Collected :/ { print $NF }'
}
echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown); $COUNT calls per case"
for case in knots weights weights_without_deviation all all_without_deviation \
    constrained constrained_without_deviation; do
    base="$(instructions "$case" 0)"
    total="$(instructions "$case" "$COUNT")"
    printf '%-32s %8d instructions/call\n' "$case" $(( (total - base) / COUNT ))
done
