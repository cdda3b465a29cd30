// What the 3D view draws of one object: a surface shaded from the service's certified mesh
// with its iso-lines at the knots, a space curve as the service's certified polyline, each
// with its control net on demand; the picked point, the drag target, and the translucent
// regions a drag reaches. Positions are stored relative to the object's `origin` (its box's
// centre) so that 32-bit floats keep them precise far from the origin.

import * as THREE from "../../vendor/three/three.module.js";
import { curveEvaluator, distinctInDomain, surfaceEvaluator } from "./nurbs.js";

export const COLOURS = {
  surface: 0x8fb3d9,
  surfaceIdle: 0xc9ccd3,
  curve: 0x0b5394,
  curveIdle: 0x8a8f99,
  iso: 0x33475e,
  net: 0xb35806,
  pick: 0xd7191c,
  target: 0x1a9641,
  knotRegion: 0x0072b2,
  weightRegion: 0x7b3294,
};

/** Every material the view draws with, one constructor each: the objects below and the
 * warm-up group (warmUpGroup) are made from these, so the warm-up draws with what the
 * objects will. */
const MATERIALS = {
  surface: (colour) =>
    new THREE.MeshLambertMaterial({ color: colour, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }),
  iso: () => new THREE.LineBasicMaterial({ color: COLOURS.iso, transparent: true, opacity: 0.55 }),
  line: (colour, opacity = 1) => new THREE.LineBasicMaterial({ color: colour, transparent: opacity < 1, opacity }),
  poles: () => new THREE.PointsMaterial({ color: COLOURS.net, size: 5, sizeAttenuation: false }),
  marker: (colour, size) => new THREE.PointsMaterial({ color: colour, size, sizeAttenuation: false, depthTest: false }),
  region: (colour) =>
    new THREE.MeshBasicMaterial({ color: colour, transparent: true, opacity: 0.18, side: THREE.DoubleSide, depthWrite: false }),
};

/** The net's opacity. */
const NET_OPACITY = 0.8;
/** A marker's size in pixels. */
const MARKER_SIZE = 9;

/** The most chords per knot span an iso-line gets (isoSpans). */
const ISO_MAX_SAMPLES_PER_SPAN = 12;

/** The box `[min, max]` of points. */
export function boxOf(points) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (const p of points) {
    for (let k = 0; k < 3; k += 1) {
      const value = p[k] ?? 0;
      if (value < min[k]) min[k] = value;
      if (value > max[k]) max[k] = value;
    }
  }
  return [min, max];
}

/** The poles of a curve or surface as one list. */
export function polesOf(item) {
  return item.kind === "surface" ? item.shape.control_points.flat() : item.shape.control_points;
}

function relative(origin, p) {
  return [(p[0] ?? 0) - origin[0], (p[1] ?? 0) - origin[1], (p[2] ?? 0) - origin[2]];
}

function lineSegments(origin, segments, colour, opacity = 1) {
  const positions = new Float32Array(segments.length * 6);
  segments.forEach(([a, b], i) => {
    positions.set(relative(origin, a), 6 * i);
    positions.set(relative(origin, b), 6 * i + 3);
  });
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  return new THREE.LineSegments(geometry, MATERIALS.line(colour, opacity));
}

/** The control net's segments: rows and columns of a surface's poles, a curve's polygon. */
function netSegments(item) {
  const poles = item.shape.control_points;
  const segments = [];
  if (item.kind === "surface") {
    for (let i = 0; i < poles.length; i += 1) {
      for (let j = 0; j < poles[i].length; j += 1) {
        if (i + 1 < poles.length) segments.push([poles[i][j], poles[i + 1][j]]);
        if (j + 1 < poles[i].length) segments.push([poles[i][j], poles[i][j + 1]]);
      }
    }
  } else {
    for (let i = 0; i + 1 < poles.length; i += 1) segments.push([poles[i], poles[i + 1]]);
  }
  return segments;
}

