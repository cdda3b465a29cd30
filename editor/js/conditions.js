// The conditions every edit keeps: pins (the curve point at a parameter stays where it is),
// tangent locks (the tangent's direction at a parameter stays) and fixed control points (no
// solution moves them). The Pin and Tangent tools add and remove them with a click; the
// solver meets them on every solve (api.solve sends them as `constraints` and
// `fixed_control_points`), and drags under conditions solve the whole curve (dragging.js).

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as store from "./store.js";
import { failureMessage, refresh } from "./committing.js";
import { PICK_RADIUS } from "./view.js";

/** The most conditions the service takes in one request (API: at most 32 constraints). */
const MOST_CONSTRAINTS = 32;

/** The state with new `constraints` and `fixed` control points, a step of the history (undo
 * takes them back): the pick's solutions list belongs to the old conditions and is dropped. */
function withConditions(state, constraints, fixed, message) {
  return { ...model.commitConditions(state, constraints, fixed), lastSolutions: null, family: null, message, error: "" };
}

/** Draws the curve again with the new conditions (their marks, and the regions at the pick,
 * which follow them). */
function redrawn(next) {
  store.nextGeneration();
  store.set(next);
  return refresh(next.message);
}

/** Fixes control point `index`, or frees it when it is fixed. */
export function toggleFixed(index) {
  const state = store.get();
  if (state.drag) return Promise.resolve(false);
  const fixed = state.fixed.includes(index) ? state.fixed.filter((k) => k !== index) : [...state.fixed, index].sort((a, b) => a - b);
  const message = fixed.length > state.fixed.length ? `Control point ${index} is fixed: no solution moves it.` : `Control point ${index} is free again.`;
  return redrawn(withConditions(state, state.constraints, fixed, message));
}

/**
 * A click of the Pin (`order` 0) or Tangent (`order` 1) tool at `point` (curve coordinates):
 * the condition at the nearest curve point (a tangent lock on a pin or on the picked point:
 * at its parameter), or, when one of that order is already within PICK_RADIUS pixels of it,
 * that one removed.
 */
export function toggleAt(point, order) {
  return store.task(async () => {
    const state = store.get();
    if (state.drag) return false;
    const curve = model.currentCurve(state);
    const mine = store.currentGeneration();
    const found = await api.closestPoint(geometry.projected(curve), point);
    if (!store.isCurrent(mine)) return false;
    if (!found.ok) {
      store.set({ ...store.get(), message: "", error: failureMessage(found.problem) });
      return false;
    }
    const closest = found.value.results[0];
    const scale = state.view.frame.scale;
    if (closest.distance * scale > PICK_RADIUS) {
      store.set({ ...store.get(), message: `Click on the curve (within ${PICK_RADIUS} pixels of it) to ${order === 0 ? "pin a point" : "lock a tangent"}.`, error: "" });
      return false;
    }
    const now = store.get();
    const marks = now.drawing?.conditionMarks ?? [];
    const near = now.constraints.findIndex((c, i) => {
      const mark = marks[i]?.point;
      return c.order === order && mark && Math.hypot(mark[0] - closest.point[0], mark[1] - closest.point[1]) * scale <= PICK_RADIUS;
    });
    const what = order === 0 ? "pin" : "tangent lock";
    if (near >= 0) {
      const constraints = now.constraints.filter((_, i) => i !== near);
      return redrawn(withConditions(now, constraints, now.fixed, `Removed the ${what} at t = ${now.constraints[near].parameter.toPrecision(6)}.`));
    }
    if (now.constraints.length >= MOST_CONSTRAINTS) {
      store.set({ ...now, message: "", error: `At most ${MOST_CONSTRAINTS} pins and tangent locks.` });
      return false;
    }
    // A tangent lock clicked on a pin or on the picked point goes exactly there.
    const onto = order === 1 ? atMark(now, closest.point, scale) : null;
    const t = onto ?? closest.parameter;
    if (now.pick && order === 0 && t === now.pick.parameter) {
      store.set({ ...now, message: "The picked point is moving: pin another point.", error: "" });
      return false;
    }
    const added = order === 0 ? { parameter: t, order: 0 } : { parameter: t, order: 1, direction_only: true };
    const message = order === 0
      ? `Pinned the curve at t = ${t.toPrecision(6)}: every edit keeps this point.`
      : `Locked the tangent's direction at t = ${t.toPrecision(6)}: every edit keeps it.`;
    // A pick on the pinned parameter would be refused (the point cannot both move and stay).
    const pick = now.pick && order === 0 && now.pick.parameter === t ? null : now.pick;
    return redrawn({ ...withConditions(now, [...now.constraints, added], now.fixed, message), pick });
  });
}

/** The parameter of the pin, or else of the picked point, within PICK_RADIUS pixels of
 * `point`; null when there is none. */
function atMark(state, point, scale) {
  const near = (mark) => mark && Math.hypot(mark[0] - point[0], mark[1] - point[1]) * scale <= PICK_RADIUS;
  const marks = state.drawing?.conditionMarks ?? [];
  const pin = state.constraints.findIndex((c, i) => c.order === 0 && near(marks[i]?.point));
  if (pin >= 0) return state.constraints[pin].parameter;
  return state.pick && near(state.pick.point) ? state.pick.parameter : null;
}

/** Removes every pin, tangent lock and fixed control point. */
export function clearAll() {
  const state = store.get();
  if (state.drag || !model.constrained(state)) return Promise.resolve(false);
  return redrawn(withConditions(state, [], [], "No pins, tangent locks or fixed control points any more."));
}
