// A drag of the picked point or of a control point, from the first move to the release.
//
// A drag keeps at most one request in flight: moves that arrive meanwhile only replace the
// pending target, so the newest target is solved next. It sends the local piece of the
// curve that the move can change (geometry.pieceAtParameter / pieceAtPole), so that a
// request costs the same on a 300-pole curve as on the sample, and draws that piece as the
// preview (from the answer's SVG path, or computed in the page where SVG cannot draw the
// curve: drawing.sampledCurve). A point drag keeps the family (method, knot family, side,
// region) of its first answer's default choice — later requests ask for that family only —
// unless the user switches with the keys 1–9; where a knot pair has several solutions (its
// map folds), the one nearest the last preview's knots. On release it commits the family's
// solution for the whole curve; when the last request failed, nothing is committed. Esc
// cancels.

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as store from "./store.js";
import { commitCurve, failureMessage } from "./committing.js";
import { drawingOf, sampledCurve } from "./drawing.js";
import { snap } from "./snapping.js";
import { visibleBox } from "./viewport.js";

/** Drag timings kept, newest last (see `record`); each drag starts a new list. */
const KEPT_TIMINGS = 2000;

/**
 * Per preview drawn: { kind, stamp: the pointer event's timeStamp, handled: when its handler
 * ran, sent: when its request left, answered: when the answer was parsed, drawn: when the
 * preview was in the page, frame: the next animation frame after that } (performance.now()
 * milliseconds; `frame` filled in later), the kept family (JSON) of a point drag, and
 * where the preview put the dragged point.
 */
export const timings = [];

/** Pointer moves the last drag received (for tests: every move reaches the page), and of
 * the targets it solved, how many had no solution of the kept family (`missed`). */
export const moves = { count: 0, solved: 0, missed: 0 };

/** The drag in progress (null when none): what the controller needs beyond the state. */
let live = null;

export function isDragging() {
  return live !== null;
}

function begin(fields) {
  moves.count = 0;
  moves.solved = 0;
  moves.missed = 0;
  timings.length = 0;
  live = { latest: null, answered: null, inFlight: false, releasing: false, failed: false, ...fields };
  document.body.dataset.dragging = "true";
}

function end() {
  live = null;
  document.body.dataset.dragging = "false";
}

/** Starts dragging the picked point; `press` is the curve point where the press was. */
export function startPointDrag(press) {
  const state = store.get();
  if (!state.pick || live) return;
  const base = model.editBase(state);
  // Under constraints or fixed control points the whole curve is solved: a local piece
  // would not carry the conditions outside it.
  const piece = model.constrained(state) ? { curve: base, poleOffset: 0, whole: true } : geometry.pieceAtParameter(base, state.pick.parameter);
  const offsets = { poleOffset: piece.poleOffset, knotOffset: geometry.knotOffsetOf(piece, base) };
  // The knots the point was last moved by (the piece's convention): a folded pair's branch.
  const knots = piece.curve.knots;
  begin({ kind: "point", base, piece, offsets, knots, parameter: state.pick.parameter, origin: state.pick.point, press, family: state.family, alternatives: null, solution: null, nearest: null });
  store.set({ ...state, drag: { kind: "point", target: null, solution: null, family: state.family }, lastSolutions: null, message: "", error: "" });
}

/** Starts dragging control point `index` of the curve being edited. */
export function startPoleDrag(index, press) {
  const state = store.get();
  if (live) return;
  const base = model.editBase(state);
  const refusal = state.fixed.includes(index)
    ? `Control point ${index} is fixed: click it with the Pin tool to free it.`
    : geometry.poleMovesConstraint(base, index, state.constraints)
      ? `Control point ${index} would move a pinned point or a locked tangent: drag the curve instead (the solver keeps them), or remove them.`
      : null;
  if (refusal) {
    store.set({ ...state, message: refusal, error: "" });
    return;
  }
  const piece = geometry.pieceAtPole(base, index);
  const origin = base.control_points[index];
  begin({ kind: "pole", base, piece, index, origin: [origin[0], origin[1]], press, point: null });
  store.set({ ...state, drag: { kind: "pole", index, target: null }, lastSolutions: null, message: "", error: "" });
}