/** The iso-lines of a plain surface at its distinct knots inside the domain: the `(u, v)` of
 * their segments' ends, two pairs per segment, as one flat array; each polyline within
 * `tolerance` of its iso-curve (isoSpans; the mesh's tolerance, about half a pixel). */
export function isoParameters(plain, tolerance) {
  const nu = plain.control_points.length;
  const nv = plain.control_points[0].length;
  const us = distinctInDomain(plain.knots_u, plain.degree_u, nu);
  const vs = distinctInDomain(plain.knots_v, plain.degree_v, nv);
  const rational = Boolean(plain.weights);
  const rows = plain.control_points;
  const columns = rows[0].map((_, j) => rows.map((row) => row[j]));
  // Lines of constant u run along v: their control points combine the rows.
  const alongV = isoSpans(rows, plain.degree_v, plain.knots_v, tolerance, rational);
  const alongU = isoSpans(columns, plain.degree_u, plain.knots_u, tolerance, rational);
  const pairs = [];
  const lines = (spans, fixedValues, pair) => {
    for (const fixed of fixedValues) {
      for (const { low, high, samples } of spans) {
        for (let k = 0; k < samples; k += 1) {
          pairs.push(...pair(fixed, low + ((high - low) * k) / samples), ...pair(fixed, low + ((high - low) * (k + 1)) / samples));
        }
      }
    }
  };
  lines(alongV, us, (u, v) => [u, v]);
  lines(alongU, vs, (v, u) => [u, v]);
  return Float64Array.from(pairs);
}

/**
 * The knot spans of one direction and the chords each needs so that every iso-line along
 * that direction stays within `tolerance` of its curve: `[{ low, high, samples }]`.
 *
 * `lines[i]` are the net's lines along the direction (degree `p`, full knots `t`). A chord
 * over a parameter step `h` of a curve with `|C''| <= M` is within `M h² / 8` of it, so a span
 * of width `h` needs `ceil(h sqrt(M / (8 tolerance)))` chords. Every iso-curve along the
 * direction has control points `Q_j = Σ_i N_i P_ij` (`N_i >= 0`, summing to one), so its
 * second derivative's control points are the same combinations of the lines' own,
 * `D''_ij = (p − 1) (D'_i,j+1 − D'_ij) / (t_{j+p+1} − t_{j+2})` with
 * `D'_ij = p (P_i,j+1 − P_ij) / (t_{j+p+1} − t_{j+1})`, and on span `s` (`t_s <= x < t_{s+1}`)
 * `M = max |D''_ij|` over every line and `j = s − p ..= s − 2` bounds it. Rational nets (the
 * bound does not hold) and a missing tolerance get `ISO_MAX_SAMPLES_PER_SPAN`; so does a span
 * the bound asks more of.
 */
function isoSpans(lines, p, t, tolerance, rational) {
  const count = lines[0].length;
  const exact = !rational && tolerance > 0;
  // The largest |D''| per index j, over every line.
  const second = new Float64Array(Math.max(count - 2, 0));
  if (exact && p >= 2) {
    for (const line of lines) {
      const first = [];
      for (let j = 0; j + 1 < count; j += 1) {
        const width = t[j + p + 1] - t[j + 1];
        first.push(line[j].map((x, c) => (width > 0 ? (p * (line[j + 1][c] - x)) / width : 0)));
      }
      for (let j = 0; j + 2 < count; j += 1) {
        const width = t[j + p + 1] - t[j + 2];
        if (!(width > 0)) continue;
        const size = Math.hypot(...first[j].map((x, c) => ((p - 1) * (first[j + 1][c] - x)) / width));
        if (size > second[j]) second[j] = size;
      }
    }
  }
  const spans = [];
  for (let s = p; s < count; s += 1) {
    const [low, high] = [t[s], t[s + 1]];
    if (!(high > low)) continue;
    let samples = ISO_MAX_SAMPLES_PER_SPAN;
    if (exact) {
      let bound = 0;
      for (let j = Math.max(s - p, 0); j <= s - 2 && j < second.length; j += 1) bound = Math.max(bound, second[j]);
      samples = Math.min(ISO_MAX_SAMPLES_PER_SPAN, Math.max(1, Math.ceil((high - low) * Math.sqrt(bound / (8 * tolerance)))));
    }
    spans.push({ low, high, samples });
  }
  return spans;
}

