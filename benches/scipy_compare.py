#!/usr/bin/env python3
"""SciPy side of the evaluation benchmark: times scipy.interpolate.BSpline on the curve that
benches/evaluate.rs wrote (same control points, same knots), over the same number of uniformly
spaced parameters, and checks SciPy's points against the Rust points stored in the file.

Usage: scipy_compare.py CURVE_JSON [--repeats N]
Prints one line `scipy_points_per_second <value>` (best of N runs) and details on stderr.
"""

import argparse
import json
import sys
import time

import numpy as np
import scipy
from scipy.interpolate import BSpline

# SciPy's points must equal the Rust evaluator's, relative to the control-point scale.
CHECK_TOL = 1e-12


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("curve_json")
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()

    with open(args.curve_json, encoding="utf-8") as f:
        data = json.load(f)
    degree = data["degree"]
    knots = np.asarray(data["knots"], dtype=np.float64)
    control = np.asarray(data["control_points"], dtype=np.float64)
    count = int(data["points_evaluated"])
    spline = BSpline(knots, control, degree, extrapolate=False)

    # Same curve: compare with the Rust points (the domain's right end is a limit from the left
    # in both).
    check_t = np.asarray(data["check_parameters"])
    lo, hi = knots[degree], knots[len(control)]
    if not np.array_equal(check_t, np.linspace(lo, hi, len(check_t))):
        print("Rust's uniform parameters differ from numpy.linspace", file=sys.stderr)
        return 1
    expected = np.asarray(data["check_points"])
    scale = max(1.0, float(np.abs(control).max()))
    error = float(np.abs(spline(check_t) - expected).max()) / scale
    if not error <= CHECK_TOL:
        print(f"SciPy and Rust disagree on the benchmark curve: {error:.3e}", file=sys.stderr)
        return 1

    parameters = np.linspace(lo, hi, count)
    best = float("inf")
    for _ in range(args.repeats):
        start = time.perf_counter()
        spline(parameters)
        best = min(best, time.perf_counter() - start)
    print(
        f"SciPy {scipy.__version__} / NumPy {np.__version__}: BSpline of degree {degree}, "
        f"{len(control)} control points, {count} points: best of {args.repeats} = "
        f"{best * 1e3:.2f} ms (check error {error:.1e})",
        file=sys.stderr,
    )
    print(f"scipy_points_per_second {count / best:.6e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
