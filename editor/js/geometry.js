// Plain facts about a curve object of the API (no drawing, no requests): its knot
// convention, domain, dimension, extent, the local piece around a parameter or a pole, and
// the curve a solution describes.

/** The full knot vector (control points + degree + 1 values) of either convention, or of
 * distinct values with multiplicities. */
export function fullKnots(curve) {
  if (curve.multiplicities) {
    // Distinct values with multiplicities (STEP's form): each value repeated.
    return curve.knots.flatMap((u, i) => Array(curve.multiplicities[i]).fill(u));
  }
  const full = curve.control_points.length + curve.degree + 1;
  if (curve.knots.length === full) {
    return curve.knots.slice();
  }
  // Trimmed (openNURBS): the two end values are implied.
  return [curve.knots[0], ...curve.knots, curve.knots[curve.knots.length - 1]];
}

/** The parameter domain [u_p, u_n] (full numbering). */
export function domain(curve) {
  const knots = fullKnots(curve);
  return [knots[curve.degree], knots[curve.control_points.length]];
}

/** Whether `knots` of `curve` is the trimmed (openNURBS) convention. */
export function isTrimmed(curve) {
  return curve.knots.length !== curve.control_points.length + curve.degree + 1;
}

/** Whether the knots are one of the two conventions this page reads (full or trimmed). */
export function hasPlainKnots(curve) {
  const count = curve.control_points.length + curve.degree + 1;
  return !curve.multiplicities && !curve.periodic && (curve.knots.length === count || curve.knots.length === count - 2);
}

/** Distinct knot values inside the domain, ends included. */
export function knotValuesInDomain(curve) {
  const [lo, hi] = domain(curve);
  const values = [];
  for (const u of fullKnots(curve)) {
    if (u >= lo && u <= hi && values[values.length - 1] !== u) {
      values.push(u);
    }
  }
  return values;
}

/** 2 or 3. */
export function dimension(curve) {
  return curve.control_points[0] ? curve.control_points[0].length : 2;
}

/** Why the knot-pair method cannot edit `curve` (it moves cubic, planar curves), or null.
 * The control-point and weight methods take any degree, 2D or 3D. */
export function knotsRefusal(curve) {
  if (curve.degree !== 3) {
    return `This curve has degree ${curve.degree}: the knot-pair method edits cubic curves only, so it is off; control points and weights move its points.`;
  }
  if (dimension(curve) !== 2) {
    return "This is a 3D curve, shown and edited in its x–y projection (z is kept): the knot-pair method is off; control points and weights move its points.";
  }
  return null;
}

/** The methods of `methods` that can edit `curve` (the knot pairs only on planar cubics). */
export function usableMethods(curve, methods) {
  return knotsRefusal(curve) ? methods.filter((method) => method !== "knots") : methods;
}

/** `curve` projected onto the x–y plane (the same weights: the projection of a NURBS curve
 * is the NURBS curve of the projected control points). A planar curve is itself. */
export function projected(curve) {
  if (dimension(curve) !== 3) return curve;
  return { ...curve, control_points: curve.control_points.map((p) => [p[0], p[1]]) };
}

/** A target in the drawing's x–y plane lifted to the curve's dimension: a 3D curve's point
 * keeps the z of `from` (the point it moves). */
export function lifted(target, from) {
  return from && from.length === 3 && target.length === 2 ? [target[0], target[1], from[2]] : target;
}

/** [[xmin, ymin], [xmax, ymax]] of the control polygon's x–y projection. */
export function extent(curve) {
  const low = [Infinity, Infinity];
  const high = [-Infinity, -Infinity];
  for (const point of curve.control_points) {
    for (const axis of [0, 1]) {
      low[axis] = Math.min(low[axis], point[axis]);
      high[axis] = Math.max(high[axis], point[axis]);
    }
  }
  return [low, high];
}

/** The curve after `solution` of /v1/shape/solve: new knots, control points or weights. */
export function applySolution(curve, solution) {
  if (solution.method === "knots") {
    return { ...curve, knots: solution.knots.slice() };
  }
  if (solution.method === "weights") {
    return { ...curve, weights: solution.weights.slice() };
  }
  return { ...curve, control_points: solution.control_points.map((p) => p.slice()) };
}

/** `curve` with control point `index` at `point` (a 3D pole keeps its z). */
export function withPole(curve, index, point) {
  const control_points = curve.control_points.slice();
  const old = control_points[index];
  control_points[index] = old.length === 3 ? [point[0], point[1], old[2]] : [point[0], point[1]];
  return { ...curve, control_points };
}

/** Whether a regions answer has a knot-pair region (one the solver reaches: the service
 * draws only those, with the same `keep_domain` and `methods` as solving). */
export function hasKnotRegion(regionsAnswer) {
  return regionsAnswer.candidates.some((candidate) => candidate.regions?.length > 0);
}

/** Poles a local piece keeps on each side beyond those a move can change. */
const PIECE_MARGIN = 2;

/**
 * The piece of `curve` made of control points `first..last` and their knots (full
 * numbering): on its own domain it is the same curve. `poleOffset` maps its pole indices
 * (and full knot indices) back to the curve's. All the poles: the curve itself (`whole`).
 */
export function localPiece(curve, first, last) {
  if (first === 0 && last === curve.control_points.length - 1) {
    return { curve, poleOffset: 0, whole: true };
  }
  const knots = fullKnots(curve);
  const piece = {
    degree: curve.degree,
    control_points: curve.control_points.slice(first, last + 1),
    knots: knots.slice(first, last + curve.degree + 2),
  };
  if (curve.weights) piece.weights = curve.weights.slice(first, last + 1);
  return { curve: piece, poleOffset: first, whole: false };
}

