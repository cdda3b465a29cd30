// "Draw by points": with the Points tool each click adds a point; Finish makes the curve
// through them (/v1/curves/interpolate) or, with a tolerance, a curve within it of every
// point with fewer control points (/v1/curves/approximate), and loads it as the curve to edit
// (undoable, like any loaded curve).

import * as api from "./api.js";
import * as store from "./store.js";
import { failureMessage, loadCurve } from "./committing.js";

/** The most points the page collects (the service takes up to its `max_fit_points`). */
const MOST_POINTS = 1000;

function told(state, sketch, message) {
  return { ...state, sketch, message, error: "" };
}

const howMany = (count) => `${count} point${count === 1 ? "" : "s"}`;

/** Adds `point` (curve coordinates) to the points being drawn. */
export function addPoint(point) {
  const state = store.get();
  if (state.sketch.length >= MOST_POINTS) {
    store.set({ ...state, message: "", error: `At most ${MOST_POINTS} points.` });
    return;
  }
  const last = state.sketch[state.sketch.length - 1];
  if (last && last[0] === point[0] && last[1] === point[1]) return; // a double click
  const sketch = [...state.sketch, [point[0], point[1]]];
  store.set(told(state, sketch, `${howMany(sketch.length)}: Finish (Enter) makes the curve through them; Backspace drops the last.`));
}

/** Drops the last point drawn. */
export function dropLast() {
  const state = store.get();
  if (state.sketch.length === 0) return;
  const sketch = state.sketch.slice(0, -1);
  store.set(told(state, sketch, howMany(sketch.length)));
}

/** Forgets the points drawn. */
export function discard() {
  store.set(told(store.get(), [], "The points are discarded."));
}

/** Makes the curve of the points drawn: through them, or within `toleranceText` (a number;
 * empty for interpolation) of them. Resolves to whether a curve was loaded. */
export function finish(toleranceText) {
  const state = store.get();
  const points = state.sketch;
  if (points.length < 2) {
    store.set({ ...state, message: "", error: "Click at least two points with the Points tool first." });
    return Promise.resolve(false);
  }
  const text = toleranceText.trim();
  const tolerance = text === "" ? null : Number(text);
  if (tolerance !== null && !(Number.isFinite(tolerance) && tolerance > 0)) {
    store.set({ ...state, message: "", error: "The tolerance must be a positive number (or empty, for a curve through every point)." });
    return Promise.resolve(false);
  }
  return store.task(async () => {
    const answer = tolerance === null ? await api.interpolate(points) : await api.approximate(points, tolerance);
    if (!answer.ok) {
      store.set({ ...store.get(), message: "", error: failureMessage(answer.problem, "No curve from these points: ") });
      return false;
    }
    const curve = answer.value.curve;
    const how = tolerance === null
      ? `through ${howMany(points.length)}`
      : `within ${tolerance} of ${howMany(points.length)} (largest distance ${answer.value.max_error.toPrecision(3)})`;
    const loaded = await loadCurve(curve, `A curve ${how}: ${curve.control_points.length} control points, degree ${curve.degree}. Undo goes back.`);
    if (loaded) store.set({ ...store.get(), sketch: [], tool: "edit" });
    return loaded;
  });
}
