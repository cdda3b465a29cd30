// The view: draws a state into the page (the SVG scene, the knot strip, the solution list,
// the legend, the messages) and mirrors what tests read into body[data-*]. It reads the
// state and never changes it.

import { currentCurve } from "./state.js";
import { fullKnots, isTrimmed } from "./geometry.js";

const SVG_NS = "http://www.w3.org/2000/svg";
const CANVAS = { width: 760, height: 520, margin: 48 };
const STRIP = { width: 760, height: 56, margin: 24 };
/** Radius of the dots, in pixels. */
const DOT = 5;

/** Okabe & Ito's colour-blind-safe palette, the same as the service's SVG picture. */
export const REGION_COLOURS = {
  omega1: "#e69f00",
  omega2: "#56b4e9",
  omega3: "#009e73",
  omega4: "#f0e442",
  omega5: "#0072b2",
  omega6: "#d55e00",
};

/** The frame that fits the box [[xmin, ymin], [xmax, ymax]] into the canvas, y up. */
export function fitFrame([low, high]) {
  const width = Math.max(high[0] - low[0], 1e-9);
  const height = Math.max(high[1] - low[1], 1e-9);
  const room = [CANVAS.width - 2 * CANVAS.margin, CANVAS.height - 2 * CANVAS.margin];
  const scale = Math.min(room[0] / width, room[1] / height);
  const centre = [(low[0] + high[0]) / 2, (low[1] + high[1]) / 2];
  return {
    scale,
    offset: [CANVAS.width / 2 - scale * centre[0], CANVAS.height / 2 + scale * centre[1]],
  };
}

function element(name, attributes, parent) {
  const node = document.createElementNS(SVG_NS, name);
  for (const [key, value] of Object.entries(attributes)) {
    node.setAttribute(key, String(value));
  }
  parent.appendChild(node);
  return node;
}

const pairs = (points) => points.map((p) => `${p[0]},${p[1]}`).join(" ");

function drawCurve(drawing, className, parent) {
  if (!drawing) {
    return;
  }
  if (drawing.path) {
    element("path", { d: drawing.path, class: className }, parent);
  } else if (drawing.polyline) {
    element("polyline", { points: pairs(drawing.polyline), class: className }, parent);
  }
}

function drawControlPolygon(curve, className, radius, parent) {
  element("polyline", { points: pairs(curve.control_points), class: `${className} polygon` }, parent);
  curve.control_points.forEach((p, index) => {
    element("circle", { cx: p[0], cy: p[1], r: radius * 0.7, class: `${className} pole`, "data-index": index }, parent);
  });
}

/** What each layer of the scene was last drawn from: a layer whose inputs are the same
 * objects is left as it is (a drag redraws only the preview and the dots). */
const drawn = new WeakMap();

function layer(scene, name) {
  let group = scene.querySelector(`:scope > g.layer-${name}`);
  if (!group) {
    group = element("g", { class: `layer-${name}` }, scene);
  }
  return group;
}

/** Redraws `group` by `paint` unless `inputs` are the objects it was drawn from. */
function redraw(group, inputs, paint) {
  const previous = drawn.get(group);
  if (previous && previous.length === inputs.length && previous.every((value, i) => value === inputs[i])) {
    return;
  }
  drawn.set(group, inputs);
  group.replaceChildren();
  paint(group);
}

function drawScene(state, scene) {
  const frame = state.frame;
  scene.setAttribute("transform", `matrix(${frame.scale} 0 0 ${-frame.scale} ${frame.offset[0]} ${frame.offset[1]})`);
  const radius = DOT / frame.scale;
  const curve = currentCurve(state);
  const layers = Object.fromEntries(["regions", "control", "curve", "preview", "marks", "dots"].map(
    (name) => [name, layer(scene, name)]));
  redraw(layers.regions, [state.regions, frame], (group) => {
    for (const candidate of state.regions?.candidates ?? []) {
      for (const region of candidate.regions) {
        element("polygon", {
          points: pairs(region.polygon),
          class: "region",
          fill: REGION_COLOURS[region.region],
          stroke: REGION_COLOURS[region.region],
          "data-region": region.region,
          "data-side": candidate.side,
        }, group);
      }
      if (candidate.applicable && candidate.triangle) {
        element("polygon", { points: pairs(candidate.triangle), class: "triangle", "data-side": candidate.side }, group);
      }
    }
  });
  redraw(layers.control, [curve, frame], (group) => drawControlPolygon(curve, "control", radius, group));
  redraw(layers.curve, [state.drawing], (group) => drawCurve(state.drawing, "curve", group));
  redraw(layers.marks, [state.drawing, frame], (group) => {
    for (const point of state.drawing?.knotPoints ?? []) {
      element("rect", {
        x: point[0] - radius * 0.6, y: point[1] - radius * 0.6,
        width: radius * 1.2, height: radius * 1.2, class: "knot",
      }, group);
    }
  });
  const drag = state.drag;
  const chosen = drag?.solutions[drag.chosen];
  redraw(layers.preview, [drag?.preview, drag?.previewDrawing, frame], (group) => {
    if (!drag?.preview) return;
    if (chosen?.method === "control_points") {
      drawControlPolygon(drag.preview, "preview-control", radius, group);
    }
    drawCurve(drag.previewDrawing, "preview", group);
  });
  redraw(layers.dots, [state.pick, chosen, drag?.target, frame], (group) => {
    if (state.pick) {
      const shown = chosen?.point ?? state.pick.point;
      element("circle", { cx: shown[0], cy: shown[1], r: radius, class: "picked" }, group);
    }
    if (drag?.target) {
      element("circle", { cx: drag.target[0], cy: drag.target[1], r: radius, class: "target" }, group);
    }
  });
}

