#!/usr/bin/env bash
# Curves from points, knotshape vs SciPy and Open CASCADE in the same run: interpolation of
# 10,000 points (the same curve as SciPy's make_interp_spline), approximation at certified
# tolerances (poles and time against GeomAPI_PointsToBSpline and splprep) and knot removal
# (against Geom_BSplineCurve::RemoveKnot). benches/fitting_compare.py writes the inputs,
# benches/fitting.rs (cargo bench --bench fitting) answers them, the Python script compares
# and prints a Markdown table. Single-threaded on both sides.
# Installs numpy, scipy and cadquery-ocp-novtk into a virtualenv under the target directory
# when the Python found lacks them (KNOTSHAPE_BENCH_PYTHON picks another interpreter).
set -euo pipefail
cd "$(dirname "$0")/.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
work="$target_dir/fitting-compare"
mkdir -p "$work"
cores=$(nproc)
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1

python=${KNOTSHAPE_BENCH_PYTHON:-python3}
if ! "$python" -c 'import numpy, scipy, OCP' 2>/dev/null; then
    venv="$target_dir/fitting-venv"
    if ! "$venv/bin/python" -c 'import numpy, scipy, OCP' 2>/dev/null; then
        echo "installing numpy, scipy and cadquery-ocp-novtk into $venv" >&2
        python3 -m venv "$venv"
        "$venv/bin/pip" install --quiet numpy scipy cadquery-ocp-novtk
    fi
    python="$venv/bin/python"
fi

load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "cores: $cores, load average before: $(load)" >&2
"$python" benches/fitting_compare.py prepare "$work/input.json"
KNOTSHAPE_FITTING_INPUT="$work/input.json" KNOTSHAPE_FITTING_OUTPUT="$work/ours.json" \
    cargo bench --bench fitting
echo "load average after Rust: $(load)" >&2
"$python" benches/fitting_compare.py compare "$work/input.json" "$work/ours.json"
echo "load average after the peers: $(load)" >&2
