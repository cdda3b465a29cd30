// The panel beside the drawing: builds its lists (tools, methods, knot families, snapping,
// layers, shortcuts, legend) from options.js once, then draws a state into it — the knot
// families' legend, the solution list, the notices, the banner, the readout, the typed
// target — and mirrors what tests read into body[data-*]. It reads the state and never
// changes it.

import { describeFamily, describeRegion, describeSolution, familyEntries, familyOf, knotsRefusal, methodsNote } from "./geometry.js";
import { FAMILIES, LAYERS, METHODS, SHORTCUTS, SNAPS, TOOLS } from "./options.js";
import { currentCurve, editBase } from "./state.js";
import { familyPairs, regionColour } from "./view.js";
import { decimals } from "./viewport.js";

const SVG_NS = "http://www.w3.org/2000/svg";

/** A colour swatch (a small SVG square: the page's style rules allow no inline style). */
function swatch(colour, title, className = "") {
  const svg = document.createElementNS(SVG_NS, "svg");
  svg.setAttribute("class", `pair-swatch ${className}`.trim());
  svg.setAttribute("width", "12");
  svg.setAttribute("height", "12");
  svg.setAttribute("viewBox", "0 0 12 12");
  const rect = document.createElementNS(SVG_NS, "rect");
  for (const [key, value] of Object.entries({ x: 0.5, y: 0.5, width: 11, height: 11, fill: colour, stroke: colour })) rect.setAttribute(key, String(value));
  const tip = document.createElementNS(SVG_NS, "title");
  tip.textContent = title;
  svg.append(tip, rect);
  return svg;
}

/** A checkbox `id` labelled `text`, appended to `parent`. */
function checkbox(parent, id, text, name) {
  const label = document.createElement("label");
  const box = document.createElement("input");
  box.type = "checkbox";
  box.id = id;
  box.name = name;
  label.append(box, ` ${text}`);
  parent.appendChild(label);
}

/** Fills the panel's lists from options.js (once, at start). */
export function buildPanel(elements) {
  for (const tool of TOOLS) {
    const button = document.createElement("button");
    button.type = "button";
    button.id = `tool-${tool.id}`;
    button.dataset.tool = tool.id;
    button.textContent = tool.label;
    button.title = `${tool.label} (${tool.key.toUpperCase()}): ${tool.help}`;
    elements.tools.appendChild(button);
  }
  for (const method of METHODS) checkbox(elements.methods, `method-${method.id.replace("_", "-")}`, method.label, "method");
  for (const family of FAMILIES) {
    // A row per knot family: a box that hides its regions (none for the triples, which are
    // never drawn), its pairs' colours and a note (how many pairs, or why none is drawn).
    const row = document.createElement("div");
    row.className = "family";
    row.dataset.family = family.id;
    row.title = family.help;
    if (family.drawn) {
      checkbox(row, `family-${family.id}`, family.label, "family");
    } else {
      const name = document.createElement("span");
      name.className = "family-name";
      name.textContent = family.label;
      row.appendChild(name);
    }
    const swatches = document.createElement("span");
    swatches.className = "family-swatches";
    const note = document.createElement("span");
    note.className = "family-note";
    row.append(swatches, note);
    elements.families.appendChild(row);
  }
  for (const kind of SNAPS) checkbox(elements.snaps, `snap-${kind.id}`, kind.label, "snap");
  for (const shown of LAYERS) checkbox(elements.layers, `layer-${shown.id}`, shown.label, "layer");
  for (const [keys, what] of SHORTCUTS) {
    const term = document.createElement("dt");
    term.textContent = keys;
    const description = document.createElement("dd");
    description.textContent = what;
    elements.shortcuts.append(term, description);
  }
  const items = [
    ["swatch knot-region", "knot pair's reach (colours: Knot families)"],
    ["swatch weights", "weight pair's reach"],
    ["swatch triangle", "control triangle"],
    ["swatch pin", "pin / tangent lock"],
    ["swatch fixed", "fixed control point"],
    ["swatch comb", "curvature comb"],
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
    elements.legend.appendChild(item);
  }
}

