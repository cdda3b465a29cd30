#!/usr/bin/env python3
"""The peers' side of the curves-from-points comparison, run by benches/fitting_compare.sh:

* `prepare IN`: writes the inputs (point sets, tolerances, curves) that benches/fitting.rs
  reads: 10,000 points to interpolate (cubic); three point sets to approximate at 1e-2,
  1e-3 and 1e-4 of their size (a real CAD curve sampled, a noisy sine, a corner); two curves
  whose knots are to be removed.
* `compare IN OURS`: reads knotshape's answers and runs the same tasks with SciPy and Open
  CASCADE in the same run: `make_interp_spline` with knotshape's parameters and knots (the
  same curve: its control points are compared) and its time; `GeomAPI_PointsToBSpline`
  (degree 3, C2) and `splprep` (cubic), each driven to the same *certified* tolerance (their
  own tolerance parameters lowered, or the smoothing searched, until the true largest
  point-to-curve distance is within the tolerance), counting poles and timing; Open
  CASCADE's `Geom_BSplineCurve::RemoveKnot` against knotshape's removal at the same
  tolerance. Every curve's true distance is measured here the same way (dense sampling of
  each knot span, then a golden-section search beside the nearest samples), knotshape's
  too. Prints a table (Markdown) on stdout and details on stderr.
"""

import json
import sys
import time

import numpy as np
import scipy
from scipy.interpolate import BSpline, make_interp_spline, splprep

from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI_PointsToBSpline
from OCP.Geom import Geom_BSplineCurve
from OCP.gp import gp_Pnt
from OCP.OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int

REPEATS = 5
SAMPLES_PER_SPAN = 64
GOLDEN_STEPS = 60
TOLERANCES = (1e-2, 1e-3, 1e-4)
REMOVAL_TOLERANCES = (1e-3, 1e-4, 1e-5)
# Open CASCADE's Tol3D is lowered by this factor until its answer is certified, at most
# this many times.
OCCT_TIGHTEN = 0.6
OCCT_TRIES = 6


def log(*args):
    print(*args, file=sys.stderr, flush=True)


def size_of(points):
    points = np.asarray(points)
    return float(np.linalg.norm(points.max(0) - points.min(0)))


def chord_parameters(points):
    points = np.asarray(points, dtype=float)
    t = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    t /= t[-1]
    t[-1] = 1.0
    return t


def averaged_knots(t, p):
    m = len(t)
    inner = [t[j:j + p].sum() / p for j in range(1, m - p)]
    return np.concatenate([[t[0]] * (p + 1), inner, [t[-1]] * (p + 1)])


def real_curve_points(count):
    with open("tests/data/real_curve_hammer_e18.json", encoding="utf-8") as f:
        real = json.load(f)
    spline = BSpline(np.asarray(real["knots"]), np.asarray(real["poles"]), real["degree"])
    lo, hi = real["domain"]
    return spline(np.linspace(lo, hi, count))


