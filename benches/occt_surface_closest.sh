#!/usr/bin/env bash
# The closest point on the 898 real surfaces (tests/data/real_surfaces.json.gz) against Open
# CASCADE's GeomAPI_ProjectPointOnSurf, both in one run: benches/surface_closest.rs answers
# seeded queries (on, near and far from each surface) and times them per query, then
# benches/occt_surface_closest.py times Open CASCADE on the same queries (Init once per
# surface, Perform per point) and counts the queries where either is farther than the other
# beyond the tolerance. Installs cadquery-ocp-novtk (Open CASCADE's Python bindings) into a
# virtualenv under the target directory when python3 lacks it.
#
# Usage: bash benches/occt_surface_closest.sh [QUERIES_PER_SURFACE]   (default 24)
set -euo pipefail
cd "$(dirname "$0")/.."

QUERIES="${1:-24}"
if ! [[ "$QUERIES" =~ ^[1-9][0-9]*$ ]]; then
    echo "occt_surface_closest.sh: QUERIES_PER_SURFACE must be a positive integer, got '$QUERIES'" >&2
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

load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "cores: $(nproc), load average before: $(load)"
answers="$target_dir/surface_closest.json"
cargo bench --bench surface_closest -- "$answers" "$QUERIES"
"$python" benches/occt_surface_closest.py "$answers"
echo "load average after: $(load)"
