// The editor's state as plain data, and the pure functions that make a new state from an
// old one. Nothing here draws or requests; the controller calls these and then draws the
// result (event → new state → draw).

import { LAYERS, METHODS, SNAPS } from "./options.js";
import { domain, usableMethods } from "./geometry.js";

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
    snap: Object.fromEntries(SNAPS.map((kind) => [kind.id, false])),
    tool: "edit",
    pointer: null, // the curve point under the pointer, for the readout
    connection: { state: "ok" }, // "ok" | "unreachable" | "retrying" (+ seconds)
    message: "",
    error: "",
  };
}

/** The methods the page asks the solver for: the ticked ones that can edit the curve (the
 * knot pairs only on planar cubics). */
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

/** The conditions that still fit `curve` (after undo or redo to another curve): parameters
 * inside its domain, control point indices among its own. */
function fitting(state, curve) {
  const [lo, hi] = domain(curve);
  const constraints = state.constraints.filter((c) => c.parameter >= lo && c.parameter <= hi);
  const fixed = state.fixed.filter((index) => index < curve.control_points.length);
  return constraints.length === state.constraints.length && fixed.length === state.fixed.length ? state : { ...state, constraints, fixed };
}

/** The committed curve. */
export function currentCurve(state) {
  return state.history.present;
}

/** The curve edits of the pick start from (the committed one, or it with knots inserted). */
export function editBase(state) {
  return state.pick?.base ?? state.history.present;
}

/** `curve` committed on top of the history (redo cleared). */
export function commit(state, curve) {
  const { past, present } = state.history;
  return { ...state, history: { past: [...past, present], present: curve, future: [] } };
}

/** The last commit replaced by `curve` (another solution of the same drag, another nudge). */
export function replaceCommit(state, curve) {
  return { ...state, history: { ...state.history, present: curve } };
}

/** One step back; the pick is dropped. */
export function undo(state) {
  const { past, present, future } = state.history;
  if (past.length === 0) {
    return state;
  }
  return fitting({
    ...cleared(state),
    history: { past: past.slice(0, -1), present: past[past.length - 1], future: [present, ...future] },
  }, past[past.length - 1]);
}

/** One step forward; the pick is dropped. */
export function redo(state) {
  const { past, present, future } = state.history;
  if (future.length === 0) {
    return state;
  }
  return fitting({
    ...cleared(state),
    history: { past: [...past, present], present: future[0], future: future.slice(1) },
  }, future[0]);
}

/** A new curve to edit (history kept: loading is undoable); its conditions start empty. */
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
