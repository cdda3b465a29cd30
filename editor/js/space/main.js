// The 3D view's start: the canvas, the editor of editing.js, the panel, and the input —
// press on an object and drag (Alt: along its normal), Esc cancels, release commits; drag the
// background to orbit, Shift/middle/right or Space + drag to pan, wheel or pinch to zoom about
// the pointer; F fits, Shift+1–7 the standard views, O toggles perspective, Ctrl+Z / Ctrl+Y
// undo and redo, 1–9 choose a solution of the last move. Tests reach it through
// `window.knotshapeSpace`.

import { createView } from "./scene.js";
import { createEditor } from "./editing.js";
import { buildSpacePanel, drawSpacePanel, VIEW_BUTTONS } from "./panel.js";
import { boxOf, polesOf, warmUpGroup } from "./objects.js";

/** Whether the browser dispatches `pointerrawupdate` (Chromium, in secure contexts). */
const RAW_UPDATES = typeof window !== "undefined" && "onpointerrawupdate" in window;

/** During a drag the panel (the move's message) is redrawn at most this often. */
const DRAG_PANEL_INTERVAL_MS = 100;

/** Zoom of one + or − key press. */
const KEY_ZOOM = 1.25;

function isTextField(target) {
  return target instanceof HTMLElement && (target.isContentEditable || /^(INPUT|TEXTAREA|SELECT)$/.test(target.tagName)) && target.type !== "checkbox";
}

/** Sets up the 3D view in the page's `elements` (canvas `space`, its frame, the panel's
 * parts); `onLeave()` is called when the user asks for the 2D view. */
