// The editor's controller: holds the one state, runs the actions (each asks the API, then
// makes a new state with state.js and draws it with view.js), and starts the interaction.
// A drag keeps at most one solve request in flight: moves that arrive meanwhile only
// replace the pending target, so the newest target is solved next and answers for a curve
// that changed meanwhile (undo, load, a new pick) are dropped.

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import { draw, fitFrame } from "./view.js";
import { bind } from "./interaction.js";
import { drawingOf } from "./drawing.js";
import { SAMPLE_CUBIC, SINGLE_BEZIER } from "./sample.js";

/** How far (pixels) from the curve a click still picks it, and from the dot a drag starts. */
const PICK_RADIUS = 12;
/** Drag timings kept (milliseconds, request to redraw), newest last. */
const KEPT_TIMINGS = 1000;

const elements = {};
let state = null;
/** Bumped whenever the committed curve or the pick changes: older answers are dropped. */
let generation = 0;
let busy = 0;
const drag = { active: false, inFlight: false, latest: null, solved: null, release: false, base: null };
const timings = [];
/** The same moves split: [solve request, preview drawing request, redraw] milliseconds. */
const phases = [];

function render() {
  draw(state, elements, geometry.describeSolution);
}

function setState(next) {
  state = next;
  render();
}

async function task(work) {
  busy += 1;
  document.body.dataset.busy = "true";
  try {
    await work();
  } catch (error) {
    console.error(error);
    setState({ ...state, error: `Unexpected error: ${error.message}` });
  } finally {
    busy -= 1;
    document.body.dataset.busy = busy > 0 ? "true" : "false";
  }
}

/** Loads `curve` (after checking it with the API), fitting the view to it. */
function loadCurve(curve, message = "") {
  return task(async () => {
    const drawing = await drawingOf(curve);
    if (drawing.problem) {
      setState({ ...state, error: `Cannot load this curve: ${api.describeProblem(drawing.problem)}` });
      return;
    }
    generation += 1;
    const next = state ? model.load(state, curve) : model.initialState(curve);
    const refusal = geometry.editingRefusal(curve);
    setState({ ...next, drawing, frame: fitFrame(geometry.extent(curve)), message: refusal ?? message, error: "" });
  });
}

/** Draws the committed curve again (after the API key changed, or at the start). */
function refresh(message = "") {
  return task(async () => {
    const mine = ++generation;
    const drawn = await redrawCommitted(model.cleared(state));
    if (mine !== generation) return;
    const refusal = geometry.editingRefusal(model.currentCurve(state));
    setState({ ...model.cleared(state), drawing: drawn.drawing, error: drawn.error, message: drawn.error ? "" : refusal ?? message });
  });
}

/** Parses pasted or opened text: a curve object, or an object with a `curve`. */
function parseCurve(text) {
  let value;
  try {
    value = JSON.parse(text);
  } catch (error) {
    return { error: `The text is not JSON: ${error.message}` };
  }
  const curve = value && typeof value === "object" && value.curve ? value.curve : value;
  if (!curve || !Array.isArray(curve.control_points) || !Array.isArray(curve.knots) || !Number.isInteger(curve.degree)) {
    return { error: "A curve needs `degree`, `control_points` and `knots` (and optionally `weights`)." };
  }
  return { curve };
}

function loadText(text) {
  const parsed = parseCurve(text);
  if (parsed.error) {
    setState({ ...state, error: parsed.error });
    return Promise.resolve();
  }
  return loadCurve(parsed.curve, "Curve loaded.");
}

async function redrawCommitted(next, parameter) {
  const curve = model.currentCurve(next);
  const [drawing, regions] = await Promise.all([
    drawingOf(curve),
    parameter === undefined ? null : api.regions(curve, parameter),
  ]);
  return {
    drawing: drawing.problem ? null : drawing,
    regions: regions?.ok ? regions.value : null,
    error: drawing.problem ? api.describeProblem(drawing.problem) : regions && !regions.ok ? api.describeProblem(regions.problem) : "",
  };
}

