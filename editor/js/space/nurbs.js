// Evaluation of B-spline and NURBS curves and surfaces in the page, for the live preview of a
// drag in 3D only: the committed shapes are meshed and evaluated by the service. Every knot
// form the API takes for a non-periodic direction (the full vector, the openNURBS/Rhino vector,
// distinct values with multiplicities) is turned into the full vector first.

/** The full knot vector (n + p + 1 values) of `knots` for `count` poles of `degree`, given
 * fully, trimmed (openNURBS) or as distinct values with `multiplicities`. */
export function fullKnotVector(knots, multiplicities, count, degree) {
  if (multiplicities) return knots.flatMap((value, i) => Array(multiplicities[i]).fill(value));
  if (knots.length === count + degree + 1) return knots.slice();
  return [knots[0], ...knots, knots[knots.length - 1]];
}

/** `surface` with full knot vectors in both directions (no multiplicities), or null when a
 * direction is periodic (the page then previews through the service). */
export function plainSurface(surface) {
  if (surface.periodic_u || surface.periodic_v) return null;
  const nu = surface.control_points.length;
  const nv = surface.control_points[0].length;
  const plain = {
    degree_u: surface.degree_u,
    degree_v: surface.degree_v,
    control_points: surface.control_points,
    knots_u: fullKnotVector(surface.knots_u, surface.multiplicities_u, nu, surface.degree_u),
    knots_v: fullKnotVector(surface.knots_v, surface.multiplicities_v, nv, surface.degree_v),
  };
  if (surface.weights) plain.weights = surface.weights;
  return plain;
}

/** `curve` with its full knot vector, or null when periodic. */
export function plainCurve(curve) {
  if (curve.periodic) return null;
  const plain = {
    degree: curve.degree,
    control_points: curve.control_points,
    knots: fullKnotVector(curve.knots, curve.multiplicities, curve.control_points.length, curve.degree),
  };
  if (curve.weights) plain.weights = curve.weights;
  return plain;
}

/** The span index `s` with `knots[s] <= t < knots[s + 1]`, `degree <= s < count` (the last
 * non-empty span at the domain's end). */
function span(knots, degree, count, t) {
  if (t >= knots[count]) {
    let s = count - 1;
    while (s > degree && knots[s] >= knots[count]) s -= 1;
    return s;
  }
  if (t <= knots[degree]) {
    let s = degree;
    while (s < count - 1 && knots[s + 1] <= knots[degree]) s += 1;
    return s;
  }
  let low = degree;
  let high = count;
  while (high - low > 1) {
    const middle = (low + high) >> 1;
    if (t < knots[middle]) high = middle;
    else low = middle;
  }
  return low;
}

/** The `degree + 1` non-zero basis values `N_{s−p..s,p}(t)` on span `s` (Cox–de Boor,
 * the triangular scheme of Piegl & Tiller's A2.2), written into `out`. */
function basis(knots, degree, s, t, out, left, right) {
  out[0] = 1;
  for (let j = 1; j <= degree; j += 1) {
    left[j] = t - knots[s + 1 - j];
    right[j] = knots[s + j] - t;
    let saved = 0;
    for (let r = 0; r < j; r += 1) {
      const denominator = right[r + 1] + left[j - r];
      const term = denominator === 0 ? 0 : out[r] / denominator;
      out[r] = saved + right[r + 1] * term;
      saved = left[j - r] * term;
    }
    out[j] = saved;
  }
}

/** A reusable evaluator of one plain surface (plainSurface): `point(u, v)` → [x, y, z]. */
export function surfaceEvaluator(surface) {
  const { degree_u: p, degree_v: q, control_points: poles, knots_u: ku, knots_v: kv, weights } = surface;
  const nu = poles.length;
  const nv = poles[0].length;
  const bu = new Float64Array(p + 1);
  const bv = new Float64Array(q + 1);
  const scratch = [new Float64Array(Math.max(p, q) + 2), new Float64Array(Math.max(p, q) + 2)];
  return (u, v) => {
    const su = span(ku, p, nu, u);
    const sv = span(kv, q, nv, v);
    basis(ku, p, su, u, bu, scratch[0], scratch[1]);
    basis(kv, q, sv, v, bv, scratch[0], scratch[1]);
    let x = 0;
    let y = 0;
    let z = 0;
    let w = 0;
    for (let a = 0; a <= p; a += 1) {
      const row = poles[su - p + a];
      const weightRow = weights ? weights[su - p + a] : null;
      for (let b = 0; b <= q; b += 1) {
        const pole = row[sv - q + b];
        const factor = bu[a] * bv[b] * (weightRow ? weightRow[sv - q + b] : 1);
        x += factor * pole[0];
        y += factor * pole[1];
        z += factor * (pole[2] ?? 0);
        w += factor;
      }
    }
    return [x / w, y / w, z / w];
  };
}

