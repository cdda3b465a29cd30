// Picking a point of the curve: the nearest curve point to a press, the regions there (what
// a knot-pair drag reaches), and — when no knot can move there, as on one Bézier piece —
// knots inserted around it. The insertion does not change the curve's shape and is not an
// undo step of its own: it becomes part of the edit that follows (a click changes nothing).

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as store from "./store.js";
import { failureMessage, regionMethods, regionsAt } from "./committing.js";
import { drawingOf } from "./drawing.js";
import { PICK_RADIUS } from "./view.js";

/** The tolerance of a regions request that only asks whether a knot pair is there, in
 * drawing tolerances (its polygons are not drawn). */
const REGION_PROBE_TOLERANCE = 10;

/** Whether a knot pair moves the point at `t` of `curve` (whatever the constraints rule
 * out): from `regions` when it was asked with the knots method and no constraints, else by
 * asking. A 3D curve is asked in its x–y projection, whose regions are always drawn (the
 * same knots move the point of both). */
async function knotRegionAt(curve, t, regions, state) {
  const planar = geometry.dimension(curve) === 2;
  if (planar && regions?.ok && regionMethods(curve, state).includes("knots") && state.constraints.length === 0) return geometry.hasKnotRegion(regions.value);
  const probed = geometry.projected(curve);
  const probe = await api.regions(probed, t, REGION_PROBE_TOLERANCE * geometry.drawingTolerance(probed), { methods: ["knots"] });
  return probe.ok && geometry.hasKnotRegion(probe.value);
}

/** Picks the curve point nearest to `point` (curve coordinates; a 3D curve is picked in its
 * x–y projection). Resolves to whether a point was picked. */
export function pick(point) {
  return store.task(async () => {
    const state = store.get();
    const curve = model.currentCurve(state);
    const mine = store.nextGeneration();
    const found = await api.closestPoint(geometry.projected(curve), point);
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
    let picked = closest.point;
    if (geometry.dimension(curve) === 3) {
      // The 3D point there: a drag moves it in its x–y plane, keeping its z.
      const spatial = await api.evaluateAt(curve, [t]);
      if (!store.isCurrent(mine)) return false;
      if (!spatial.ok) {
        store.set({ ...store.get(), message: "", error: failureMessage(spatial.problem) });
        return false;
      }
      picked = spatial.value.points[0];
    }
    const knotsOn = geometry.usableMethods(curve, state.methods).includes("knots");
    let base = curve;
    let message = `Picked t = ${t.toPrecision(6)}. Drag the dot, or nudge it with the arrow keys.`;
    let regions = await regionsAt(curve, t, state);
    if (!store.isCurrent(mine)) return false;
    let drawing = store.get().drawing;
    if (knotsOn && !(await knotRegionAt(curve, t, regions, state))) {
      if (!store.isCurrent(mine)) return false;
      if (state.fixed.length > 0) {
        message = `No knot pair moves the point at t = ${t.toPrecision(4)}, and no knots are inserted while control points are fixed (their numbers would change). ${message}`;
      } else {
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
          const [again, marks] = await Promise.all([regionsAt(base, t, state), drawingOf(base)]);
          if (!store.isCurrent(mine)) return false;
          regions = again;
          if (!marks.problem) drawing = { ...drawing, ...marks };
        }
      }
    }
    const now = store.get();
    store.set({
      ...now,
      drawing,
      pick: { parameter: t, point: picked, base },
      regions: regions?.ok ? regions.value : null,
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