/** What the list shows: during a drag the solutions of its first answer with the kept one's
 * live value; after a release every solution at the release's target. */
function listed(state) {
  const drag = state.drag;
  if (drag?.kind === "point" && drag.alternatives) {
    return { solutions: drag.alternatives, chosen: drag.keptIndex, live: drag.solution, nearest: drag.nearest, family: drag.family, offsets: drag.offsets };
  }
  const entry = state.lastSolutions;
  return entry ? { solutions: entry.solutions, chosen: entry.chosen, live: null, nearest: entry.nearest, excluded: entry.excluded, family: state.family } : null;
}

let drawnList = null;

/** The list's note: the nearest point followed, the family kept, what the conditions left out. */
function solutionsNote(state, entry) {
  let note = "";
  if (entry?.nearest) {
    note = `Target outside every region: following the nearest reachable point (distance ${entry.nearest.distance.toPrecision(3)}).`;
  } else if (state.drag?.kind === "point" && entry?.family) {
    note = `Kept through this drag: ${describeFamily(entry.family)} (keys 1–${Math.min(entry.solutions.length, 9)} switch).`;
  }
  if (entry?.excluded?.length > 0) {
    // What the pins, tangent locks and fixed control points ruled out (the API's `excluded`).
    const dropped = entry.excluded.map((e) => `${e.count} ${e.method.replace("_", " ")} (${e.reason})`).join("; ");
    note = `${note ? `${note} ` : ""}Left out under the conditions: ${dropped}.`;
  }
  return note;
}

/** The text of the list's entry `index`: the solution (the kept one's live values during a
 * drag), numbered among its pair's solutions when a folded pair has several. */
function entryText(entry, keys, index) {
  const { poleOffset = 0, knotOffset = poleOffset } = entry.offsets ?? {};
  const shown = index === entry.chosen && entry.live ? entry.live : entry.solutions[index];
  const siblings = keys.filter((key) => key === keys[index]).length;
  const which = siblings > 1 ? ` · solution ${keys.slice(0, index + 1).filter((key) => key === keys[index]).length} of ${siblings}` : "";
  return ` ${describeSolution(shown, poleOffset, knotOffset)}${which}`;
}

/** The solution list. A drag move changes only the kept entry's live values: then only
 * that entry's text is rewritten (rebuilding some forty entries per move costs the browser
 * a layout of them all). */
function drawSolutions(state, elements) {
  const entry = listed(state);
  const key = entry && [entry.solutions, entry.chosen, entry.live, entry.nearest];
  if (drawnList && key && key.every((value, i) => value === drawnList[i])) return;
  if (!drawnList && !key) return;
  const note = solutionsNote(state, entry);
  const { poleOffset = 0, knotOffset = poleOffset } = entry?.offsets ?? {};
  // A knot pair whose map folds gives several solutions: numbered "solution 2 of 3".
  const keys = (entry?.solutions ?? []).map((solution) => JSON.stringify(familyOf(solution, poleOffset, knotOffset)));
  const sameList = drawnList && key && key[0] === drawnList[0] && key[1] === drawnList[1] && key[3] === drawnList[3];
  drawnList = key;
  if (sameList && elements.solutionsNote.textContent === note) {
    const text = elements.solutions.children[entry.chosen]?.firstChild?.lastChild;
    if (text) {
      text.data = entryText(entry, keys, entry.chosen);
      return;
    }
  }
  elements.solutions.replaceChildren();
  elements.solutionsNote.textContent = note;
  for (const index of (entry?.solutions ?? []).keys()) {
    const item = document.createElement("li");
    const label = document.createElement("label");
    const radio = document.createElement("input");
    radio.type = "radio";
    radio.name = "solution";
    radio.value = String(index);
    radio.checked = index === entry.chosen;
    label.append(radio, document.createTextNode(entryText(entry, keys, index)));
    item.appendChild(label);
    if (index === entry.chosen) item.className = "kept";
    elements.solutions.appendChild(item);
  }
}

