// What changes the committed curve: a drag's or a nudge's solution, a dragged control
// point, another solution from the list, undo and redo, a loaded curve. Each first asks the
// API for the new curve's drawing and changes the state only once it has it: when the
// service does not answer, nothing is committed and the drawing stays as it was.

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as store from "./store.js";
import { drawingOf } from "./drawing.js";
import { describeProblem } from "./problems.js";
import { fit, needsFit } from "./viewport.js";

/** How far (pixels, at the zoom of the request) a drawn region's edge may be from the true
 * boundary. */
const REGION_PIXELS = 0.5;

/** The direct pairs' regions are asked within this fraction of the control polygon's size
 * at least (about a pixel and a half on the fitted sample): the service's outline of a
 * folded direct pair can take seconds at finer tolerances (the sample cubic's at t = 0.42:
 * 0.2 s at 1/1000, 3 s at 1/5000, over its 10 s limit at 1/10000), so zoomed in they are
 * drawn within this instead of half a pixel. */
const DIRECT_REGION_FRACTION = 2e-3;

/** Milliseconds the page waits for the direct pairs' regions before it shows the pick
 * without them (the legend says so). */
const DIRECT_REGION_BUDGET = 2500;

/** Teeth of the curvature comb: TEETH_PER_SPAN per knot span, within these bounds. */
const FEWEST_TEETH = 200;
const MOST_TEETH = 2000;
const TEETH_PER_SPAN = 8;

/** The methods whose reachable sets the page asks for on `curve` in `state`: the ticked
 * knots and weights that can edit it; on a 3D curve only the knots (whose families the
 * legend explains; their regions are drawn where they lie in the view's plane:
 * geometry.familyEntries). */
export function regionMethods(curve, state) {
  const methods = geometry.usableMethods(curve, state.methods).filter((method) => method === "knots" || method === "weights");
  return geometry.dimension(curve) === 2 ? methods : methods.filter((method) => method === "knots");
}

/** The regions answer at `parameter` of `curve` for the methods and conditions of `state`
 * (under constraints only the pairs whose edits surely keep them), drawn within
 * REGION_PIXELS at its frame, the direct pairs' within DIRECT_REGION_FRACTION of the curve's
 * size at least (a request of their own, merged into the answer's `families`; each family
 * entry gets the `tolerance` it was drawn within); null when no region is drawn. When only
 * the direct pairs' request fails, the legend says so and the rest is drawn. */
export async function regionsAt(curve, parameter, state) {
  const methods = regionMethods(curve, state);
  if (methods.length === 0) return null;
  const conditions = model.conditions(state);
  const tolerance = REGION_PIXELS / state.view.frame.scale;
  const [low, high] = geometry.extent(curve);
  const directTolerance = Math.max(tolerance, DIRECT_REGION_FRACTION * Math.max(high[0] - low[0], high[1] - low[1]));
  const knots = methods.includes("knots");
  const families = knots ? geometry.knotFamiliesOf(curve) : [];
  const others = families.filter((family) => family !== "direct");
  const mainMethods = others.length > 0 ? methods : methods.filter((method) => method !== "knots");
  const [main, direct] = await Promise.all([
    mainMethods.length > 0 ? api.regions(curve, parameter, tolerance, { methods: mainMethods, knotFamilies: others.length > 0 ? others : null, ...conditions }) : null,
    families.includes("direct") ? api.regions(curve, parameter, directTolerance, { methods: ["knots"], knotFamilies: ["direct"], ...conditions, budget: DIRECT_REGION_BUDGET }) : null,
  ]);
  if (main && !main.ok) return main;
  const value = main ? { ...main.value } : { candidates: [], families: [], weight_regions: [] };
  value.families = (value.families ?? []).map((entry) => ({ ...entry, tolerance }));
  if (direct?.ok) {
    value.families.push(...direct.value.families.map((entry) => ({ ...entry, tolerance: directTolerance })));
  } else if (direct) {
    if (!main && direct.problem.type !== api.OVER_BUDGET) return direct;
    const reason = `not drawn: ${direct.problem.type === api.OVER_BUDGET ? direct.problem.title : direct.problem.title.toLowerCase()}`;
    value.families.push({ family: "direct", applicable: false, reason, span: 0, control_points: [], regions: [], tolerance: directTolerance });
  }
  return { ok: true, value };
}

/** The marks of `state`'s constraints on `curve` ({ point, tangent } each, same order) and
 * the curvature comb's teeth ({ points, teeth: the unit normals times the curvature }), when
 * shown: one evaluate request each. */
async function overlays(curve, state) {
  const [lo, hi] = geometry.domain(curve);
  const spans = geometry.knotValuesInDomain(curve).length - 1;
  const teeth = Math.min(Math.max(TEETH_PER_SPAN * spans, FEWEST_TEETH), MOST_TEETH);
  const comb = state.layers.comb ? Array.from({ length: teeth + 1 }, (_, i) => lo + ((hi - lo) * i) / teeth) : [];
  const [marks, combAnswer] = await Promise.all([
    state.constraints.length > 0 ? api.evaluateWithCurvature(curve, state.constraints.map((c) => c.parameter)) : null,
    comb.length > 0 ? api.evaluateWithCurvature(curve, comb) : null,
  ]);
  return {
    conditionMarks: marks?.ok ? marks.value.points.map((point, i) => ({ point, tangent: marks.value.derivatives[0][i] })) : null,
    comb: combAnswer?.ok ? geometry.combOf(combAnswer.value) : null,
  };
}

