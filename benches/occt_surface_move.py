#!/usr/bin/env python3
"""Open CASCADE's side of benches/occt_surface_move.sh: Geom_BSplineSurface::MovePoint on every
real surface (tests/data/real_surfaces.json.gz, rebuilt from its `occt` form), for one
deterministic parameter pair and target per surface; writes the moves for
benches/surface_move.rs, which runs knotshape's methods on the same input and prints the table.

For surface number k (in file order) the pair is `(u, v) = (u0 + a (u1 - u0), v0 + b (v1 - v0))`
with `a = 0.2 + 0.6 frac(0.5 + k / phi)`, `b = 0.2 + 0.6 frac(0.5 + k / phi^2)` (the first of
ten such pairs, k, k + 1000, ..., where the unit normal is defined: |S_u x S_v| above 1e-9 of
|S_u| |S_v|). The target is `S(u, v) + size (1e-2 n + 5e-3 t)`, `n` the unit normal, `t` the
unit `S_u`, `size` the diagonal of the poles' bounding box.

MovePoint(U, V, P, UIndex1, UIndex2, VIndex1, VIndex2) may move the poles of rows
UIndex1..UIndex2 and columns VIndex1..VIndex2 (1-based); it moves only those among them whose
basis functions are non-zero at (u, v) (BSplSLib::MovePoint) and returns the first and last
moved indices. The ranges passed are the poles active at (u, v): rows `first .. first + p_u`
with `first` the first non-zero basis function (Open CASCADE's own span search,
BSplCLib::LocateParameter on the flat knots), and the same in v; for the one
periodic direction the whole row range. A call that raises (Open CASCADE's
Standard_Failure) is written as an error for that surface. Its time is the median of five calls on copies of the
surface (each built anew, not timed), through the Python binding.

Usage: occt_surface_move.py OUTPUT_JSON
"""

import gzip
import json
import math
import statistics
import sys
import time
from pathlib import Path

from OCP.Geom import Geom_BSplineSurface
from OCP.collections import Array1_double, Array1_int, Array2_double, Array2_gp_Pnt
from OCP.gp import gp_Pnt, gp_Vec

PHI = (1.0 + math.sqrt(5.0)) / 2.0
REPEATS = 5


def occt_surface(data):
    """The surface rebuilt from its Open CASCADE form (poles not repeated)."""
    occt = data["occt"]
    n_u, n_v = occt["n_u"], occt["n_v"]
    poles = Array2_gp_Pnt(1, n_u, 1, n_v)
    for i in range(n_u):
        for j in range(n_v):
            poles.SetValue(i + 1, j + 1, gp_Pnt(*data["poles"][i][j]))

    def array(values, kind):
        out = kind(1, len(values))
        for k, value in enumerate(values):
            out.SetValue(k + 1, value)
        return out

    knots_u, knots_v = array(occt["knots_u"], Array1_double), array(occt["knots_v"], Array1_double)
    mults_u, mults_v = array(occt["mults_u"], Array1_int), array(occt["mults_v"], Array1_int)
    args = (knots_u, knots_v, mults_u, mults_v, data["degree_u"], data["degree_v"],
            occt["periodic_u"], occt["periodic_v"])
    if data.get("weights"):
        weights = Array2_double(1, n_u, 1, n_v)
        for i in range(n_u):
            for j in range(n_v):
                weights.SetValue(i + 1, j + 1, data["weights"][i][j])
        return Geom_BSplineSurface(poles, weights, *args)
    return Geom_BSplineSurface(poles, *args)


def first_active(knots, degree, count, t):
    """0-based index of the first pole whose basis function may be non-zero at t: the span
    `a` with knots[a] <= t < knots[a + 1] among p <= a < count (the last span holds its end),
    minus the degree (the same span search as knotshape's and Open CASCADE's
    BSplCLib::LocateParameter on the flat knots)."""
    span = degree
    for a in range(degree, count):
        if knots[a] <= t:
            span = a
    return span - degree