function drawBanner(state, elements) {
  const connection = state.connection;
  elements.banner.hidden = connection.state === "ok";
  elements.banner.classList.toggle("retrying", connection.state === "retrying");
  elements.retry.hidden = connection.state !== "unreachable";
  elements.bannerText.textContent =
    connection.state === "unreachable"
      ? "The knotshape service does not answer. The drawing stays as it was and nothing is committed; the page tries again every few seconds."
      : connection.state === "retrying"
        ? `The service is busy (503): trying again in ${connection.seconds} s…`
        : "";
}

const format = (value, digits) => (Number.isFinite(value) ? value.toFixed(digits) : "");

function drawReadout(state, elements) {
  const digits = decimals(state.view.frame);
  const parts = [];
  if (state.pointer) parts.push(`pointer x ${format(state.pointer[0], digits)}  y ${format(state.pointer[1], digits)}`);
  const drag = state.drag;
  if (drag?.target) {
    parts.push(`${drag.kind === "pole" ? `control point ${drag.index}` : "target"} x ${format(drag.target[0], digits)}  y ${format(drag.target[1], digits)}${drag.snapped ? ` (snapped to ${drag.snapped})` : ""}`);
  } else if (state.pick) {
    parts.push(`picked t = ${state.pick.parameter.toPrecision(6)} at x ${format(state.pick.point[0], digits)}  y ${format(state.pick.point[1], digits)}`);
  }
  parts.push(`zoom ${(state.view.frame.scale / state.view.frame.fitted).toPrecision(3)}×`);
  elements.readout.textContent = parts.join("   ·   ");
}

let shownPick = null;

function drawTargetFields(state, elements) {
  const enabled = Boolean(state.pick) && !state.drag;
  for (const field of [elements.targetX, elements.targetY, elements.moveTo]) field.disabled = !enabled;
  if (state.pick !== shownPick) {
    shownPick = state.pick;
    const digits = decimals(state.view.frame) + 2;
    elements.targetX.value = state.pick ? format(state.pick.point[0], digits) : "";
    elements.targetY.value = state.pick ? format(state.pick.point[1], digits) : "";
  }
}

const counted = (count, one) => `${count} ${one}${count === 1 ? "" : "s"}`;

let drawnConditions = null;

/** The methods' note (the knot pairs off for this curve), the conditions' summary and the
 * draw-by-points buttons; rewritten only when what they show changed (a drag draws the
 * panel on every move, and every text set makes the browser lay the page out again). */
function drawConditions(state, elements) {
  const key = [currentCurve(state), state.constraints, state.fixed, state.sketch];
  if (drawnConditions && key.every((value, i) => value === drawnConditions[i])) return;
  drawnConditions = key;
  const body = document.body.dataset;
  body.constraints = JSON.stringify(state.constraints);
  body.fixed = JSON.stringify(state.fixed);
  body.sketch = JSON.stringify(state.sketch);
  elements.sketchFinish.disabled = state.sketch.length < 2;
  elements.sketchDiscard.disabled = state.sketch.length === 0;
  const curve = currentCurve(state);
  document.getElementById("method-knots").disabled = Boolean(knotsRefusal(curve));
  elements.methodsNote.textContent = methodsNote(curve) ?? "";
  const pins = state.constraints.filter((c) => c.order === 0).length;
  const tangents = state.constraints.length - pins;
  const parts = [];
  if (pins > 0) parts.push(counted(pins, "pin"));
  if (tangents > 0) parts.push(counted(tangents, "tangent lock"));
  if (state.fixed.length > 0) parts.push(`${counted(state.fixed.length, "fixed control point")} (${state.fixed.join(", ")})`);
  const note = state.constraints.length > 0 ? "; only the regions whose edits keep them are drawn" : "";
  elements.conditionsSummary.textContent = parts.length > 0 ? `${parts.join(", ")}${note}.` : "Nothing pinned.";
  elements.clearConditions.disabled = parts.length === 0;
}

let drawnFamilies = null;

/** The knot families' legend: per family its drawn pairs' colours and a note — how many
 * pairs are drawn, or why none is (the family does not apply, the service does not draw its
 * reach, or its regions lie in a tilted plane of a 3D curve) — and the boxes' state;
 * rewritten only when the regions or the boxes changed (not on every drag move). */
