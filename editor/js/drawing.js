// The drawing of a curve, from the API: an SVG path of its Bézier pieces when SVG can draw
// it exactly (planar, non-rational, degree <= 3), else a polyline certified within a small
// tolerance (rational and 3D curves, the latter in their x–y projection), plus the curve's
// points at its knots. Plain samples only where the certified polyline is refused (a jump).
// A drag's preview of a curve SVG cannot draw exactly (rational, 3D, degree above 3) is
// computed in the page instead (sampledCurve: de Boor's algorithm on the solution's knots,
// poles and weights), so that a move costs one request (the solve) and not two; only the
// preview is drawn that way, the committed curve always from the API.

import * as api from "./api.js";
import * as geometry from "./geometry.js";

/** Samples of the fallback polyline. */
const FALLBACK_SAMPLES = 512;

/** The drawing of `curve`: an SVG path (Bézier pieces) or a certified polyline, and the
 * curve's points at its knots. */
export async function drawingOf(curve, { marks = true } = {}) {
  const exact = geometry.dimension(curve) === 2 && !curve.weights && curve.degree <= 3;
  const tolerance = geometry.drawingTolerance(curve);
  const [first, knots] = await Promise.all([
    exact ? api.bezier(curve) : api.evaluatePolyline(curve, tolerance),
    marks ? api.evaluateAt(curve, geometry.knotValuesInDomain(curve)) : null,
  ]);
  const shape = first.ok || exact ? first : await fetchSamples(curve);
  if (!shape.ok) {
    return { problem: shape.problem };
  }
  const knotPoints = knots?.ok ? knots.value.points : [];
  if (exact && shape.value.svg_path) {
    return { path: shape.value.svg_path, knotPoints };
  }
  let line = exact ? await api.evaluatePolyline(curve, tolerance) : shape;
  if (!line.ok) {
    // The certified polyline is refused where the curve jumps: plain samples instead.
    line = await fetchSamples(curve);
    if (!line.ok) {
      return { problem: line.problem };
    }
  }
  return { polyline: line.value.points, knotPoints };
}

async function fetchSamples(curve) {
  const [lo, hi] = geometry.domain(curve);
  const parameters = Array.from({ length: FALLBACK_SAMPLES }, (_, i) => lo + ((hi - lo) * i) / (FALLBACK_SAMPLES - 1));
  return api.evaluateAt(curve, parameters);
}

/** Whether all `points` lie on one side of the box [[xmin, ymin], [xmax, ymax]]. */
function outside(points, [[x0, y0], [x1, y1]]) {
  return points.every((q) => q[0] < x0) || points.every((q) => q[0] > x1) || points.every((q) => q[1] < y0) || points.every((q) => q[1] > y1);
}

/** Screen pixels between two samples, about. */
const PIXELS_PER_SAMPLE = 4;
/** Samples per knot span, at least and at most. */
const FEWEST_PER_SPAN = 4;
const MOST_PER_SPAN = 200;

/** The x–y point of `curve` at `u` in span `k` (u_k <= u <= u_k+1), from the homogeneous
 * poles `h` ([w x, w y, w]) and the full knot vector `knots`. */
function pointAt(degree, knots, h, k, u) {
  const d = [];
  for (let j = 0; j <= degree; j += 1) d.push(h[k - degree + j].slice());
  for (let r = 1; r <= degree; r += 1) {
    for (let j = degree; j >= r; j -= 1) {
      const i = k - degree + j;
      const span = knots[i + degree + 1 - r] - knots[i];
      const a = span > 0 ? (u - knots[i]) / span : 0;
      for (let c = 0; c < 3; c += 1) d[j][c] = (1 - a) * d[j - 1][c] + a * d[j][c];
    }
  }
  const [x, y, w] = d[degree];
  return [x / w, y / w];
}

/**
 * Points along the x–y projection of `curve` over its domain, about PIXELS_PER_SAMPLE
 * apart at `scale` pixels per unit (per knot span, from its length, about);
 * a span whose control points all lie outside `box` ([[xmin, ymin], [xmax, ymax]], the
 * visible part of the drawing) gets the fewest samples, for it is out of view (the convex
 * hull of its p + 1 control points holds it). Null for a periodic curve (its knots are in a
 * form this does not unwrap).
 */
export function sampledCurve(curve, scale, box = null) {
  if (curve.periodic) return null;
  const knots = geometry.fullKnots(curve);
  const p = curve.degree;
  const poles = curve.control_points;
  const n = poles.length;
  const weights = curve.weights ?? null;
  const h = poles.map((point, i) => {
    const w = weights ? weights[i] : 1;
    return [w * point[0], w * point[1], w];
  });
  const points = [];
  let last = -1;
  for (let k = p; k < n; k += 1) {
    if (knots[k + 1] > knots[k]) last = k;
  }
  for (let k = p; k <= last; k += 1) {
    const [lo, hi] = [knots[k], knots[k + 1]];
    if (!(hi > lo)) continue;
    const hidden = box && outside(poles.slice(k - p, k + 1), box);
    let count = FEWEST_PER_SPAN;
    if (!hidden) {
      // The span's length, about: a polyline of FEWEST_PER_SPAN pieces.
      let length = 0;
      let before = pointAt(p, knots, h, k, lo);
      for (let j = 1; j <= FEWEST_PER_SPAN; j += 1) {
        const next = pointAt(p, knots, h, k, lo + ((hi - lo) * j) / FEWEST_PER_SPAN);
        length += Math.hypot(next[0] - before[0], next[1] - before[1]);
        before = next;
      }
      count = Math.min(Math.max(Math.ceil((length * scale) / PIXELS_PER_SAMPLE), FEWEST_PER_SPAN), MOST_PER_SPAN);
    }
    const end = k === last ? count : count - 1;
    for (let j = 0; j <= end; j += 1) points.push(pointAt(p, knots, h, k, lo + ((hi - lo) * j) / count));
  }
  return points.length > 1 ? points : null;
}
