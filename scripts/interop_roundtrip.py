"""Round trips of B-spline curves through real readers and writers (run by
scripts/interop-roundtrip, which installs Open CASCADE (cadquery-ocp-novtk) and ezdxf and
starts the service; usage: interop_roundtrip.py BASE_URL DATA_DIR).

1. Curves we export (POST /v1/curves/export), read back by Open CASCADE's STEPControl_Reader
   and by ezdxf, compared with our evaluation (POST /v1/curves/evaluate); the DXF also through
   ezdxf's construction_tool(), which rounds the knots to the file's knot tolerance (group 42):
   the knots must come through as written.
2. Files Open CASCADE (STEPControl_Writer) and ezdxf write, imported by us
   (POST /v1/curves/import), compared with their evaluation.
3. The real STEP files of DATA_DIR, imported by us and read by Open CASCADE, entity by entity.
4. Surfaces: random B-spline and NURBS surfaces (degrees 1-5 each way, a periodic direction
   too) we export as STEP, transferred by Open CASCADE's STEPControl_Reader to faces (one per
   surface) and each entity's surface compared with ours (POST /v1/surfaces/evaluate on an
   11 x 11 grid of the domain) and number for number; the 32 B-spline surfaces of the real
   STEP files imported by us and compared likewise with Open CASCADE's reading.

Every comparison evaluates both curves at 101 parameters across the domain; differences are
relative to the curve's size (largest control-point coordinate). Exits 1 when one exceeds
TOLERANCE.
"""

import json
import math
import random
import sys
import tempfile
import urllib.error
import urllib.request

import ezdxf
from ezdxf.math import BSpline, closed_uniform_bspline
from ezdxf.math.bspline import round_knots
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.BRep import BRep_Builder
from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int
from OCP.Geom import Geom_BSplineCurve
from OCP.gp import gp_Pnt
from OCP.StepGeom import StepGeom_BSplineCurve, StepGeom_BSplineSurface
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.StepToGeom import StepToGeom
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound

# Evaluation differences of twice the same data, relative to the curve's size: both sides
# round, most at high degrees and short spans.
TOLERANCE = 1e-11
SAMPLES = 101
BASE = sys.argv[1]
DATA = sys.argv[2]
rng = random.Random(21)
failures = []


def post(path, body):
    request = urllib.request.Request(
        BASE + path, data=json.dumps(body).encode(), headers={"content-type": "application/json"}
    )
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            return answer.read().decode(), answer.headers.get("content-type")
    except urllib.error.HTTPError as error:
        raise SystemExit(f"{path} answered {error.code}: {error.read().decode()[:2000]}")


def evaluate(curve, parameters):
    curve = {key: value for key, value in curve.items() if key != "source"}
    text, _ = post("/v1/curves/evaluate", {"curve": curve, "parameters": parameters})
    points = json.loads(text)["points"]
    return [p + [0.0] * (3 - len(p)) for p in points]


def size(points):
    return max(1.0, max(abs(c) for p in points for c in p))


def difference(ours, theirs, scale):
    return max(math.dist(a, b) for a, b in zip(ours, theirs)) / scale


def report(name, differences, things="curves"):
    worst = max(differences) if differences else 0.0
    status = "ok" if worst <= TOLERANCE else "FAILED"
    thing = things[:-1]
    print(f"{name}: {len(differences)} {things}, max difference {worst:.2e} of the {thing} size ({status})")
    if worst > TOLERANCE or not differences:
        failures.append(name)


def domain_parameters(lo, hi):
    return [lo + (hi - lo) * k / (SAMPLES - 1) for k in range(SAMPLES - 1)] + [hi]


