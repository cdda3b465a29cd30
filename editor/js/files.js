// Curves and surfaces in and out: JSON text pasted or opened (a curve or surface object, or
// an object with a `curve` or `surface`), exported as JSON; STEP and DXF files opened through
// /v1/curves/import and exported through /v1/curves/export. Planar curves open in the 2D
// editor (the first curve loaded, the others offered in a list); a file with surfaces or
// space curves, a surface and a space curve open in the 3D view (every object of the file
// shown, one chosen for editing), which exports them all as STEP. Errors name the line and
// column of the user's own text.

import * as api from "./api.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as store from "./store.js";
import { failureMessage, loadCurve } from "./committing.js";
import { describeSyntaxError, textSource } from "./problems.js";

/** Opens objects in the 3D view (main.js sets it: `(objects, message) => Promise`). */
let openInSpace = null;

/** Sets the function that opens `{ kind, shape, name }` objects in the 3D view. */
export function setSpaceOpener(opener) {
  openInSpace = opener;
}

/** Whether `curve` has a control point off the plane z = 0. */
function isSpaceCurve(curve) {
  return curve.control_points.some((p) => p.length === 3 && p[2] !== 0);
}

/** The surface in parsed JSON `value` (a surface object or `{ surface }`), or null. */
function surfaceIn(value) {
  const surface = value && typeof value === "object" && value.surface && typeof value.surface === "object" ? value.surface : value;
  return surface && typeof surface === "object" && Number.isInteger(surface.degree_u) && Array.isArray(surface.control_points) ? surface : null;
}

/** The curve in `text` and where it sits in it, or { error }. */
export function parseCurve(text) {
  let value;
  try {
    value = JSON.parse(text);
  } catch {
    return { error: `The text is not JSON: ${describeSyntaxError(text)}` };
  }
  const wrapped = value && typeof value === "object" && value.curve && typeof value.curve === "object";
  const curve = wrapped ? value.curve : value;
  if (!curve || typeof curve !== "object" || !Array.isArray(curve.control_points) || !Array.isArray(curve.knots) || !Number.isInteger(curve.degree)) {
    return { error: "A curve needs `degree`, `control_points` and `knots` (and optionally `weights`)." };
  }
  return { curve, source: textSource(text, wrapped ? "/curve" : "") };
}

/** Loads the curve in `text` (pasted or opened). */
export function loadText(text, message = "Curve loaded.") {
  let value = null;
  try {
    value = JSON.parse(text);
  } catch {
    // parseCurve says where.
  }
  const surface = surfaceIn(value);
  if (surface) return openInSpace([{ kind: "surface", shape: surface, name: "the surface" }], "Surface loaded: press on it and drag.");
  const parsed = parseCurve(text);
  if (!parsed.error && isSpaceCurve(parsed.curve)) {
    // Loaded in the 2D editor as before (its x–y projection), and shown in 3D, where it is
    // edited in space; *2D view* goes back to the projection.
    return loadCurve(parsed.curve, message, parsed.source).then(async (loaded) => {
      if (loaded) await openInSpace([{ kind: "curve", shape: parsed.curve, name: "the space curve" }], "Space curve loaded in 3D: press on it and drag (2D view: its x–y projection).");
      return loaded;
    });
  }
  if (parsed.error) {
    store.set({ ...store.get(), message: "", error: parsed.error });
    return Promise.resolve(false);
  }
  return loadCurve(parsed.curve, message, parsed.source);
}

/** Puts the committed curve into the text field and offers it as a download. */
export function exportCurve(elements) {
  const text = JSON.stringify(model.currentCurve(store.get()), null, 2);
  elements.json.value = text;
  offer(elements, text, "curve.json", "application/json");
  store.set({ ...store.get(), message: "Exported: the curve is in the text field and in the download link.", error: "" });
}

/** The file formats the service reads and writes, by file name extension. */
const FORMATS = { step: "step", stp: "step", p21: "step", dxf: "dxf" };

/** The format of a file called `name` ("step", "dxf"), or null (JSON). */
export function formatOf(name) {
  const extension = name.toLowerCase().split(".").pop();
  return FORMATS[extension] ?? null;
}

/** An imported curve as the page edits it: the full knot vector instead of distinct values
 * with multiplicities, 2D when every z is 0 (DXF writes planar curves so), without `source`.
 * A periodic curve keeps its form. */
export function editable(imported) {
  const { source: _source, ...curve } = imported;
  const planar = curve.control_points.every((p) => p.length === 2 || p[2] === 0);
  const control_points = planar ? curve.control_points.map((p) => [p[0], p[1]]) : curve.control_points;
  if (curve.periodic) return { ...curve, control_points };
  const plain = { degree: curve.degree, control_points, knots: geometry.fullKnots(curve) };
  if (curve.weights) plain.weights = curve.weights;
  return plain;
}

/** The curves of the last STEP or DXF file opened (for the list). */
let imported = [];

function describeImported(curve, index) {
  return `${index + 1}. ${curve.source ?? ""} · degree ${curve.degree} · ${curve.control_points.length} control points${curve.weights ? " · rational" : ""}`;
}