def prepare(path):
    rng = np.random.default_rng(20240601)
    # 10,000 points on a wavy spiral (2D).
    a = np.linspace(0.0, 12.0 * np.pi, 10_000)
    spiral = np.c_[np.cos(a) * (1 + 0.1 * a), np.sin(a) * (1 + 0.1 * a) + 0.05 * np.sin(7 * a)]
    # The approximation sets.
    real = real_curve_points(600)
    t = np.linspace(0.0, 1.0, 600)
    noisy = np.c_[10.0 * t, 2.0 * np.sin(4.0 * np.pi * t) + rng.normal(0.0, 0.01, t.size)]
    leg = np.linspace(0.0, 1.0, 300, endpoint=False)
    corner = np.r_[np.c_[5.0 * leg, 0.0 * leg], np.c_[5.0 + 0.0 * leg, 5.0 * np.linspace(0.0, 1.0, 300)]]
    sets = [("real curve (hammer.iges e18, 3D)", real), ("noisy sine", noisy), ("corner", corner)]
    approximation = [
        {
            "name": name,
            "points": points.tolist(),
            "size": size_of(points),
            "relative": list(TOLERANCES),
            "tolerances": [r * size_of(points) for r in TOLERANCES],
        }
        for name, points in sets
    ]
    # Removal: a cubic interpolant of 300 samples of the real curve (SciPy, chord length,
    # averaged knots), and the real curve with 60 knots inserted (exactly removable).
    samples = real_curve_points(300)
    u = chord_parameters(samples)
    interpolant = make_interp_spline(u, samples, k=3, t=averaged_knots(u, 3))
    with open("tests/data/real_curve_hammer_e18.json", encoding="utf-8") as f:
        real_data = json.load(f)
    refined = refine(real_data, 60)
    removal = [
        {
            "name": "interpolant of 300 samples of the real curve",
            "curve": {"degree": 3, "control_points": interpolant.c.tolist(), "knots": interpolant.t.tolist()},
            "size": size_of(samples),
            "relative": list(REMOVAL_TOLERANCES),
            "tolerances": [r * size_of(samples) for r in REMOVAL_TOLERANCES],
        },
        {
            "name": "the real curve with 60 knots inserted",
            "curve": refined,
            "size": size_of(samples),
            "relative": [1e-9],
            "tolerances": [1e-9 * size_of(samples)],
        },
    ]
    document = {
        "repeats": REPEATS,
        "interpolation": {"degree": 3, "points": spiral.tolist()},
        "approximation": approximation,
        "removal": removal,
    }
    with open(path, "w", encoding="utf-8") as f:
        json.dump(document, f)


def refine(real, count):
    """The real curve with `count` knots inserted (Open CASCADE's InsertKnot), unclamped ends
    kept as they are (the curve is clamped)."""
    curve = to_occt(real["degree"], real["poles"], real["knots"])
    lo, hi = real["domain"]
    for value in np.linspace(lo, hi, count + 2)[1:-1]:
        curve.InsertKnot(float(value), 1, 0.0, True)
    return from_occt(curve)


def to_occt(degree, poles, knots):
    """A Geom_BSplineCurve from a full (flat) knot vector."""
    poles = np.asarray(poles, dtype=float)
    if poles.shape[1] == 2:
        poles = np.c_[poles, np.zeros(len(poles))]
    array = Array1_gp_Pnt(1, len(poles))
    for i, p in enumerate(poles):
        array.SetValue(i + 1, gp_Pnt(*map(float, p)))
    values, mults = np.unique(np.asarray(knots, dtype=float), return_counts=True)
    knot_array = Array1_double(1, len(values))
    mult_array = Array1_int(1, len(values))
    for i, (value, mult) in enumerate(zip(values, mults)):
        knot_array.SetValue(i + 1, float(value))
        mult_array.SetValue(i + 1, int(mult))
    return Geom_BSplineCurve(array, knot_array, mult_array, degree)


def from_occt(curve):
    poles = [[curve.Pole(i).X(), curve.Pole(i).Y(), curve.Pole(i).Z()] for i in range(1, curve.NbPoles() + 1)]
    knots = []
    for i in range(1, curve.NbKnots() + 1):
        knots += [curve.Knot(i)] * curve.Multiplicity(i)
    return {"degree": curve.Degree(), "control_points": poles, "knots": knots}


def spline_of(curve):
    c = np.asarray(curve["control_points"], dtype=float)
    return BSpline(np.asarray(curve["knots"], dtype=float), c, curve["degree"])


def sample_parameters(spline):
    t, k = spline.t, spline.k
    lo, hi = t[k], t[len(t) - k - 1]
    breaks = np.unique(t[(t >= lo) & (t <= hi)])
    parts = [np.linspace(a, b, SAMPLES_PER_SPAN, endpoint=False) for a, b in zip(breaks[:-1], breaks[1:])]
    return np.concatenate(parts + [[hi]])


