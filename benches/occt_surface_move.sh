#!/usr/bin/env bash
# Moving one point of every real surface (tests/data/real_surfaces.json.gz) onto a target off
# the surface, Open CASCADE's Geom_BSplineSurface::MovePoint against knotshape's surface edit
# (control points, weights, knots), in one run: benches/occt_surface_move.py picks a
# deterministic (u, v) and target per surface (along the normal by 1e-2 of the size plus
# 5e-3 of it along S_u), moves the point with MovePoint over the poles active at (u, v) and
# writes the moved poles; benches/surface_move.rs runs knotshape's methods on the same input,
# measures every result the same way (target met, pole-displacement norm, sampled and certified
# max deviation) and prints the table of docs/performance.md. Installs cadquery-ocp-novtk
# (Open CASCADE's Python bindings) into a virtualenv under the target directory when python3
# lacks it.
#
# Usage: bash benches/occt_surface_move.sh
set -euo pipefail
cd "$(dirname "$0")/.."

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
moves="$target_dir/occt_surface_moves.json"
"$python" benches/occt_surface_move.py "$moves"
cargo bench --bench surface_move -- "$moves"
echo "load average after: $(load)"