def random_curve(degree, dim, rational, form):
    """A curve object of ours: form is 'full', 'multiplicities' or 'periodic'."""
    spans = rng.randint(1, 6)
    values = sorted(rng.uniform(-2, 5) for _ in range(spans + 1))
    if form == "periodic":
        seam = rng.randint(1, degree)
        mults = [seam] + [rng.randint(1, degree) for _ in range(spans - 1)] + [seam]
        count = sum(mults) - mults[-1]
        if count < max(degree, 2):
            mults[0] = mults[-1] = degree
            mults[1:-1] = [degree] * (spans - 1)
            count = sum(mults) - mults[-1]
            if count < max(degree, 2):
                return random_curve(degree, dim, rational, "multiplicities")
    else:
        mults = [degree + 1] + [rng.randint(1, degree) for _ in range(spans - 1)] + [degree + 1]
        count = sum(mults) - degree - 1
    curve = {
        "degree": degree,
        "control_points": [[rng.uniform(-10, 10) for _ in range(dim)] for _ in range(count)],
    }
    if form == "full":
        curve["knots"] = [u for u, m in zip(values, mults) for _ in range(m)]
    else:
        curve["knots"], curve["multiplicities"] = values, mults
    if form == "periodic":
        curve["periodic"] = True
    if rational:
        curve["weights"] = [rng.uniform(0.2, 4) for _ in range(count)]
    return curve


def domain(curve):
    if curve.get("periodic"):
        return curve["knots"][0], curve["knots"][-1]
    full = curve["knots"]
    if "multiplicities" in curve:
        full = [u for u, m in zip(curve["knots"], curve["multiplicities"]) for _ in range(m)]
    p, n = curve["degree"], len(curve["control_points"])
    return full[p], full[n]


def occt_points(curve, parameters):
    points = []
    for t in parameters:
        p = curve.Value(t)
        points.append([p.X(), p.Y(), p.Z() if hasattr(p, "Z") else 0.0])
    return points


def edges_of(path):
    reader = STEPControl_Reader()
    assert reader.ReadFile(path) == reader.ReadFile(path)
    reader.TransferRoots()
    explorer = TopExp_Explorer(reader.OneShape(), TopAbs_EDGE)
    curves = []
    while explorer.More():
        edge = TopoDS.Edge(explorer.Current())
        curves.append(BRep_Tool.Curve_s(edge, 0.0, 0.0))
        explorer.Next()
    return curves


def our_curves():
    curves = []
    for degree in range(1, 8):
        for dim in (2, 3):
            for rational in (False, True):
                for form in ("full", "multiplicities", "periodic"):
                    curves.append(random_curve(degree, dim, rational, form))
    return curves


def export_to_open_cascade(curves):
    text, content_type = post("/v1/curves/export", {"format": "step", "curves": curves})
    assert content_type.startswith("model/step"), content_type
    with tempfile.NamedTemporaryFile("w", suffix=".step", delete=False) as file:
        file.write(text)
    theirs = edges_of(file.name)
    assert len(theirs) == len(curves), (len(theirs), len(curves))
    differences = []
    for curve, occt in zip(curves, theirs):
        lo, hi = domain(curve)
        assert abs(occt.FirstParameter() - lo) <= 1e-15 * max(1, abs(lo)), (occt.FirstParameter(), lo)
        parameters = domain_parameters(lo, hi)
        differences.append(
            difference(evaluate(curve, parameters), occt_points(occt, parameters), size(curve["control_points"]))
        )
    report("STEP export read by Open CASCADE (STEPControl_Reader)", differences)
    # The numbers in the file are the doubles sent (periodic curves are written clamped).
    sent = [c for c in curves if not c.get("periodic")]
    entities = [e for (c, e), curve in zip(step_entity_curves(file.name), curves) if not curve.get("periodic")]
    same = sum(
        1
        for curve, entity in zip(sent, entities)
        if [p + [0.0] * (3 - len(p)) for p in curve["control_points"]]
        == [list(entity.ControlPointsListValue(i).Coordinates()) for i in range(1, entity.NbControlPointsList() + 1)]
        and curve.get("weights") == ([entity.WeightsDataValue(i) for i in range(1, entity.NbWeightsData() + 1)] if hasattr(entity, "NbWeightsData") else None)
    )
    print(f"  control points and weights as Open CASCADE parsed them: {same} of {len(sent)} non-periodic curves bit for bit")
    if same != len(sent):
        failures.append("STEP export numbers")


