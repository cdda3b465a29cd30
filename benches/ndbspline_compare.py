#!/usr/bin/env python3
"""SciPy side of the surface evaluation benchmark: times scipy.interpolate.NdBSpline on the
surface that benches/surface_evaluate.rs wrote (same poles, weights and knots), at the same
parameter pairs, and checks SciPy's values against the Rust ones stored in the file.

A rational surface is evaluated as NdBSpline does it: the homogeneous surface (w x, w y, w z, w)
as four channels, then divided (and the quotient rule for the partials), all in NumPy.

Usage: ndbspline_compare.py SURFACE_JSON [--repeats N]
Prints one line `ndbspline_ns_per_point <points> <points_and_first_partials>` (best of N
runs each) and details on stderr.
"""

import argparse
import json
import sys
import time

import numpy as np
import scipy
from scipy.interpolate import NdBSpline

# SciPy's values must equal the Rust ones, relative to the values' scale.
CHECK_TOL = 1e-10


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("surface_json")
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()

    with open(args.surface_json, encoding="utf-8") as f:
        data = json.load(f)
    degree = data["degree"]
    poles = np.asarray(data["poles"], dtype=np.float64)
    weights = data["weights"]
    knots = (np.asarray(data["knots_u"]), np.asarray(data["knots_v"]))
    pairs = np.asarray(data["pairs"], dtype=np.float64)
    rational = weights is not None
    if rational:
        w = np.asarray(weights, dtype=np.float64)[..., None]
        coefficients = np.concatenate([poles * w, w], axis=-1)
    else:
        coefficients = poles
    spline = NdBSpline(knots, coefficients, (degree, degree), extrapolate=False)

    def points(xi):
        values = spline(xi)
        if rational:
            return values[:, :3] / values[:, 3:]
        return values

    def first_partials(xi):
        values = spline(xi)
        du = spline(xi, nu=(1, 0))
        dv = spline(xi, nu=(0, 1))
        if rational:
            w = values[:, 3:]
            s = values[:, :3] / w
            du = (du[:, :3] - du[:, 3:] * s) / w
            dv = (dv[:, :3] - dv[:, 3:] * s) / w
            return s, du, dv
        return values, du, dv

    check = np.asarray(data["check"])
    xi = pairs[: len(check)]
    found = first_partials(xi)
    errors = []
    for index, name in enumerate(("points", "du", "dv")):
        expected = check[:, index, :]
        scale = max(1.0, float(np.abs(expected).max()))
        errors.append(float(np.abs(found[index] - expected).max()) / scale)
    if not max(errors) <= CHECK_TOL:
        print(f"SciPy and Rust disagree on the benchmark surface: {errors}", file=sys.stderr)
        return 1

    def best(function):
        best = float("inf")
        for _ in range(args.repeats):
            start = time.perf_counter()
            function(pairs)
            best = min(best, time.perf_counter() - start)
        return best

    points_time = best(points)
    partials_time = best(first_partials)
    count = len(pairs)
    print(
        f"SciPy {scipy.__version__} / NumPy {np.__version__}: NdBSpline of degree {degree}x{degree}, "
        f"{poles.shape[0]}x{poles.shape[1]} poles{' (rational)' if rational else ''}, {count} pairs: "
        f"points {points_time * 1e3:.1f} ms, with first partials {partials_time * 1e3:.1f} ms "
        f"(check errors {max(errors):.1e})",
        file=sys.stderr,
    )
    print(f"ndbspline_ns_per_point {points_time / count * 1e9:.3f} {partials_time / count * 1e9:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
