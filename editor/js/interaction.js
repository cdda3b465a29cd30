// The interaction: turns what a person does (pointer down, move and up on the drawing,
// keys, buttons, the solution list, pasted or opened files) into the controller's actions.
// It keeps no editor state of its own.

/** Wires the page's `elements` to `actions` (see main.js). */
export function bind(elements, actions) {
  const canvas = elements.canvas;
  let pointerDown = false;

  canvas.addEventListener("pointerdown", async (event) => {
    if (event.button !== 0) return;
    event.preventDefault();
    pointerDown = true;
    canvas.setPointerCapture(event.pointerId);
    const point = actions.pointerToCurve(event);
    if (actions.onPickedPoint(point)) {
      actions.startDrag();
      actions.dragTo(point);
    } else {
      await actions.pick(point);
    }
  });

  canvas.addEventListener("pointermove", (event) => {
    if (pointerDown && actions.isDragging()) {
      actions.dragTo(actions.pointerToCurve(event));
    }
  });

  const up = (event) => {
    if (!pointerDown) return;
    pointerDown = false;
    if (canvas.hasPointerCapture(event.pointerId)) {
      canvas.releasePointerCapture(event.pointerId);
    }
    if (actions.isDragging()) {
      actions.dragTo(actions.pointerToCurve(event));
      actions.releaseDrag();
    }
  };
  canvas.addEventListener("pointerup", up);
  canvas.addEventListener("pointercancel", up);

  document.addEventListener("keydown", (event) => {
    const target = event.target;
    if (target instanceof HTMLTextAreaElement || (target instanceof HTMLInputElement && target.type !== "checkbox" && target.type !== "radio")) {
      return; // the field's own undo
    }
    const key = event.key.toLowerCase();
    if ((event.ctrlKey || event.metaKey) && key === "z") {
      event.preventDefault();
      if (event.shiftKey) {
        actions.redo();
      } else {
        actions.undo();
      }
    } else if ((event.ctrlKey || event.metaKey) && key === "y") {
      event.preventDefault();
      actions.redo();
    }
  });

  elements.undo.addEventListener("click", () => actions.undo());
  elements.redo.addEventListener("click", () => actions.redo());
  elements.sample.addEventListener("click", () => actions.sample());
  elements.bezierSample.addEventListener("click", () => actions.bezierSample());
  elements.load.addEventListener("click", () => actions.loadText(elements.json.value));
  elements.export.addEventListener("click", () => actions.exportCurve());
  elements.openFile.addEventListener("change", async () => {
    const file = elements.openFile.files[0];
    if (file) {
      const text = await file.text();
      elements.json.value = text;
      actions.loadText(text);
    }
  });
  elements.solutions.addEventListener("change", (event) => {
    if (event.target.name === "solution") {
      actions.choose(Number(event.target.value));
    }
  });
  const methods = () => [
    ...(elements.methodKnots.checked ? ["knots"] : []),
    ...(elements.methodControlPoints.checked ? ["control_points"] : []),
  ];
  for (const box of [elements.methodKnots, elements.methodControlPoints]) {
    box.addEventListener("change", () => {
      if (!actions.setMethods(methods())) {
        box.checked = true;
        actions.setMethods(methods());
      }
    });
  }
  elements.apiKey.value = actions.apiKey();
  elements.apiKey.addEventListener("change", () => actions.setApiKey(elements.apiKey.value.trim()));
}