def de_boor(degree, knots, points, weights, t):
    """The curve point at t by de Boor's algorithm on homogeneous points (written here from
    The NURBS Book, A2.1 and A4.1; independent of the service)."""
    n = len(points) - 1
    if t >= knots[n + 1]:
        span = max(k for k in range(degree, n + 1) if knots[k] < knots[k + 1])
    else:
        span = max(k for k in range(degree, n + 1) if knots[k] <= t)
    d = []
    for j in range(degree + 1):
        w = weights[span - degree + j] if weights else 1.0
        x = points[span - degree + j]
        d.append([w * x[0], w * x[1], w * x[2], w])
    for r in range(1, degree + 1):
        for j in range(degree, r - 1, -1):
            lo, hi = knots[j + span - degree], knots[j + 1 + span - r]
            alpha = (t - lo) / (hi - lo)
            d[j] = [(1 - alpha) * a + alpha * b for a, b in zip(d[j - 1], d[j])]
    return [c / d[degree][3] for c in d[degree][:3]]


def ezdxf_points(spline, parameters):
    """The points of a spline as ezdxf read it (its control points, knots and weights),
    evaluated by de_boor."""
    points = [list(p) for p in spline.control_points]
    weights = list(spline.weights) if len(spline.weights) else None
    knots = list(spline.knots)
    return [de_boor(spline.dxf.degree, knots, points, weights, t) for t in parameters]


def ezdxf_own_points(spline, parameters):
    """The points by ezdxf's own evaluation, which maps a knot vector onto [0, 1] (None where
    it fails)."""
    bspline = BSpline(
        spline.control_points, order=spline.dxf.degree + 1, knots=spline.knots,
        weights=spline.weights if len(spline.weights) else None,
    )
    first, last = spline.knots[0], spline.knots[-1]
    try:
        return [list(bspline.point((t - first) / (last - first))) for t in parameters]
    except ZeroDivisionError:
        return None


def construction_tool_points(spline, parameters):
    """The points by ezdxf's construction tool (Spline.construction_tool(): the knots rounded to
    the decimals of the knot tolerance, group 42), which maps a knot vector that does not start
    at 0 onto [0, 1] (None where it fails)."""
    tool = spline.construction_tool()
    knots = round_knots(list(spline.knots), spline.dxf.knot_tolerance)
    first, last = knots[0], knots[-1]
    scale = 1.0 if first == 0.0 else last - first
    try:
        return [list(tool.point((t - first) / scale)) for t in parameters]
    except ZeroDivisionError:
        return None


def export_to_ezdxf(curves):
    text, content_type = post("/v1/curves/export", {"format": "dxf", "curves": curves})
    assert content_type.startswith("image/vnd.dxf"), content_type
    with tempfile.NamedTemporaryFile("w", suffix=".dxf", delete=False) as file:
        file.write(text)
    document = ezdxf.readfile(file.name)
    auditor = document.audit()
    assert not auditor.has_errors, auditor.errors
    splines = document.modelspace().query("SPLINE")
    assert len(splines) == len(curves)
    differences, own, failed, tool, kept, tolerances = [], [], 0, [], 0, []
    for curve, spline in zip(curves, splines):
        lo, hi = domain(curve)
        parameters = domain_parameters(lo, hi)
        ours, scale = evaluate(curve, parameters), size(curve["control_points"])
        differences.append(difference(ours, ezdxf_points(spline, parameters), scale))
        theirs = ezdxf_own_points(spline, parameters)
        if theirs is None:
            failed += 1
        else:
            own.append(difference(ours, theirs, scale))
        tolerances.append(spline.dxf.knot_tolerance)
        kept += round_knots(list(spline.knots), spline.dxf.knot_tolerance) == list(spline.knots)
        through_tool = construction_tool_points(spline, parameters)
        # A curve the construction tool cannot evaluate counts as infinitely far.
        tool.append(math.inf if through_tool is None else difference(ours, through_tool, scale))
    report("DXF export read by ezdxf (its data by de Boor)", differences)
    print(f"  (ezdxf's own evaluation: {len(own)} curves, max {max(own):.2e}; it failed on {failed})")
    report("DXF export through ezdxf's construction_tool() (knots rounded to group 42)", tool)
    finite = [d for d in tool if d != math.inf]
    print(f"  knot vectors kept as written: {kept} of {len(splines)} (knot tolerances "
          f"{min(tolerances):.0e} to {max(tolerances):.0e}); evaluated {len(finite)} curves, "
          f"max {max(finite, default=0.0):.2e}, failed on {len(tool) - len(finite)}")
    if kept != len(splines):
        failures.append("DXF knots rounded by their knot tolerance")