function drawFamilies(state, elements) {
  const key = [state.regions, state.families, state.methods];
  if (drawnFamilies && key.every((value, i) => value === drawnFamilies[i])) return;
  drawnFamilies = key;
  const entries = familyEntries(state.regions);
  const pairs = familyPairs(state.regions);
  const knotsOn = state.methods.includes("knots");
  for (const family of FAMILIES) {
    const row = elements.families.querySelector(`[data-family=${family.id}]`);
    const box = row.querySelector("input");
    if (box) box.checked = state.families[family.id];
    const labels = pairs[family.id] ?? [];
    const swatches = row.querySelector(".family-swatches");
    swatches.replaceChildren(...labels.map((label, index) => swatch(regionColour(family.id, label, index, labels.length), describeRegion(label))));
    const own = entries.filter((e) => e.entry.family === family.id);
    let note = "";
    if (!knotsOn) {
      note = "knots off";
    } else if (!state.regions) {
      note = family.drawn ? "pick a point" : "never drawn";
    } else if (labels.length > 0) {
      const sides = own.filter((e) => e.drawn && e.entry.side).map((e) => e.entry.side);
      note = `${labels.length} pair${labels.length === 1 ? "" : "s"}${sides.length > 0 ? ` (${sides.join(", ")})` : ""}`;
    } else if (own.length > 0) {
      note = [...new Set(own.map((e) => e.note))].join("; ");
    } else {
      note = family.id === "envelope" ? "degree 3 or more" : family.id === "triples" ? "3D curves" : "does not apply here";
    }
    const shownNote = row.querySelector(".family-note");
    shownNote.textContent = note;
    row.classList.toggle("hidden-family", Boolean(box) && !state.families[family.id]);
    row.dataset.pairs = String(labels.length);
  }
}

/** Sets body[data-name] to `value` only when it differs: every attribute written on the body
 * makes the browser match again the style rules that depend on the body's attributes. */
function mirror(name, value) {
  const body = document.body.dataset;
  if (body[name] !== value) body[name] = value;
}

let mirroredCurve = null;
let mirroredBase = null;

/** Draws the panel part of `state`. */
export function drawPanel(state, elements) {
  drawSolutions(state, elements);
  drawBanner(state, elements);
  drawReadout(state, elements);
  drawTargetFields(state, elements);
  elements.message.textContent = state.message;
  elements.error.textContent = state.error;
  elements.undo.disabled = state.history.past.length === 0;
  elements.redo.disabled = state.history.future.length === 0;
  for (const button of elements.tools.children) button.setAttribute("aria-pressed", String(button.dataset.tool === state.tool));
  for (const method of METHODS) document.getElementById(`method-${method.id.replace("_", "-")}`).checked = state.methods.includes(method.id);
  drawConditions(state, elements);
  drawFamilies(state, elements);
  for (const kind of SNAPS) document.getElementById(`snap-${kind.id}`).checked = state.snap[kind.id];
  for (const shown of LAYERS) document.getElementById(`layer-${shown.id}`).checked = state.layers[shown.id];
  const body = document.body.dataset;
  const curve = currentCurve(state);
  if (curve !== mirroredCurve) {
    mirroredCurve = curve;
    body.curve = JSON.stringify(curve);
  }
  const base = editBase(state);
  if (base !== mirroredBase) {
    mirroredBase = base;
    body.base = base === curve ? body.curve : JSON.stringify(base);
  }
  mirror("picked", state.pick ? JSON.stringify({ parameter: state.pick.parameter, point: state.pick.point }) : "");
  mirror("target", state.drag?.target ? JSON.stringify(state.drag.target) : state.lastTarget ? JSON.stringify(state.lastTarget) : "");
  mirror("family", state.drag?.family ? JSON.stringify(state.drag.family) : state.family ? JSON.stringify(state.family) : "");
  mirror("solutions", String(listed(state)?.solutions.length ?? 0));
  mirror("message", state.message);
  mirror("error", state.error);
  mirror("connection", state.connection.state);
  mirror("tool", state.tool);
  mirror("frame", JSON.stringify(state.view.frame));
}
