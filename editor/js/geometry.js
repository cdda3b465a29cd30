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

/** Why the knot method cannot edit `curve` (a polyline's shape does not depend on its
 * knots), or null. It moves the points of every curve of degree 2 or more, planar or 3D
 * (3D curves in their x–y projection, the point keeping its z). */
export function knotsRefusal(curve) {
  if (curve.degree < 2) {
    return `This curve has degree ${curve.degree}: a polyline's shape does not depend on its knots, so the knot method is off; control points and weights move its points.`;
  }
  return null;
}

/** What the page says about editing `curve` beside its methods: why the knot method is off
 * (degree 1), or how a 3D curve is edited; null for a planar curve of degree 2 or more. */
export function methodsNote(curve) {
  const refusal = knotsRefusal(curve);
  if (refusal) return refusal;
  if (dimension(curve) === 3) {
    return "A 3D curve, shown and edited in its x–y projection: a dragged point keeps its z. The knot triples reach such targets near the point, the pairs only targets on their surfaces; regions are drawn only where they lie in the view's plane.";
  }
  return null;
}

/** The knot families that apply to `curve` (the API's default `knot_families`): the
 * envelope on degree 3 or more, the direct pairs on degree 2 or more, triples on 3D curves. */
export function knotFamiliesOf(curve) {
  const families = [];
  if (curve.degree >= 3) families.push("envelope");
  if (curve.degree >= 2) families.push("direct");
  if (dimension(curve) === 3) families.push("triples");
  return families;
}

/** The methods of `methods` that can edit `curve` (the knots on degree 2 or more). */
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

/** Whether a regions answer has a region of a knot pair (one the solver reaches: the
 * service draws only those, with the same `keep_domain` and `methods` as solving). */
export function hasKnotRegion(regionsAnswer) {
  const families = regionsAnswer.families ?? [];
  return families.some((family) => family.regions?.length > 0) || (regionsAnswer.candidates ?? []).some((candidate) => candidate.regions?.length > 0);
}

/** Whether all `points` have the same z (2D points: yes). */
function levelIn(points) {
  if (points.length === 0 || points[0].length < 3) return true;
  const z = points.map((p) => p[2]);
  const size = Math.max(...points.map((p) => Math.max(Math.abs(p[0]), Math.abs(p[1]), Math.abs(p[2]))), 1);
  return Math.max(...z) - Math.min(...z) <= 1e-12 * size;
}

/**
 * The knot families of a regions answer as the page draws them: per family entry (one per
 * side for the envelope) `{ entry, drawn, note }`. A family's regions are drawn when the
 * service drew them and, on a 3D curve, when they lie in the view's plane (the acting control
 * points share one z): a drag keeps the point's z, so a region in a tilted plane holds no
 * target the page sends.
 */