/** The index k of the knot span [u_k, u_k+1) holding `t` (full numbering, p <= k < n). */
export function spanIndex(curve, t) {
  const knots = fullKnots(curve);
  const n = curve.control_points.length;
  let k = curve.degree;
  while (k < n - 1 && knots[k + 1] <= t) k += 1;
  return k;
}

/**
 * The local piece a drag at parameter `t` in span k changes. A knot pair there moves knots
 * among u_k−2 … u_k+3 (a cubic), which changes poles k−6 … k+3 and the curve on
 * [u_k−3, u_k+4]; a control-point move changes poles k−p … k. The piece keeps poles
 * k−2p−2 … k+p+3 (a margin of PIECE_MARGIN beyond that), so its own domain ends never move
 * (or are the curve's), and solving it gives the same solutions as solving the whole curve.
 * The whole curve when the curve is small or its knots are in a form the page does not cut.
 */
export function pieceAtParameter(curve, t) {
  if (!hasPlainKnots(curve)) return { curve, poleOffset: 0, whole: true };
  const k = spanIndex(curve, t);
  const n = curve.control_points.length;
  const p = curve.degree;
  return localPiece(curve, Math.max(0, k - 2 * p - PIECE_MARGIN), Math.min(n - 1, k + 1 + p + PIECE_MARGIN));
}

/** The local piece that moving pole `index` changes: the curve on [u_index, u_index+p+1]. */
export function pieceAtPole(curve, index) {
  if (!hasPlainKnots(curve)) return { curve, poleOffset: 0, whole: true };
  const n = curve.control_points.length;
  return localPiece(curve, Math.max(0, index - curve.degree), Math.min(n - 1, index + curve.degree));
}

/** A polyline tolerance: 1/2000 of the control polygon's longer side. */
export function drawingTolerance(curve) {
  const [low, high] = extent(curve);
  const size = Math.max(high[0] - low[0], high[1] - low[1]);
  return size > 0 ? size / 2000 : 1e-3;
}

/** The way a solution moves the point: its method, for knot pairs the side and region,
 * for weights the pair of poles (numbered on the whole curve: a solution of a local piece
 * whose first pole is the curve's `poleOffset` gives the same family as the whole curve's).
 * A drag keeps one family from its first answer to its release. */
export function familyOf(solution, poleOffset = 0) {
  if (solution.method === "knots") return { method: "knots", side: solution.side, region: solution.region };
  if (solution.method === "weights") return { method: "weights", poles: solution.poles.map((k) => k + poleOffset) };
  return { method: solution.method };
}

/** Whether `solution` (of a piece starting at pole `poleOffset`) belongs to `family`. */
export function inFamily(solution, family, poleOffset = 0) {
  const own = familyOf(solution, poleOffset);
  return own.method === family.method && own.side === family.side && own.region === family.region && String(own.poles) === String(family.poles);
}

/** A family in words: "knots · Ω2 (right)", "weights · poles 3, 4" or "control points". */
export function describeFamily(family) {
  if (family.method === "knots") {
    return `knots · ${family.region.replace("omega", "Ω")} (${family.side})`;
  }
  if (family.method === "weights") return `weights · poles ${family.poles.join(", ")}`;
  return family.method.replace("_", " ");
}

/** A short description of a solution for the list (of a local piece whose first pole is
 * the curve's `poleOffset`: poles numbered on the whole curve). */
export function describeSolution(solution, poleOffset = 0) {
  const deviation = solution.max_deviation.toPrecision(3);
  if (solution.method === "knots") {
    return `${describeFamily(familyOf(solution))} · knots ${solution.changed_knots.join(", ")} · max deviation ${deviation}`;
  }
  if (solution.method === "weights") {
    const weights = solution.poles.map((k) => +solution.weights[k].toPrecision(4)).join(", ");
    return `weights · poles ${solution.poles.map((k) => k + poleOffset).join(", ")} → ${weights} · max deviation ${deviation}`;
  }
  return `control points · poles ${solution.changed_control_points.map((k) => k + poleOffset).join(", ")} · max deviation ${deviation}`;
}

/** The curvature comb of an evaluate answer with derivatives and curvature: per parameter
 * the curve point and its unit normal (the x–y tangent turned left) times the curvature κ
 * (signed for planar curves, so teeth point to the centre of curvature; the magnitude for 3D
 * ones). A tangent of zero length has no tooth. */
export function combOf(answer) {
  const points = [];
  const teeth = [];
  answer.points.forEach((point, i) => {
    const [dx, dy] = answer.derivatives[0][i];
    const length = Math.hypot(dx, dy);
    const kappa = answer.curvature[i];
    if (!(length > 0) || !Number.isFinite(kappa)) return;
    points.push([point[0], point[1]]);
    teeth.push([(-dy / length) * kappa, (dx / length) * kappa]);
  });
  return { points, teeth };
}

/** Whether moving control point `index` changes the curve at some constraint's parameter:
 * its basis function is non-zero on [u_index, u_index+p+1] (ends included, so that the
 * derivatives there are counted too); knots in a form the page does not read: any constraint. */
export function poleMovesConstraint(curve, index, constraints) {
  if (!hasPlainKnots(curve)) return constraints.length > 0;
  const knots = fullKnots(curve);
  const [from, to] = [knots[index], knots[index + curve.degree + 1]];
  return constraints.some((c) => c.parameter >= from && c.parameter <= to);
}
