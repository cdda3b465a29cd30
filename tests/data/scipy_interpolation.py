#!/usr/bin/env python3
"""Writes tests/data/scipy_interpolation.json: curves through points computed by SciPy's
make_interp_spline from the same parameters and knots as knotshape's /v1/curves/interpolate
chooses them (chord length or centripetal parameters, knots by averaging, The NURBS Book
eq. 9.8 / 9.22; SciPy's own periodic knots for closed curves), for tests/spline_core to
compare with. Run: python3 tests/data/scipy_interpolation.py (needs numpy and scipy).
"""

import json
import sys

import numpy as np
import scipy
from scipy.interpolate import make_interp_spline


def parameters(points, kind, closed):
    q = np.asarray(points, dtype=float)
    if closed:
        q = np.vstack([q, q[:1]])
    chords = np.linalg.norm(np.diff(q, axis=0), axis=1)
    steps = {"chord_length": chords, "centripetal": np.sqrt(chords)}[kind]
    t = np.concatenate([[0.0], np.cumsum(steps)])
    t /= t[-1]
    t[-1] = 1.0
    return t


def averaged_knots(t, p, start_tangent, end_tangent):
    m = len(t)
    first = 0 if start_tangent else 1
    last = m - p - 1 + (1 if end_tangent else 0)
    inner = [sum(t[j:j + p]) / p for j in range(first, last + 1)]
    return [t[0]] * (p + 1) + inner + [t[-1]] * (p + 1)


def case(name, points, degree, kind, tangents=(None, None), closed=False):
    t = parameters(points, kind, closed)
    q = np.asarray(points, dtype=float)
    if closed:
        spline = make_interp_spline(t, np.vstack([q, q[:1]]), k=degree, bc_type="periodic")
    else:
        knots = np.asarray(averaged_knots(t, degree, tangents[0] is not None, tangents[1] is not None))
        bc = None
        if tangents != (None, None):
            bc = (
                [(1, np.asarray(tangents[0]))] if tangents[0] is not None else None,
                [(1, np.asarray(tangents[1]))] if tangents[1] is not None else None,
            )
        spline = make_interp_spline(t, q, k=degree, t=knots, bc_type=bc)
    return {
        "name": name,
        "points": q.tolist(),
        "degree": degree,
        "parametrization": kind,
        "end_tangents": [None if v is None else list(v) for v in tangents],
        "closed": closed,
        "parameters": (t[:-1] if closed else t).tolist(),
        "knots": spline.t.tolist(),
        "control_points": np.asarray(spline.c).tolist(),
    }


def main():
    rng = np.random.default_rng(20240519)
    book = [[0, 0], [3, 4], [-1, 4], [-4, 0], [-4, -3]]
    spiral = [[np.cos(a) * (1 + a), np.sin(a) * (1 + a), 0.3 * a] for a in np.linspace(0, 6, 9)]
    wobbly = (rng.normal(size=(8, 2)) * [3.0, 1.0] + np.arange(8)[:, None] * [1.0, 0.5]).tolist()
    ring = [[np.cos(a) * 2 + 0.3 * np.cos(3 * a), np.sin(a) * 1.5] for a in np.linspace(0, 2 * np.pi, 7, endpoint=False)]
    ring3 = [[np.cos(a), np.sin(a), 0.2 * np.sin(2 * a)] for a in np.linspace(0, 2 * np.pi, 10, endpoint=False)]
    cases = [
        case("book example 9.1, cubic", book, 3, "chord_length"),
        case("spiral, quintic, centripetal", spiral, 5, "centripetal"),
        case("wobbly, cubic, both end tangents", wobbly, 3, "chord_length", ([4.0, -1.0], [0.0, 6.0])),
        case("wobbly, quadratic, start tangent", wobbly, 2, "centripetal", ([2.0, 2.0], None)),
        case("ring, closed cubic", ring, 3, "chord_length", closed=True),
        case("ring, closed quadratic", ring, 2, "centripetal", closed=True),
        case("ring 3D, closed quintic", ring3, 5, "chord_length", closed=True),
        case("ring 3D, closed degree 4", ring3, 4, "chord_length", closed=True),
    ]
    document = {
        "about": "Curves through points by SciPy's make_interp_spline, from the parameters and knots "
        "knotshape chooses (periodic: SciPy's own knots); written by tests/data/scipy_interpolation.py",
        "scipy": scipy.__version__,
        "numpy": np.__version__,
        "cases": cases,
    }
    with open(sys.argv[1] if len(sys.argv) > 1 else "tests/data/scipy_interpolation.json", "w") as f:
        json.dump(document, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