/** Writes the points of `evaluate` at the `(u, v)` pairs of `parameters` that lie inside
 * `affected` (all when null) into `array` (x, y, z relative to `origin`). */
function evaluateInto(array, parameters, evaluate, origin, affected) {
  const [[u0, u1], [v0, v1]] = affected ?? [[-Infinity, Infinity], [-Infinity, Infinity]];
  for (let i = 0; 2 * i < parameters.length; i += 1) {
    const u = parameters[2 * i];
    const v = parameters[2 * i + 1];
    if (u < u0 || u > u1 || v < v0 || v > v1) continue;
    const p = evaluate(u, v);
    array[3 * i] = p[0] - origin[0];
    array[3 * i + 1] = p[1] - origin[1];
    array[3 * i + 2] = p[2] - origin[2];
  }
}

/** A three.js group for `item` (a surface with its `mesh`, or a curve with its `polyline`),
 * positioned at `item.origin`. Its children are named: "body" (picked), "iso", "net". */
export function buildGroup(item, { selected, showNet, showIso }) {
  const group = new THREE.Group();
  group.position.set(...item.origin);
  if (item.kind === "surface") {
    const mesh = item.mesh;
    const positions = new Float32Array(mesh.vertices.length * 3);
    mesh.vertices.forEach((p, i) => positions.set(relative(item.origin, p), 3 * i));
    const normals = new Float32Array(mesh.normals.flat());
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
    geometry.setAttribute("normal", new THREE.BufferAttribute(normals, 3));
    geometry.setIndex(mesh.triangles.flat());
    geometry.computeBoundingSphere();
    const body = new THREE.Mesh(geometry, MATERIALS.surface(selected ? COLOURS.surface : COLOURS.surfaceIdle));
    body.name = "body";
    group.add(body);
    if (item.plain) {
      const parameters = isoParameters(item.plain, item.tolerance);
      const positions = new Float32Array((parameters.length / 2) * 3);
      evaluateInto(positions, parameters, surfaceEvaluator(item.plain), item.origin, null);
      const isoGeometry = new THREE.BufferGeometry();
      isoGeometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
      const iso = new THREE.LineSegments(isoGeometry, MATERIALS.iso());
      iso.userData.parameters = parameters;
      iso.name = "iso";
      iso.visible = showIso;
      group.add(iso);
    }
  } else {
    const positions = new Float32Array(item.polyline.points.length * 3);
    item.polyline.points.forEach((p, i) => positions.set(relative(item.origin, p), 3 * i));
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
    geometry.computeBoundingSphere();
    const body = new THREE.Line(geometry, MATERIALS.line(selected ? COLOURS.curve : COLOURS.curveIdle));
    body.name = "body";
    group.add(body);
  }
  const net = lineSegments(item.origin, netSegments(item), COLOURS.net, NET_OPACITY);
  net.name = "net";
  net.visible = showNet && selected;
  const poles = polesOf(item);
  const polePositions = new Float32Array(poles.length * 3);
  poles.forEach((p, i) => polePositions.set(relative(item.origin, p), 3 * i));
  const poleGeometry = new THREE.BufferGeometry();
  poleGeometry.setAttribute("position", new THREE.BufferAttribute(polePositions, 3));
  const points = new THREE.Points(poleGeometry, MATERIALS.poles());
  points.name = "poles";
  net.add(points);
  group.add(net);
  return group;
}

/** Moves the drawn object to `shape` (a preview): the mesh vertices inside `affected`
 * (`[[u0, u1], [v0, v1]]`, null for all) or the polyline's points are evaluated on the new
 * shape at their own parameters, the iso-lines and the net drawn again. Normals are kept from
 * the committed mesh (the release meshes the new surface anew). Returns false when the page
 * cannot evaluate the shape (a periodic one). */