def distances(spline, points):
    """Each point's distance to the curve: the nearest of dense samples, then a golden-section
    search on both sample intervals beside it (vectorised over the points)."""
    points = np.asarray(points, dtype=float)
    dim = spline.c.shape[1]
    if points.shape[1] < dim:
        points = np.c_[points, np.zeros((len(points), dim - points.shape[1]))]
    u = sample_parameters(spline)
    samples = spline(u)
    nearest = np.empty(len(points), dtype=int)
    best = np.empty(len(points))
    for start in range(0, len(points), 256):
        block = points[start:start + 256]
        d = ((block[:, None, :] - samples[None, :, :]) ** 2).sum(-1)
        nearest[start:start + 256] = d.argmin(1)
        best[start:start + 256] = np.sqrt(d.min(1))
    ratio = 0.5 * (np.sqrt(5.0) - 1.0)
    for side in (-1, 1):
        other = np.clip(nearest + side, 0, len(u) - 1)
        lo = np.minimum(u[nearest], u[other])
        hi = np.maximum(u[nearest], u[other])
        f = lambda x: np.sqrt(((spline(x) - points) ** 2).sum(-1))
        for _ in range(GOLDEN_STEPS):
            a = hi - ratio * (hi - lo)
            b = lo + ratio * (hi - lo)
            left = f(a) < f(b)
            hi = np.where(left, b, hi)
            lo = np.where(left, lo, a)
        best = np.minimum(best, f(0.5 * (lo + hi)))
    return best


def occt_approximation(points, tolerance):
    """Open CASCADE at the certified tolerance: Tol3D lowered until the measured error is
    within `tolerance`. Returns (poles, measured error, seconds of the certified call, the
    first call's poles and error)."""
    array = Array1_gp_Pnt(1, len(points))
    for i, p in enumerate(points):
        p = list(p) + [0.0] * (3 - len(p))
        array.SetValue(i + 1, gp_Pnt(*map(float, p)))
    tol3d = tolerance
    first = None
    for attempt in range(OCCT_TRIES):
        start = time.perf_counter()
        api = GeomAPI_PointsToBSpline(array, 3, 3, GeomAbs_C2, tol3d)
        seconds = time.perf_counter() - start
        if not api.IsDone():
            return None, None, seconds, first
        curve = from_occt(api.Curve())
        spline = BSpline(np.asarray(curve["knots"]), np.asarray(curve["control_points"]), 3)
        error = float(distances(spline, points).max())
        poles = len(curve["control_points"])
        log(f"    OCCT Tol3D {tol3d:.3e}: {poles} poles, measured {error:.3e} ({seconds * 1e3:.1f} ms)")
        if first is None:
            first = (poles, error)
        if error <= tolerance:
            return poles, error, seconds, first
        tol3d *= OCCT_TIGHTEN
    return None, None, None, first


def splprep_approximation(points, tolerance):
    """SciPy's splprep (cubic, chord-length parameters) with the largest smoothing whose
    answer is certified within `tolerance` (bisection on log s). Returns (poles, error,
    seconds of that call)."""
    pts = np.asarray(points, dtype=float).T
    u = chord_parameters(points)
    m = len(points)
    best = None

    def attempt(s):
        start = time.perf_counter()
        tck, _ = splprep(pts, u=u, k=3, s=s, quiet=2)
        seconds = time.perf_counter() - start
        t, c, k = tck
        spline = BSpline(t, np.asarray(c).T, k)
        error = float(distances(spline, points).max())
        return len(t) - k - 1, error, seconds

    lo, hi = np.log(1e-12 * m * tolerance**2), np.log(m * tolerance**2)
    for _ in range(24):
        mid = 0.5 * (lo + hi)
        poles, error, seconds = attempt(float(np.exp(mid)))
        if error <= tolerance:
            if best is None or poles <= best[0]:
                best = (poles, error, seconds)
            lo = mid
        else:
            hi = mid
    return best


def occt_removal(curve, tolerance, size, repeat_passes=5):
    """Open CASCADE's RemoveKnot with `tolerance` on every interior knot, in passes until one
    removes nothing; the count, the measured deviation and the seconds."""
    start = time.perf_counter()
    occt = to_occt(curve["degree"], curve["control_points"], curve["knots"])
    removed = 0
    for _ in range(repeat_passes):
        before = removed
        index = occt.NbKnots() - 1
        while index >= 2:
            mult = occt.Multiplicity(index)
            if occt.RemoveKnot(index, mult - 1, tolerance):
                removed += 1
            index -= 1
            index = min(index, occt.NbKnots() - 1)
        if removed == before:
            break
    seconds = time.perf_counter() - start
    return removed, from_occt(occt), seconds


