// The interaction: turns what a person does into the controller's actions. On the drawing:
// a press on the curve picks and, once the pointer has moved a few pixels, drags in the same
// gesture; a press on the dot or a control point drags it; a press on the background (or
// anywhere with Space held, the middle button or the pan tool) pans; the wheel and a pinch
// zoom about the pointer. A press that never moves is a click and changes no curve. Keys:
// see options.js SHORTCUTS. The panel's buttons, lists and fields call their actions. It
// keeps only what a gesture in progress needs (where it started, whether it moved).

/** Pixels the pointer must move before a press becomes a drag. */
export const DRAG_THRESHOLD = 4;
/** Zoom per wheel pixel (trackpad pinches come as wheel events with Ctrl, and finer). */
const WHEEL_ZOOM = 0.002;
const PINCH_WHEEL_ZOOM = 0.01;
/** Zoom of one + or − key press. */
const KEY_ZOOM = 1.25;

const isTextField = (target) =>
  target instanceof HTMLTextAreaElement ||
  target instanceof HTMLSelectElement ||
  (target instanceof HTMLInputElement && !["checkbox", "radio", "button"].includes(target.type));

/** Wires the page's `elements` to `actions` (see main.js). */
export function bind(elements, actions) {
  const canvas = elements.canvas;
  const raw = "onpointerrawupdate" in canvas;
  let gesture = null;
  let spaceHeld = false;
  const touches = new Map();
  let pinch = null;
  let bounds = canvas.getBoundingClientRect();

  const pixelOf = (event) => [event.clientX - bounds.left, event.clientY - bounds.top];

  /** What a press on `target` grabs. */
  function grabbed(event) {
    if (actions.tool() === "pan" || spaceHeld || event.button === 1) return { kind: "pan" };
    const classes = event.target.classList;
    if (actions.tool() === "points") return { kind: "point" };
    if (actions.tool() === "pin" || actions.tool() === "tangent") {
      // A click marks (pins, locks a tangent, fixes a control point); a drag pans.
      if (classes?.contains("pole-grip")) return { kind: "mark", index: Number(event.target.dataset.index) };
      if (classes?.contains("curve-hit") || classes?.contains("picked")) return { kind: "mark" };
      return { kind: "background" };
    }
    if (classes?.contains("picked")) return { kind: "dot" };
    if (classes?.contains("pole-grip")) return { kind: "pole", index: Number(event.target.dataset.index) };
    if (classes?.contains("curve-hit")) return { kind: "curve" };
    return { kind: "background" };
  }

  function beginDrag(g) {
    g.dragging = true;
    if (g.kind === "pole") {
      actions.startPoleDrag(g.index, g.press);
    } else {
      actions.startPointDrag(g.press);
    }
    actions.dragTo(actions.toCurve(g.lastPixel), g.lastStamp);
  }

  canvas.addEventListener("pointerdown", (event) => {
    bounds = canvas.getBoundingClientRect();
    const pixel = pixelOf(event);
    if (event.pointerType === "touch") {
      touches.set(event.pointerId, pixel);
      if (touches.size === 2) {
        // A second finger: the gesture becomes a pinch (a drag in progress is cancelled).
        if (gesture?.dragging) actions.cancel();
        gesture = null;
        const [a, b] = [...touches.values()];
        pinch = { distance: Math.hypot(a[0] - b[0], a[1] - b[1]), middle: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] };
        return;
      }
    }
    if (gesture || (event.button !== 0 && event.button !== 1)) return;
    event.preventDefault();
    canvas.focus({ preventScroll: true });
    canvas.setPointerCapture(event.pointerId);
    const what = grabbed(event);
    const g = {
      id: event.pointerId,
      ...what,
      startPixel: pixel,
      lastPixel: pixel,
      lastStamp: event.timeStamp,
      press: actions.toCurve(pixel),
      moved: false,
      ready: what.kind !== "curve",
      dragging: false,
      cancelled: false,
    };
    gesture = g;
    if (g.kind === "curve") {
      actions.pick(g.press).then((picked) => {
        // The pointer may be up already: a quick flick still drags, then releases.
        if (gesture !== g && !g.released) return;
        g.ready = picked;
        if (!picked) {
          g.kind = "background";
        } else if (g.moved && !g.cancelled) {
          beginDrag(g);
          if (g.released) actions.release();
        }
      });
    }
  });

  function pinchMove(event) {
    touches.set(event.pointerId, pixelOf(event));
    const [a, b] = [...touches.values()];
    const distance = Math.hypot(a[0] - b[0], a[1] - b[1]);
    const middle = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    actions.panBy([middle[0] - pinch.middle[0], middle[1] - pinch.middle[1]]);
    if (pinch.distance > 0 && distance > 0) actions.zoomAt(middle, distance / pinch.distance);
    pinch = { distance, middle };
  }

  function gestureMove(event) {
    if (pinch && touches.has(event.pointerId)) {
      pinchMove(event);
      return;
    }
    const g = gesture;
    if (!g || event.pointerId !== g.id || g.cancelled) return;
    const pixel = pixelOf(event);
    const previous = g.lastPixel;
    g.lastPixel = pixel;
    g.lastStamp = event.timeStamp;
    if (!g.moved) {
      if (Math.hypot(pixel[0] - g.startPixel[0], pixel[1] - g.startPixel[1]) < DRAG_THRESHOLD) return;
      g.moved = true;
      if (g.kind === "mark" || g.kind === "point") g.kind = "background";
      if (g.kind === "pan" || g.kind === "background") {
        document.body.dataset.panning = "true";
        actions.panBy([pixel[0] - g.startPixel[0], pixel[1] - g.startPixel[1]]);
        return;
      }
      if (g.ready === true) beginDrag(g);
      return;
    }
    if (g.kind === "pan" || g.kind === "background") {
      actions.panBy([pixel[0] - previous[0], pixel[1] - previous[1]]);
    } else if (g.dragging) {
      actions.dragTo(actions.toCurve(pixel), event.timeStamp);
    }
  }

  // pointerrawupdate (secure contexts) comes as soon as the pointer moves, not at the next
  // frame like pointermove: a drag's request leaves up to a frame earlier.
  canvas.addEventListener(raw ? "pointerrawupdate" : "pointermove", gestureMove);
  canvas.addEventListener("pointermove", (event) => {
    if (!gesture?.dragging && !pinch) actions.hover(actions.toCurve(pixelOf(event)));
  });
  canvas.addEventListener("pointerleave", () => {
    if (!gesture) actions.hover(null);
  });

  function gestureEnd(event, cancelled) {
    if (touches.delete(event.pointerId) && pinch) {
      if (touches.size < 2) pinch = null;
      return;
    }
    const g = gesture;
    if (!g || event.pointerId !== g.id) return;
    gesture = null;
    document.body.dataset.panning = "false";
    if (canvas.hasPointerCapture(event.pointerId)) canvas.releasePointerCapture(event.pointerId);
    if (g.cancelled) return;
    g.released = true;
    if (g.dragging) {
      if (cancelled) actions.cancel();
      else actions.release();
    } else if (!g.moved && g.kind === "background" && !cancelled) {
      actions.dropPick();
    } else if (!g.moved && g.kind === "mark" && !cancelled) {
      actions.mark(g.press, g.index);
    } else if (!g.moved && g.kind === "point" && !cancelled) {
      actions.addSketchPoint(g.press);
    }
  }
  canvas.addEventListener("pointerup", (event) => gestureEnd(event, false));
  canvas.addEventListener("pointercancel", (event) => gestureEnd(event, true));

  canvas.addEventListener("wheel", (event) => {
    event.preventDefault();
    bounds = canvas.getBoundingClientRect();
    const lines = event.deltaMode === 1 ? 16 : event.deltaMode === 2 ? 400 : 1;
    const rate = event.ctrlKey ? PINCH_WHEEL_ZOOM : WHEEL_ZOOM;
    actions.zoomAt(pixelOf(event), Math.exp(-event.deltaY * lines * rate));
  }, { passive: false });

  const setSpace = (held) => {
    spaceHeld = held;
    document.body.dataset.space = String(held);
  };

  document.addEventListener("keydown", (event) => {
    const target = event.target;
    const key = event.key;
    if (key === "Escape") {
      if (gesture) {
        // The rest of this press does nothing (also when its pick is still on its way).
        gesture.cancelled = true;
        if (gesture.dragging) actions.cancel();
      } else if (!isTextField(target)) {
        actions.escape();
      }
      return;
    }
    if (isTextField(target)) return; // the field's own keys
    const onDrawing = target === canvas || target === document.body || target === document.documentElement;
    const command = event.ctrlKey || event.metaKey;
    const lower = key.toLowerCase();
    if (command && lower === "z") {
      event.preventDefault();
      if (event.shiftKey) actions.redo();
      else actions.undo();
    } else if (command && lower === "y") {
      event.preventDefault();
      actions.redo();
    } else if (command || event.altKey) {
      // Leave the browser's own shortcuts alone.
    } else if (key === " " && onDrawing) {
      event.preventDefault();
      setSpace(true);
    } else if (key.startsWith("Arrow") && onDrawing) {
      event.preventDefault();
      const step = event.shiftKey ? 10 : 1;
      const [dx, dy] = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, -step], ArrowDown: [0, step] }[key];
      actions.nudge([dx, dy]);
    } else if (lower === "f") {
      actions.fit();
    } else if (key === "+" || key === "=") {
      actions.zoomCentre(KEY_ZOOM);
    } else if (key === "-" || key === "_") {
      actions.zoomCentre(1 / KEY_ZOOM);
    } else if (lower === "v") {
      actions.setTool("edit");
    } else if (lower === "h") {
      actions.setTool("pan");
    } else if (lower === "p") {
      actions.setTool("pin");
    } else if (lower === "t") {
      actions.setTool("tangent");
    } else if (lower === "d") {
      actions.setTool("points");
    } else if (key === "Enter" && onDrawing && actions.tool() === "points") {
      event.preventDefault();
      actions.finishSketch();
    } else if (key === "Backspace" && onDrawing && actions.tool() === "points") {
      event.preventDefault();
      actions.dropSketchPoint();
    } else if (/^[1-9]$/.test(key)) {
      actions.choose(Number(key) - 1);
    }
  });
  document.addEventListener("keyup", (event) => {
    if (event.key === " ") setSpace(false);
  });
  window.addEventListener("blur", () => setSpace(false));
  // The drawing takes its frame's size (main.js sizes it in pixels).
  const frame = canvas.parentElement;
  new ResizeObserver(() => {
    actions.resize({ width: frame.clientWidth, height: frame.clientHeight });
    bounds = canvas.getBoundingClientRect();
  }).observe(frame);

  elements.undo.addEventListener("click", () => actions.undo());
  elements.redo.addEventListener("click", () => actions.redo());
  elements.fit.addEventListener("click", () => actions.fit());
  elements.tools.addEventListener("click", (event) => {
    const tool = event.target.closest("button")?.dataset.tool;
    if (tool) actions.setTool(tool);
  });
  elements.sample.addEventListener("click", () => actions.sample());
  elements.bezierSample.addEventListener("click", () => actions.bezierSample());
  elements.load.addEventListener("click", () => actions.loadText(elements.json.value));
  elements.export.addEventListener("click", () => actions.exportCurve());
  elements.openFile.addEventListener("change", async () => {
    const file = elements.openFile.files[0];
    if (file) {
      const text = await file.text();
      // Cleared, so that opening the same file again is a change too.
      elements.openFile.value = "";
      actions.openFile(file.name, text);
    }
  });
  elements.exportStep.addEventListener("click", () => actions.exportFile("step"));
  elements.exportDxf.addEventListener("click", () => actions.exportFile("dxf"));
  elements.imported.addEventListener("change", () => actions.chooseImported(Number(elements.imported.value)));
  elements.solutions.addEventListener("change", (event) => {
    if (event.target.name === "solution") actions.choose(Number(event.target.value));
  });
  const ticked = (fieldset) => Object.fromEntries([...fieldset.querySelectorAll("input[type=checkbox]")].map((box) => [box.id.replace(/^[a-z]+-/, ""), box.checked]));
  elements.methods.addEventListener("change", () => {
    const methods = Object.entries(ticked(elements.methods)).filter(([, on]) => on).map(([id]) => id.replace("-", "_"));
    actions.setMethods(methods);
  });
  elements.snaps.addEventListener("change", () => actions.setSnap(ticked(elements.snaps)));
  elements.layers.addEventListener("change", () => actions.setLayers(ticked(elements.layers)));
  elements.families.addEventListener("change", () => actions.setFamilies(ticked(elements.families)));
  const typed = () => actions.moveToTyped(Number.parseFloat(elements.targetX.value), Number.parseFloat(elements.targetY.value));
  elements.moveTo.addEventListener("click", typed);
  for (const field of [elements.targetX, elements.targetY]) {
    field.addEventListener("keydown", (event) => {
      if (event.key === "Enter") typed();
    });
  }
  elements.retry.addEventListener("click", () => actions.retry());
  elements.clearConditions.addEventListener("click", () => actions.clearConditions());
  elements.sketchFinish.addEventListener("click", () => actions.finishSketch());
  elements.sketchDiscard.addEventListener("click", () => actions.discardSketch());
  elements.sketchTolerance.addEventListener("keydown", (event) => {
    if (event.key === "Enter") actions.finishSketch();
  });
  elements.apiKey.value = actions.apiKey();
  elements.apiKey.addEventListener("change", () => actions.setApiKey(elements.apiKey.value.trim()));
}
