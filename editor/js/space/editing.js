// The 3D editor's objects and edits: the surfaces and space curves shown (one of them
// selected for editing), meshed by the service at about half a pixel, picked by the ray from
// the pointer (refined by the service's closest point), dragged in the plane through the
// picked point facing the viewer (Alt: along the surface normal or the curve's principal
// normal), each move solved by the service and previewed at once (the page evaluates the
// solution at the mesh's own parameters), committed on release, cancelled by Esc, with undo
// and redo. Everything here talks to the view through `view` (scene.js) and to the panel
// through `notify()`. Over 600 lines because a drag's life (pick, moves, previews, regions,
// release) shares one closure over the editor's state; what is drawn (objects.js), the view
// (scene.js) and the evaluation (nurbs.js) are apart.

import * as api from "../api.js";
import { buildGroup, boxOf, COLOURS, marker, moveMarker, polesOf, previewShape, regionsGroup } from "./objects.js";
import { plainCurve, plainSurface, surfacePiece, withPiece } from "./nurbs.js";

/** The methods offered per kind of object (the API's names) and which are on at first. */
export const SPACE_METHODS = {
  surface: [
    { id: "knots", label: "knots (iso-curve families, mixed moves)", on: true },
    { id: "control_points", label: "control points", on: true },
    { id: "weights", label: "weights (three per move)", on: false },
  ],
  curve: [
    { id: "knots", label: "knots (pairs, triples)", on: true },
    { id: "control_points", label: "control points", on: true },
    { id: "weights", label: "weights (two per move)", on: false },
  ],
};

/** A mesh is made anew when the pixel's size changed by more than this factor. */
const REMESH_FACTOR = 2;
/** The mesh tolerance in pixels. */
const TOLERANCE_PIXELS = 0.5;
/** Pick distance to a curve, in pixels. */
const CURVE_PICK_PIXELS = 6;
/** A drag asks for the regions of its picked point once the pointer has rested this long
 * (milliseconds), or at a release without a move. While moves stream, computing them (for a
 * 30 × 30-pole surface some 20 ms of the service's time and 10 of the page's) would hold up
 * the previews. */
const REGIONS_AFTER_REST_MS = 150;
/** Timings kept (the latest). */
const TIMINGS_KEPT = 2000;