/** Opens the file `name` with `text`: JSON as pasted text, STEP and DXF through the service
 * (the first curve loaded; with several, a list offers the others). */
export function openFile(name, text, elements) {
  const format = formatOf(name);
  if (!format) {
    elements.json.value = text;
    return loadText(text, `Opened ${name}.`);
  }
  return store.task(async () => {
    const answer = await api.importFile(format, text);
    if (!answer.ok) {
      store.set({ ...store.get(), message: "", error: failureMessage(answer.problem, `Cannot read ${name}: `) });
      return false;
    }
    const { curves, skipped } = answer.value;
    const surfaces = answer.value.surfaces ?? [];
    const others = skipped > 0 ? ` (${skipped} other curve entities skipped)` : "";
    if (surfaces.length > 0 || curves.some(isSpaceCurve)) {
      // Curves are loaded in the 2D editor as before (the list offers the others); the 3D
      // view shows every surface and curve of the file.
      if (curves.length > 0) {
        imported = curves;
        const list = elements.imported;
        list.replaceChildren(...curves.map((curve, index) => new Option(describeImported(curve, index), String(index))));
        list.hidden = curves.length < 2;
        const more = curves.length > 1 ? `: curve 1 of ${curves.length} (choose another in the list)` : "";
        await loadCurve(editable(curves[0]), `Opened ${name}${more}${others}.`);
      }
      const objects = [
        ...surfaces.map((surface, index) => ({ kind: "surface", shape: withoutSource(surface), name: `surface ${surface.source ?? index + 1} · ${surface.degree_u}×${surface.degree_v} · ${surface.control_points.length}×${surface.control_points[0].length} poles` })),
        ...curves.map((curve, index) => ({ kind: "curve", shape: withoutSource(curve), name: `curve ${curve.source ?? index + 1} · degree ${curve.degree} · ${curve.control_points.length} poles` })),
      ];
      await openInSpace(objects, `Opened ${name}: ${surfaces.length} surface${surfaces.length === 1 ? "" : "s"} and ${curves.length} curve${curves.length === 1 ? "" : "s"} in 3D (choose the one to edit in the list)${others}.`);
      return true;
    }
    if (curves.length === 0) {
      store.set({ ...store.get(), message: "", error: `No B-spline curve in ${name}${others}.` });
      return false;
    }
    imported = curves;
    const list = elements.imported;
    list.replaceChildren(...curves.map((curve, index) => new Option(describeImported(curve, index), String(index))));
    list.hidden = curves.length < 2;
    const more = curves.length > 1 ? `: curve 1 of ${curves.length} (choose another in the list)` : "";
    return loadCurve(editable(curves[0]), `Opened ${name}${more}${others}.`);
  });
}

/** Loads curve `index` of the last file opened. */
export function chooseImported(index) {
  const curve = imported[index];
  if (!curve) return Promise.resolve(false);
  return loadCurve(editable(curve), `Curve ${index + 1} of ${imported.length} (${curve.source ?? "no name"}).`);
}

/** `object` without its `source` (the entity it came from). */
function withoutSource(object) {
  const { source: _source, ...rest } = object;
  return rest;
}

/** Exports every object of the 3D view (`{ curves, surfaces }`) as one STEP file. */
export function exportSpaceStep({ curves, surfaces }, elements) {
  return store.task(async () => {
    const answer = await api.exportStep(curves, surfaces);
    if (!answer.ok) {
      elements.download.hidden = true;
      document.getElementById("space-error").textContent = failureMessage(answer.problem, "Cannot export: ");
      return false;
    }
    offer(elements, answer.value, "model.step", "model/step");
    document.getElementById("space-message").textContent = "Exported: model.step (written by the service) is in the download link.";
    return true;
  });
}

/** Puts the selected 3D object's JSON (`{ "surface": .. }` or `{ "curve": .. }`) into the text
 * field and offers it as a download. */
export function exportSpaceSelected(item, elements) {
  if (!item) return;
  const text = JSON.stringify({ [item.kind]: item.shape }, null, 2);
  elements.json.value = text;
  offer(elements, text, `${item.kind}.json`, "application/json");
}

/** Offers `text` as the download `name` in the page's download link (a data: URL: the
 * file is in the link itself, nothing to revoke). */
function offer(elements, text, name, type) {
  const link = elements.download;
  link.href = `data:${type};charset=utf-8,${encodeURIComponent(text)}`;
  link.download = name;
  link.textContent = `Download ${name}`;
  link.hidden = false;
}

/** Exports the committed curve as a STEP or DXF file (written by the service). */
export function exportFile(format, elements) {
  return store.task(async () => {
    const answer = await api.exportFile(format, [model.currentCurve(store.get())]);
    if (!answer.ok) {
      store.set({ ...store.get(), message: "", error: failureMessage(answer.problem, "Cannot export: ") });
      return false;
    }
    const name = format === "step" ? "curve.step" : "curve.dxf";
    offer(elements, answer.value, name, format === "step" ? "model/step" : "image/vnd.dxf");
    store.set({ ...store.get(), message: `Exported: ${name} (written by the service) is in the download link.`, error: "" });
    return true;
  });
}