def occt_curve(curve):
    """A Geom_BSplineCurve of a curve object of ours (full knots become distinct + mults)."""
    knots, mults = curve["knots"], curve.get("multiplicities")
    if mults is None:
        distinct, mults = [], []
        for u in knots:
            if distinct and distinct[-1] == u:
                mults[-1] += 1
            else:
                distinct.append(u)
                mults.append(1)
        knots = distinct
    poles = Array1_gp_Pnt(1, len(curve["control_points"]))
    for i, p in enumerate(curve["control_points"]):
        poles.SetValue(i + 1, gp_Pnt(*(p + [0.0] * (3 - len(p)))))
    k = Array1_double(1, len(knots))
    for i, u in enumerate(knots):
        k.SetValue(i + 1, u)
    m = Array1_int(1, len(mults))
    for i, v in enumerate(mults):
        m.SetValue(i + 1, v)
    periodic = bool(curve.get("periodic"))
    if "weights" in curve:
        w = Array1_double(1, len(curve["weights"]))
        for i, v in enumerate(curve["weights"]):
            w.SetValue(i + 1, v)
        return Geom_BSplineCurve(poles, w, k, m, curve["degree"], periodic)
    return Geom_BSplineCurve(poles, k, m, curve["degree"], periodic)


def open_cascade_to_import(curves):
    # Open CASCADE refuses interior multiplicity degree + 1; our generator never makes one.
    built = [occt_curve(curve) for curve in curves]
    builder, compound = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(compound)
    for curve in built:
        builder.Add(compound, BRepBuilderAPI_MakeEdge(curve).Edge())
    writer = STEPControl_Writer()
    writer.Transfer(compound, STEPControl_AsIs)
    path = tempfile.mktemp(suffix=".step")
    writer.Write(path)
    text = open(path).read()
    answer = json.loads(post("/v1/curves/import", {"format": "step", "data": text})[0])
    ours = answer["curves"]
    assert len(ours) == len(curves), (len(ours), len(curves))
    # Open CASCADE's reading of its own file (it writes numbers with fewer digits than a
    # double has, so the file's curves differ from `built` by its rounding).
    read_back = step_entity_curves(path)
    differences, to_original, data = [], [], []
    for curve, original, (occt, entity) in zip(ours, built, read_back):
        data.append(data_difference(curve, entity))
        lo, hi = occt.FirstParameter(), occt.LastParameter()
        parameters = domain_parameters(lo, hi)
        mine = evaluate(curve, parameters)
        scale = size(curve["control_points"])
        differences.append(difference(mine, occt_points(occt, parameters), scale))
        to_original.append(difference(mine, occt_points(original, parameters), scale))
    report("STEP written by Open CASCADE (STEPControl_Writer), imported", differences)
    exact(data, "  its control points, weights, knots and multiplicities against Open CASCADE's reading")
    print(f"  (the same against the curves before Open CASCADE wrote them: max {max(to_original):.2e}, its rounding)")


