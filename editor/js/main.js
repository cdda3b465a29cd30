// The editor's start: finds the page's elements, builds the panel, sets up the one state
// (store.js) drawn by view.js, strip.js and panel.js, and binds the interaction to the
// actions of picking.js, dragging.js, precision.js, committing.js, files.js and the view's
// frame (viewport.js); sets up the 3D view (space/main.js) beside it, which surfaces and
// space curves open in, and routes the shared buttons (undo, redo, fit) to the view shown.
// Tests read the drag timings from window.editorTimings (2D) and window.knotshapeSpace (3D).

import * as api from "./api.js";
import * as committing from "./committing.js";
import * as conditions from "./conditions.js";
import * as connection from "./connection.js";
import * as dragging from "./dragging.js";
import * as files from "./files.js";
import * as geometry from "./geometry.js";
import * as model from "./state.js";
import * as picking from "./picking.js";
import * as precision from "./precision.js";
import * as sketching from "./sketching.js";
import * as store from "./store.js";
import * as viewport from "./viewport.js";
import { bind } from "./interaction.js";
import { buildPanel, drawPanel } from "./panel.js";
import { drawScene } from "./view.js";
import { drawStrip } from "./strip.js";
import { setAttribute } from "./render.js";
import { SAMPLE_CUBIC, SINGLE_BEZIER, sampleSurface } from "./sample.js";
import { setupSpace } from "./space/main.js";

const IDS = {
  scene: "scene", canvas: "canvas", strip: "knot-strip", solutions: "solutions", solutionsNote: "solutions-note",
  legend: "legend", message: "message", error: "error", undo: "undo", redo: "redo", fit: "fit", tools: "tools",
  sample: "sample", bezierSample: "bezier-sample", json: "curve-json", load: "load", export: "export",
  openFile: "open-file", download: "download", apiKey: "api-key", methods: "methods", snaps: "snaps",
  layers: "layers", shortcuts: "shortcuts", banner: "banner", bannerText: "banner-text", retry: "retry",
  readout: "readout", targetX: "target-x", targetY: "target-y", moveTo: "move-to",
  exportStep: "export-step", exportDxf: "export-dxf", imported: "imported",
  sketchTolerance: "sketch-tolerance", sketchFinish: "sketch-finish", sketchDiscard: "sketch-discard",
  methodsNote: "methods-note", families: "families", conditionsSummary: "conditions-summary", clearConditions: "clear-conditions",
};

const elements = Object.fromEntries(Object.entries(IDS).map(([name, id]) => [name, document.getElementById(id)]));

/** The 3D view's elements. */
const SPACE_IDS = {
  canvas: "space", frame: "space-frame", objects: "space-objects", methods: "space-methods", view: "space-view",
  solutions: "space-solutions", message: "space-message", error: "space-error", undo: "undo", redo: "redo",
};
const spaceElements = Object.fromEntries(Object.entries(SPACE_IDS).map(([name, id]) => [name, document.getElementById(id)]));
let space = null;

/** Switches between the 2D drawing and the 3D view. From 2D: the 3D view shows what it
 * had, or else the 2D editor's curve in space. From 3D with a curve selected that was edited
 * in 3D: that curve opens in the 2D editor (edited in its x–y projection, its z kept). */
function toggleMode() {
  if (space.active()) {
    const item = space.editor.selectedItem();
    space.hide();
    document.getElementById("view-mode").textContent = "3D view";
    // The 2D panel (its Undo and Redo among them) drawn again for the 2D editor.
    store.set({ ...store.get() });
    if (item?.kind === "curve" && item.edited) committing.loadCurve(files.editable(item.shape), `${item.name} in 2D (its x–y projection; z is kept).`);
    return;
  }
  document.getElementById("view-mode").textContent = "2D view";
  if (space.editor.items.length > 0) {
    space.show();
    return;
  }
  space.open([{ kind: "curve", shape: model.currentCurve(store.get()), name: "the curve" }], "The curve in 3D: orbit to see it from any side.");
}

/** Opens `objects` (`{ kind, shape, name }`) in the 3D view. */
function openInSpace(objects, message) {
  document.getElementById("view-mode").textContent = "2D view";
  return space.open(objects, message);
}

/** The knot strip's width, kept by a ResizeObserver: reading it while drawing would make
 * the browser lay the page out in the middle of every drag move. */
let stripWidth = 100;

function draw(state) {
  drawScene(state, elements.scene);
  drawStrip(state, elements.strip, stripWidth);
  drawPanel(state, elements);
}

/** Changes the view's frame by `change(frame)`. */
function reframe(change) {
  const state = store.get();
  store.set(model.withFrame(state, change(state.view.frame)));
}

function fitView() {
  const state = store.get();
  store.set(model.withFrame(state, viewport.fit(geometry.extent(model.editBase(state)), state.view.size)));
}

/** Gives the drawing `size` in pixels. Its size is set, not `100%` of its frame: the browser
 * lays the frame out more than once whenever the panel beside it changes (a drag move), and a
 * drawing that followed each of those sizes would lay all its marks out again every time
 * (2–3 ms per move on a 300-pole curve, measured by tests/editor/timing.rs). */
function sizeCanvas(size) {
  setAttribute(elements.canvas, "width", String(size.width));
  setAttribute(elements.canvas, "height", String(size.height));
  setAttribute(elements.canvas, "viewBox", `0 0 ${size.width} ${size.height}`);
}

