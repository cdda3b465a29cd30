// The scene: draws a state into the drawing's SVG, layer by layer (grid, regions, control
// polygon, curve, preview, knot marks, control-point handles, dots). Each layer is redrawn
// only when what it shows changed. It reads the state and never changes it.

import { familyEntries } from "./geometry.js";
import { editBase } from "./state.js";
import { element, layer, pairs, redraw, setAttribute } from "./render.js";
import { gridStep, toScreen, visibleBox } from "./viewport.js";

/** Radius of the dots, in pixels. */
const DOT = 5;
/** Half the width of the band around the curve that picks it, in pixels. */
export const PICK_RADIUS = 12;
/** Radius of a control point's grip, in pixels. */
const GRIP = 8;
/** Marks and grips closer than this (pixels) to the last one drawn are left out. */
const MARK_SPACING = 8;
/** A control point closer than this (pixels) to a neighbour has no grip. */
const GRIP_SPACING = 14;

/** The longest tooth of the curvature comb, in pixels (the others in proportion). */
const COMB_PIXELS = 60;
/** Half the length of a tangent lock's mark, in pixels. */
const TANGENT_MARK = 22;

/** A cubic's envelope pairs Ω1–Ω6: Okabe & Ito's colour-blind-safe palette, the same as
 * the service's SVG picture. */
export const REGION_COLOURS = {
  omega1: "#e69f00",
  omega2: "#56b4e9",
  omega3: "#009e73",
  omega4: "#f0e442",
  omega5: "#0072b2",
  omega6: "#d55e00",
};

/** The hue of each knot family's pairs (other than a cubic's Ω1–Ω6): the envelope orange,
 * the direct pairs reddish purple (Okabe & Ito's seventh colour, used by no Ω), each pair a
 * tint of it. */
const FAMILY_HUES = { envelope: 32, direct: 326, triples: 200 };

/** The colour of the `index`th of a family's `count` pairs, `region` its label. */
export function regionColour(family, region, index, count) {
  if (REGION_COLOURS[region]) return REGION_COLOURS[region];
  const lightness = count > 1 ? 28 + (44 * index) / (count - 1) : 50;
  return `hsl(${FAMILY_HUES[family] ?? 0}, 72%, ${lightness.toFixed(1)}%)`;
}

/** Per knot family of a regions answer, its drawn pairs' labels in order (the envelope's two
 * sides share a pair's label, and its colour). */
export function familyPairs(regions) {
  const pairs = {};
  for (const { entry, drawn } of familyEntries(regions)) {
    if (!drawn) continue;
    const labels = (pairs[entry.family] ??= []);
    for (const region of entry.regions) if (!labels.includes(region.region)) labels.push(region.region);
  }
  return pairs;
}

/** Indices of `points` spaced at least `spacing` pixels apart on screen (ends kept). */
function thinned(frame, points, spacing) {
  const kept = [];
  let last = null;
  points.forEach((point, index) => {
    const pixel = toScreen(frame, point);
    if (!last || Math.hypot(pixel[0] - last[0], pixel[1] - last[1]) >= spacing) {
      kept.push(index);
      last = pixel;
    }
  });
  // The last point is kept too, instead of a kept one too close to it.
  const lastIndex = points.length - 1;
  if (lastIndex > 0 && kept[kept.length - 1] !== lastIndex) {
    const end = toScreen(frame, points[lastIndex]);
    const before = kept.length > 1 ? toScreen(frame, points[kept[kept.length - 1]]) : null;
    if (before && Math.hypot(end[0] - before[0], end[1] - before[1]) < spacing) kept.pop();
    kept.push(lastIndex);
  }
  return kept;
}

function drawCurve(drawing, className, parent, hitWidth) {
  if (!drawing) {
    return;
  }
  const shape = drawing.path ? ["path", { d: drawing.path }] : drawing.polyline ? ["polyline", { points: pairs(drawing.polyline) }] : null;
  if (!shape) return;
  if (hitWidth) {
    // An invisible wide band along the curve: a press on it picks (and the cursor says so).
    element(shape[0], { ...shape[1], class: "curve-hit", "stroke-width": hitWidth }, parent);
  }
  element(shape[0], { ...shape[1], class: className }, parent);
}

function drawGrid(frame, size, group) {
  const step = gridStep(frame);
  const [[x0, y0], [x1, y1]] = visibleBox(frame, size);
  const lines = [];
  for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) lines.push(`M${x} ${y0}V${y1}`);
  for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) lines.push(`M${x0} ${y}H${x1}`);
  element("path", { d: lines.join(""), class: "grid" }, group);
}

