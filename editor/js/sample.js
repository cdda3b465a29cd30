// The curves the editor starts from: the API documentation's sample cubic and a single
// cubic Bézier piece (no interior knot: the editor inserts knots before it can move one).

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
