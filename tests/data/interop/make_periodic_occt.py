"""Writes periodic_occt.json: random periodic B-spline curves built with Open CASCADE
(OCP, `pip install cadquery-ocp-novtk`; Geom_BSplineCurve with Periodic = True) and Open
CASCADE's own points and first derivatives at parameters inside and outside the period.
Run: python tests/data/interop/make_periodic_occt.py (deterministic: seeded)."""
import json
import random
import sys

from OCP.Geom import Geom_BSplineCurve
from OCP.gp import gp_Pnt, gp_Vec
from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int


def build(degree, poles, weights, knots, mults):
    array = Array1_gp_Pnt(1, len(poles))
    for i, p in enumerate(poles):
        array.SetValue(i + 1, gp_Pnt(*p))
    k = Array1_double(1, len(knots))
    for i, u in enumerate(knots):
        k.SetValue(i + 1, u)
    m = Array1_int(1, len(mults))
    for i, v in enumerate(mults):
        m.SetValue(i + 1, v)
    if weights is None:
        return Geom_BSplineCurve(array, k, m, degree, True)
    w = Array1_double(1, len(weights))
    for i, v in enumerate(weights):
        w.SetValue(i + 1, v)
    return Geom_BSplineCurve(array, w, k, m, degree, True)


def main():
    rng = random.Random(20)
    cases = []
    case = -1
    while len(cases) < 40:
        case += 1
        degree = rng.randint(1, 7)
        spans = rng.randint(1, 6)
        knots = sorted(rng.uniform(-3, 5) for _ in range(spans + 1))
        seam = rng.randint(1, degree)
        inner = [rng.randint(1, degree) for _ in range(spans - 1)]
        mults = [seam] + inner + [seam]
        count = sum(mults) - mults[-1]
        if count < max(degree, 2):
            continue
        dim = 2 if case % 3 == 0 else 3
        poles = [[rng.uniform(-10, 10) for _ in range(dim)] for _ in range(count)]
        weights = [rng.uniform(0.3, 3) for _ in range(count)] if case % 2 else None
        curve = build(degree, [p + [0.0] * (3 - dim) for p in poles], weights, knots, mults)
        assert curve.IsPeriodic()
        lo, hi = knots[0], knots[-1]
        period = hi - lo
        parameters = [lo, hi] + knots[1:-1] + [rng.uniform(lo, hi) for _ in range(12)]
        parameters += [lo + period * 0.3 + 2 * period, lo - period * 0.6, hi + 1e-9, lo - 1e-9]
        points, derivatives = [], []
        for u in parameters:
            p, v = gp_Pnt(), gp_Vec()
            curve.D1(u, p, v)
            points.append([p.X(), p.Y(), p.Z()][:dim])
            derivatives.append([v.X(), v.Y(), v.Z()][:dim])
        entry = {"degree": degree, "control_points": poles, "knots": knots,
                 "multiplicities": mults, "periodic": True}
        if weights is not None:
            entry["weights"] = weights
        cases.append({"curve": entry, "parameters": parameters, "points": points,
                      "first_derivatives": derivatives})
    json.dump({"about": __doc__.strip(), "cases": cases}, sys.stdout, indent=1)


main()