def data_difference(ours, entity):
    """The number of values of our imported curve (distinct knots with multiplicities) that
    differ from Open CASCADE's reading of its STEP entity (its parser's numbers)."""
    count = entity.NbControlPointsList()
    poles = []
    for i in range(1, count + 1):
        # Open CASCADE gives a 2D point 3 coordinates, the last 0.
        coordinates = list(entity.ControlPointsListValue(i).Coordinates())
        dimension = len(ours["control_points"][0])
        if dimension == 2 and len(coordinates) == 3 and coordinates[2] == 0.0:
            coordinates = coordinates[:2]
        poles.append(coordinates)
    weights = None
    if hasattr(entity, "NbWeightsData"):
        weights = [entity.WeightsDataValue(i) for i in range(1, entity.NbWeightsData() + 1)]
    knots = [entity.KnotsValue(i) for i in range(1, entity.NbKnots() + 1)]
    mults = [entity.KnotMultiplicitiesValue(i) for i in range(1, entity.NbKnotMultiplicities() + 1)]
    mismatches = int(ours["degree"] != entity.Degree())
    mismatches += sum(a != b for a, b in zip(ours["control_points"], poles)) + abs(len(poles) - len(ours["control_points"]))
    mismatches += int(ours.get("weights") != weights)
    mismatches += int(ours["knots"] != knots) + int(ours["multiplicities"] != mults)
    return mismatches


def exact(mismatches, name):
    bad = sum(1 for m in mismatches if m)
    print(f"{name}: {len(mismatches) - bad} of {len(mismatches)} identical")
    if bad:
        failures.append(name.strip())


def step_entity_curves(path):
    """Open CASCADE's curve and entity of every B-spline curve entity of a STEP file, in file
    order."""
    reader = STEPControl_Reader()
    reader.ReadFile(path)
    model = reader.StepModel()
    curves = []
    for index in range(1, model.NbEntities() + 1):
        entity = model.Value(index)
        if isinstance(entity, StepGeom_BSplineCurve):
            curve = StepToGeom.MakeBSplineCurve_s(entity) or StepToGeom.MakeBSplineCurve2d_s(entity)
            curves.append((curve, entity))
    return curves


def ezdxf_to_import():
    document = ezdxf.new("R2000")
    space = document.modelspace()
    written = []
    for degree in range(1, 7):
        for rational in (False, True):
            count = degree + 1 + rng.randint(0, 5)
            points = [(rng.uniform(-9, 9), rng.uniform(-9, 9), rng.uniform(-9, 9) * (degree % 2)) for _ in range(count)]
            if rational:
                weights = [rng.uniform(0.2, 4) for _ in range(count)]
                spline = space.add_rational_spline(points, weights, degree=degree)
            else:
                spline = space.add_open_spline(points, degree=degree)
            written.append(spline)
    # A closed (periodic) spline as ezdxf makes one: unclamped uniform knots, repeated points.
    closed = space.add_spline()
    closed.apply_construction_tool(closed_uniform_bspline([(0, 0, 0), (4, 1, 0), (5, 5, 1), (1, 4, 0)], order=4))
    closed.closed = True
    written.append(closed)
    space.add_spline(fit_points=[(0, 0), (1, 1), (2, 0)])
    space.add_line((0, 0), (1, 1))
    path = tempfile.mktemp(suffix=".dxf")
    document.saveas(path)
    answer = json.loads(post("/v1/curves/import", {"format": "dxf", "data": open(path).read()})[0])
    assert answer["skipped"] == 2, answer["skipped"]
    reread = ezdxf.readfile(path).modelspace().query("SPLINE")
    reread = [s for s in reread if len(s.control_points)]
    assert len(answer["curves"]) == len(written) == len(reread)
    differences = []
    for ours, spline in zip(answer["curves"], reread):
        assert ours["source"] == spline.dxf.handle
        lo, hi = domain(ours)
        parameters = domain_parameters(lo, hi)
        differences.append(
            difference(evaluate(ours, parameters), ezdxf_points(spline, parameters), size(ours["control_points"]))
        )
    report("DXF written by ezdxf, imported", differences)


