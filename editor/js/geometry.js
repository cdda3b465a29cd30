// Plain facts about a curve object of the API (no drawing, no requests): its knot
// convention, domain, dimension, extent, and the curve a solution describes.

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

/** Whether the editor can move points of `curve`; else the reason, for a message. */
export function editingRefusal(curve) {
  if (dimension(curve) !== 2) {
    return "This is a 3D curve: it is shown in its x–y projection, and the editor does not edit 3D curves (use the API with a target in the control triangle's plane).";
  }
  if (curve.degree !== 3) {
    return `This curve has degree ${curve.degree}: the knot-pair method edits cubic curves only, so it is shown but cannot be edited.`;
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

/**
 * Whether a regions answer has a region the solver can use with the domain kept: one of
 * an applicable candidate whose moved knot and knot pair are not the domain's end knots
 * (full indices p and n).
 */
export function hasUsableRegion(curve, regionsAnswer) {
  const offset = isTrimmed(curve) ? 1 : 0;
  const ends = [curve.degree, curve.control_points.length];
  return regionsAnswer.candidates.some((candidate) =>
    candidate.applicable &&
    candidate.regions.some((region) =>
      [candidate.moved_knot, ...region.knots].every((index) => !ends.includes(index + offset))));
}

/** A polyline tolerance: 1/2000 of the control polygon's longer side. */
export function drawingTolerance(curve) {
  const [low, high] = extent(curve);
  const size = Math.max(high[0] - low[0], high[1] - low[1]);
  return size > 0 ? size / 2000 : 1e-3;
}

/** A short description of a solution for the list. */
export function describeSolution(solution) {
  const deviation = solution.max_deviation.toPrecision(3);
  if (solution.method === "knots") {
    const region = solution.region.replace("omega", "Ω");
    return `knots · ${region} (${solution.side}) · knots ${solution.changed_knots.join(", ")} · max deviation ${deviation}`;
  }
  return `control points · poles ${solution.changed_control_points.join(", ")} · max deviation ${deviation}`;
}
