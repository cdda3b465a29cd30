// The 3D editor's side panel: the objects shown (choose the one to edit), the methods a drag
// solves with, the view's buttons and layers, the solutions of the last move, and the
// notices. Built once; `draw(editor)` brings it up to date.

import { SPACE_METHODS, describe } from "./editing.js";

/** The standard views with their keys (Onshape's: Shift + 1–7). */
export const VIEW_BUTTONS = [
  { id: "front", label: "Front", key: "Shift+1" },
  { id: "back", label: "Back", key: "Shift+2" },
  { id: "left", label: "Left", key: "Shift+3" },
  { id: "right", label: "Right", key: "Shift+4" },
  { id: "top", label: "Top", key: "Shift+5" },
  { id: "bottom", label: "Bottom", key: "Shift+6" },
  { id: "isometric", label: "Isometric", key: "Shift+7" },
];

/** The layers the view can hide. */
const LAYERS = [
  { id: "iso", label: "iso-lines", on: true },
  { id: "net", label: "control net", on: false },
  { id: "regions", label: "regions (where a drag reaches)", on: true },
];

function checkbox(label, checked, onChange, name) {
  const box = document.createElement("input");
  box.type = "checkbox";
  box.checked = checked;
  if (name) box.name = name;
  box.addEventListener("change", () => onChange(box));
  const wrapper = document.createElement("label");
  wrapper.append(box, ` ${label}`);
  return wrapper;
}

function button(label, title, onClick) {
  const element = document.createElement("button");
  element.type = "button";
  element.textContent = label;
  if (title) element.title = title;
  element.addEventListener("click", onClick);
  return element;
}

/** Builds the panel into `elements` (space-objects, space-methods, space-view,
 * space-solutions, space-message, space-error) with `actions`. */
export function buildSpacePanel(elements, actions) {
  elements.objects.addEventListener("change", () => actions.select(Number(elements.objects.value)));
  for (const view of VIEW_BUTTONS) {
    elements.view.append(button(view.label, `${view.label} view (${view.key})`, () => actions.standardView(view.id)));
  }
  elements.view.append(button("Fit", "Fit everything into the view (F)", () => actions.fit()));
  const layers = Object.fromEntries(LAYERS.map((layer) => [layer.id, layer.on]));
  elements.view.append(checkbox("perspective (O)", true, (box) => actions.setPerspective(box.checked), "perspective"));
  for (const layer of LAYERS) {
    elements.view.append(checkbox(layer.label, layer.on, (box) => {
      layers[layer.id] = box.checked;
      actions.setLayers({ ...layers });
    }, `layer-${layer.id}`));
  }
  elements.solutions.addEventListener("click", (event) => {
    const item = event.target.closest("li");
    if (item) actions.choose(Number(item.dataset.index));
  });
}

/** Brings the panel up to date with `editor`. */
export function drawSpacePanel(editor, elements, actions) {
  const names = editor.items.map((item, index) => `${index + 1}. ${item.name}`);
  if (elements.objects.options.length !== names.length || [...elements.objects.options].some((option, i) => option.text !== names[i])) {
    elements.objects.replaceChildren(...names.map((name, index) => new Option(name, String(index))));
  }
  elements.objects.value = String(editor.selected);
  elements.objects.size = Math.min(Math.max(editor.items.length, 2), 8);

  const item = editor.selectedItem();
  const kind = item?.kind ?? "surface";
  if (elements.methods.dataset.kind !== kind) {
    elements.methods.dataset.kind = kind;
    const legend = document.createElement("legend");
    legend.textContent = kind === "surface" ? "Methods (surface)" : "Methods (space curve)";
    const boxes = SPACE_METHODS[kind].map((method) =>
      checkbox(method.label, editor.methods[kind].includes(method.id), () => {
        const chosen = SPACE_METHODS[kind].filter((m, i) => boxes[i].querySelector("input").checked).map((m) => m.id);
        actions.setMethods(kind, chosen);
      }, `method-${method.id}`),
    );
    elements.methods.replaceChildren(legend, ...boxes);
  }

  const lines = editor.solutions.map((solution, index) => {
    const li = document.createElement("li");
    li.dataset.index = String(index);
    li.textContent = describe(solution, editor.solutions.length).replace(/; \d+ solutions?\.$/, "");
    return li;
  });
  elements.solutions.replaceChildren(...lines);
  // The toolbar's Undo and Redo step through the 3D view's history while it is shown.
  elements.undo.disabled = editor.history.length === 0 || editor.drag !== null;
  elements.redo.disabled = editor.future.length === 0 || editor.drag !== null;
  elements.message.textContent = editor.busy > 0 && !editor.message ? "Working…" : editor.message;
  elements.error.textContent = editor.error;
}
