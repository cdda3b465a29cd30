// Small helpers the drawing modules share: making SVG elements, and redrawing a node only
// when what it is drawn from changed (a drag then redraws the preview and the dots, not the
// 300 control points of a large curve).

const SVG_NS = "http://www.w3.org/2000/svg";

/** A new SVG element `name` with `attributes`, appended to `parent`. */
export function element(name, attributes, parent) {
  const node = document.createElementNS(SVG_NS, name);
  for (const [key, value] of Object.entries(attributes)) {
    node.setAttribute(key, String(value));
  }
  parent.appendChild(node);
  return node;
}

/** Sets `node`'s attribute `name` to `value` unless it has it already: the browser takes a
 * write of the same value as a change too and matches the element's style again (DevTools'
 * invalidation tracking shows one per drag move for the scene's transform). */
export function setAttribute(node, name, value) {
  if (node.getAttribute(name) !== value) node.setAttribute(name, value);
}

/** "x,y x,y …" of the points' x–y projections. */
export const pairs = (points) => points.map((p) => `${p[0]},${p[1]}`).join(" ");

/** What each node was last drawn from. */
const drawnFrom = new WeakMap();

/** Redraws `node` by `paint(node)` unless `inputs` are the very values it was drawn from. */
export function redraw(node, inputs, paint) {
  const previous = drawnFrom.get(node);
  if (previous && previous.length === inputs.length && previous.every((value, i) => value === inputs[i])) {
    return;
  }
  drawnFrom.set(node, inputs);
  node.replaceChildren();
  paint(node);
}

/** The child `g.layer-<name>` of `parent`, made on first use (layers keep their order). */
export function layer(parent, name) {
  let group = parent.querySelector(`:scope > g.layer-${name}`);
  if (!group) {
    group = element("g", { class: `layer-${name}` }, parent);
  }
  return group;
}
