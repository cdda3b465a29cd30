#!/usr/bin/env bash
# Surface evaluation per point, knotshape vs SciPy's NdBSpline, on the same surfaces and
# parameter pairs in the same run: runs the criterion benchmark benches/surface_evaluate.rs
# (a bicubic, a biquintic and a rational biquadratic, each written as JSON with 100,000
# random pairs), then benches/ndbspline_compare.py on each file, and prints the time per point
# (points alone, and points with both first partials) and the ratios (criterion's estimate and
# its best sample against SciPy's best of 7: the machine's load moves both). Both sides are
# single-threaded. Installs numpy and scipy into a virtualenv under the target directory when
# python3 lacks them.
#
# Usage: bash benches/surface_compare.sh
set -euo pipefail
cd "$(dirname "$0")/.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
export KNOTSHAPE_BENCH_CURVE_DIR="$target_dir"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
surfaces=(bicubic biquintic rational_biquadratic)

python=python3
if ! "$python" -c 'from scipy.interpolate import NdBSpline' 2>/dev/null; then
    venv="$target_dir/scipy-venv"
    if ! "$venv/bin/python" -c 'from scipy.interpolate import NdBSpline' 2>/dev/null; then
        echo "installing numpy and scipy into $venv" >&2
        python3 -m venv "$venv"
        "$venv/bin/pip" install --quiet numpy scipy
    fi
    python="$venv/bin/python"
fi

load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "cores: $(nproc), load average before: $(load)"
cargo bench --bench surface_evaluate -- --noplot 2>&1 | grep -E '^surface|time:|written to'
echo "load average after Rust: $(load)"
for surface in "${surfaces[@]}"; do
    scipy_line=$("$python" benches/ndbspline_compare.py "$target_dir/surface_$surface.json")
    "$python" - "$target_dir/criterion" "$scipy_line" "$surface" <<'PY'
import json, sys
criterion_dir, scipy_line, surface = sys.argv[1], sys.argv[2], sys.argv[3]
scipy = [float(x) for x in scipy_line.split()[1:]]
with open(f"{criterion_dir}/surface_100k_{surface}/points/new/benchmark.json") as f:
    pairs = json.load(f)["throughput"]["Elements"]
for name, theirs in (("points", scipy[0]), ("first_partials", scipy[1])):
    base = f"{criterion_dir}/surface_100k_{surface}/{name}/new"
    with open(f"{base}/estimates.json") as f:
        estimates = json.load(f)
    ns = (estimates.get("slope") or estimates["mean"])["point_estimate"] / pairs
    with open(f"{base}/sample.json") as f:
        sample = json.load(f)
    best = min(t / n for t, n in zip(sample["times"], sample["iters"])) / pairs
    print(f"{surface}: {name:15} knotshape {ns:7.1f} ns/point (best sample {best:6.1f}), "
          f"SciPy NdBSpline {theirs:7.1f} ns/point (best of 7): {theirs / ns:4.1f}x "
          f"({theirs / best:.1f}x best to best)")
PY
done
echo "load average after SciPy: $(load)"
