// What the page offers, as lists the panel is built from: the tool modes, the ways of
// moving a picked point (the solver's `methods`), the layers of the drawing, and the kinds
// of snapping. A new capability is one more entry here plus what it does.

/** Tool modes: what a press on the drawing does. `key` is the shortcut. */
export const TOOLS = [
  { id: "edit", label: "Edit", key: "v", help: "press on the curve and drag it; drag a control point; drag the background to pan" },
  { id: "pan", label: "Pan", key: "h", help: "every drag pans the view" },
  { id: "pin", label: "Pin", key: "p", help: "click the curve to pin that point (again to unpin); click a control point to fix it (again to free it)" },
  { id: "tangent", label: "Tangent", key: "t", help: "click the curve to lock the tangent's direction there (again to unlock)" },
  { id: "points", label: "Points", key: "d", help: "click to add points, then Finish (Enter) makes a curve through them" },
];

/** The solver's methods the page can ask for (`id` is the API's name; `on` by default). */
export const METHODS = [
  { id: "knots", label: "knots (pairs; triples in 3D)", on: true },
  { id: "control_points", label: "control points", on: true },
  { id: "weights", label: "weights (two per move)", on: false },
];

/** The knot families (the API's `knot_families`), each with its regions' legend and a box
 * that hides them (solving still offers their solutions); `drawn`: whether the service
 * draws its regions at all. */
export const FAMILIES = [
  { id: "envelope", label: "envelope", help: "a knot next to t moves to t, then a pair of the envelope's knots (degree 3 or more; a cubic's Ω1–Ω6)", drawn: true },
  { id: "direct", label: "direct", help: "a pair of the curve's own knots around t (degree 2 or more)", drawn: true },
  { id: "triples", label: "triples", help: "three of the curve's own knots: they reach 3D targets off the pairs' surfaces (3D curves)", drawn: false },
];

/** Layers of the drawing that can be hidden; `shown` is the default. */
export const LAYERS = [
  { id: "regions", label: "regions", shown: true },
  { id: "control", label: "control polygon", shown: true },
  { id: "knots", label: "knot marks", shown: true },
  { id: "grid", label: "grid", shown: false },
  { id: "comb", label: "curvature comb", shown: false },
];

/** What a dragged point can snap to (all off by default). */
export const SNAPS = [
  { id: "grid", label: "grid" },
  { id: "poles", label: "control points" },
  { id: "knots", label: "knot points" },
];

/** The keyboard shortcuts, for the list on the page (and the test that checks it). */
export const SHORTCUTS = [
  ["Tab", "focus the drawing"],
  ["← ↑ → ↓", "nudge the picked point by one pixel (Shift: ten)"],
  ["Esc", "cancel the drag (or drop the pick)"],
  ["F", "fit the curve into the view"],
  ["+ / −", "zoom in / out about the centre"],
  ["Space + drag", "pan"],
  ["V / H / P / T / D", "edit / pan / pin / tangent / points tool"],
  ["Enter / Backspace", "points tool: make the curve / drop the last point"],
  ["1 – 9", "choose a solution from the list (also during a drag)"],
  ["Ctrl+Z / Ctrl+Shift+Z", "undo / redo"],
  ["3D: drag / Shift + drag", "orbit / pan (also the middle or right button, Space + drag)"],
  ["3D: Alt + drag", "move the picked point along the surface normal (a curve's principal normal)"],
  ["3D: Shift+1 – Shift+7", "front, back, left, right, top, bottom, isometric view"],
  ["3D: O", "perspective or orthographic"],
];