def deviation(original, reduced):
    """max |C(u) − C'(u)| over a dense grid of the union of both knot vectors (same
    parametrization: the domain is kept)."""
    a, b = spline_of(original), spline_of(reduced)
    u = np.unique(np.concatenate([sample_parameters(a), sample_parameters(b)]))
    ca, cb = a(u), b(u)
    width = min(ca.shape[1], cb.shape[1])
    return float(np.sqrt(((ca[:, :width] - cb[:, :width]) ** 2).sum(-1)).max())


def occt_certified_removal(curve, tolerance, size):
    """Open CASCADE at the same certified tolerance: its per-removal tolerance lowered
    (halved, then bisected six times) to the largest whose measured deviation stays within
    `tolerance`. Returns (removed, deviation, factor of the tolerance)."""
    factor, passing, failing = 1.0, None, None
    for _ in range(30):
        removed, reduced, _ = occt_removal(curve, tolerance * factor, size)
        measured = deviation(curve, reduced)
        if measured <= tolerance:
            passing = (factor, removed, measured)
            break
        failing = factor
        factor *= 0.5
    if passing is None:
        return None
    if failing is not None:
        low, high = passing[0], failing
        for _ in range(6):
            middle = 0.5 * (low + high)
            removed, reduced, _ = occt_removal(curve, tolerance * middle, size)
            measured = deviation(curve, reduced)
            if measured <= tolerance:
                low = middle
                if removed >= passing[1]:
                    passing = (middle, removed, measured)
            else:
                high = middle
    return passing[1], passing[2], passing[0]