function drawKnotStrip(state, strip) {
  strip.replaceChildren();
  const knots = fullKnots(currentCurve(state));
  const drag = state.drag;
  const chosen = drag?.solutions[drag.chosen] ?? state.lastSolutions?.solutions[state.lastSolutions.chosen];
  const previewKnots = chosen?.method === "knots" && drag?.preview ? fullKnots(drag.preview) : null;
  const low = Math.min(...knots, ...(previewKnots ?? []));
  const high = Math.max(...knots, ...(previewKnots ?? []));
  const span = high - low || 1;
  const x = (u) => STRIP.margin + ((u - low) / span) * (STRIP.width - 2 * STRIP.margin);
  element("line", { x1: x(low), y1: 48, x2: x(high), y2: 48, class: "axis" }, strip);
  const changed = new Set(chosen?.method === "knots" ? chosen.changed_knots : []);
  const offset = isTrimmed(currentCurve(state)) ? 1 : 0;
  const stack = new Map();
  knots.forEach((u, index) => {
    const level = stack.get(u) ?? 0;
    stack.set(u, level + 1);
    element("circle", {
      cx: x(u), cy: 48 - 7 * level, r: 3,
      class: changed.has(index - offset) && !previewKnots ? "knot-tick changed" : "knot-tick",
    }, strip);
  });
  for (const [index, u] of (previewKnots ?? []).entries()) {
    if (changed.has(index - offset)) {
      element("circle", { cx: x(u), cy: 48, r: 4, class: "knot-tick preview" }, strip);
    }
  }
  const label = element("text", { x: STRIP.margin, y: 12, class: "strip-label" }, strip);
  label.textContent = `knots (${knots.length}): ${knots.map((u) => +u.toPrecision(4)).join(", ")}`;
}

function drawSolutions(state, list, describe) {
  const entry = state.drag ?? state.lastSolutions;
  list.replaceChildren();
  if (!entry) {
    return;
  }
  if (entry.nearest) {
    const note = document.createElement("li");
    note.className = "note";
    note.textContent = `Target outside every region: following the nearest reachable point (distance ${entry.nearest.distance.toPrecision(3)}).`;
    list.appendChild(note);
  }
  entry.solutions.forEach((solution, index) => {
    const item = document.createElement("li");
    const label = document.createElement("label");
    const radio = document.createElement("input");
    radio.type = "radio";
    radio.name = "solution";
    radio.value = String(index);
    radio.checked = index === entry.chosen;
    label.append(radio, ` ${describe(solution)}`);
    item.appendChild(label);
    list.appendChild(item);
  });
}

function drawLegend(legend) {
  if (legend.childElementCount > 0) {
    return;
  }
  const items = [
    ...Object.keys(REGION_COLOURS).map((name) => [`swatch ${name}`, name.replace("omega", "Ω")]),
    ["swatch triangle", "control triangle"],
    ["swatch curve", "curve"],
    ["swatch preview", "preview"],
    ["swatch knot", "knots"],
    ["swatch picked", "picked point"],
    ["swatch target", "target"],
  ];
  for (const [className, text] of items) {
    const item = document.createElement("li");
    const swatch = document.createElement("span");
    swatch.className = className;
    item.append(swatch, text);
    legend.appendChild(item);
  }
}

/** Draws `state` into the page's `elements`. */
export function draw(state, elements, describe) {
  drawScene(state, elements.scene);
  drawKnotStrip(state, elements.strip);
  drawSolutions(state, elements.solutions, describe);
  drawLegend(elements.legend);
  elements.message.textContent = state.message;
  elements.error.textContent = state.error;
  elements.undo.disabled = state.history.past.length === 0;
  elements.redo.disabled = state.history.future.length === 0;
  const body = document.body.dataset;
  body.curve = JSON.stringify(currentCurve(state));
  body.picked = state.pick ? JSON.stringify(state.pick) : "";
  body.solutions = String((state.drag ?? state.lastSolutions)?.solutions.length ?? 0);
  body.message = state.message;
  body.error = state.error;
}