export function previewShape(item, group, plainShape, shape, affected) {
  if (!plainShape) return false;
  const body = group.getObjectByName("body");
  const attribute = body.geometry.getAttribute("position");
  const array = attribute.array;
  if (item.kind === "surface") {
    const evaluate = surfaceEvaluator(plainShape);
    if (!item.meshParameters) item.meshParameters = Float64Array.from(item.mesh.parameters.flat());
    evaluateInto(array, item.meshParameters, evaluate, item.origin, affected);
    const iso = group.getObjectByName("iso");
    if (iso) {
      const isoPositions = iso.geometry.getAttribute("position");
      evaluateInto(isoPositions.array, iso.userData.parameters, evaluate, item.origin, affected);
      isoPositions.needsUpdate = true;
    }
  } else {
    const evaluate = curveEvaluator(plainShape);
    const [ox, oy, oz] = item.origin;
    item.polyline.parameters.forEach((t, i) => {
      const p = evaluate(t);
      array[3 * i] = p[0] - ox;
      array[3 * i + 1] = p[1] - oy;
      array[3 * i + 2] = p[2] - oz;
    });
  }
  attribute.needsUpdate = true;
  body.geometry.computeBoundingSphere();
  const net = group.getObjectByName("net");
  replaceSegments(net, item.origin, netSegments({ kind: item.kind, shape }));
  const poles = (item.kind === "surface" ? shape.control_points.flat() : shape.control_points).map((p) => relative(item.origin, p));
  const polePositions = net.getObjectByName("poles").geometry.getAttribute("position");
  poles.forEach((p, i) => polePositions.array.set(p, 3 * i));
  polePositions.needsUpdate = true;
  return true;
}

function replaceSegments(lines, origin, segments) {
  const attribute = lines.geometry.getAttribute("position");
  if (attribute.count !== segments.length * 2) {
    const fresh = new Float32Array(segments.length * 6);
    lines.geometry.setAttribute("position", new THREE.BufferAttribute(fresh, 3));
  }
  const array = lines.geometry.getAttribute("position").array;
  segments.forEach(([a, b], i) => {
    array.set(relative(origin, a), 6 * i);
    array.set(relative(origin, b), 6 * i + 3);
  });
  lines.geometry.getAttribute("position").needsUpdate = true;
}

/** A small marker (a screen-sized dot) at `point`. */
export function marker(point, colour, size = MARKER_SIZE) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(point), 3));
  const points = new THREE.Points(geometry, MATERIALS.marker(colour, size));
  points.renderOrder = 10;
  return points;
}

/** Moves a marker to `point`. */
export function moveMarker(points, point) {
  const attribute = points.geometry.getAttribute("position");
  attribute.array.set(point);
  attribute.needsUpdate = true;
}

/** Triangles of a planar polygon (closed ring of 3D points) in its own plane, as positions
 * relative to `origin` (three.js's ear clipping on the ring projected onto its best plane). */
function ringTriangles(origin, ring) {
  const points = ring.length > 1 && ring[0].every((x, k) => x === ring[ring.length - 1][k]) ? ring.slice(0, -1) : ring;
  if (points.length < 3) return [];
  const vectors = points.map((p) => new THREE.Vector3(...relative(origin, p)));
  // Newell's normal of the ring.
  const normal = new THREE.Vector3();
  for (let i = 0; i < vectors.length; i += 1) {
    const a = vectors[i];
    const b = vectors[(i + 1) % vectors.length];
    normal.x += (a.y - b.y) * (a.z + b.z);
    normal.y += (a.z - b.z) * (a.x + b.x);
    normal.z += (a.x - b.x) * (a.y + b.y);
  }
  if (normal.lengthSq() === 0) return [];
  normal.normalize();
  const axis = Math.abs(normal.x) < 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0);
  const e1 = axis.sub(normal.clone().multiplyScalar(axis.dot(normal))).normalize();
  const e2 = normal.clone().cross(e1);
  const flat = vectors.map((v) => new THREE.Vector2(v.dot(e1), v.dot(e2)));
  const triangles = THREE.ShapeUtils.triangulateShape(flat, []);
  return triangles.flatMap(([a, b, c]) => [vectors[a], vectors[b], vectors[c]]);
}