/** The dragged point for the pointer at `point`: moved by the pointer's displacement since
 * the press (so nothing jumps when the press was beside the dot), then snapped. */
function draggedTo(point) {
  const state = store.get();
  const moved = [live.origin[0] + point[0] - live.press[0], live.origin[1] + point[1] - live.press[1]];
  const snapped = snap(moved, state.snap, {
    frame: state.view.frame,
    poles: live.base.control_points,
    knotPoints: state.drawing?.knotPoints ?? [],
    skipPole: live.kind === "pole" ? live.index : -1,
  });
  // A point of a 3D curve moves in its x–y plane (a pole keeps its z in withPole).
  return live.kind === "point" ? { ...snapped, point: geometry.lifted(snapped.point, live.origin) } : snapped;
}

/** The pointer is at `point` (curve coordinates); `stamp` is the event's timeStamp. */
export function dragTo(point, stamp) {
  if (!live) return;
  moves.count += 1;
  const snapped = draggedTo(point);
  live.latest = { target: snapped.point, snapped: snapped.to, stamp, handled: performance.now() };
  if (!live.inFlight) {
    work(live);
  }
}

/** Solves (or redraws) the newest target until none is pending. */
async function work(drag) {
  drag.inFlight = true;
  store.busyBy(1);
  try {
    while (live === drag && drag.latest && drag.latest !== drag.answered) {
      const move = drag.latest;
      const timing = { kind: drag.kind, stamp: move.stamp, handled: move.handled, sent: performance.now() };
      const shown = drag.kind === "point" ? await solveMove(drag, move, timing) : await redrawPole(drag, move, timing);
      if (live !== drag) break;
      drag.answered = move;
      if (shown) record(timing, drag);
    }
  } finally {
    drag.inFlight = false;
    store.busyBy(-1);
  }
  if (live === drag && drag.releasing) {
    finish(drag);
  }
}

function record(timing, drag) {
  timing.drawn = performance.now();
  timing.family = drag.family ? JSON.stringify(drag.family) : null;
  timing.point = drag.kind === "point" ? drag.solution.point : drag.point;
  timings.push(timing);
  if (timings.length > KEPT_TIMINGS) timings.shift();
  requestAnimationFrame(() => {
    timing.frame = performance.now();
  });
}

/** The new knot values [[full index of the curve, value]] of a knot-pair solution of the piece. */
function movedKnots(drag, solution) {
  if (solution.method !== "knots") return null;
  const offset = drag.piece.poleOffset + (geometry.isTrimmed(drag.piece.curve) ? 1 : 0);
  return solution.changed_knots.map((index) => [index + offset, solution.knots[index]]);
}

/** The moved control points of a pole solution of the piece, with their neighbours; the two
 * poles whose weights a weight solution changes. */
function movedPoles(solution, piece) {
  if (solution.method === "weights") return { points: [], moved: solution.poles.map((k) => piece.control_points[k]) };
  if (solution.method !== "control_points") return null;
  const changed = solution.changed_control_points;
  const points = solution.control_points;
  const first = Math.max(0, Math.min(...changed) - 1);
  const last = Math.min(points.length - 1, Math.max(...changed) + 1);
  return { points: points.slice(first, last + 1), moved: changed.map((index) => points[index]) };
}