def best_time(function, repeats=REPEATS):
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def compare(input_path, ours_path):
    with open(input_path, encoding="utf-8") as f:
        data = json.load(f)
    with open(ours_path, encoding="utf-8") as f:
        ours = json.load(f)
    log(f"SciPy {scipy.__version__}, NumPy {np.__version__}, Open CASCADE (OCP) from cadquery-ocp-novtk")
    out = []

    # Interpolation: the same curve from the same parameters and knots.
    points = np.asarray(data["interpolation"]["points"])
    ours_interp = ours["interpolation"]
    t = np.asarray(ours_interp["parameters"])
    knots = np.asarray(ours_interp["curve"]["knots"])
    scipy_seconds, spline = best_time(lambda: make_interp_spline(t, points, k=3, t=knots))
    our_poles = np.asarray(ours_interp["curve"]["control_points"])
    scale = float(np.abs(our_poles).max())
    difference = float(np.abs(spline.c - our_poles).max()) / scale
    through = float(np.abs(spline(t) - points).max())
    ratio = ours_interp["seconds"] / scipy_seconds
    out.append("### Interpolation, 10,000 points, cubic, chord length, averaged knots\n")
    out.append("| | time (best of 5) | |")
    out.append("|---|---|---|")
    out.append(f"| knotshape `interpolate` | {ours_interp['seconds'] * 1e3:.2f} ms | |")
    out.append(f"| SciPy `make_interp_spline` (same parameters and knots) | {scipy_seconds * 1e3:.2f} ms | |")
    out.append(f"| ratio knotshape / SciPy | {ratio:.2f} | control points agree to {difference:.1e} (relative); SciPy's curve passes the points to {through:.1e} |")
    out.append("")

    # Approximation.
    out.append("### Approximation at a certified tolerance (cubic; poles, time)\n")
    out.append("Tolerance relative to the point set's bounding-box diagonal; every curve's largest point-to-curve distance measured here the same way. Open CASCADE: `GeomAPI_PointsToBSpline(points, 3, 3, C2, Tol3D)`, Tol3D lowered by 0.6 until certified (its first answer, at Tol3D = tolerance, in brackets: poles / measured error ÷ tolerance). SciPy: `splprep(k=3, s)` with the largest smoothing `s` that is certified (bisection); its ends are not pinned.\n")
    out.append("| point set | tolerance | knotshape poles (error ÷ tol, time) | Open CASCADE poles (time) [first answer] | SciPy splprep poles (time) |")
    out.append("|---|---|---|---|---|")
    for case in data["approximation"]:
        for relative, tolerance in zip(case["relative"], case["tolerances"]):
            answer = next(a for a in ours["approximation"] if a["name"] == case["name"] and a["tolerance"] == tolerance)
            log(f"{case['name']} at {relative:g}:")
            measured = float(distances(spline_of(answer["curve"]), case["points"]).max())
            log(f"    knotshape: {answer['poles']} poles, reported {answer['max_error']:.3e}, measured {measured:.3e}")
            occt_poles, occt_error, occt_seconds, first = occt_approximation(case["points"], tolerance)
            fitpack = splprep_approximation(case["points"], tolerance)
            occt_cell = "not certified" if occt_poles is None else f"{occt_poles} ({occt_seconds * 1e3:.0f} ms)"
            if first is not None:
                occt_cell += f" [{first[0]} / {first[1] / tolerance:.2f}]"
            fitpack_cell = "none certified" if fitpack is None else f"{fitpack[0]} ({fitpack[2] * 1e3:.1f} ms)"
            out.append(
                f"| {case['name']} ({len(case['points'])} points) | {relative:g} | {answer['poles']} ({measured / tolerance:.2f}, {answer['seconds'] * 1e3:.1f} ms) | {occt_cell} | {fitpack_cell} |"
            )
    out.append("")

    # Knot removal.
    out.append("### Knot removal within a tolerance\n")
    out.append("Open CASCADE: `Geom_BSplineCurve::RemoveKnot(index, m − 1, tolerance)` on every interior knot, in passes until one removes nothing; its tolerance bounds each removal, not their sum, so the last column lowers it until the measured deviation is within the tolerance. Deviation `max |C(u) − C'(u)|` measured here on a dense grid for both (knotshape's certified bound in brackets).\n")
    out.append("| curve | tolerance | interior knots | knotshape removed (deviation [bound], time) | Open CASCADE removed at the tolerance (deviation, time) | Open CASCADE removed within the tolerance (deviation; its tolerance ÷ ours) |")
    out.append("|---|---|---|---|---|---|")
    for case in data["removal"]:
        curve = case["curve"]
        degree = curve["degree"]
        interior = len(curve["knots"]) - 2 * (degree + 1)
        for relative, tolerance in zip(case["relative"], case["tolerances"]):
            answer = next(a for a in ours["removal"] if a["name"] == case["name"] and a["tolerance"] == tolerance)
            our_deviation = deviation(curve, answer["curve"])
            removed, reduced, seconds = occt_removal(curve, tolerance, case["size"])
            occt_deviation = deviation(curve, reduced)
            log(f"{case['name']} at {relative:g}: knotshape {answer['removed']} ({our_deviation:.2e}), OCCT {removed} ({occt_deviation:.2e})")
            certified = occt_certified_removal(curve, tolerance, case["size"])
            certified_cell = "none" if certified is None else f"{certified[0]} ({certified[1] / case['size']:.1e}; {certified[2]:.3g})"
            out.append(
                f"| {case['name']} | {relative:g} | {interior} | {answer['removed']} ({our_deviation / case['size']:.1e} [{answer['max_deviation'] / case['size']:.1e}], {answer['seconds'] * 1e3:.1f} ms) | {removed} ({occt_deviation / case['size']:.1e}, {seconds * 1e3:.1f} ms) | {certified_cell} |"
            )
    out.append("")
    out.append("Deviations relative to the curve's size (bounding-box diagonal of the samples).")
    print("\n".join(out))


def main():
    if len(sys.argv) >= 3 and sys.argv[1] == "prepare":
        prepare(sys.argv[2])
    elif len(sys.argv) >= 4 and sys.argv[1] == "compare":
        compare(sys.argv[2], sys.argv[3])
    else:
        print(__doc__, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
