// The knot strip under the drawing: the knot vector on a line (repeated knots stacked), the
// knots a solution changes highlighted, their new values during a drag, and a label that is
// cut to the strip's width.

import { fullKnots, isTrimmed } from "./geometry.js";
import { element, layer, redraw, setAttribute } from "./render.js";
import { editBase } from "./state.js";

const HEIGHT = 56;
const MARGIN = 24;
/** About how wide one character of the label is, in pixels (11 px system font). */
const CHARACTER_WIDTH = 6.4;

/** Full indices of the knots the chosen solution (during or after a drag) changes, and the
 * new values [[index, value]] during a drag. */
function changes(state) {
  const drag = state.drag;
  if (drag?.previewKnots) {
    return { changed: new Set(drag.previewKnots.map(([index]) => index)), preview: drag.previewKnots };
  }
  const entry = state.lastSolutions;
  const chosen = entry?.solutions[entry.chosen];
  if (chosen?.method === "knots") {
    const offset = isTrimmed(entry.base) ? 1 : 0;
    return { changed: new Set(chosen.changed_knots.map((index) => index + offset)), preview: null };
  }
  return { changed: new Set(), preview: null };
}

/** The label "knots (n): u0, u1, …", cut with an ellipsis to `room` pixels. */
export function stripLabel(knots, room) {
  const text = `knots (${knots.length}): ${knots.map((u) => +u.toPrecision(4)).join(", ")}`;
  const fits = Math.max(Math.floor(room / CHARACTER_WIDTH), 12);
  return text.length <= fits ? text : `${text.slice(0, fits - 1)}…`;
}

/** Draws the strip of `state` into the <svg> `strip`, `width` pixels wide. */
export function drawStrip(state, strip, width) {
  setAttribute(strip, "viewBox", `0 0 ${width} ${HEIGHT}`);
  const base = editBase(state);
  const knots = fullKnots(base);
  const { changed, preview } = changes(state);
  const low = Math.min(...knots, ...(preview ?? []).map(([, u]) => u));
  const high = Math.max(...knots, ...(preview ?? []).map(([, u]) => u));
  const span = high - low || 1;
  const x = (u) => MARGIN + ((u - low) / span) * (width - 2 * MARGIN);
  const ticks = layer(strip, "ticks");
  const moved = layer(strip, "moved");
  redraw(ticks, [knots.join(), changed.size > 0 && !preview ? [...changed].join() : "", low, high, width], (group) => {
    element("line", { x1: x(low), y1: 48, x2: x(high), y2: 48, class: "axis" }, group);
    const stack = new Map();
    knots.forEach((u, index) => {
      const level = stack.get(u) ?? 0;
      stack.set(u, level + 1);
      element("circle", {
        cx: x(u), cy: 48 - 7 * level, r: 3,
        class: changed.has(index) && !preview ? "knot-tick changed" : "knot-tick",
      }, group);
    });
    const label = element("text", { x: MARGIN, y: 12, class: "strip-label" }, group);
    label.textContent = stripLabel(knots, width - 2 * MARGIN);
  });
  redraw(moved, [preview, low, high, width], (group) => {
    for (const [, u] of preview ?? []) {
      element("circle", { cx: x(u), cy: 48, r: 4, class: "knot-tick preview" }, group);
    }
  });
}
