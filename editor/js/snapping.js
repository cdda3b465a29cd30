// Snapping: a dragged point is pulled onto a control point or onto the curve's point at a
// knot when it comes within a few pixels of one, else onto the grid; each kind can be turned
// off. Pure: curve coordinates in, curve coordinates out.

import { gridStep, toScreen } from "./viewport.js";

/** How close (pixels) a pole or knot point must be to pull the dragged point onto it. */
export const SNAP_PIXELS = 8;

/** The nearest of `points` within SNAP_PIXELS of `point` on screen, or null. */
function nearestWithin(frame, point, points, skip) {
  const [px, py] = toScreen(frame, point);
  let best = null;
  let bestDistance = SNAP_PIXELS;
  points.forEach((candidate, index) => {
    if (index === skip) return;
    const [cx, cy] = toScreen(frame, candidate);
    const distance = Math.hypot(cx - px, cy - py);
    if (distance <= bestDistance) {
      best = candidate;
      bestDistance = distance;
    }
  });
  return best;
}

/**
 * `point` snapped as `settings` ({ grid, poles, knots } booleans) allow: onto the nearest
 * pole (but pole `skipPole`, the one being dragged) or knot point within reach, else onto
 * the nearest grid point. Returns { point, to } with `to` one of "pole", "knot", "grid" or
 * null (not snapped).
 */
export function snap(point, settings, { frame, poles = [], knotPoints = [], skipPole = -1 }) {
  if (settings.poles) {
    const pole = nearestWithin(frame, point, poles, skipPole);
    if (pole) return { point: [pole[0], pole[1]], to: "pole" };
  }
  if (settings.knots) {
    const knot = nearestWithin(frame, point, knotPoints, -1);
    if (knot) return { point: [knot[0], knot[1]], to: "knot" };
  }
  if (settings.grid) {
    const step = gridStep(frame);
    return { point: point.map((value) => roundTo(value, step)), to: "grid" };
  }
  return { point, to: null };
}

/** `value` rounded to a multiple of `step`, without the roundoff of `k·step` (0.1·3). */
function roundTo(value, step) {
  const multiple = Math.round(value / step);
  const digits = Math.max(0, -Math.floor(Math.log10(step)) + 1);
  return Number((multiple * step).toFixed(Math.min(digits, 15)));
}
