#!/usr/bin/env python3
"""Open CASCADE's side of benches/occt_surface_closest.sh: GeomAPI_ProjectPointOnSurf on every
real surface (tests/data/real_surfaces.json.gz, rebuilt from its `occt` form) for the queries
that benches/surface_closest.rs answered, timed per query (Init once per surface, then Perform
per point), and the distances compared with knotshape's.

A query counts as knotshape worse when its distance exceeds Open CASCADE's by more than the
tolerance `1e-12 (size + d) + 8 eps magnitude` (size: the diagonal of the poles' bounding box,
magnitude: their largest coordinate), Open CASCADE worse the other way round; a projection
that finds no point (NbPoints() == 0) is a failure of Open CASCADE.

Usage: occt_surface_closest.py KNOTSHAPE_JSON
"""

import gzip
import json
import math
import sys
import time
from pathlib import Path

from OCP.Geom import Geom_BSplineSurface
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.collections import Array1_double, Array1_int, Array2_double, Array2_gp_Pnt
from OCP.gp import gp_Pnt

EPS = 2.0 ** -52


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


def main() -> int:
    root = Path(__file__).resolve().parent.parent
    with gzip.open(root / "tests/data/real_surfaces.json.gz", "rt", encoding="utf-8") as f:
        corpus = {s["id"]: s for s in json.load(f)["surfaces"]}
    with open(sys.argv[1], encoding="utf-8") as f:
        ours = json.load(f)["surfaces"]
    queries = worse = better = failures = 0
    ours_seconds = occt_seconds = occt_setup = 0.0
    worst_gap = worst_gain = 0.0
    examples = []
    for row in ours:
        data = corpus[row["id"]]
        surface = occt_surface(data)
        u0, u1, v0, v1 = data["bounds"]
        poles = [p for line in data["poles"] for p in line]
        lows = [min(p[c] for p in poles) for c in range(3)]
        highs = [max(p[c] for p in poles) for c in range(3)]
        size = math.dist(lows, highs)
        magnitude = max(abs(x) for p in poles for x in p)
        started = time.perf_counter()
        projection = GeomAPI_ProjectPointOnSurf()
        projection.Init(surface, u0, u1, v0, v1)
        occt_setup += time.perf_counter() - started
        points = [gp_Pnt(*q) for q in row["queries"]]
        found = []
        started = time.perf_counter()
        for point in points:
            projection.Perform(point)
            if projection.NbPoints() > 0:
                found.append(projection.LowerDistance())
            else:
                found.append(None)
        occt_seconds += time.perf_counter() - started
        ours_seconds += row["seconds"]
        for q, answer, theirs in zip(row["queries"], row["answers"], found):
            queries += 1
            mine = answer[2]
            if theirs is None:
                failures += 1
                continue
            tolerance = 1e-12 * (size + min(mine, theirs)) + 8 * EPS * magnitude
            if mine > theirs + tolerance:
                worse += 1
                worst_gap = max(worst_gap, (mine - theirs) / (size + theirs))
                if len(examples) < 5:
                    examples.append((row["id"], q, mine, theirs))
            elif theirs > mine + tolerance:
                better += 1
                worst_gain = max(worst_gain, (theirs - mine) / (size + mine))
    print(f"surfaces {len(ours)}, queries {queries}")
    print(f"knotshape: {ours_seconds / queries * 1e6:.2f} µs per query")
    print(f"Open CASCADE GeomAPI_ProjectPointOnSurf: {occt_seconds / queries * 1e6:.2f} µs per query "
          f"(Init {occt_setup / len(ours) * 1e6:.1f} µs per surface, not counted)")
    print(f"ratio: knotshape {occt_seconds / ours_seconds:.1f}x faster per query")
    print(f"knotshape nearer than Open CASCADE (beyond the tolerance): {better} queries, "
          f"by up to {worst_gain:.2e} of size + distance")
    print(f"knotshape farther than Open CASCADE (beyond the tolerance): {worse} queries"
          + (f", by up to {worst_gap:.2e}: {examples}" if worse else ""))
    print(f"Open CASCADE found no point: {failures} queries")
    return 0


if __name__ == "__main__":
    sys.exit(main())
