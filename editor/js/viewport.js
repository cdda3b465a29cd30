// The view's frame: how curve coordinates map to the drawing's pixels (y up), and the
// zoom, pan and fit that change it. Pure functions of plain data: a frame is
// { scale, offset: [ox, oy], fitted } with pixel = (scale·x + ox, oy − scale·y), and a size
// is the drawing's { width, height } in CSS pixels.

/** Free pixels kept around a fitted curve. */
const MARGIN = 40;
/** How far one may zoom in and out, as multiples of the fitted scale. */
const ZOOM_IN_LIMIT = 1e5;
const ZOOM_OUT_LIMIT = 1e-2;
/** A curve whose box spans less than this share of the view (both ways) is refitted. */
const SMALLEST_SHARE = 0.2;

/** Pixel of the curve point `point` (its x–y projection). */
export function toScreen(frame, point) {
  return [frame.scale * point[0] + frame.offset[0], frame.offset[1] - frame.scale * point[1]];
}

/** Curve point under `pixel`. */
export function toCurve(frame, pixel) {
  return [(pixel[0] - frame.offset[0]) / frame.scale, (frame.offset[1] - pixel[1]) / frame.scale];
}

/** The frame that fits the box [[xmin, ymin], [xmax, ymax]] into `size`. */
export function fit([low, high], size) {
  const width = Math.max(high[0] - low[0], 1e-9);
  const height = Math.max(high[1] - low[1], 1e-9);
  const room = [Math.max(size.width - 2 * MARGIN, 10), Math.max(size.height - 2 * MARGIN, 10)];
  const scale = Math.min(room[0] / width, room[1] / height);
  const centre = [(low[0] + high[0]) / 2, (low[1] + high[1]) / 2];
  return {
    scale,
    offset: [size.width / 2 - scale * centre[0], size.height / 2 + scale * centre[1]],
    fitted: scale,
  };
}

/** The frame zoomed by `factor` about `pixel`: the curve point under it stays there. */
export function zoomAbout(frame, pixel, factor) {
  const scale = Math.min(Math.max(frame.scale * factor, frame.fitted * ZOOM_OUT_LIMIT), frame.fitted * ZOOM_IN_LIMIT);
  const [x, y] = toCurve(frame, pixel);
  return { ...frame, scale, offset: [pixel[0] - scale * x, pixel[1] + scale * y] };
}

/** The frame moved by `delta` pixels (the drawing follows the pointer). */
export function pan(frame, delta) {
  return { ...frame, offset: [frame.offset[0] + delta[0], frame.offset[1] + delta[1]] };
}

/** The curve-coordinate box [[xmin, ymin], [xmax, ymax]] that `size` shows. */
export function visibleBox(frame, size) {
  const [x0, y1] = toCurve(frame, [0, 0]);
  const [x1, y0] = toCurve(frame, [size.width, size.height]);
  return [[x0, y0], [x1, y1]];
}

/** Whether the box [[xmin, ymin], [xmax, ymax]] should be refitted: part of it is out of
 * view, or it is too small to work on. */
export function needsFit(frame, size, [low, high]) {
  const [viewLow, viewHigh] = visibleBox(frame, size);
  const outside = low[0] < viewLow[0] || low[1] < viewLow[1] || high[0] > viewHigh[0] || high[1] > viewHigh[1];
  const share = Math.max((high[0] - low[0]) / (viewHigh[0] - viewLow[0]), (high[1] - low[1]) / (viewHigh[1] - viewLow[1]));
  return outside || share < SMALLEST_SHARE;
}

/** The frame after the drawing changed from `before` to `after` size: the centre stays. */
export function resized(frame, before, after) {
  return pan(frame, [(after.width - before.width) / 2, (after.height - before.height) / 2]);
}

/** A grid spacing in curve units: 1, 2 or 5 times a power of ten, about `pixels` apart. */
export function gridStep(frame, pixels = 40) {
  const raw = pixels / frame.scale;
  const power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * power).find((candidate) => candidate >= raw);
  return step;
}

/** Decimals that show one pixel's worth of curve units. */
export function decimals(frame) {
  return Math.min(Math.max(Math.ceil(Math.log10(frame.scale)), 0), 12);
}