export function createEditor(view, notify) {
  const editor = {
    items: [],
    selected: -1,
    methods: {
      surface: SPACE_METHODS.surface.filter((m) => m.on).map((m) => m.id),
      curve: SPACE_METHODS.curve.filter((m) => m.on).map((m) => m.id),
    },
    showNet: false,
    showIso: true,
    showRegions: true,
    history: [],
    future: [],
    pick: null,
    drag: null,
    solutions: [],
    message: "",
    error: "",
    busy: 0,
    /** Per preview of a drag (tests): the pointer event's time stamp, when its handler ran,
     * when its request went and its answer came, when the preview was drawn (the WebGL calls
     * done) and when that frame was rasterized. */
    timings: [],
    /** Counts of the moves a drag saw and previewed (tests). */
    moves: { seen: 0, previewed: 0 },
    regions: null,
    markers: { pick: marker([0, 0, 0], COLOURS.pick), target: marker([0, 0, 0], COLOURS.target) },
  };
  editor.markers.pick.visible = false;
  editor.markers.target.visible = false;
  view.scene.add(editor.markers.pick, editor.markers.target);

  const say = (message, error = "") => {
    editor.message = message;
    editor.error = error;
    notify();
  };
  const failed = (problem, prefix) => {
    const detail = problem.errors?.map((e) => `${e.pointer ?? e.field ?? ""} ${e.detail ?? e.message ?? ""}`.trim()).join("; ");
    say("", `${prefix}${problem.title ?? "failed"}${problem.detail ? `: ${problem.detail}` : ""}${detail ? ` (${detail})` : ""}`);
  };

  const tolerance = (item) => {
    const size = Math.max(item.size, 1e-300);
    return Math.min(Math.max(TOLERANCE_PIXELS * view.pixelSize(), size * 1e-6), size * 0.05);
  };

  /** Meshes (or samples) `item` at the view's tolerance and draws it; resolves to success. */
  async function display(item) {
    let wanted = tolerance(item);
    for (let attempt = 0; attempt < 6; attempt += 1) {
      const answer = item.kind === "surface" ? await api.tessellate(item.shape, wanted) : await api.evaluatePolyline(item.shape, wanted);
      if (answer.ok) {
        if (item.kind === "surface") {
          item.mesh = answer.value;
          item.meshParameters = null;
        }
        else item.polyline = { parameters: answer.value.parameters, points: answer.value.points };
        item.tolerance = wanted;
        redraw(item);
        return true;
      }
      // Too many triangles for the limit: a coarser mesh.
      if (answer.problem.status === 422 && JSON.stringify(answer.problem).includes("/tolerance")) {
        wanted *= 4;
        continue;
      }
      failed(answer.problem, `Cannot draw ${item.name}: `);
      return false;
    }
    return false;
  }

  function redraw(item) {
    if (item.group) view.scene.remove(item.group);
    if ((item.kind === "surface" && !item.mesh) || (item.kind === "curve" && !item.polyline)) return;
    const index = editor.items.indexOf(item);
    item.group = buildGroup(item, { selected: index === editor.selected, showNet: editor.showNet, showIso: editor.showIso });
    item.group.userData.index = index;
    view.scene.add(item.group);
    view.request();
  }

  function itemOf(kind, shape, name) {
    const plain = kind === "surface" ? plainSurface(shape) : plainCurve(lifted(shape));
    const edited = plain ?? (kind === "curve" ? lifted(shape) : shape);
    const [min, max] = boxOf(kind === "surface" ? edited.control_points.flat() : edited.control_points);
    const origin = min.map((low, k) => (low + max[k]) / 2);
    const size = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]) || 1;
    return { kind, name, shape: edited, plain, origin, size, group: null, mesh: null, polyline: null, tolerance: 0 };
  }

  /** Opens `objects` (`{ kind: "surface" | "curve", shape, name }`), replacing what is shown;
   * the first surface (else the first object) is selected. */
  editor.open = async (objects, message) => {
    cancelDrag();
    for (const item of editor.items) if (item.group) view.scene.remove(item.group);
    clearRegions();
    editor.items = objects.map(({ kind, shape, name }) => itemOf(kind, shape, name));
    const firstSurface = editor.items.findIndex((item) => item.kind === "surface");
    editor.selected = editor.items.length === 0 ? -1 : Math.max(firstSurface, 0);
    editor.history = [];
    editor.future = [];
    editor.solutions = [];
    editor.pick = null;
    hideMarkers();
    view.fit(boxOf(editor.items.flatMap((item) => polesOf(item))), "isometric");
    editor.busy += 1;
    notify();
    try {
      const shown = await Promise.all(editor.items.map(display));
      if (shown.every(Boolean)) say(message);
    } finally {
      editor.busy -= 1;
      notify();
    }
  };

  editor.select = (index) => {
    if (index === editor.selected || !editor.items[index]) return;
    cancelDrag();
    clearRegions();
    hideMarkers();
    const before = editor.selected;
    editor.selected = index;
    editor.pick = null;
    editor.solutions = [];
    for (const i of [before, index]) if (editor.items[i]) redraw(editor.items[i]);
    say(`Editing ${editor.items[index].name}.`);
  };

  editor.selectedItem = () => editor.items[editor.selected] ?? null;

  editor.setMethods = (kind, methods) => {
    if (methods.length === 0) {
      say("", "Choose at least one method.");
      return;
    }
    editor.methods[kind] = methods;
    clearRegions();
    notify();
  };

  editor.setLayers = ({ net, iso, regions }) => {
    editor.showNet = net;
    editor.showIso = iso;
    editor.showRegions = regions;
    for (const item of editor.items) {
      const netLines = item.group?.getObjectByName("net");
      if (netLines) netLines.visible = net && editor.items.indexOf(item) === editor.selected;
      const isoLines = item.group?.getObjectByName("iso");
      if (isoLines) isoLines.visible = iso;
    }
    if (editor.regions) editor.regions.visible = regions;
    view.request();
    notify();
  };

  /** After the view settled: meshes again where the pixel's size changed much. */
  editor.viewSettled = () => {
    if (editor.drag) return;
    for (const item of editor.items) {
      const wanted = tolerance(item);
      if (item.tolerance > 0 && (wanted > item.tolerance * REMESH_FACTOR || wanted < item.tolerance / REMESH_FACTOR)) {
        display(item);
      }
    }
  };

  // Picking ------------------------------------------------------------------------------

  /** The object under canvas pixel `pixel`: `{ index, point, parameter }` (the parameter
   * interpolated in the mesh or polyline, refined later by the service), or null. */
  editor.hit = (pixel) => {
    const raycaster = view.rayAt(pixel);
    raycaster.params.Line.threshold = CURVE_PICK_PIXELS * view.pixelSize();
    raycaster.params.Points.threshold = 0;
    const bodies = editor.items.map((item) => item.group?.getObjectByName("body")).filter(Boolean);
    const hits = raycaster.intersectObjects(bodies, false);
    if (hits.length === 0) return null;
    // A curve near the ray wins over a surface behind it.
    const hit = hits.find((h) => h.object.isLine) ?? hits[0];
    const index = hit.object.parent.userData.index;
    const item = editor.items[index];
    const point = hit.point.toArray();
    let parameter;
    if (item.kind === "surface") {
      const { a, b, c } = hit.face;
      const weights = hit.barycoord ? hit.barycoord.toArray() : [1 / 3, 1 / 3, 1 / 3];
      const parameters = item.mesh.parameters;
      parameter = [0, 1].map((k) => weights[0] * parameters[a][k] + weights[1] * parameters[b][k] + weights[2] * parameters[c][k]);
    } else {
      const i = Math.min(hit.index, item.polyline.parameters.length - 2);
      parameter = (item.polyline.parameters[i] + item.polyline.parameters[i + 1]) / 2;
    }
    return { index, point, parameter, ray: raycaster.ray };
  };

  /** Refines a hit on the service: the exact closest point of the object to the point hit
   * and its parameter, and (a promise: a drag does not wait for it) the direction Alt drags
   * along (unit normal / principal normal). */
  async function refine(item, hit) {
    if (item.kind === "surface") {
      const answer = await api.surfaceClosestPoint(item.shape, hit.point);
      if (!answer.ok) return { error: answer.problem };
      const result = answer.value.results[0];
      const parameter = [result.u, result.v];
      return { parameter, point: result.point, normal: surfaceNormal(item, parameter) };
    }
    const answer = await api.closestPoint(item.shape, hit.point);
    if (!answer.ok) return { error: answer.problem };
    const result = answer.value.results?.[0] ?? answer.value;
    const t = result.parameter ?? result.t;
    return { parameter: t, point: result.point, normal: curveNormal(item, t) };
  }

  async function surfaceNormal(item, parameter) {
    const frame = await api.surfaceNormals(item.shape, [parameter]);
    return frame.ok ? frame.value.normals?.[0] ?? null : null;
  }

  async function curveNormal(item, t) {
    const frame = await api.curveFrames(item.shape, [t]);
    let normal = null;
    if (frame.ok) {
      const [d1, d2] = [frame.value.derivatives[0][0], frame.value.derivatives[1][0]];
      const along = dot(d2, d1) / Math.max(dot(d1, d1), 1e-300);
      const n = d2.map((x, k) => x - along * d1[k]);
      const length = Math.hypot(...n);
      if (length > 1e-12 * Math.hypot(...d2) && length > 0) normal = n.map((x) => x / length);
    }
    return normal;
  }

  // Dragging -----------------------------------------------------------------------------

  /** Starts a drag at `hit` (pointer at canvas pixel `pixel`, event time `stamp`). */
  editor.startDrag = (hit) => {
    cancelDrag();
    if (hit.index !== editor.selected) editor.select(hit.index);
    const item = editor.items[hit.index];
    const drag = {
      item,
      committedShape: item.shape,
      parameter: hit.parameter,
      point: hit.point,
      normal: null,
      refined: false,
      regionsAsked: false,
      regionsTimer: null,
      target: null,
      alongNormal: false,
      inFlight: false,
      waiting: null,
      shown: null,
      solution: null,
      released: false,
      cancelled: false,
    };
    editor.drag = drag;
    // The last pick's regions go; this pick's come once the pointer rests.
    clearRegions();
    view.setInteractive(true);
    editor.solutions = [];
    showMarker(editor.markers.pick, hit.point);
    askRegionsAtRest(drag);
    notify();
    refine(item, hit).then((refined) => {
      if (drag.cancelled) return;
      if (refined.error) {
        failed(refined.error, "Cannot pick: ");
        cancelDrag();
        return;
      }
      drag.parameter = refined.parameter;
      drag.point = refined.point;
      refined.normal.then((normal) => {
        drag.normal = normal;
      });
      // A surface's drag sends only the piece the move can change (nurbs.js surfacePiece).
      drag.piece = item.kind === "surface" && item.plain ? surfacePiece(item.plain, refined.parameter) : null;
      drag.refined = true;
      editor.pick = { index: hit.index, parameter: refined.parameter, point: refined.point };
      moveMarker(editor.markers.pick, refined.point);
      drawUnlessPreviewComes();
      pump(drag);
    });
    // The drag's resolution is drawn now, while the service refines the pick: the browser
    // allocates the smaller drawing buffer (with software WebGL 15–20 ms), which at the next
    // frame would hold up the first moves.
    view.renderNow();
    view.finishFrame();
  };

  /** The drag's target for the pointer at `pixel`: on the plane through the picked point
   * facing the viewer, or with `alongNormal` on the normal line through it (the point of
   * that line nearest the pointer's ray). */
  editor.targetAt = (pixel, alongNormal) => {
    const drag = editor.drag;
    if (!drag) return null;
    const { THREE } = view;
    const ray = view.rayAt(pixel).ray;
    const origin = new THREE.Vector3(...drag.point);
    if (alongNormal && drag.normal) {
      const direction = new THREE.Vector3(...drag.normal);
      const onLine = new THREE.Vector3();
      ray.distanceSqToSegment(origin.clone().addScaledVector(direction, -1e6 * drag.item.size), origin.clone().addScaledVector(direction, 1e6 * drag.item.size), null, onLine);
      return onLine.toArray();
    }
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(view.viewDirection(), origin);
    const point = ray.intersectPlane(plane, new THREE.Vector3());
    return point ? point.toArray() : null;
  };

  /** A pointer move of the drag: its target, `stamp` the event's time. */
  editor.dragTo = (pixel, alongNormal, stamp) => {
    const drag = editor.drag;
    if (!drag || drag.released) return;
    const target = editor.targetAt(pixel, alongNormal);
    if (!target) return;
    editor.moves.seen += 1;
    askRegionsAtRest(drag);
    drag.target = target;
    drag.waiting = { target, stamp, handled: performance.now() };
    // The target's marker is drawn with the move's preview (one render per move).
    moveMarker(editor.markers.target, target);
    editor.markers.target.visible = true;
    pump(drag);
  };

  /** Sends the newest waiting target when nothing is on its way (one request at a time; a
   * move that comes while one is out replaces the waiting one). */
  async function pump(drag) {
    if (!drag.refined || drag.inFlight || !drag.waiting || drag.cancelled) {
      if (drag.released && !drag.inFlight && !drag.waiting && drag.refined) finish(drag);
      return;
    }
    const move = drag.waiting;
    drag.waiting = null;
    drag.inFlight = true;
    const item = drag.item;
    const methods = editor.methods[item.kind];
    const sent = performance.now();
    const sentShape = drag.piece ? drag.piece.shape : drag.committedShape;
    const answer = item.kind === "surface"
      ? await api.surfaceSolve(sentShape, drag.parameter, move.target, methods)
      : await api.solve(sentShape, drag.parameter, move.target, { methods });
    const answered = performance.now();
    drag.inFlight = false;
    if (drag.cancelled) return;
    if (!answer.ok) {
      failed(answer.problem, "Cannot move the point: ");
      view.request();
    } else {
      const solutions = answer.value.solutions ?? [];
      editor.solutions = solutions;
      if (solutions.length > 0) {
        drag.solution = solutions[0];
        drag.shown = shapeAfter(drag, solutions[0]);
        drag.shownTarget = move.target;
        preview(item, drag.shown, solutions[0].affected_domain ?? null);
        const drawn = performance.now();
        // The next move's request goes out first; the frame is rasterized while the
        // service solves it.
        pump(drag);
        view.finishFrame();
        const rasterized = performance.now();
        editor.moves.previewed += 1;
        editor.timings.push({ stamp: move.stamp, handled: move.handled, sent, answered, drawn, rasterized });
        if (editor.timings.length > TIMINGS_KEPT) editor.timings.shift();
        editor.message = describe(solutions[0], solutions.length);
        editor.error = "";
      } else {
        editor.message = "";
        editor.error = "No method reaches this target (with the methods chosen).";
        view.request();
      }
      notify();
    }
    pump(drag);
  }

  /** Asks for the regions of the drag's picked point once the pointer has rested for
   * `REGIONS_AFTER_REST_MS` (each move starts the wait again). */
  function askRegionsAtRest(drag) {
    clearTimeout(drag.regionsTimer);
    if (drag.regionsAsked) return;
    drag.regionsTimer = setTimeout(() => {
      if (editor.drag !== drag) return;
      if (drag.refined) askRegions(drag);
      else askRegionsAtRest(drag);
    }, REGIONS_AFTER_REST_MS);
  }

  /** Asks for the regions of the drag's picked point, once. */
  function askRegions(drag) {
    clearTimeout(drag.regionsTimer);
    if (drag.regionsAsked) return;
    drag.regionsAsked = true;
    fetchRegions(drag.item, drag.parameter, drag.piece?.shape ?? drag.item.shape);
  }

  /** The whole object after `solution` (of the piece the drag sent, or of the whole). */
  function shapeAfter(drag, solution) {
    if (!drag.piece) return applied(drag.committedShape, drag.item.kind, solution);
    return withPiece(drag.committedShape, drag.piece, applied(drag.piece.shape, "surface", solution));
  }

  function preview(item, shape, affected) {
    const plain = item.kind === "surface" ? plainSurface(shape) : plainCurve(shape);
    if (!previewShape(item, item.group, plain, shape, affected)) return;
    view.renderNow();
  }

  /** Releases the drag: commits the last previewed solution once the last move is solved. */
  editor.release = () => {
    const drag = editor.drag;
    if (!drag) return;
    drag.released = true;
    pump(drag);
  };

  async function finish(drag) {
    if (editor.drag !== drag) return;
    editor.drag = null;
    view.setInteractive(false);
    hideTarget();
    if (!drag.shown) {
      // A press without a move keeps its pick: its regions are drawn.
      askRegions(drag);
      redraw(drag.item);
      notify();
      return;
    }
    clearTimeout(drag.regionsTimer);
    editor.lastCommit = { index: editor.items.indexOf(drag.item), parameter: drag.parameter, target: drag.shownTarget, solution: drag.solution };
    editor.lastPiece = drag.piece;
    commit(drag.item, drag.committedShape, drag.shown, describe(drag.solution, editor.solutions.length));
  }

  function commit(item, before, after, message) {
    item.edited = true;
    editor.history.push({ index: editor.items.indexOf(item), before, after });
    editor.future = [];
    setShape(item, after, message);
  }

  async function setShape(item, shape, message) {
    item.shape = shape;
    item.plain = item.kind === "surface" ? plainSurface(shape) : plainCurve(shape);
    clearRegions();
    editor.busy += 1;
    notify();
    try {
      if (await display(item)) say(message);
    } finally {
      editor.busy -= 1;
      notify();
    }
  }

  /** Esc: the drag ends and the object is as it was. Returns whether a drag was cancelled. */
  editor.cancel = () => {
    if (!editor.drag) return false;
    cancelDrag();
    say("Cancelled: the object is as it was.");
    return true;
  };

  function cancelDrag() {
    const drag = editor.drag;
    if (!drag) return;
    drag.cancelled = true;
    clearTimeout(drag.regionsTimer);
    editor.drag = null;
    view.setInteractive(false);
    hideTarget();
    redraw(drag.item);
  }

  /** Chooses solution `index` of the last move: the committed edit becomes that one. */
  editor.choose = (index) => {
    const solution = editor.solutions[index];
    const last = editor.history[editor.history.length - 1];
    if (!solution || !last || editor.drag) return;
    const item = editor.items[last.index];
    const after = editor.lastPiece && item.kind === "surface"
      ? withPiece(last.before, editor.lastPiece, applied(editor.lastPiece.shape, "surface", solution))
      : applied(last.before, item.kind, solution);
    last.after = after;
    setShape(item, after, describe(solution, editor.solutions.length));
  };

  editor.undo = () => {
    if (editor.drag) return;
    const step = editor.history.pop();
    if (!step) return;
    editor.future.push(step);
    editor.solutions = [];
    hideMarkers();
    setShape(editor.items[step.index], step.before, "Undone.");
  };

  editor.redo = () => {
    if (editor.drag) return;
    const step = editor.future.pop();
    if (!step) return;
    editor.history.push(step);
    setShape(editor.items[step.index], step.after, "Redone.");
  };

  // Regions ------------------------------------------------------------------------------

  /** Takes the regions out of the view (a frame is drawn only when there were some). */
  function clearRegions() {
    if (!editor.regions) return;
    view.scene.remove(editor.regions);
    editor.regions = null;
    view.request();
  }

  async function fetchRegions(item, parameter, shape) {
    clearRegions();
    const methods = editor.methods[item.kind];
    const answer = item.kind === "surface"
      ? await api.surfaceRegions(shape, parameter, methods, 3000)
      : await api.regions(shape, parameter, item.size * 1e-3, { methods, budget: 3000 });
    if (!answer.ok || editor.pick?.parameter !== parameter) return;
    editor.regions = regionsGroup(item.origin, answer.value, item.kind);
    editor.regions.visible = editor.showRegions;
    view.scene.add(editor.regions);
    drawUnlessPreviewComes();
    notify();
  }

  /** Asks for a frame, unless a drag's request is on its way or about to go: its preview
   * draws the view anyway, and during a drag every extra frame holds up the next move
   * (each is rasterized, with software WebGL for several milliseconds). */
  function drawUnlessPreviewComes() {
    const drag = editor.drag;
    if (drag && !drag.cancelled && !drag.released && (drag.inFlight || (drag.waiting && drag.refined))) return;
    view.request();
  }

  // Markers ------------------------------------------------------------------------------

  function showMarker(points, point) {
    moveMarker(points, point);
    points.visible = true;
    view.request();
  }
  function hideTarget() {
    editor.markers.target.visible = false;
    view.request();
  }
  function hideMarkers() {
    editor.markers.pick.visible = false;
    hideTarget();
  }

  // Files --------------------------------------------------------------------------------

  /** The objects as the export sends them: `{ curves, surfaces }`. */
  editor.exportable = () => ({
    curves: editor.items.filter((item) => item.kind === "curve").map((item) => item.shape),
    surfaces: editor.items.filter((item) => item.kind === "surface").map((item) => item.shape),
  });

  return editor;
}