/** Picks the curve point nearest to `point`; inserts knots when none can move there. */
function pick(point) {
  return task(async () => {
    const curve = model.currentCurve(state);
    const refusal = geometry.editingRefusal(curve);
    if (refusal) {
      setState({ ...state, message: refusal });
      return;
    }
    const mine = ++generation;
    const found = await api.closestPoint(curve, point);
    if (mine !== generation) return;
    if (!found.ok) {
      setState({ ...state, error: api.describeProblem(found.problem) });
      return;
    }
    const closest = found.value.results[0];
    if (closest.distance * state.frame.scale > PICK_RADIUS) {
      setState({ ...model.cleared(state), drawing: state.drawing, message: "Click on the curve (within 12 pixels of it) to pick a point." });
      return;
    }
    const t = closest.parameter;
    let next = state;
    let message = `Picked t = ${t.toPrecision(6)}. Drag the dot.`;
    let regions = await api.regions(curve, t);
    if (mine !== generation) return;
    if (!regions.ok || !geometry.hasUsableRegion(curve, regions.value)) {
      const refined = await api.insertKnotsForEditing(curve, t);
      if (mine !== generation) return;
      if (!refined.ok) {
        setState({ ...state, error: `This point cannot be edited: ${api.describeProblem(refined.problem)}` });
        return;
      }
      if (refined.value.inserted.length > 0) {
        next = model.commit(state, refined.value.curve);
        const values = refined.value.inserted.map((u) => +u.toPrecision(4)).join(", ");
        message = `No knot could move near t = ${t.toPrecision(4)}: inserted knots ${values} (the same curve, more control points). Drag the dot.`;
        regions = await api.regions(refined.value.curve, t);
        if (mine !== generation) return;
      }
    }
    const drawn = await redrawCommitted(next);
    if (mine !== generation) return;
    setState({
      ...next,
      drawing: drawn.drawing ?? state.drawing,
      pick: { parameter: t, point: closest.point },
      regions: regions.ok ? regions.value : null,
      drag: null,
      lastSolutions: null,
      message,
      error: regions.ok ? "" : api.describeProblem(regions.problem),
    });
  });
}

/** Whether `point` (curve coordinates) is on the picked dot. */
function onPickedPoint(point) {
  if (!state.pick) return false;
  const [x, y] = state.pick.point;
  return Math.hypot(point[0] - x, point[1] - y) * state.frame.scale <= PICK_RADIUS;
}

function startDrag() {
  Object.assign(drag, { active: true, inFlight: false, latest: null, solved: null, release: false, base: model.currentCurve(state) });
  timings.length = 0;
  phases.length = 0;
  document.body.dataset.dragging = "true";
  setState({ ...state, drag: { target: null, solutions: [], chosen: 0, nearest: null, preview: null, previewDrawing: null }, lastSolutions: null });
}

function dragTo(target) {
  if (!drag.active) return;
  drag.latest = target;
  if (!drag.inFlight) {
    solveLatest();
  }
}

async function solveLatest() {
  drag.inFlight = true;
  busy += 1;
  document.body.dataset.busy = "true";
  const mine = generation;
  const { parameter } = state.pick;
  try {
    while (drag.latest && drag.latest !== drag.solved && mine === generation) {
      const target = drag.latest;
      const started = performance.now();
      const answer = await api.solve(drag.base, parameter, target, state.methods);
      if (mine !== generation) break;
      drag.solved = target;
      if (!answer.ok) {
        setState({ ...state, error: api.describeProblem(answer.problem) });
        continue;
      }
      const nearest = answer.value.nearest ?? null;
      const solutions = answer.value.solutions.length > 0 ? answer.value.solutions : nearest?.solutions ?? [];
      if (solutions.length === 0) {
        setState({ ...state, drag: { ...state.drag, target, solutions, nearest, preview: null, previewDrawing: null }, message: "No method moves the point towards this target.", error: "" });
        continue;
      }
      const chosen = model.defaultChoice(solutions);
      const preview = geometry.applySolution(drag.base, solutions[chosen]);
      const solvedAt = performance.now();
      // The answer carries the new curve's SVG path when SVG draws it exactly: one round trip.
      const path = solutions[chosen].svg_path;
      const previewDrawing = path ? { path, knotPoints: [] } : await drawingOf(preview, { marks: false });
      if (mine !== generation) break;
      const fetchedAt = performance.now();
      setState({
        ...state,
        drag: { target, solutions, chosen, nearest, preview, previewDrawing: previewDrawing.problem ? null : previewDrawing },
        message: nearest ? "Outside every region: the point follows the nearest reachable target." : "",
        error: previewDrawing.problem ? api.describeProblem(previewDrawing.problem) : "",
      });
      const drawnAt = performance.now();
      timings.push(drawnAt - started);
      phases.push([solvedAt - started, fetchedAt - solvedAt, drawnAt - fetchedAt]);
      if (timings.length > KEPT_TIMINGS) {
        timings.shift();
        phases.shift();
      }
      document.body.dataset.dragTimings = JSON.stringify(timings);
      document.body.dataset.dragPhases = JSON.stringify(phases);
    }
  } finally {
    drag.inFlight = false;
    busy -= 1;
    document.body.dataset.busy = busy > 0 ? "true" : "false";
  }
  if (drag.release && mine === generation) {
    finishDrag();
  }
}

