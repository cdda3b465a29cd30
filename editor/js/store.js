// The one state of the page and the bookkeeping around changing it: every change is drawn
// at once; `busy` counts the requests in flight (shown as body[data-busy] for tests); the
// generation is bumped by every change that makes older answers meaningless (a commit, an
// undo, a new pick), and an answer that arrives for an older generation is dropped.

let state = null;
let drawState = () => {};
let busy = 0;
let generation = 0;

/** Starts with `initial`, drawn by `draw(state)` after every change. */
export function setup(initial, draw) {
  state = initial;
  drawState = draw;
  draw(state);
}

/** The state now. */
export function get() {
  return state;
}

/** Replaces the state and draws it. */
export function set(next) {
  state = next;
  drawState(state);
}

/** A new generation: answers asked for before it are dropped (see `isCurrent`). */
export function nextGeneration() {
  generation += 1;
  return generation;
}

/** The generation now (for requests that must not outlive a change, but make none). */
export function currentGeneration() {
  return generation;
}

/** Whether `mark` (from `nextGeneration` or `currentGeneration`) is still the generation. */
export function isCurrent(mark) {
  return mark === generation;
}

/** Counts a request in flight (+1) or finished (−1). */
export function busyBy(delta) {
  busy += delta;
  document.body.dataset.busy = busy > 0 ? "true" : "false";
}

/** Runs `work` counted as busy; an unexpected exception becomes an error message. */
export async function task(work) {
  busyBy(1);
  try {
    return await work();
  } catch (error) {
    console.error(error);
    set({ ...state, message: "", error: `Unexpected error: ${error.message}` });
    return undefined;
  } finally {
    busyBy(-1);
  }
}
