// Picking a point of the curve: the nearest curve point to a press, the regions there (what
// a knot-pair drag reaches), and — when no knot can move there, as on one Bézier piece —
// knots inserted around it. The insertion does not change the curve's shape and is not an
// undo step of its own: it becomes part of the edit that follows (a click changes nothing).

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as store from "./store.js";
import { failureMessage, regionsAt } from "./committing.js";
import { drawingOf } from "./drawing.js";
import { PICK_RADIUS } from "./view.js";

/** Picks the curve point nearest to `point` (curve coordinates). Resolves to whether a
 * point was picked. */
export function pick(point) {
  return store.task(async () => {
    const state = store.get();
    const curve = model.currentCurve(state);
    const refusal = geometry.editingRefusal(curve);
    if (refusal) {
      store.set({ ...state, message: refusal, error: "" });
      return false;
    }
    const mine = store.nextGeneration();
    const found = await api.closestPoint(curve, point);
    if (!store.isCurrent(mine)) return false;
    if (!found.ok) {
      store.set({ ...store.get(), message: "", error: failureMessage(found.problem) });
      return false;
    }
    const closest = found.value.results[0];
    if (closest.distance * store.get().view.frame.scale > PICK_RADIUS) {
      store.set({ ...model.cleared(store.get()), drawing: store.get().drawing, message: `Press on the curve (within ${PICK_RADIUS} pixels of it) to pick a point.`, error: "" });
      return false;
    }
    const t = closest.parameter;
    const knotsOn = state.methods.includes("knots");
    let base = curve;
    let message = `Picked t = ${t.toPrecision(6)}. Drag the dot, or nudge it with the arrow keys.`;
    let regions = knotsOn ? await regionsAt(curve, t, state.view.frame) : null;
    if (!store.isCurrent(mine)) return false;
    let drawing = store.get().drawing;
    if (knotsOn && (!regions.ok || !geometry.hasUsableRegion(curve, regions.value))) {
      const refined = await api.insertKnotsForEditing(curve, t);
      if (!store.isCurrent(mine)) return false;
      if (!refined.ok) {
        store.set({ ...store.get(), message: "", error: failureMessage(refined.problem, "This point cannot be edited: ") });
        return false;
      }
      if (refined.value.inserted.length > 0) {
        base = refined.value.curve;
        const values = refined.value.inserted.map((u) => +u.toPrecision(4)).join(", ");
        message = `No knot could move near t = ${t.toPrecision(4)}: inserted knots ${values} (the same curve, more control points; undone with the edit). Drag the dot.`;
        const [again, marks] = await Promise.all([regionsAt(base, t, state.view.frame), drawingOf(base)]);
        if (!store.isCurrent(mine)) return false;
        regions = again;
        if (!marks.problem) drawing = marks;
      }
    }
    const now = store.get();
    store.set({
      ...now,
      drawing,
      pick: { parameter: t, point: closest.point, base },
      regions: regions?.ok ? geometry.reachableRegions(base, regions.value) : null,
      drag: null,
      lastSolutions: null,
      family: null,
      lastTarget: null,
      message,
      error: regions && !regions.ok ? failureMessage(regions.problem) : "",
    });
    return true;
  });
}

/** Drops the pick (a click on the background, or Esc without a drag). */
export function dropPick() {
  const state = store.get();
  if (!state.pick || state.drag) return;
  store.nextGeneration();
  store.set({ ...state, pick: null, regions: null, lastSolutions: null, family: null, lastTarget: null, message: "", error: "" });
}