function resize(size) {
  const state = store.get();
  if (size.width === 0 || size.height === 0) return;
  const before = state.view.size;
  sizeCanvas(size);
  if (before.width === size.width && before.height === size.height) return;
  store.set({ ...state, view: { size, frame: viewport.resized(state.view.frame, before, size) } });
}

function setMethods(methods) {
  const state = store.get();
  if (methods.length === 0) {
    store.set({ ...state, message: "", error: "Choose at least one method." });
    return;
  }
  // The regions drawn follow the methods (knot pairs, weight pairs): fetched again.
  store.nextGeneration();
  store.set({ ...state, methods, family: null, lastSolutions: null, regions: null, message: "", error: "" });
  if (state.pick) committing.refresh();
}

/** Which knot families' regions are drawn (solving still offers every family). */
function setFamilies(families) {
  store.set({ ...store.get(), families });
}

function setLayers(layers) {
  const state = store.get();
  store.set({ ...state, layers });
  // The comb is fetched when it is first shown.
  if (layers.comb && !state.drawing?.comb && !state.drag) committing.refresh();
}

function choose(index) {
  if (dragging.switchFamily(index)) return;
  committing.choose(index);
}

function start() {
  document.body.dataset.mode = "2d";
  space = setupSpace(spaceElements);
  files.setSpaceOpener(openInSpace);
  document.getElementById("view-mode").addEventListener("click", toggleMode);
  document.getElementById("surface-sample").addEventListener("click", () =>
    openInSpace([{ kind: "surface", shape: sampleSurface(6), name: "sample surface (bicubic, 6 × 6 poles)" }],
      "The sample surface: press on it and drag; drag the background to orbit."));
  document.getElementById("space-export-step").addEventListener("click", () => files.exportSpaceStep(space.editor.exportable(), elements));
  document.getElementById("space-export").addEventListener("click", () => files.exportSpaceSelected(space.editor.selectedItem(), elements));
  buildPanel(elements);
  stripWidth = Math.max(elements.strip.clientWidth, 100);
  new ResizeObserver(() => {
    stripWidth = Math.max(elements.strip.clientWidth, 100);
    if (store.get()) draw(store.get());
  }).observe(elements.strip);
  const frame = elements.canvas.parentElement;
  const size = { width: Math.max(frame.clientWidth, 100), height: Math.max(frame.clientHeight, 100) };
  sizeCanvas(size);
  const first = structuredClone(SAMPLE_CUBIC);
  store.setup(model.initialState(first, viewport.fit(geometry.extent(first), size), size), draw);
  connection.watch(() => {
    if (!store.get().drawing) committing.refresh();
  });
  bind(elements, {
    toCurve: (pixel) => viewport.toCurve(store.get().view.frame, pixel),
    tool: () => store.get().tool,
    pick: picking.pick,
    dropPick: picking.dropPick,
    startPointDrag: dragging.startPointDrag,
    startPoleDrag: dragging.startPoleDrag,
    dragTo: dragging.dragTo,
    release: dragging.release,
    cancel: dragging.cancel,
    escape: () => dragging.cancel() || picking.dropPick(),
    hover: (point) => store.set({ ...store.get(), pointer: point }),
    panBy: (delta) => reframe((frame) => viewport.pan(frame, delta)),
    zoomAt: (pixel, factor) => reframe((frame) => viewport.zoomAbout(frame, pixel, factor)),
    zoomCentre: (factor) => {
      const { width, height } = store.get().view.size;
      reframe((frame) => viewport.zoomAbout(frame, [width / 2, height / 2], factor));
    },
    fit: () => (space.active() ? space.fit() : fitView()),
    resize,
    nudge: precision.nudge,
    moveToTyped: precision.moveToTyped,
    choose,
    undo: () => (space.active() ? space.undo() : committing.historyStep(model.undo)),
    redo: () => (space.active() ? space.redo() : committing.historyStep(model.redo)),
    setTool: (tool) => {
      document.body.dataset.tool = tool;
      store.set({ ...store.get(), tool });
    },
    setMethods,
    setSnap: (snap) => store.set({ ...store.get(), snap }),
    setLayers,
    setFamilies,
    mark: (point, pole) => {
      const tool = store.get().tool;
      if (pole !== undefined) return tool === "pin" ? conditions.toggleFixed(pole) : conditions.toggleAt(point, 1);
      return conditions.toggleAt(point, tool === "pin" ? 0 : 1);
    },
    clearConditions: conditions.clearAll,
    addSketchPoint: sketching.addPoint,
    dropSketchPoint: sketching.dropLast,
    discardSketch: sketching.discard,
    finishSketch: () => sketching.finish(elements.sketchTolerance.value),
    sample: () => committing.loadCurve(structuredClone(SAMPLE_CUBIC), "The sample cubic."),
    bezierSample: () => committing.loadCurve(structuredClone(SINGLE_BEZIER), "A single Bézier piece: pick a point and knots are inserted around it."),
    loadText: files.loadText,
    exportCurve: () => files.exportCurve(elements),
    exportFile: (format) => files.exportFile(format, elements),
    openFile: (name, text) => files.openFile(name, text, elements),
    chooseImported: files.chooseImported,
    retry: connection.probe,
    setApiKey: (key) => {
      api.setApiKey(key);
      return committing.refresh();
    },
    apiKey: api.apiKey,
  });
  document.body.dataset.tool = "edit";
  window.editorTimings = dragging.timings;
  window.editorMoves = dragging.moves;
  committing.refresh("The sample cubic: press on the curve and drag it.").then(() => {
    document.body.dataset.ready = "true";
  });
}

start();