/** The translucent regions of a regions answer (surfaces: knot rings and weight
 * tetrahedra; curves: knot families' polygons and weight polygons), as one group at
 * `origin`; `families` filters the knot families drawn (null: all). */
export function regionsGroup(origin, answer, kind) {
  const group = new THREE.Group();
  group.position.set(...origin);
  const knotTriangles = [];
  const weightTriangles = [];
  if (kind === "surface") {
    for (const method of answer.methods ?? []) {
      for (const region of method.knot_regions ?? []) {
        for (const ring of region.rings ?? []) knotTriangles.push(...ringTriangles(origin, ring));
      }
      for (const tetrahedron of method.tetrahedra ?? []) {
        const [a, b, c, d] = tetrahedron.tetrahedron.map((p) => new THREE.Vector3(...relative(origin, p)));
        weightTriangles.push(a, b, c, a, b, d, a, c, d, b, c, d);
      }
    }
  } else {
    for (const family of answer.families ?? []) {
      for (const region of family.regions ?? []) knotTriangles.push(...ringTriangles(origin, region.polygon));
    }
    for (const region of answer.weight_regions ?? []) {
      if (region.polygon) weightTriangles.push(...ringTriangles(origin, region.polygon));
    }
  }
  const add = (triangles, colour, name) => {
    if (triangles.length === 0) return;
    const geometry = new THREE.BufferGeometry().setFromPoints(triangles);
    const mesh = new THREE.Mesh(geometry, MATERIALS.region(colour));
    mesh.name = name;
    mesh.renderOrder = 5;
    group.add(mesh);
  };
  add(knotTriangles, COLOURS.knotRegion, "knot-regions");
  add(weightTriangles, COLOURS.weightRegion, "weight-regions");
  group.userData.counts = { knots: knotTriangles.length / 3, weights: weightTriangles.length / 3 };
  return group;
}

/** One degenerate primitive (its vertices coincide: nothing shows) of every kind the view
 * draws, with the objects' materials and attributes, never culled. Drawing it once before
 * the objects makes the browser compile the shaders and pipeline states that a drag would
 * otherwise compile on its first moves, when the regions and the first previews come (with
 * software WebGL some 50 ms: the first frame with the regions took 16 ms to draw and 35 ms
 * to rasterize, tests/editor/space.rs). */
export function warmUpGroup() {
  const group = new THREE.Group();
  const geometry = (vertices, { normals = false, indexed = false } = {}) => {
    const made = new THREE.BufferGeometry();
    made.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * vertices), 3));
    if (normals) made.setAttribute("normal", new THREE.BufferAttribute(new Float32Array(3 * vertices).fill(1), 3));
    if (indexed) made.setIndex([0, 1, 2]);
    return made;
  };
  const add = (object, renderOrder = 0) => {
    object.frustumCulled = false;
    object.renderOrder = renderOrder;
    group.add(object);
  };
  add(new THREE.Mesh(geometry(3, { normals: true, indexed: true }), MATERIALS.surface(COLOURS.surface)));
  add(new THREE.LineSegments(geometry(2), MATERIALS.iso()));
  add(new THREE.Line(geometry(2), MATERIALS.line(COLOURS.curve)));
  add(new THREE.LineSegments(geometry(2), MATERIALS.line(COLOURS.net, NET_OPACITY)));
  add(new THREE.Points(geometry(1), MATERIALS.poles()));
  add(new THREE.Points(geometry(1), MATERIALS.marker(COLOURS.pick, MARKER_SIZE)), 10);
  add(new THREE.Mesh(geometry(3), MATERIALS.region(COLOURS.knotRegion)), 5);
  return group;
}