def active_ranges(surface, data, u, v):
    """1-based pole ranges active at (u, v) (module docs)."""
    ranges = []
    for knots, degree, n, periodic, t in (
        (data["knots_u"], data["degree_u"], surface.NbUPoles(), surface.IsUPeriodic(), u),
        (data["knots_v"], data["degree_v"], surface.NbVPoles(), surface.IsVPeriodic(), v),
    ):
        if periodic:
            ranges.append((1, n))
            continue
        count = len(knots) - degree - 1
        first = first_active(knots, degree, count, t)
        ranges.append((first + 1, min(n, first + degree + 1)))
    return ranges


def pick(surface, data, k):
    """The parameter pair, point, normal and target of surface number k (module docs)."""
    u0, u1, v0, v1 = data["bounds"]
    poles = [p for line in data["poles"] for p in line]
    lows = [min(p[c] for p in poles) for c in range(3)]
    highs = [max(p[c] for p in poles) for c in range(3)]
    size = math.dist(lows, highs)
    for attempt in range(10):
        j = k + 1000 * attempt
        a = 0.2 + 0.6 * math.modf(0.5 + j / PHI)[0]
        b = 0.2 + 0.6 * math.modf(0.5 + j / PHI**2)[0]
        u, v = u0 + a * (u1 - u0), v0 + b * (v1 - v0)
        point, su, sv = gp_Pnt(), gp_Vec(), gp_Vec()
        surface.D1(u, v, point, su, sv)
        normal = su.Crossed(sv)
        if su.Magnitude() == 0.0 or sv.Magnitude() == 0.0:
            continue
        if normal.Magnitude() <= 1e-9 * su.Magnitude() * sv.Magnitude():
            continue
        n = normal.Normalized()
        t = su.Normalized()
        s = (point.X(), point.Y(), point.Z())
        target = tuple(s[c] + size * (1e-2 * n.Coord(c + 1) + 5e-3 * t.Coord(c + 1)) for c in range(3))
        return u, v, s, target, size
    return None


def main() -> int:
    root = Path(__file__).resolve().parent.parent
    with gzip.open(root / "tests/data/real_surfaces.json.gz", "rt", encoding="utf-8") as f:
        surfaces = json.load(f)["surfaces"]
    rows = []
    skipped = 0
    for k, data in enumerate(surfaces):
        surface = occt_surface(data)
        picked = pick(surface, data, k)
        if picked is None:
            skipped += 1
            continue
        u, v, s, target, size = picked
        (ui1, ui2), (vi1, vi2) = active_ranges(surface, data, u, v)
        p = gp_Pnt(*target)
        copies = [occt_surface(data) for _ in range(REPEATS)]
        times = []
        indices = None
        error = None
        for copy in copies:
            started = time.perf_counter()
            try:
                indices = copy.MovePoint(u, v, p, ui1, ui2, vi1, vi2)
            except Exception as failure:  # Open CASCADE raised (a Standard_Failure)
                error = f"{type(failure).__name__}: {failure}"
                break
            times.append(time.perf_counter() - started)
        if error is not None:
            rows.append({"id": data["id"], "index": k, "u": u, "v": v, "point": s,
                         "target": target, "size": size, "ranges": [ui1, ui2, vi1, vi2],
                         "error": error})
            continue
        moved = copies[0]
        n_u, n_v = moved.NbUPoles(), moved.NbVPoles()
        poles = [[list(moved.Pole(i + 1, j + 1).Coord()) for j in range(n_v)] for i in range(n_u)]
        reached = moved.Value(u, v)
        rows.append({
            "id": data["id"],
            "index": k,
            "u": u,
            "v": v,
            "point": s,
            "target": target,
            "size": size,
            "ranges": [ui1, ui2, vi1, vi2],
            "moved": list(indices),
            "poles": poles,
            "occt_residual": reached.Distance(p),
            "seconds": statistics.median(times),
        })
    out = {"surfaces": rows, "skipped": skipped}
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        json.dump(out, f)
    print(f"Open CASCADE MovePoint: {len(rows)} surfaces, {skipped} without a defined normal "
          f"at ten tried pairs", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
