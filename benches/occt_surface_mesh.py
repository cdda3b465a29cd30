#!/usr/bin/env python3
"""Open CASCADE's side of benches/occt_surface_mesh.sh: BRepMesh_IncrementalMesh on a face over
the whole domain of every real surface (tests/data/real_surfaces.json.gz, rebuilt from its
`occt` form as benches/occt_surface_closest.py does), at linear deflections that are fractions
of the surface's size, with Open CASCADE's default angular deflection (0.5 rad) and with a
loose one (1.5 rad, so that the linear deflection alone drives the mesh). Writes every mesh
(the nodes' (u, v) and points, the triangles) as JSON for benches/surface_mesh.rs, which
measures its deviation from the surface and meshes the same surface with knotshape to the
same deviation.

Usage: occt_surface_mesh.py OUT_JSON FRACTION [FRACTION ...]
"""

import gzip
import json
import math
import sys
import time
from pathlib import Path

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.TopLoc import TopLoc_Location

sys.path.insert(0, str(Path(__file__).resolve().parent))
from occt_surface_closest import occt_surface  # noqa: E402

ANGLES = [0.5, 1.5]


def mesh(data, deflection, angle):
    """Open CASCADE's mesh of the surface's face over its whole domain, or None."""
    surface = occt_surface(data)
    u0, u1, v0, v1 = data["bounds"]
    maker = BRepBuilderAPI_MakeFace(surface, u0, u1, v0, v1, 1e-7)
    if not maker.IsDone():
        return None
    face = maker.Face()
    started = time.perf_counter()
    BRepMesh_IncrementalMesh(face, deflection, False, angle, False)
    seconds = time.perf_counter() - started
    triangulation = BRep_Tool.Triangulation_s(face, TopLoc_Location())
    if triangulation is None or not triangulation.HasUVNodes():
        return None
    uv, points, triangles = [], [], []
    for k in range(1, triangulation.NbNodes() + 1):
        p = triangulation.UVNode(k)
        uv.append([p.X(), p.Y()])
        q = triangulation.Node(k)
        points.append([q.X(), q.Y(), q.Z()])
    for k in range(1, triangulation.NbTriangles() + 1):
        a, b, c = triangulation.Triangle(k).Get()
        triangles.append([a - 1, b - 1, c - 1])
    return {"uv": uv, "points": points, "triangles": triangles, "seconds": seconds}


def main() -> int:
    out = sys.argv[1]
    fractions = [float(f) for f in sys.argv[2:]] or [1e-2, 1e-3]
    root = Path(__file__).resolve().parent.parent
    with gzip.open(root / "tests/data/real_surfaces.json.gz", "rt", encoding="utf-8") as f:
        corpus = json.load(f)["surfaces"]
    rows, failures = [], 0
    for data in corpus:
        poles = [p for line in data["poles"] for p in line]
        lows = [min(p[c] for p in poles) for c in range(3)]
        highs = [max(p[c] for p in poles) for c in range(3)]
        size = math.dist(lows, highs)
        meshes = []
        for fraction in fractions:
            for angle in ANGLES:
                found = mesh(data, fraction * size, angle)
                if found is None:
                    failures += 1
                    continue
                found.update({"fraction": fraction, "angle": angle})
                meshes.append(found)
        rows.append({"id": data["id"], "meshes": meshes})
    with open(out, "w", encoding="utf-8") as f:
        json.dump({"fractions": fractions, "angles": ANGLES, "surfaces": rows}, f)
    print(f"Open CASCADE meshed {len(rows)} surfaces ({failures} meshes failed) -> {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
