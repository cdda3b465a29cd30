// The curves the editor starts from: the API documentation's sample cubic and a single
// cubic Bézier piece (no interior knot: the editor inserts knots before it can move one);
// and the 3D view's sample surface, a gently waved bicubic.

/** The sample cubic (eight control points, full knot vector). */
export const SAMPLE_CUBIC = Object.freeze({
  degree: 3,
  control_points: [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
  knots: [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1],
});

/** One cubic Bézier piece, knots [0,0,0,0,1,1,1,1]. */
export const SINGLE_BEZIER = Object.freeze({
  degree: 3,
  control_points: [[0, 0], [2, 6], [7, 6], [9, 0]],
  knots: [0, 0, 0, 0, 1, 1, 1, 1],
});

/** A bicubic surface of `n × n` poles over `[0, n − 1]²` (uniform clamped knots in both
 * directions), waved by `z = 0.6 sin(x / 2) cos(y / 3)`: the 3D view's sample. */
export function sampleSurface(n = 6) {
  const control_points = [];
  for (let i = 0; i < n; i += 1) {
    const row = [];
    for (let j = 0; j < n; j += 1) row.push([i, j, 0.6 * Math.sin(i / 2) * Math.cos(j / 3)]);
    control_points.push(row);
  }
  const interior = Array.from({ length: n - 4 }, (_, k) => (k + 1) / (n - 3));
  const knots = [0, 0, 0, 0, ...interior, 1, 1, 1, 1];
  return { degree_u: 3, degree_v: 3, control_points, knots_u: knots.slice(), knots_v: knots.slice() };
}