export function setupSpace(elements) {
  let settleTimer = null;
  const view = createView(elements.canvas, (kind) => {
    if (kind === "settled") {
      clearTimeout(settleTimer);
      settleTimer = setTimeout(() => editor.viewSettled(), 150);
    }
  });
  // The panel is redrawn once per change, but during a drag at most every
  // `DRAG_PANEL_INTERVAL_MS`: each redraw costs the page a style, layout and paint pass in the
  // frame that shows the preview, and the preview comes first.
  let scheduled = false;
  let lastPanel = 0;
  const redrawPanel = () => {
    scheduled = false;
    lastPanel = performance.now();
    drawSpacePanel(editor, elements, actions);
    document.body.dataset.spaceBusy = String(editor.busy > 0 || editor.drag !== null);
  };
  const notify = () => {
    if (scheduled) return;
    scheduled = true;
    const wait = editor.drag ? lastPanel + DRAG_PANEL_INTERVAL_MS - performance.now() : 0;
    if (wait > 0) setTimeout(redrawPanel, wait);
    else queueMicrotask(redrawPanel);
  };
  const editor = createEditor(view, notify);

  const fit = () => {
    if (editor.items.length === 0) return;
    view.fit(boxOf(editor.items.flatMap((item) => polesOf(item))));
  };
  const actions = {
    select: (index) => editor.select(index),
    standardView: (name) => {
      if (editor.items.length === 0) return;
      view.fit(boxOf(editor.items.flatMap((item) => polesOf(item))), name);
    },
    fit,
    setPerspective: (on) => view.setPerspective(on),
    setLayers: (layers) => editor.setLayers(layers),
    setMethods: (kind, methods) => editor.setMethods(kind, methods),
    choose: (index) => editor.choose(index),
  };
  buildSpacePanel(elements, actions);

  new ResizeObserver(() => {
    const frame = elements.frame;
    if (frame.clientWidth > 0 && frame.clientHeight > 0) view.resize(frame.clientWidth, frame.clientHeight);
  }).observe(elements.frame);

  // Pointer: a press on an object picks and drags it; anywhere else the orbit controls
  // take the press (this listener runs first: capture at the canvas).
  const canvas = elements.canvas;
  let gesture = null;
  let spaceHeld = false;
  const pixelOf = (event) => {
    const bounds = canvas.getBoundingClientRect();
    return [event.clientX - bounds.left, event.clientY - bounds.top];
  };
  canvas.addEventListener("pointerdown", (event) => {
    canvas.focus({ preventScroll: true });
    if (event.button !== 0 || event.shiftKey || event.ctrlKey || event.metaKey || spaceHeld) return;
    const hit = editor.hit(pixelOf(event));
    if (!hit) return;
    event.stopImmediatePropagation();
    event.preventDefault();
    canvas.setPointerCapture(event.pointerId);
    gesture = { pointerId: event.pointerId };
    canvas.dataset.dragging = "true";
    editor.startDrag(hit);
  }, { capture: true });
  // Hover: the cursor shows *grab* over an object (a ray cast at most once a frame).
  let hoverAt = null;
  const hover = () => {
    const pixel = hoverAt;
    hoverAt = null;
    if (!pixel || gesture) return;
    const over = editor.hit(pixel) !== null;
    if (canvas.dataset.hover !== String(over)) canvas.dataset.hover = String(over);
  };
  canvas.addEventListener("pointermove", (event) => {
    if (!gesture || event.pointerId !== gesture.pointerId) {
      if (event.buttons === 0 && hoverAt === null) requestAnimationFrame(hover);
      if (event.buttons === 0) hoverAt = pixelOf(event);
      return;
    }
    event.stopImmediatePropagation();
    if (!RAW_UPDATES) editor.dragTo(pixelOf(event), event.altKey, event.timeStamp);
  }, { capture: true });
  // A drag follows the pointer's raw updates where the browser has them: they are
  // dispatched as they come, where `pointermove` waits for the next frame (Chromium aligns
  // it with the frames, which come late while WebGL frames are presented in software).
  if (RAW_UPDATES) {
    canvas.addEventListener("pointerrawupdate", (event) => {
      if (!gesture || event.pointerId !== gesture.pointerId) return;
      editor.dragTo(pixelOf(event), event.altKey, event.timeStamp);
    });
  }
  canvas.addEventListener("pointerleave", () => {
    canvas.dataset.hover = "false";
  });
  const end = (event) => {
    if (!gesture || event.pointerId !== gesture.pointerId) return;
    event.stopImmediatePropagation();
    gesture = null;
    canvas.dataset.dragging = "false";
    if (event.type === "pointercancel") editor.cancel();
    else editor.release();
  };
  canvas.addEventListener("pointerup", end, { capture: true });
  canvas.addEventListener("pointercancel", end, { capture: true });

  const setSpaceHeld = (held) => {
    spaceHeld = held;
    view.controls.mouseButtons.LEFT = held ? view.THREE.MOUSE.PAN : view.THREE.MOUSE.ROTATE;
  };
  const zoomBy = (factor) => {
    if (view.camera.isOrthographicCamera) {
      view.camera.zoom *= factor;
      view.camera.updateProjectionMatrix();
    } else {
      const target = view.controls.target;
      view.camera.position.sub(target).multiplyScalar(1 / factor).add(target);
    }
    view.controls.update();
    view.request();
  };

  // Keys, while the 3D view is shown: handled here first (the 2D editor's own keys do not
  // apply to it).
  window.addEventListener("keydown", (event) => {
    if (document.body.dataset.mode !== "3d") return;
    if (event.key === "Escape") {
      if (gesture) gesture = null;
      canvas.dataset.dragging = "false";
      editor.cancel();
      event.stopImmediatePropagation();
      return;
    }
    if (isTextField(event.target)) return;
    const command = event.ctrlKey || event.metaKey;
    const lower = event.key.toLowerCase();
    const standard = /^Digit([1-7])$/.exec(event.code);
    let handled = true;
    if (command && lower === "z") {
      if (event.shiftKey) editor.redo();
      else editor.undo();
    } else if (command && lower === "y") {
      editor.redo();
    } else if (command || event.altKey) {
      handled = event.key === "Alt";
    } else if (event.shiftKey && standard) {
      actions.standardView(VIEW_BUTTONS[Number(standard[1]) - 1].id);
    } else if (lower === "f") {
      fit();
    } else if (lower === "o") {
      const box = elements.view.querySelector('input[name="perspective"]');
      box.checked = !box.checked;
      view.setPerspective(box.checked);
    } else if (event.key === " ") {
      setSpaceHeld(true);
    } else if (event.key === "+" || event.key === "=") {
      zoomBy(KEY_ZOOM);
    } else if (event.key === "-" || event.key === "_") {
      zoomBy(1 / KEY_ZOOM);
    } else if (/^[1-9]$/.test(event.key)) {
      editor.choose(Number(event.key) - 1);
    } else {
      // The 2D editor's keys (its tools, nudges) do nothing in 3D; Tab and Enter keep their
      // meaning on the page's controls.
      handled = !["Tab", "Enter"].includes(event.key);
    }
    if (handled) {
      event.preventDefault();
      event.stopImmediatePropagation();
    }
  }, { capture: true });
  window.addEventListener("keyup", (event) => {
    if (event.key === " ") setSpaceHeld(false);
  });
  window.addEventListener("blur", () => setSpaceHeld(false));

  // The first time the view is shown, it draws one of every kind of primitive it draws
  // (objects.js warmUpGroup): the browser compiles their shaders and states then, not during
  // the first moves of a drag.
  let warmedUp = false;
  const warmUpOnce = () => {
    if (warmedUp) return;
    warmedUp = true;
    view.warmUp(warmUpGroup());
  };

  const space = {
    view,
    editor,
    active: () => document.body.dataset.mode === "3d",
    /** Shows the 3D view with `objects` (`{ kind, shape, name }`). */
    open: (objects, message) => {
      document.body.dataset.mode = "3d";
      view.resize(elements.frame.clientWidth, elements.frame.clientHeight);
      warmUpOnce();
      return editor.open(objects, message);
    },
    /** Shows the 3D view with what it had. */
    show: () => {
      document.body.dataset.mode = "3d";
      view.resize(elements.frame.clientWidth, elements.frame.clientHeight);
      warmUpOnce();
      notify();
    },
    hide: () => {
      editor.cancel();
      document.body.dataset.mode = "2d";
    },
    undo: () => editor.undo(),
    redo: () => editor.redo(),
    cancel: () => editor.cancel(),
    fit,
  };

  // For tests: the camera, projections of model points to client pixels, the objects.
  window.knotshapeSpace = {
    camera: () => view.describe(),
    project: (point) => {
      const bounds = canvas.getBoundingClientRect();
      const [x, y] = view.toPixel(point);
      return [bounds.left + x, bounds.top + y];
    },
    shapes: () => editor.items.map((item) => ({ kind: item.kind, name: item.name, shape: item.shape, triangles: item.mesh?.triangles.length ?? 0 })),
    selected: () => editor.selected,
    pick: () => editor.pick,
    lastCommit: () => editor.lastCommit ?? null,
    lastPiece: () => (editor.lastPiece ? { rows: editor.lastPiece.rows, columns: editor.lastPiece.columns } : null),
    busy: () => editor.busy > 0 || editor.drag !== null,
    history: () => ({ undo: editor.history.length, redo: editor.future.length }),
    regions: () => editor.regions?.userData.counts ?? null,
    timings: editor.timings,
    moves: editor.moves,
    renderMs: () => view.lastRenderMs,
    /** Whether the page found WebGL drawn in software (it then waits for each preview's raster). */
    software: () => view.software,
    /** The selected surface's iso-lines: the (u, v) of their chords' ends and the tolerance. */
    isoLines: () => {
      const item = editor.selectedItem();
      const iso = item?.group?.getObjectByName("iso");
      return iso ? { parameters: Array.from(iso.userData.parameters), tolerance: item.tolerance } : null;
    },
    /** Draws now (a test reads the canvas in the same task: the drawing buffer is not kept). */
    renderNow: () => view.renderNow(),
  };
  return space;
}