function releaseDrag() {
  if (!drag.active) return;
  drag.release = true;
  if (!drag.inFlight) {
    finishDrag();
  }
}

/** Commits the chosen solution of the last solved target (release). */
function finishDrag() {
  drag.active = false;
  document.body.dataset.dragging = "false";
  const current = state.drag;
  if (!current || current.solutions.length === 0) {
    setState({ ...state, drag: null });
    return Promise.resolve();
  }
  return commitChoice(current, current.chosen, false);
}

/** Commits solution `index` of `entry` (a drag's solutions) on top of the drag's base. */
function commitChoice(entry, index, replace) {
  return task(async () => {
    const solution = entry.solutions[index];
    const base = entry.base ?? drag.base;
    const curve = geometry.applySolution(base, solution);
    const mine = ++generation;
    const next = replace ? model.replaceCommit(state, curve) : model.commit(state, curve);
    const pick = { parameter: state.pick.parameter, point: solution.point };
    const lastSolutions = { solutions: entry.solutions, chosen: index, nearest: entry.nearest, base, target: entry.target };
    setState({ ...next, drag: null, lastSolutions, pick, drawing: entry.previewDrawing && !replace ? { ...entry.previewDrawing, knotPoints: [] } : state.drawing });
    const drawn = await redrawCommitted(next, pick.parameter);
    if (mine !== generation) return;
    setState({ ...state, drawing: drawn.drawing ?? state.drawing, regions: drawn.regions, error: drawn.error, message: `Committed: ${geometry.describeSolution(solution)}.` });
  });
}

/** Another solution of the last drag, chosen from the list after the release. */
function choose(index) {
  const entry = state.lastSolutions;
  if (!entry || drag.active || index === entry.chosen || !entry.solutions[index]) return Promise.resolve();
  return commitChoice(entry, index, true);
}

function historyStep(step) {
  if (drag.active) return Promise.resolve();
  return task(async () => {
    const next = step(state);
    if (next === state) return;
    const mine = ++generation;
    setState({ ...next, drawing: state.drawing, message: "", error: "" });
    const drawn = await redrawCommitted(next);
    if (mine !== generation) return;
    setState({ ...state, drawing: drawn.drawing, error: drawn.error });
  });
}

function setMethods(methods) {
  if (methods.length === 0) {
    setState({ ...state, error: "Choose at least one method." });
    return false;
  }
  setState({ ...state, methods, error: "" });
  return true;
}

function exportCurve() {
  const text = JSON.stringify(model.currentCurve(state), null, 2);
  elements.json.value = text;
  const link = elements.download;
  if (link.href) URL.revokeObjectURL(link.href);
  link.href = URL.createObjectURL(new Blob([text], { type: "application/json" }));
  link.hidden = false;
}

function start() {
  for (const [name, id] of Object.entries({
    scene: "scene", canvas: "canvas", strip: "knot-strip", solutions: "solutions", legend: "legend",
    message: "message", error: "error", undo: "undo", redo: "redo", sample: "sample",
    bezierSample: "bezier-sample", json: "curve-json", load: "load", export: "export",
    openFile: "open-file", download: "download", apiKey: "api-key",
    methodKnots: "method-knots", methodControlPoints: "method-control-points",
  })) {
    elements[name] = document.getElementById(id);
  }
  bind(elements, {
    pointerToCurve: (event) => {
      const matrix = elements.scene.getScreenCTM();
      const local = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix.inverse());
      return [local.x, local.y];
    },
    isDragging: () => drag.active,
    onPickedPoint,
    pick,
    startDrag,
    dragTo,
    releaseDrag,
    choose,
    undo: () => historyStep(model.undo),
    redo: () => historyStep(model.redo),
    sample: () => loadCurve(structuredClone(SAMPLE_CUBIC), "The sample cubic."),
    bezierSample: () => loadCurve(structuredClone(SINGLE_BEZIER), "A single Bézier piece: pick a point and knots are inserted around it."),
    loadText,
    exportCurve,
    setMethods,
    setApiKey: (key) => {
      api.setApiKey(key);
      return refresh();
    },
    apiKey: api.apiKey,
  });
  window.editorTimings = timings;
  // A state to draw before the first answer (or when the first request is refused).
  const first = structuredClone(SAMPLE_CUBIC);
  setState({ ...model.initialState(first), frame: fitFrame(geometry.extent(first)) });
  refresh("The sample cubic: click near the curve to pick a point.").then(() => {
    document.body.dataset.ready = "true";
  });
}

start();
