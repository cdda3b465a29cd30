// Moving the picked point exactly: to typed coordinates, or nudged by arrow keys (one pixel,
// ten with Shift). Each solves for the target with the family the point was last moved by
// (or the default choice) and commits; nudges in a row are one undo step.

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as store from "./store.js";
import { commitCurve, failed } from "./committing.js";
import { isDragging } from "./dragging.js";

/** Pixel steps not yet solved (key repeats arrive faster than answers). */
let pendingNudge = null;

/** Moves the picked point to `target`; `merge` folds it into the previous nudge's commit,
 * `nudging` marks it as a nudge (so that the next one may merge). */
function moveTo(target, { merge = false, nudging = false } = {}) {
  const state = store.get();
  if (!state.pick || isDragging()) return Promise.resolve(false);
  const base = model.editBase(state);
  const { parameter } = state.pick;
  const lifted = geometry.lifted(target, state.pick.point);
  return store.task(async () => {
    const mine = store.currentGeneration();
    const answer = await api.solve(base, parameter, lifted, { methods: model.methodsFor(state), family: state.family, conditions: model.conditions(state) });
    if (!store.isCurrent(mine)) return false;
    if (!answer.ok) {
      store.set(failed(store.get(), answer.problem, "Nothing committed: "));
      return false;
    }
    const nearest = answer.value.nearest ?? null;
    const solutions = answer.value.solutions.length > 0 ? answer.value.solutions : nearest?.solutions ?? [];
    // The kept family's solution (of a folded pair's several, the smallest knot move).
    const chosen = state.family ? geometry.indexInFamily(solutions, state.family, { knots: base.knots }) : model.defaultChoice(solutions);
    if (chosen < 0 || solutions.length === 0) {
      store.set({ ...store.get(), message: "No solution moves the point towards this target.", error: "" });
      return false;
    }
    const solution = solutions[chosen];
    const done = await commitCurve(geometry.applySolution(base, solution), {
      replace: merge,
      pick: { parameter, point: solution.point, nudged: nudging },
      lastSolutions: { solutions, chosen, nearest, excluded: answer.value.excluded ?? [], base, target: lifted },
      family: geometry.familyOf(solution),
      lastTarget: lifted,
      message: `Moved to (${target.map((v) => +v.toPrecision(8)).join(", ")}): ${geometry.describeSolution(solution)}.`,
    });
    return done;
  });
}

/** Moves the picked point to typed coordinates. */
export function moveToTyped(x, y) {
  if (!Number.isFinite(x) || !Number.isFinite(y)) {
    store.set({ ...store.get(), message: "", error: "Type two numbers for the target's x and y." });
    return Promise.resolve(false);
  }
  return moveTo([x, y]);
}

/** Nudges the picked point's target by `pixels` [dx, dy] (screen pixels, y down). */
export async function nudge(pixels) {
  if (!store.get().pick || isDragging()) return false;
  if (pendingNudge) {
    pendingNudge[0] += pixels[0];
    pendingNudge[1] += pixels[1];
    return true;
  }
  pendingNudge = pixels.slice();
  let moved = false;
  while (pendingNudge) {
    const [dx, dy] = pendingNudge;
    const state = store.get();
    if (!state.pick) break;
    const scale = state.view.frame.scale;
    const from = state.lastTarget && state.pick.nudged ? state.lastTarget : state.pick.point;
    const target = [from[0] + dx / scale, from[1] - dy / scale];
    // Only the pending steps from now on: further key presses add to a new batch.
    pendingNudge = [0, 0];
    moved = (await moveTo(target, { merge: Boolean(state.pick.nudged), nudging: true })) || moved;
    if (pendingNudge[0] === 0 && pendingNudge[1] === 0) pendingNudge = null;
  }
  pendingNudge = null;
  return moved;
}