export function familyEntries(regionsAnswer) {
  return (regionsAnswer?.families ?? []).map((entry) => {
    if (!entry.applicable) return { entry, drawn: false, note: entry.reason ?? "not drawn" };
    if (!levelIn(entry.control_points)) {
      return { entry, drawn: false, note: "its regions lie in a tilted plane, and a drag keeps the point's z: not drawn" };
    }
    return { entry, drawn: entry.regions.length > 0, note: entry.regions.length > 0 ? "" : "no pair moves the point here" };
  });
}

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
 * The local piece a drag at parameter `t` in span k changes. Every knot family there moves
 * knots among u_k−p+1 … u_k+p (the envelope's moved knot, u_k or u_k+1, is one of them), and
 * a knot u_m shapes the curve only on [u_m−p, u_m+p]: the curve changes on
 * [u_k−2p+1, u_k+2p]; a control-point or weight move changes poles k−p … k, less. The piece
 * keeps poles k−3p+1 … k+2p, whose own domain [u_k−2p+1, u_k+2p+1] holds all of that, so its
 * domain ends never move (or are the curve's), and solving it gives the same solutions, and
 * the same deviations, as solving the whole curve. The whole curve when the curve is small
 * or its knots are in a form the page does not cut.
 */
export function pieceAtParameter(curve, t) {
  if (!hasPlainKnots(curve)) return { curve, poleOffset: 0, whole: true };
  const k = spanIndex(curve, t);
  const n = curve.control_points.length;
  const p = curve.degree;
  return localPiece(curve, Math.max(0, k - 3 * p + 1), Math.min(n - 1, k + 2 * p));
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

/** The region label `label` ("omega2", "direct:5,7", "triples:4,5,7") with its knot
 * indices moved by `offset` (a solution of a local piece, numbered on the whole curve). */
export function relabel(label, offset) {
  if (!offset) return label;
  const colon = label.indexOf(":");
  if (colon < 0) return label;
  const indices = label.slice(colon + 1).split(",").map((k) => Number(k) + offset);
  return `${label.slice(0, colon)}:${indices.join(",")}`;
}

/** The offset from the knot indices of a drag's `piece` (geometry.localPiece) to those of
 * the curve `whole` (its caller's convention); its pole offset is piece.poleOffset. */
export function knotOffsetOf(piece, whole) {
  if (piece.whole) return 0;
  return piece.poleOffset - (isTrimmed(whole) ? 1 : 0);
}

/** The way a solution moves the point: its method, for knots the family, its side (the
 * envelope's) and region (the pair or triple), for weights the pair of poles. A solution of
 * a local piece whose first pole is the curve's `poleOffset` (and whose knot indices are
 * the curve's minus `knotOffset`) gives the family numbered on the whole curve. A drag
 * keeps one family from its first answer to its release. */
export function familyOf(solution, poleOffset = 0, knotOffset = poleOffset) {
  if (solution.method === "knots") {
    const family = { method: "knots", family: solution.family ?? "envelope", region: relabel(solution.region, knotOffset) };
    if (solution.side) family.side = solution.side;
    return family;
  }
  if (solution.method === "weights") return { method: "weights", poles: solution.poles.map((k) => k + poleOffset) };
  return { method: solution.method };
}

/** Whether `solution` (of a piece; offsets as in familyOf) belongs to `family`. */
export function inFamily(solution, family, poleOffset = 0, knotOffset = poleOffset) {
  const own = familyOf(solution, poleOffset, knotOffset);
  return own.method === family.method && own.family === family.family && own.side === family.side && own.region === family.region && String(own.poles) === String(family.poles);
}

/** The largest difference between two knot vectors of the same curve (Infinity when their
 * lengths differ). */
function knotDistance(a, b) {
  if (!a || !b || a.length !== b.length) return Infinity;
  let largest = 0;
  for (let i = 0; i < a.length; i += 1) largest = Math.max(largest, Math.abs(a[i] - b[i]));
  return largest;
}

/**
 * Index of the solution of `family` in `solutions` (of a piece; offsets as in familyOf), -1
 * when none. A knot pair whose map folds has up to three solutions for one target: the one
 * whose knots are nearest `knots` (the knot vector the point was last moved by, in the
 * same curve's convention) is taken, so that a drag follows one branch and never jumps to
 * another.
 */
export function indexInFamily(solutions, family, { poleOffset = 0, knotOffset = poleOffset, knots = null } = {}) {
  let best = -1;
  let bestDistance = Infinity;
  solutions.forEach((solution, index) => {
    if (!inFamily(solution, family, poleOffset, knotOffset)) return;
    const distance = solution.method === "knots" ? knotDistance(solution.knots, knots) : 0;
    if (best < 0 || distance < bestDistance) {
      best = index;
      bestDistance = distance;
    }
  });
  return best;
}

/** The knots of `curve` (its convention) with the full-numbered `moved` values
 * [[full index, value]] in place. */
export function withMovedKnots(curve, moved) {
  const knots = curve.knots.slice();
  const shift = isTrimmed(curve) ? 1 : 0;
  for (const [index, value] of moved) {
    if (index - shift >= 0 && index - shift < knots.length) knots[index - shift] = value;
  }
  return knots;
}

/** A region in words: "Ω2 (left)", "envelope u6,u9 (right)", "direct u5,u7",
 * "triples u4,u5,u7". */
export function describeRegion(region, side) {
  const colon = region.indexOf(":");
  const name = colon < 0 ? region.replace("omega", "Ω") : `${region.slice(0, colon)} ${region.slice(colon + 1).split(",").map((k) => `u${k}`).join(",")}`;
  return side ? `${name} (${side})` : name;
}

/** A family in words: "knots · Ω2 (right)", "knots · direct u5,u7", "weights · poles 3, 4"
 * or "control points". */
export function describeFamily(family) {
  if (family.method === "knots") return `knots · ${describeRegion(family.region, family.side)}`;
  if (family.method === "weights") return `weights · poles ${family.poles.join(", ")}`;
  return family.method.replace("_", " ");
}

/** A short description of a solution for the list (of a local piece whose first pole is
 * the curve's `poleOffset`, knot indices as in familyOf: numbered on the whole curve). */
export function describeSolution(solution, poleOffset = 0, knotOffset = poleOffset) {
  const deviation = solution.max_deviation.toPrecision(3);
  if (solution.method === "knots") {
    const changed = solution.changed_knots.map((k) => k + knotOffset).join(", ");
    return `${describeFamily(familyOf(solution, poleOffset, knotOffset))} · knots ${changed} · max deviation ${deviation}`;
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
