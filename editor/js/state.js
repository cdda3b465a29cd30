// The editor's state as plain data, and the pure functions that make a new state from an
// old one. Nothing here draws or requests; main.js and interaction.js call these and then
// draw the result (event → new state → draw).

/** A fresh state editing `curve`. */
export function initialState(curve) {
  return {
    history: { past: [], present: curve, future: [] },
    drawing: null, // { path | polyline, knotPoints } of the committed curve
    pick: null, // { parameter, point }
    regions: null, // the /v1/shape/regions answer at the pick
    drag: null, // { target, solutions, nearest, chosen, preview, previewDrawing }
    lastSolutions: null, // after a release: { solutions, chosen, base, target } to re-choose
    methods: ["knots", "control_points"],
    message: "",
    error: "",
  };
}

/** The committed curve. */
export function currentCurve(state) {
  return state.history.present;
}

/** `curve` committed on top of the history (redo cleared). */
export function commit(state, curve) {
  const { past, present } = state.history;
  return { ...state, history: { past: [...past, present], present: curve, future: [] } };
}

/** The last commit replaced by `curve` (another solution of the same drag). */
export function replaceCommit(state, curve) {
  return { ...state, history: { ...state.history, present: curve } };
}

/** One step back; the pick is dropped. */
export function undo(state) {
  const { past, present, future } = state.history;
  if (past.length === 0) {
    return state;
  }
  return {
    ...cleared(state),
    history: { past: past.slice(0, -1), present: past[past.length - 1], future: [present, ...future] },
  };
}

/** One step forward; the pick is dropped. */
export function redo(state) {
  const { past, present, future } = state.history;
  if (future.length === 0) {
    return state;
  }
  return {
    ...cleared(state),
    history: { past: [...past, present], present: future[0], future: future.slice(1) },
  };
}

/** A new curve to edit (history kept: loading is undoable). */
export function load(state, curve) {
  return { ...cleared(commit(state, curve)), message: "", error: "" };
}

/** The state without pick, regions, drag and re-choosable solutions. */
export function cleared(state) {
  return { ...state, pick: null, regions: null, drag: null, lastSolutions: null, drawing: null };
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