/** One solve of a point drag; resolves to whether a preview was drawn. */
async function solveMove(drag, move, timing) {
  const now = store.get();
  const answer = await api.solve(drag.piece.curve, drag.parameter, move.target, { methods: model.methodsFor(now), family: drag.family, svgPaths: true, conditions: model.conditions(now) });
  timing.answered = performance.now();
  if (live !== drag) return false;
  if (!answer.ok) {
    drag.failed = true;
    const state = store.get();
    store.set({ ...state, drag: { ...state.drag, target: move.target, snapped: move.snapped, solution: null, previewDrawing: null, movedPoles: null, previewKnots: null }, message: "", error: failureMessage(answer.problem, "This move failed: ") });
    return false;
  }
  const nearest = answer.value.nearest ?? null;
  const solutions = answer.value.solutions.length > 0 ? answer.value.solutions : nearest?.solutions ?? [];
  const { offsets } = drag;
  if (!drag.family && solutions.length > 0) {
    const chosen = model.defaultChoice(solutions);
    drag.family = geometry.familyOf(solutions[chosen], offsets.poleOffset, offsets.knotOffset);
    drag.alternatives = solutions;
    if (solutions[chosen].method === "knots") drag.knots = solutions[chosen].knots;
  }
  const found = drag.family ? geometry.indexInFamily(solutions, drag.family, { ...offsets, knots: drag.knots }) : -1;
  const solution = found >= 0 ? solutions[found] : null;
  const state = store.get();
  moves.solved += 1;
  if (!solution) {
    moves.missed += 1;
    drag.failed = true;
    store.set({ ...state, drag: { ...state.drag, target: move.target, snapped: move.snapped, solution: null, previewDrawing: null, movedPoles: null, previewKnots: null, family: drag.family }, message: drag.family ? `No solution of the kept family (${geometry.describeFamily(drag.family)}) moves the point towards this target: go back, or switch with the keys 1–9.` : "No solution moves the point towards this target.", error: "" });
    return false;
  }
  drag.failed = false;
  drag.solution = solution;
  drag.nearest = nearest;
  if (solution.method === "knots") drag.knots = solution.knots;
  let previewDrawing = solution.svg_path ? { path: solution.svg_path, knotPoints: [] } : null;
  if (!previewDrawing) {
    // Rational, 3D and curves of degree above 3: computed in the page.
    const moved = geometry.applySolution(drag.piece.curve, solution);
    const polyline = sampledCurve(moved, state.view.frame.scale, visibleBox(state.view.frame, state.view.size));
    if (polyline) {
      previewDrawing = { polyline, knotPoints: [] };
    } else {
      // A periodic curve: the API's certified polyline (a second request).
      const drawing = await drawingOf(moved, { marks: false });
      if (live !== drag) return false;
      previewDrawing = drawing.problem ? null : drawing;
    }
  }
  const alternatives = drag.alternatives ?? [solution];
  const keptIndex = geometry.indexInFamily(alternatives, drag.family, { ...offsets, knots: drag.knots });
  store.set({
    ...store.get(),
    drag: {
      kind: "point",
      target: move.target,
      snapped: move.snapped,
      solution,
      nearest,
      family: drag.family,
      alternatives,
      keptIndex,
      offsets,
      previewDrawing,
      movedPoles: movedPoles(solution, drag.piece.curve),
      previewKnots: movedKnots(drag, solution),
    },
    message: nearest ? "Outside the reachable set: the point follows the nearest reachable target." : "",
    error: "",
  });
  return true;
}

/** One redraw of a control-point drag; resolves to whether a preview was drawn. */
async function redrawPole(drag, move, timing) {
  const local = drag.index - drag.piece.poleOffset;
  const piece = geometry.withPole(drag.piece.curve, local, move.target);
  const drawing = await drawingOf(piece, { marks: false });
  timing.answered = performance.now();
  if (live !== drag) return false;
  const state = store.get();
  if (drawing.problem) {
    drag.failed = true;
    store.set({ ...state, drag: { ...state.drag, target: move.target, snapped: move.snapped, previewDrawing: null, movedPoles: null }, message: "", error: failureMessage(drawing.problem, "This move failed: ") });
    return false;
  }
  drag.failed = false;
  drag.point = move.target;
  const poles = piece.control_points;
  const neighbours = poles.slice(Math.max(0, local - 1), local + 2);
  store.set({
    ...state,
    drag: { kind: "pole", index: drag.index, target: move.target, snapped: move.snapped, previewDrawing: drawing, movedPoles: { points: neighbours, moved: [poles[local]] } },
    message: "",
    error: "",
  });
  return true;
}