/** A reusable evaluator of one plain curve (plainCurve): `point(t)` → [x, y, z]. */
export function curveEvaluator(curve) {
  const { degree: p, control_points: poles, knots, weights } = curve;
  const n = poles.length;
  const values = new Float64Array(p + 1);
  const left = new Float64Array(p + 2);
  const right = new Float64Array(p + 2);
  return (t) => {
    const s = span(knots, p, n, t);
    basis(knots, p, s, t, values, left, right);
    let x = 0;
    let y = 0;
    let z = 0;
    let w = 0;
    for (let a = 0; a <= p; a += 1) {
      const pole = poles[s - p + a];
      const factor = values[a] * (weights ? weights[s - p + a] : 1);
      x += factor * pole[0];
      y += factor * pole[1];
      z += factor * (pole[2] ?? 0);
      w += factor;
    }
    return [x / w, y / w, z / w];
  };
}

/** The distinct knot values of a full vector inside `[knots[degree], knots[count]]`. */
export function distinctInDomain(knots, degree, count) {
  const low = knots[degree];
  const high = knots[count];
  return [...new Set(knots.filter((k) => k >= low && k <= high))];
}

/** The index s of the knot span [k_s, k_s+1) holding `t` (full vector, degree <= s < count). */
function spanOf(knots, degree, count, t) {
  let s = degree;
  while (s < count - 1 && knots[s + 1] <= t) s += 1;
  return s;
}

/**
 * The piece of a plain surface (plainSurface) that a drag at `(u, v)` can change, as the 2D
 * editor cuts a curve (geometry.js `pieceAtParameter`), in each direction: every knot move
 * at span k moves knots among k_{k−p+1} … k_{k+p}, which shape the surface on
 * [k_{k−2p+1}, k_{k+2p}]; a control-point or weight move changes poles k−p … k. The piece
 * keeps poles k−3p+1 … k+2p of each direction and their knots: on its own domain it is the
 * same surface, and solving it gives the whole surface's solutions and deviations, with a
 * fraction of the poles to send (225 of a 30 × 30 bicubic's 900).
 * Returns `{ shape, rows: [i0, i1], columns: [j0, j1] }`.
 */
export function surfacePiece(plain, [u, v]) {
  const range = (knots, degree, count, t) => {
    const k = spanOf(knots, degree, count, t);
    return [Math.max(0, k - 3 * degree + 1), Math.min(count - 1, k + 2 * degree)];
  };
  const nu = plain.control_points.length;
  const nv = plain.control_points[0].length;
  const [i0, i1] = range(plain.knots_u, plain.degree_u, nu, u);
  const [j0, j1] = range(plain.knots_v, plain.degree_v, nv, v);
  const shape = {
    degree_u: plain.degree_u,
    degree_v: plain.degree_v,
    control_points: plain.control_points.slice(i0, i1 + 1).map((row) => row.slice(j0, j1 + 1)),
    knots_u: plain.knots_u.slice(i0, i1 + plain.degree_u + 2),
    knots_v: plain.knots_v.slice(j0, j1 + plain.degree_v + 2),
  };
  if (plain.weights) shape.weights = plain.weights.slice(i0, i1 + 1).map((row) => row.slice(j0, j1 + 1));
  return { shape, rows: [i0, i1], columns: [j0, j1] };
}

/** The whole plain surface with `piece` (surfacePiece's, after an edit: `edited` its new
 * shape) put back in place: its poles, weights and knots replace the ones it was cut from. */
export function withPiece(plain, piece, edited) {
  const [i0] = piece.rows;
  const [j0] = piece.columns;
  const control_points = plain.control_points.map((row) => row.slice());
  edited.control_points.forEach((row, a) => row.forEach((p, b) => {
    control_points[i0 + a][j0 + b] = p;
  }));
  const whole = { ...plain, control_points, knots_u: plain.knots_u.slice(), knots_v: plain.knots_v.slice() };
  edited.knots_u.forEach((k, a) => {
    whole.knots_u[i0 + a] = k;
  });
  edited.knots_v.forEach((k, b) => {
    whole.knots_v[j0 + b] = k;
  });
  if (edited.weights) {
    const weights = plain.weights ? plain.weights.map((row) => row.slice()) : plain.control_points.map((row) => row.map(() => 1));
    edited.weights.forEach((row, a) => row.forEach((w, b) => {
      weights[i0 + a][j0 + b] = w;
    }));
    whole.weights = weights;
  }
  return whole;
}
