// Curves in and out as JSON text: pasted or opened (a curve object, or an object with a
// `curve`), and exported. Errors name the line and column of the user's own text.

import * as model from "./state.js";
import * as store from "./store.js";
import { loadCurve } from "./committing.js";
import { describeSyntaxError, textSource } from "./problems.js";

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
  const parsed = parseCurve(text);
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
  const link = elements.download;
  if (link.href) URL.revokeObjectURL(link.href);
  link.href = URL.createObjectURL(new Blob([text], { type: "application/json" }));
  link.hidden = false;
  store.set({ ...store.get(), message: "Exported: the curve is in the text field and in the download link.", error: "" });
}
