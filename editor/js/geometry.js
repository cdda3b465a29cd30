// Plain facts about a curve object of the API (no drawing, no requests): its knot
// convention, domain, dimension, extent, the local piece around a parameter or a pole, and
// the curve a solution describes.

/** The full knot vector (control points + degree + 1 values) of either convention. */
export function fullKnots(curve) {
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

/** Whether the editor can move points of `curve` through the solver; else the reason. */
export function editingRefusal(curve) {
  if (dimension(curve) !== 2) {
    return "This is a 3D curve: it is shown in its x–y projection. Drag its control points (z is kept); moving curve points needs a target in the control triangle's plane (use the API).";
  }
  if (curve.degree !== 3) {
    return `This curve has degree ${curve.degree}: the knot-pair method edits cubic curves only. Drag its control points to change it.`;
  }
  return null;
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

/** The curve after `solution` of /v1/shape/solve: new knots or new control points. */
export function applySolution(curve, solution) {
  if (solution.method === "knots") {
    return { ...curve, knots: solution.knots.slice() };
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

/**
 * Whether a knot-pair region survives `keep_domain` (the solver's default): neither the
 * moved knot nor the pair is an end knot of the domain (full indices p and n). The solver
 * drops every solution that moves those, so such regions hold no reachable target.
 */
export function keepsDomain(curve, candidate, region) {
  const offset = isTrimmed(curve) ? 1 : 0;
  const ends = [curve.degree, curve.control_points.length];
  return [candidate.moved_knot, ...region.knots].every((index) => !ends.includes(index + offset));
}

/** The regions answer with only what solving with `keep_domain` can reach. */
export function reachableRegions(curve, regionsAnswer) {
  return {
    ...regionsAnswer,
    candidates: regionsAnswer.candidates.map((candidate) => ({
      ...candidate,
      regions: candidate.applicable ? candidate.regions.filter((region) => keepsDomain(curve, candidate, region)) : [],
    })),
  };
}

/** Whether a regions answer has a region the solver can use with the domain kept. */
export function hasUsableRegion(curve, regionsAnswer) {
  return reachableRegions(curve, regionsAnswer).candidates.some((candidate) => candidate.regions.length > 0);
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

/** The way a solution moves the point: its method, and for knot pairs the side and region.
 * A drag keeps one family from its first answer to its release. */
export function familyOf(solution) {
  return solution.method === "knots"
    ? { method: "knots", side: solution.side, region: solution.region }
    : { method: solution.method };
}

/** Whether `solution` belongs to `family`. */
export function inFamily(solution, family) {
  const own = familyOf(solution);
  return own.method === family.method && own.side === family.side && own.region === family.region;
}

/** A family in words: "knots · Ω2 (right)" or "control points". */
export function describeFamily(family) {
  if (family.method === "knots") {
    return `knots · ${family.region.replace("omega", "Ω")} (${family.side})`;
  }
  return family.method.replace("_", " ");
}

/** A short description of a solution for the list. */
export function describeSolution(solution) {
  const deviation = solution.max_deviation.toPrecision(3);
  if (solution.method === "knots") {
    return `${describeFamily(familyOf(solution))} · knots ${solution.changed_knots.join(", ")} · max deviation ${deviation}`;
  }
  return `control points · poles ${solution.changed_control_points.join(", ")} · max deviation ${deviation}`;
}