def real_step_files():
    differences, data = [], []
    for name in ("splinecage.stp", "screw.step"):
        path = f"{DATA}/{name}"
        answer = json.loads(post("/v1/curves/import", {"format": "step", "data": open(path).read()})[0])
        theirs = step_entity_curves(path)
        assert len(answer["curves"]) == len(theirs), (name, len(answer["curves"]), len(theirs))
        for ours, (occt, entity) in zip(answer["curves"], theirs):
            data.append(data_difference(ours, entity))
            lo, hi = occt.FirstParameter(), occt.LastParameter()
            parameters = domain_parameters(lo, hi)
            theirs_points = occt_points(occt, parameters)
            differences.append(difference(evaluate(ours, parameters), theirs_points, size(ours["control_points"])))
    report("real STEP files imported, against Open CASCADE's reading", differences)
    exact(data, "  their control points, weights, knots and multiplicities")


def evaluate_surface(surface, parameters):
    surface = {key: value for key, value in surface.items() if key != "source"}
    text, _ = post("/v1/surfaces/evaluate", {"surface": surface, "parameters": parameters})
    return json.loads(text)["points"]


def random_surface(degree_u, degree_v, rational, periodic_u):
    def direction(degree, periodic):
        if periodic:
            count = degree + 2 + rng.randint(0, 3)
            knots = sorted(rng.uniform(0, 1) for _ in range(count - 1))
            return count, {"knots": [0.0] + knots + [1.5], "multiplicities": [1] * (count + 1)}, count
        count = degree + 1 + rng.randint(0, 4)
        inner = sorted(rng.uniform(0, 2) for _ in range(count - degree - 1))
        return count, {"knots": [0.0] * (degree + 1) + inner + [2.0] * (degree + 1)}, count

    n_u, form_u, rows = direction(degree_u, periodic_u)
    n_v, form_v, columns = direction(degree_v, False)
    surface = {
        "degree_u": degree_u,
        "degree_v": degree_v,
        "control_points": [[[rng.uniform(-9, 9) for _ in range(3)] for _ in range(columns)] for _ in range(rows)],
        "knots_u": form_u["knots"],
        "knots_v": form_v["knots"],
    }
    if periodic_u:
        surface["multiplicities_u"] = form_u["multiplicities"]
        surface["periodic_u"] = True
    if rational:
        surface["weights"] = [[rng.uniform(0.3, 3) for _ in range(columns)] for _ in range(rows)]
    return surface


def surface_domain(surface):
    def one(knots, multiplicities, degree, periodic):
        if multiplicities is not None:
            return knots[0], knots[-1]
        return knots[degree], knots[-degree - 1]

    return (
        one(surface["knots_u"], surface.get("multiplicities_u"), surface["degree_u"], surface.get("periodic_u")),
        one(surface["knots_v"], surface.get("multiplicities_v"), surface["degree_v"], surface.get("periodic_v")),
    )


def grid(domain):
    (u0, u1), (v0, v1) = domain
    return [[u0 + (u1 - u0) * i / 10, v0 + (v1 - v0) * j / 10] for i in range(11) for j in range(11)]


def step_entity_surfaces(path):
    """Open CASCADE's surface and entity of every B-spline surface entity of a STEP file, in
    file order."""
    reader = STEPControl_Reader()
    reader.ReadFile(path)
    model = reader.StepModel()
    surfaces = []
    for index in range(1, model.NbEntities() + 1):
        entity = model.Value(index)
        if isinstance(entity, StepGeom_BSplineSurface):
            surfaces.append((StepToGeom.MakeBSplineSurface_s(entity), entity))
    return surfaces


def surface_difference(ours, occt):
    parameters = grid(surface_domain(ours))
    points = evaluate_surface(ours, parameters)
    theirs = [list(occt.Value(u, v).Coord()) for u, v in parameters]
    scale = max(1.0, max(abs(c) for row in ours["control_points"] for p in row for c in p))
    return difference(points, theirs, scale)