/** A curve with 3D control points (z = 0 added to 2D ones). */
function lifted(curve) {
  if (curve.control_points.every((p) => p.length === 3)) return curve;
  return { ...curve, control_points: curve.control_points.map((p) => [p[0], p[1], p[2] ?? 0]) };
}

function dot(a, b) {
  return a.reduce((sum, x, k) => sum + x * b[k], 0);
}

/** The shape after `solution`: new knots, control points or weights. */
export function applied(shape, kind, solution) {
  if (kind === "curve") {
    if (solution.method === "knots") return { ...shape, knots: solution.knots.slice() };
    if (solution.method === "weights") return { ...shape, weights: solution.weights.slice() };
    return { ...shape, control_points: solution.control_points.map((p) => p.slice()) };
  }
  if (solution.method === "knots") {
    const next = { ...shape };
    if (solution.knots_u) next.knots_u = solution.knots_u.slice();
    if (solution.knots_v) next.knots_v = solution.knots_v.slice();
    if (solution.multiplicities_u) next.multiplicities_u = solution.multiplicities_u.slice();
    if (solution.multiplicities_v) next.multiplicities_v = solution.multiplicities_v.slice();
    return next;
  }
  if (solution.method === "weights") return { ...shape, weights: solution.weights.map((row) => row.slice()) };
  return { ...shape, control_points: solution.control_points.map((row) => row.map((p) => p.slice())) };
}

/** One line about a solution. */
export function describe(solution, count) {
  if (!solution) return "";
  const name = solution.family ? `${solution.method} (${solution.family}${solution.region ? `, ${solution.region}` : ""})` : solution.method.replace("_", " ");
  const deviation = Number.isFinite(solution.max_deviation) ? solution.max_deviation.toPrecision(3) : "—";
  return `${name}: max deviation ${deviation}; ${count} solution${count === 1 ? "" : "s"}.`;
}