/** The pointer went up: commit once the last target is answered. */
export function release() {
  if (!live) return;
  live.releasing = true;
  if (!live.inFlight) {
    finish(live);
  }
}

/** Esc: the drag ends and nothing changes. */
export function cancel() {
  if (!live) return false;
  end();
  store.nextGeneration();
  const state = store.get();
  store.set({ ...state, drag: null, message: "Drag cancelled: nothing changed.", error: "" });
  return true;
}

/** During a point drag: keep the family of the first answer's solution `index` instead. */
export function switchFamily(index) {
  if (!live || live.kind !== "point" || !live.alternatives?.[index]) return false;
  const chosen = live.alternatives[index];
  live.family = geometry.familyOf(chosen, live.offsets.poleOffset, live.offsets.knotOffset);
  if (chosen.method === "knots") live.knots = chosen.knots;
  live.answered = null;
  if (live.latest && !live.inFlight) work(live);
  return true;
}

function finish(drag) {
  end();
  const state = store.get();
  if (!drag.answered) {
    store.set({ ...state, drag: null });
    return Promise.resolve(false);
  }
  if (drag.failed) {
    // The failure is on the page already (an error, or the banner); say what it means.
    const silent = state.error || state.connection.state !== "ok";
    store.set({ ...state, drag: null, message: silent ? "" : "Nothing committed: the last move had no solution." });
    return Promise.resolve(false);
  }
  return drag.kind === "pole" ? finishPole(drag) : finishPoint(drag);
}

/** Commits the curve with the dragged control point where the last preview showed it (the
 * pick is dropped: its regions belong to the old curve). */
function finishPole(drag) {
  const curve = geometry.withPole(drag.base, drag.index, drag.point);
  return commitCurve(curve, { message: `Moved control point ${drag.index}.`, lastTarget: drag.point });
}

/** Commits the kept family's solution for the whole curve at the last target, with the list
 * of every solution there (for choosing another one after the release). */
function finishPoint(drag) {
  const target = drag.answered.target;
  const state = store.get();
  const methods = model.methodsFor(state);
  const conditions = model.conditions(state);
  return store.task(async () => {
    const [own, all] = await Promise.all([
      drag.piece.whole ? null : api.solve(drag.base, drag.parameter, target, { methods, family: drag.family, conditions }),
      api.solve(drag.base, drag.parameter, target, { methods, conditions }),
    ]);
    let solution = drag.solution;
    // The whole curve's knots as the last preview moved them: the branch to commit.
    const knots = solution.method === "knots" ? geometry.withMovedKnots(drag.base, movedKnots(drag, solution)) : null;
    if (own) {
      const candidates = own.ok ? [...own.value.solutions, ...(own.value.nearest?.solutions ?? [])] : [];
      const found = candidates[geometry.indexInFamily(candidates, drag.family, { knots })];
      if (!found) {
        const state = store.get();
        store.set({ ...state, drag: null, message: "", error: own.ok ? "Nothing committed: the kept family has no solution for the whole curve." : failureMessage(own.problem, "Nothing committed: ") });
        return false;
      }
      solution = found;
    }
    const listedSolutions = all.ok ? (all.value.solutions.length > 0 ? all.value.solutions : all.value.nearest?.solutions ?? []) : [];
    let chosen = geometry.indexInFamily(listedSolutions, drag.family, { knots });
    const solutions = chosen >= 0 ? listedSolutions.map((s, i) => (i === chosen ? solution : s)) : [solution, ...listedSolutions];
    if (chosen < 0) chosen = 0;
    return commitCurve(geometry.applySolution(drag.base, solution), {
      pick: { parameter: drag.parameter, point: solution.point },
      lastSolutions: { solutions, chosen, nearest: all.ok ? all.value.nearest ?? null : null, excluded: all.ok ? all.value.excluded ?? [] : [], base: drag.base, target },
      family: drag.family,
      lastTarget: target,
      message: `Committed: ${geometry.describeSolution(solution)}.`,
    });
  });
}