/** The SVG path of closed `rings` (each with its first point repeated last). */
export function ringsPath(rings) {
  return rings.map((ring) => `M${ring.slice(0, -1).map((p) => `${p[0]},${p[1]}`).join("L")}Z`).join("");
}

/** The knot families' regions whose family is `shown` (each region one path of all its
 * rings, filled by the non-zero rule: outer rings counter-clockwise, holes clockwise), and a
 * cubic's control triangles. */
function drawRegions(regions, shown, group) {
  const colours = familyPairs(regions);
  for (const { entry, drawn } of familyEntries(regions)) {
    if (!drawn || !shown[entry.family]) continue;
    const labels = colours[entry.family];
    for (const region of entry.regions) {
      const colour = regionColour(entry.family, region.region, labels.indexOf(region.region), labels.length);
      const attributes = {
        d: ringsPath(region.polygons),
        class: `region family-${entry.family}${REGION_COLOURS[region.region] ? "" : " tinted"}`,
        fill: colour,
        stroke: colour,
        "fill-rule": "nonzero",
        "data-family": entry.family,
        "data-region": region.region,
        "data-tolerance": entry.tolerance ?? "",
      };
      if (entry.side) attributes["data-side"] = entry.side;
      element("path", attributes, group);
    }
    if (entry.family === "envelope" && entry.control_points.length === 3) {
      element("polygon", { points: pairs(entry.control_points), class: "triangle", "data-side": entry.side }, group);
    }
  }
  // The weight pairs' quadrilaterals: where moving the two weights of poles k, l puts the point.
  for (const region of regions?.weight_regions ?? []) {
    element("polygon", { points: pairs(region.polygon), class: "region weight-region", "data-region": "weights", "data-poles": region.poles.join(",") }, group);
  }
}

/** The curvature comb: per tooth a line from the curve along the normal, κ long (scaled so
 * that the longest is COMB_PIXELS), and the line through the teeth's ends. */
function drawComb(comb, frame, group) {
  const longest = Math.max(...comb.teeth.map(([x, y]) => Math.hypot(x, y)), 0);
  if (!(longest > 0)) return;
  const factor = COMB_PIXELS / (frame.scale * longest);
  const ends = comb.points.map((p, i) => [p[0] + comb.teeth[i][0] * factor, p[1] + comb.teeth[i][1] * factor]);
  const teeth = comb.points.map((p, i) => `M${p[0]} ${p[1]}L${ends[i][0]} ${ends[i][1]}`).join("");
  element("path", { d: teeth, class: "comb-teeth" }, group);
  element("polyline", { points: pairs(ends), class: "comb-envelope" }, group);
}

/** The points of "draw by points", joined in their order. */
function drawSketch(points, frame, group) {
  if (points.length === 0) return;
  element("polyline", { points: pairs(points), class: "sketch-line" }, group);
  for (const [x, y] of points) element("circle", { cx: x, cy: y, r: DOT / frame.scale, class: "sketch-point" }, group);
}

/** The pins (rings on the curve) and tangent locks (a bar along the tangent) of `state`. */
function drawConditions(constraints, marks, frame, group) {
  constraints.forEach((constraint, i) => {
    const mark = marks?.[i];
    if (!mark) return;
    const [x, y] = mark.point;
    if (constraint.order === 0) {
      element("circle", { cx: x, cy: y, r: (DOT * 1.4) / frame.scale, class: "pin", "data-parameter": constraint.parameter }, group);
      return;
    }
    const [dx, dy] = mark.tangent;
    const length = Math.hypot(dx, dy) || 1;
    const half = TANGENT_MARK / frame.scale;
    const [ux, uy] = [(dx / length) * half, (dy / length) * half];
    element("path", { d: `M${x - ux} ${y - uy}L${x + ux} ${y + uy}`, class: "tangent-lock", "data-parameter": constraint.parameter }, group);
  });
}

/** The control points' dots (thinned where dense) and their grips: only a control point at
 * least GRIP_SPACING pixels from its neighbours has one, so that dense control points do not
 * cover the curve (zoom in to reach them). */
