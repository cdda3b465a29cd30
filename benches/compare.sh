#!/usr/bin/env bash
# Evaluation throughput, knotshape vs SciPy, on the same curves in the same run: runs the criterion
# benchmark benches/evaluate.rs (a cubic and a degree-9 curve, each written as JSON), then
# benches/scipy_compare.py on each file, and prints the throughputs and their ratios. Both sides
# are single-threaded.
# Installs numpy and scipy into a virtualenv under the target directory when python3 lacks them.
set -euo pipefail
cd "$(dirname "$0")/.."

target_dir=$(cargo metadata --format-version 1 --no-deps |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
export KNOTSHAPE_BENCH_CURVE_DIR="$target_dir"
curves=(cubic_2d degree9_2d)
cores=$(nproc)
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1

python=python3
if ! "$python" -c 'import numpy, scipy' 2>/dev/null; then
    venv="$target_dir/scipy-venv"
    if ! "$venv/bin/python" -c 'import numpy, scipy' 2>/dev/null; then
        echo "installing numpy and scipy into $venv" >&2
        python3 -m venv "$venv"
        "$venv/bin/pip" install --quiet numpy scipy
    fi
    python="$venv/bin/python"
fi

load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "cores: $cores, load average before: $(load)"
cargo bench --bench evaluate -- --noplot "$@" 2>&1 | grep -E '^evaluate|time:|thrpt:|written to'
echo "load average after Rust: $(load)"
for curve in "${curves[@]}"; do
scipy_line=$("$python" benches/scipy_compare.py "$target_dir/evaluate_curve_$curve.json")
echo "load average after SciPy ($curve): $(load)"

"$python" - "$target_dir/criterion" "$scipy_line" "$curve" <<'PY'
import json, sys
criterion_dir, scipy_line, curve = sys.argv[1], sys.argv[2], sys.argv[3]
scipy = float(scipy_line.split()[1])
with open(f"{criterion_dir}/evaluate_1M_{curve}/uniform_points_into/new/benchmark.json") as f:
    elements = json.load(f)["throughput"]["Elements"]
print(f"{curve}: SciPy BSpline (best of 7):        {scipy / 1e6:10.2f} M points/s")
for name in ("uniform_points_into", "points_into"):
    base = f"{criterion_dir}/evaluate_1M_{curve}/{name}/new"
    with open(f"{base}/estimates.json") as f:
        estimates = json.load(f)
    ns = (estimates.get("slope") or estimates["mean"])["point_estimate"]
    with open(f"{base}/sample.json") as f:
        sample = json.load(f)
    best_ns = min(t / n for t, n in zip(sample["times"], sample["iters"]))
    typical, best = elements / (ns * 1e-9), elements / (best_ns * 1e-9)
    print(f"{curve}: knotshape {name + ':':21} {typical / 1e6:10.2f} M points/s (criterion estimate), "
          f"{best / 1e6:.2f} best sample; ratio to SciPy {typical / scipy:.1f}x ({best / scipy:.1f}x best)")
PY
done