/** The drawing of `curve` and, for the region methods of `state` (regionMethods), its
 * reachable regions at `parameter`, the marks of its constraints and its curvature comb;
 * or { problem } when the drawing cannot be had. */
export async function drawn(curve, parameter, state) {
  const wantsRegions = parameter !== undefined;
  const [drawing, regions, extra] = await Promise.all([drawingOf(curve), wantsRegions ? regionsAt(curve, parameter, state) : null, overlays(curve, state)]);
  if (drawing.problem) return { problem: drawing.problem };
  return {
    drawing: { ...drawing, ...extra },
    regions: regions?.ok ? regions.value : null,
    regionsProblem: regions && !regions.ok ? regions.problem : null,
  };
}

/** The message for a failed request; none when the service did not answer (the banner
 * says so). */
export function failureMessage(problem, prefix = "", source = null) {
  if (problem.type === api.NETWORK_ERROR) return "";
  return `${prefix}${describeProblem(problem, source)}`;
}

/** The state `state` telling `error` (after a failure; everything else unchanged). */
export function failed(state, problem, prefix) {
  return { ...state, drag: null, message: "", error: failureMessage(problem, prefix) };
}

/** The frame for showing `curve`: refitted when `always`, or when the curve would leave the
 * view or be too small in it. */
function frameFor(state, curve, always) {
  const box = geometry.extent(curve);
  return always || needsFit(state.view.frame, state.view.size, box) ? fit(box, state.view.size) : state.view.frame;
}

/**
 * Commits `curve` (on top of the history, or replacing the last commit with `replace`)
 * once its drawing is in. `pick` ({ parameter, point, … }) stays on the new curve; the
 * other fields go into the state as they are. Resolves to whether it committed.
 */
export function commitCurve(curve, { replace = false, pick = null, lastSolutions = null, family = null, lastTarget = null, message = "" }) {
  return store.task(async () => {
    const mine = store.nextGeneration();
    const result = await drawn(curve, pick?.parameter, store.get());
    if (!store.isCurrent(mine)) return false;
    const state = store.get();
    if (result.problem) {
      store.set(failed(state, result.problem, "Nothing committed: "));
      return false;
    }
    const next = replace ? model.replaceCommit(state, curve) : model.commit(state, curve);
    store.set({
      ...next,
      drawing: result.drawing,
      regions: result.regions,
      pick: pick ? { ...pick, base: curve } : null,
      drag: null,
      lastSolutions,
      family,
      lastTarget,
      message,
      error: result.regionsProblem ? describeProblem(result.regionsProblem) : "",
    });
    return true;
  });
}

/** Another solution `index` of the last drag's list, replacing what the drag committed. */
export function choose(index) {
  const state = store.get();
  const entry = state.lastSolutions;
  if (!entry || state.drag || index === entry.chosen || !entry.solutions[index]) return Promise.resolve(false);
  const solution = entry.solutions[index];
  return commitCurve(geometry.applySolution(entry.base, solution), {
    replace: true,
    pick: { parameter: state.pick.parameter, point: solution.point },
    lastSolutions: { ...entry, chosen: index },
    family: geometry.familyOf(solution),
    lastTarget: entry.target,
    message: `Committed: ${geometry.describeSolution(solution)}.`,
  });
}

/** Undo or redo (`step` is state.undo or state.redo); refits the view when needed. */
export function historyStep(step) {
  const state = store.get();
  if (state.drag) return Promise.resolve(false);
  const next = step(state);
  if (next === state) return Promise.resolve(false);
  return store.task(async () => {
    const mine = store.nextGeneration();
    const curve = model.currentCurve(next);
    const result = await drawn(curve, undefined, next);
    if (!store.isCurrent(mine)) return false;
    const now = store.get();
    if (result.problem) {
      store.set(failed(now, result.problem, "Cannot show that curve: "));
      return false;
    }
    store.set({ ...next, drawing: result.drawing, view: { ...now.view, frame: frameFor(now, curve, false) }, message: "", error: "" });
    return true;
  });
}

/** Loads `curve` (checked by drawing it), fitting the view to it. `source` points errors
 * into the text it came from. */
export function loadCurve(curve, message, source = null) {
  return store.task(async () => {
    const mine = store.nextGeneration();
    const result = await drawn(curve, undefined, { ...store.get(), constraints: [], fixed: [] });
    if (!store.isCurrent(mine)) return false;
    const state = store.get();
    if (result.problem) {
      store.set({ ...state, message: "", error: failureMessage(result.problem, "Cannot load this curve: ", source) });
      return false;
    }
    const refusal = geometry.methodsNote(curve);
    store.set({
      ...model.load(state, curve),
      drawing: result.drawing,
      view: { ...state.view, frame: frameFor(state, curve, true) },
      message: refusal ? `${message} ${refusal}` : message,
      error: "",
    });
    return true;
  });
}

/** Draws the committed curve again (at the start, after the key changed, when the service
 * is back), keeping the pick when there is one. */
export function refresh(message = "") {
  return store.task(async () => {
    const mine = store.nextGeneration();
    const state = store.get();
    const curve = model.editBase(state);
    const result = await drawn(curve, state.pick?.parameter, state);
    if (!store.isCurrent(mine)) return false;
    const now = store.get();
    if (result.problem) {
      store.set({ ...now, message: "", error: failureMessage(result.problem) });
      return false;
    }
    const refusal = geometry.methodsNote(model.currentCurve(now));
    store.set({ ...now, drawing: result.drawing, regions: result.regions, message: message || (refusal ?? ""), error: result.regionsProblem ? describeProblem(result.regionsProblem) : "" });
    return true;
  });
}