function drawGrips(curve, frame, fixed, group) {
  const radius = (DOT * 0.7) / frame.scale;
  const poles = curve.control_points;
  for (const index of thinned(frame, poles, MARK_SPACING)) {
    element("circle", { cx: poles[index][0], cy: poles[index][1], r: radius, class: "pole" }, group);
  }
  const pixels = poles.map((point) => toScreen(frame, point));
  const apart = (i, j) => j < 0 || j >= pixels.length || Math.hypot(pixels[i][0] - pixels[j][0], pixels[i][1] - pixels[j][1]) >= GRIP_SPACING;
  poles.forEach(([x, y], index) => {
    if (apart(index, index - 1) && apart(index, index + 1)) {
      element("circle", { cx: x, cy: y, r: GRIP / frame.scale, class: "pole-grip", "data-index": index }, group);
    }
  });
  // Fixed control points: a square around the dot (drawn whatever the spacing).
  const half = (DOT * 1.2) / frame.scale;
  for (const index of fixed) {
    const [x, y] = poles[index] ?? [];
    if (x === undefined) continue;
    element("rect", { x: x - half, y: y - half, width: 2 * half, height: 2 * half, class: "pole-fixed", "data-index": index }, group);
  }
}

/** The preview of a drag: the moved control points with their polygon, and the new piece
 * of curve (the part of the curve the move changes). */
function drawPreview(drag, frame, group) {
  const radius = (DOT * 0.7) / frame.scale;
  if (drag.movedPoles) {
    const { points, moved } = drag.movedPoles;
    element("polyline", { points: pairs(points), class: "preview-control polygon" }, group);
    for (const point of moved) {
      element("circle", { cx: point[0], cy: point[1], r: radius, class: "preview-control pole" }, group);
    }
  }
  drawCurve(drag.previewDrawing, "preview", group, 0);
}

function drawMarks(knotPoints, frame, group) {
  const half = (DOT * 0.6) / frame.scale;
  for (const index of thinned(frame, knotPoints, MARK_SPACING)) {
    const [x, y] = knotPoints[index];
    element("rect", { x: x - half, y: y - half, width: 2 * half, height: 2 * half, class: "knot" }, group);
  }
}

function drawDots(state, frame, group) {
  const radius = DOT / frame.scale;
  const drag = state.drag;
  if (state.pick) {
    const shown = drag?.solution?.point ?? state.pick.point;
    element("circle", { cx: shown[0], cy: shown[1], r: radius, class: "picked" }, group);
  }
  if (drag?.target) {
    element("circle", { cx: drag.target[0], cy: drag.target[1], r: radius, class: drag.snapped ? "target snapped" : "target" }, group);
  }
}

/** Draws `state` into `scene` (the <g> inside the drawing). */
export function drawScene(state, scene) {
  const { frame, size } = state.view;
  setAttribute(scene, "transform", `matrix(${frame.scale} 0 0 ${-frame.scale} ${frame.offset[0]} ${frame.offset[1]})`);
  const base = editBase(state);
  const shows = state.layers;
  const layers = Object.fromEntries(["grid", "regions", "control", "comb", "curve", "preview", "marks", "grips", "conditions", "sketch", "dots"].map(
    (name) => [name, layer(scene, name)]));
  const showGrid = shows.grid || state.snap.grid;
  redraw(layers.grid, [showGrid, frame, size], (group) => showGrid && drawGrid(frame, size, group));
  const regions = shows.regions ? state.regions : null;
  redraw(layers.regions, [regions, state.families], (group) => drawRegions(regions, state.families, group));
  redraw(layers.control, [shows.control, base], (group) => {
    if (shows.control) element("polyline", { points: pairs(base.control_points), class: "control polygon" }, group);
  });
  const comb = shows.comb ? state.drawing?.comb ?? null : null;
  redraw(layers.comb, [comb, frame], (group) => comb && drawComb(comb, frame, group));
  redraw(layers.curve, [state.drawing, frame], (group) => drawCurve(state.drawing, "curve", group, (2 * PICK_RADIUS) / frame.scale));
  const drag = state.drag;
  redraw(layers.preview, [drag?.previewDrawing, drag?.movedPoles, frame], (group) => drag && drawPreview(drag, frame, group));
  const marks = shows.knots ? state.drawing?.knotPoints ?? [] : [];
  redraw(layers.marks, [marks, frame], (group) => drawMarks(marks, frame, group));
  redraw(layers.grips, [shows.control, base, frame, state.fixed], (group) => shows.control && drawGrips(base, frame, state.fixed, group));
  const conditionMarks = state.drawing?.conditionMarks;
  redraw(layers.conditions, [state.constraints, conditionMarks, frame], (group) => drawConditions(state.constraints, conditionMarks, frame, group));
  redraw(layers.sketch, [state.sketch, frame], (group) => drawSketch(state.sketch, frame, group));
  redraw(layers.dots, [state.pick, drag?.solution, drag?.target, frame], (group) => drawDots(state, frame, group));
}
