#!/usr/bin/env bash
# The constrained control-point move against Open CASCADE's Geom_BSplineCurve::
# MovePointAndTangent on random point-and-tangent moves (benches/occt_move_point_and_tangent.py):
# both must meet the conditions; prints the ratio of max deviations (ours / OCCT's) and of the
# pole displacements' norms. Builds and starts the release binary on a loopback port for the
# run and stops it afterwards. Installs cadquery-ocp-novtk (Open CASCADE's Python bindings)
# into a virtualenv under the target directory when python3 lacks it.
#
# Usage: bash benches/occt_compare.sh [MOVES]   (default 300)
set -euo pipefail
cd "$(dirname "$0")/.."

MOVES="${1:-300}"
if ! [[ "$MOVES" =~ ^[1-9][0-9]*$ ]]; then
    echo "occt_compare.sh: MOVES must be a positive integer, got '$MOVES'" >&2
    exit 2
fi
target_dir=$(cargo metadata --format-version 1 --no-deps |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')

python=python3
if ! "$python" -c 'import OCP.Geom' 2>/dev/null; then
    venv="$target_dir/occt-venv"
    if ! "$venv/bin/python" -c 'import OCP.Geom' 2>/dev/null; then
        echo "installing cadquery-ocp-novtk into $venv" >&2
        python3 -m venv "$venv"
        "$venv/bin/pip" install --quiet cadquery-ocp-novtk
    fi
    python="$venv/bin/python"
fi

cargo build --release --quiet
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
"$target_dir/release/knotshape" --listen "127.0.0.1:$port" >/dev/null 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
for _ in $(seq 1 100); do
    if curl -fsS "http://127.0.0.1:$port/healthz" >/dev/null 2>&1; then break; fi
    sleep 0.1
done
"$python" benches/occt_move_point_and_tangent.py --url "http://127.0.0.1:$port" --moves "$MOVES" \
    --json "$target_dir/occt_move_point_and_tangent.json"