def surfaces_round_trip():
    sent = []
    for degree_u in range(1, 6):
        for degree_v in (1, 2, 3, 5):
            for rational in (False, True):
                sent.append(random_surface(degree_u, degree_v, rational, False))
    sent += [random_surface(3, 2, rational, True) for rational in (False, True)]
    text, content_type = post("/v1/curves/export", {"format": "step", "surfaces": sent})
    assert content_type.startswith("model/step"), content_type
    path = tempfile.mktemp(suffix=".step")
    with open(path, "w") as file:
        file.write(text)
    reader = STEPControl_Reader()
    reader.ReadFile(path)
    reader.TransferRoots()
    faces = 0
    explorer = TopExp_Explorer(reader.OneShape(), TopAbs_FACE)
    while explorer.More():
        faces += 1
        explorer.Next()
    print(f"surfaces exported as STEP: Open CASCADE's STEPControl_Reader transfers {faces} faces of {len(sent)} surfaces")
    if faces != len(sent):
        failures.append("STEP surface export transfer")
    theirs = step_entity_surfaces(path)
    assert len(theirs) == len(sent), (len(theirs), len(sent))
    differences, same = [], 0
    for surface, (occt, entity) in zip(sent, theirs):
        # Open CASCADE's surface over its own domain: ours clamped over the period when periodic.
        (u0, u1, v0, v1) = occt.Bounds()
        assert abs(u0 - surface_domain(surface)[0][0]) <= 1e-15 and abs(v1 - surface_domain(surface)[1][1]) <= 1e-15
        differences.append(surface_difference(surface, occt))
        if not surface.get("periodic_u"):
            poles = [
                [list(entity.ControlPointsListValue(i, j).Coordinates()) for j in range(1, entity.NbControlPointsListJ() + 1)]
                for i in range(1, entity.NbControlPointsListI() + 1)
            ]
            weights = (
                [[entity.WeightsDataValue(i, j) for j in range(1, entity.NbWeightsDataJ() + 1)] for i in range(1, entity.NbWeightsDataI() + 1)]
                if hasattr(entity, "NbWeightsDataI")
                else None
            )
            same += int(poles == surface["control_points"] and weights == surface.get("weights"))
    report("STEP surfaces exported, read by Open CASCADE", differences, "surfaces")
    plain = sum(1 for s in sent if not s.get("periodic_u"))
    print(f"  control points and weights as Open CASCADE parsed them: {same} of {plain} non-periodic surfaces bit for bit")
    if same != plain:
        failures.append("STEP surface export numbers")


def real_step_surfaces():
    differences, data = [], []
    for name in ("splinecage.stp", "as1-oc-214.stp"):
        path = f"{DATA}/{name}"
        answer = json.loads(post("/v1/curves/import", {"format": "step", "data": open(path).read()})[0])
        theirs = step_entity_surfaces(path)
        assert len(answer["surfaces"]) == len(theirs), (name, len(answer["surfaces"]), len(theirs))
        for ours, (occt, entity) in zip(answer["surfaces"], theirs):
            differences.append(surface_difference(ours, occt))
            poles = [
                [list(entity.ControlPointsListValue(i, j).Coordinates()) for j in range(1, entity.NbControlPointsListJ() + 1)]
                for i in range(1, entity.NbControlPointsListI() + 1)
            ]
            data.append(int(poles != ours["control_points"]))
    report("real STEP surfaces imported, against Open CASCADE's reading", differences, "surfaces")
    exact(data, "  their control points")


def main():
    curves = our_curves()
    export_to_open_cascade(curves)
    export_to_ezdxf(curves)
    # Open CASCADE takes every form, periodic ones as periodic curves.
    open_cascade_to_import(curves)
    ezdxf_to_import()
    real_step_files()
    surfaces_round_trip()
    real_step_surfaces()
    if failures:
        print("interop round trips FAILED: " + "; ".join(failures))
        sys.exit(1)
    print("interop round trips: all passed")


main()
