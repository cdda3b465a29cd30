// The editor's state as plain data, and the pure functions that make a new state from an
// old one. Nothing here draws or requests; the controller calls these and then draws the
// result (event → new state → draw).

import { FAMILIES, LAYERS, METHODS, SNAPS } from "./options.js";
import { usableMethods } from "./geometry.js";

/** A fresh state editing `curve`, drawn in `frame` on a drawing of `size`. */
export function initialState(curve, frame, size) {
  return {
    history: { past: [], present: curve, future: [] },
    view: { frame, size },
    drawing: null, // { path | polyline, knotPoints } of the committed curve
    pick: null, // { parameter, point, base }: base is the curve edits start from
    regions: null, // the /v1/shape/regions answer at the pick, only what solving reaches
    drag: null, // see dragging.js
    lastSolutions: null, // after a release: { solutions, chosen, base, target } to re-choose
    family: null, // the way of moving the point that drags and nudges keep (geometry.familyOf)
    methods: METHODS.filter((method) => method.on).map((method) => method.id),
    constraints: [], // pins { parameter, order: 0 } and tangent locks { parameter, order: 1, direction_only: true }
    fixed: [], // indices of the control points no solution may move
    sketch: [], // the points of "draw by points" (sketching.js)
    layers: Object.fromEntries(LAYERS.map((layer) => [layer.id, layer.shown])),
    families: Object.fromEntries(FAMILIES.map((family) => [family.id, true])), // the knot families whose regions are shown
    snap: Object.fromEntries(SNAPS.map((kind) => [kind.id, false])),
    tool: "edit",
    pointer: null, // the curve point under the pointer, for the readout
    connection: { state: "ok" }, // "ok" | "unreachable" | "retrying" (+ seconds)
    message: "",
    error: "",
  };
}

/** The methods the page asks the solver for: the ticked ones that can edit the curve (the
 * knots on degree 2 or more). */
export function methodsFor(state) {
  return usableMethods(editBase(state), state.methods);
}

/** Whether solving carries conditions (constraints or fixed control points). */
export function constrained(state) {
  return state.constraints.length > 0 || state.fixed.length > 0;
}

/** The conditions of the requests ({ constraints, fixed }, API names in api.js). */
export function conditions(state) {
  return { constraints: state.constraints, fixed: state.fixed };
}

/** The committed curve. */
export function currentCurve(state) {
  return state.history.present;
}

/** The curve edits of the pick start from (the committed one, or it with knots inserted). */
export function editBase(state) {
  return state.pick?.base ?? state.history.present;
}

/** The history keeps steps of the document: a curve and the conditions (pins, tangent locks,
 * fixed control points) it was edited under. `present` is the committed curve; the
 * conditions now are the state's own. */
function step(state) {
  return { curve: state.history.present, constraints: state.constraints, fixed: state.fixed };
}

/** `curve` committed on top of the history (redo cleared). */
export function commit(state, curve) {
  const { past } = state.history;
  return { ...state, history: { past: [...past, step(state)], present: curve, future: [] } };
}

/** New conditions as a step of their own (undo takes them back), the curve unchanged. */
export function commitConditions(state, constraints, fixed) {
  return { ...commit(state, state.history.present), constraints, fixed };
}

/** The last commit replaced by `curve` (another solution of the same drag, another nudge). */
export function replaceCommit(state, curve) {
  return { ...state, history: { ...state.history, present: curve } };
}

/** One step back, the curve with its conditions; the pick is dropped. */
export function undo(state) {
  const { past, future } = state.history;
  if (past.length === 0) {
    return state;
  }
  const back = past[past.length - 1];
  return {
    ...cleared(state),
    history: { past: past.slice(0, -1), present: back.curve, future: [step(state), ...future] },
    constraints: back.constraints,
    fixed: back.fixed,
  };
}

/** One step forward, the curve with its conditions; the pick is dropped. */
export function redo(state) {
  const { past, future } = state.history;
  if (future.length === 0) {
    return state;
  }
  const forward = future[0];
  return {
    ...cleared(state),
    history: { past: [...past, step(state)], present: forward.curve, future: future.slice(1) },
    constraints: forward.constraints,
    fixed: forward.fixed,
  };
}

/** A new curve to edit (history kept: loading is undoable, and undo gives the old curve its
 * conditions back); its conditions start empty. */
export function load(state, curve) {
  return { ...cleared(commit(state, curve)), family: null, constraints: [], fixed: [] };
}

/** The state without pick, regions, drag and re-choosable solutions. */
export function cleared(state) {
  return { ...state, pick: null, regions: null, drag: null, lastSolutions: null, drawing: null };
}

/** The state with `message` (info) or `error` shown, and nothing older. */
export function told(state, { message = "", error = "" }) {
  return { ...state, message: error ? "" : message, error };
}

/** Index of the solution with the smallest max deviation (the default choice). */
export function defaultChoice(solutions) {
  let best = 0;
  solutions.forEach((solution, index) => {
    if (solution.max_deviation < solutions[best].max_deviation) {
      best = index;
    }
  });
  return best;
}

/** The frame of the state with `frame` in place. */
export function withFrame(state, frame) {
  return { ...state, view: { ...state.view, frame } };
}
