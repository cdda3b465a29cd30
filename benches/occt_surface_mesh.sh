#!/usr/bin/env bash
# Triangles of knotshape's certified meshes against Open CASCADE's BRepMesh_IncrementalMesh for
# the same measured deviation, over the 898 real surfaces (tests/data/real_surfaces.json.gz),
# in one run: benches/occt_surface_mesh.py meshes a face over every surface's whole domain at
# deflections that are fractions of its size (angular deflection 0.5, Open CASCADE's default,
# and 1.5) and writes the meshes; benches/surface_mesh.rs measures each mesh's deviation from
# the surface (45 points per triangle, surface and mesh at the same (u, v)), meshes the surface
# with knotshape to that deviation, measures that mesh the same way, and prints the tables of
# docs/performance.md: at tolerance = BRepMesh's measured deviation (certified at it), and at
# equal measured deviation (the largest tolerance a short search finds whose knotshape mesh
# still measures at most BRepMesh's deviation). Installs cadquery-ocp-novtk (Open CASCADE's Python bindings) into a
# virtualenv under the target directory when python3 lacks it.
#
# Usage: bash benches/occt_surface_mesh.sh [FRACTION ...]   (default 1e-2 1e-3)
# (PROFILE=dev uses the unoptimised build: the same triangles, slower timings.)
set -euo pipefail
cd "$(dirname "$0")/.."

fractions=("$@")
if [ ${#fractions[@]} -eq 0 ]; then
    fractions=(1e-2 1e-3)
fi
for fraction in "${fractions[@]}"; do
    if ! python3 -c "import sys; f = float(sys.argv[1]); sys.exit(0 if 0 < f < 1 else 1)" "$fraction" 2>/dev/null; then
        echo "occt_surface_mesh.sh: a FRACTION is a number in (0, 1), got '$fraction'" >&2
        exit 2
    fi
done
target_dir=$(cargo metadata --format-version 1 --no-deps |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')

python=python3
if ! "$python" -c 'import OCP.BRepMesh' 2>/dev/null; then
    venv="$target_dir/occt-venv"
    if ! "$venv/bin/python" -c 'import OCP.BRepMesh' 2>/dev/null; then
        echo "installing cadquery-ocp-novtk into $venv" >&2
        python3 -m venv "$venv"
        "$venv/bin/pip" install --quiet cadquery-ocp-novtk
    fi
    python="$venv/bin/python"
fi

load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "cores: $(nproc), load average before: $(load)"
meshes="$target_dir/occt_surface_meshes.json"
"$python" benches/occt_surface_mesh.py "$meshes" "${fractions[@]}"
cargo bench --profile "${PROFILE:-bench}" --bench surface_mesh -- "$meshes"
echo "load average after: $(load)"
