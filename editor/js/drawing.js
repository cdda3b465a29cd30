// The drawing of a curve, from the API: an SVG path of its Bézier pieces when SVG can draw
// it exactly (planar, non-rational, degree <= 3), else a polyline certified within a small
// tolerance (rational and 3D curves, the latter in their x–y projection), plus the curve's
// points at its knots. Plain samples only where the certified polyline is refused (a jump).

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

