// The API client: one function per endpoint the editor uses. Each resolves to
// { ok: true, value } with the parsed answer, or { ok: false, problem } with a problem
// document (RFC 9457) — also for network failures — and never throws. A 503 with
// Retry-After is retried after the time it names (a few times, each wait capped); what the
// connection does (unreachable, busy and retrying, answering again) is reported to the
// listener that `onConnection` sets, so the page can show it.

const API_KEY_STORAGE = "knotshape.apiKey";
/** Attempts of one request when the service answers 503 with Retry-After. */
const ATTEMPTS = 4;
/** The longest wait before a retry, in seconds, whatever Retry-After says. */
const LONGEST_WAIT_SECONDS = 5;
/** The problem `type` of a request that never got an answer. */
export const NETWORK_ERROR = "about:network-error";
/** The problem `type` of a request the page gave up waiting for (its `budget`). */
export const OVER_BUDGET = "about:over-budget";

let connectionListener = () => {};

/** Sets the function told `{ state: "ok" | "unreachable" | "retrying", seconds?, path }`. */
export function onConnection(listener) {
  connectionListener = listener;
}

/** The API key kept for this tab (sessionStorage), or "". */
export function apiKey() {
  try {
    return sessionStorage.getItem(API_KEY_STORAGE) || "";
  } catch {
    return "";
  }
}

/** Keeps `key` for this tab ("" forgets it). */
export function setApiKey(key) {
  try {
    if (key) {
      sessionStorage.setItem(API_KEY_STORAGE, key);
    } else {
      sessionStorage.removeItem(API_KEY_STORAGE);
    }
  } catch {
    // Storage disabled: the key lasts until the page is reloaded.
  }
}

const sleep = (seconds) => new Promise((resolve) => setTimeout(resolve, seconds * 1000));

/** Seconds a 503 asks to wait (Retry-After as seconds or an HTTP date), or null. */
function retryAfter(response) {
  const value = response.headers.get("Retry-After");
  if (response.status !== 503 || value === null) return null;
  const seconds = /^\d+$/.test(value.trim()) ? Number(value) : (Date.parse(value) - Date.now()) / 1000;
  return Number.isFinite(seconds) ? Math.min(Math.max(seconds, 0), LONGEST_WAIT_SECONDS) : null;
}

/** POSTs `body` as JSON; the answer is parsed as JSON, or kept as text with `text` (a file
 * export). With `budget` (milliseconds) the page stops waiting after that long: the request
 * is aborted and answered with an OVER_BUDGET problem (not a connection failure). */
async function post(path, body, { text: asText = false, budget = 0 } = {}) {
  const headers = { "Content-Type": "application/json", Accept: asText ? "*/*" : "application/json" };
  const key = apiKey();
  if (key) {
    headers.Authorization = `Bearer ${key}`;
  }
  const text = JSON.stringify(body);
  for (let attempt = 1; ; attempt += 1) {
    let response;
    const abort = budget > 0 ? new AbortController() : null;
    const timer = abort ? setTimeout(() => abort.abort(), budget) : null;
    try {
      response = await fetch(path, { method: "POST", headers, body: text, signal: abort?.signal });
    } catch (error) {
      if (abort?.signal.aborted) {
        return failure({ type: OVER_BUDGET, title: `no answer within ${budget / 1000} s`, detail: path });
      }
      connectionListener({ state: "unreachable", path });
      return failure({ type: NETWORK_ERROR, title: "The service does not answer", detail: `${path}: ${error.message}` });
    }
    if (timer) clearTimeout(timer);
    const wait = retryAfter(response);
    if (wait !== null && attempt < ATTEMPTS) {
      connectionListener({ state: "retrying", seconds: wait, path });
      await sleep(wait);
      continue;
    }
    connectionListener({ state: "ok", path });
    if (asText && response.ok) return { ok: true, value: await response.text() };
    return answer(path, response);
  }
}

async function answer(path, response) {
  let parsed = null;
  try {
    parsed = await response.json();
  } catch {
    parsed = null;
  }
  if (response.ok && parsed !== null) {
    return { ok: true, value: parsed };
  }
  if (parsed && typeof parsed === "object" && parsed.title) {
    return failure(parsed);
  }
  return failure({ status: response.status, title: response.statusText || "Error", detail: `${path} answered ${response.status}` });
}

function failure(problem) {
  return { ok: false, problem };
}

/** Whether the service answers `GET /healthz` (no key needed). */
export async function healthy() {
  try {
    const response = await fetch("/healthz", { cache: "no-store" });
    return response.ok;
  } catch {
    return false;
  }
}

/** POST /v1/curves/evaluate at given parameters. */
export function evaluateAt(curve, parameters) {
  return post("/v1/curves/evaluate", { curve, parameters });
}

/** POST /v1/curves/evaluate with `tolerance`: a polyline certified within it. */
export function evaluatePolyline(curve, tolerance) {
  return post("/v1/curves/evaluate", { curve, tolerance });
}

/** POST /v1/curves/interpolate: the cubic (or lower degree, for few points) through `points`. */
export function interpolate(points) {
  return post("/v1/curves/interpolate", { points, degree: Math.min(3, points.length - 1) });
}

/** POST /v1/curves/approximate: a curve within `tolerance` of every point. */
export function approximate(points, tolerance) {
  return post("/v1/curves/approximate", { points, tolerance, degree: Math.min(3, points.length - 1) });
}

/** POST /v1/curves/import: every B-spline curve of a STEP or DXF file's text. */
export function importFile(format, data) {
  return post("/v1/curves/import", { format, data });
}

/** POST /v1/curves/export: the STEP or DXF file of `curves`, as text. */
export function exportFile(format, curves) {
  return post("/v1/curves/export", { format, curves }, { text: true });
}

/** POST /v1/curves/bezier: the Bézier pieces and, when SVG can draw it, an SVG path. */
export function bezier(curve) {
  return post("/v1/curves/bezier", { curve });
}

/** POST /v1/curves/closest-point for one query point. */
export function closestPoint(curve, point) {
  return post("/v1/curves/closest-point", { curve, points: [point] });
}

/** POST /v1/curves/insert-knots with `editable_at`: knots for the method around `parameter`. */
export function insertKnotsForEditing(curve, parameter) {
  return post("/v1/curves/insert-knots", { curve, editable_at: { parameter } });
}

/** POST /v1/curves/evaluate at `parameters` with the first derivatives and the curvature
 * (for the tangent marks and the curvature comb). */
export function evaluateWithCurvature(curve, parameters) {
  return post("/v1/curves/evaluate", { curve, parameters, derivatives: 1, curvature: true });
}

/** The conditions every solve, membership and regions request of the page carries: the
 * constraints (pins, tangent locks) and the fixed control points, when there are any. */
function withConditions(body, { constraints = [], fixed = [] } = {}) {
  if (constraints.length > 0) body.constraints = constraints;
  if (fixed.length > 0) body.fixed_control_points = fixed;
  return body;
}

/** POST /v1/shape/regions: the reachable sets at `parameter` of the knot pairs of every
 * family that applies, or of `knotFamilies` (`families`; the envelope's on both sides) and
 * of the weight pairs,
 * for the same `keep_domain`, `methods` and conditions as solving (so that every drawn
 * region holds only targets solve reaches), within `tolerance` of the true boundaries. */
export function regions(curve, parameter, tolerance, { methods, knotFamilies = null, constraints = [], fixed = [], budget = 0 }) {
  const body = { curve, parameter, side: "both", keep_domain: true, methods, tolerance };
  if (knotFamilies) body.knot_families = knotFamilies;
  return post("/v1/shape/regions", withConditions(body, { constraints, fixed }), { budget });
}

/**
 * POST /v1/shape/solve with `nearest`. `family` (optional) narrows the request to one way of
 * moving the point — `{ method, family?, side?, region? }` (geometry.familyOf) — as far as
 * the API can: the method, for knots the knot family (`knot_families`), the envelope's side,
 * and a cubic's envelope pair (`regions`, which names only Ω1–Ω6); the caller picks the
 * family's solution out of the answer. `svgPaths` asks for each solution's new curve as an
 * SVG path (so a drag's preview needs no second request); `conditions` ({ constraints,
 * fixed }) are sent as they are.
 */
export function solve(curve, parameter, target, { methods, family = null, svgPaths = false, conditions = {} }) {
  const body = withConditions({ curve, parameter, target, side: "both", keep_domain: true, nearest: true, methods }, conditions);
  if (family) {
    body.methods = [family.method];
    if (family.method === "knots") {
      body.knot_families = [family.family];
      if (family.side) body.side = family.side;
      if (/^omega[1-6]$/.test(family.region)) body.regions = [family.region];
    }
  }
  if (svgPaths) body.svg_paths = true;
  return post("/v1/shape/solve", body);
}

/** POST /v1/curves/export with curves and surfaces (STEP), as text. */
export function exportStep(curves, surfaces) {
  return post("/v1/curves/export", { format: "step", curves, surfaces }, { text: true });
}

/** POST /v1/surfaces/tessellate: a mesh within `tolerance` of the surface (JSON). */
export function tessellate(surface, tolerance) {
  return post("/v1/surfaces/tessellate", { surface, tolerance });
}

/** POST /v1/surfaces/closest-point for one query point. */
export function surfaceClosestPoint(surface, point) {
  return post("/v1/surfaces/closest-point", { surface, points: [point] });
}

/** POST /v1/surfaces/evaluate at `parameters` with unit normals. */
export function surfaceNormals(surface, parameters) {
  return post("/v1/surfaces/evaluate", { surface, parameters, normals: true });
}

/** POST /v1/curves/evaluate at `parameters` with derivatives to order 2. */
export function curveFrames(curve, parameters) {
  return post("/v1/curves/evaluate", { curve, parameters, derivatives: 2 });
}

/** POST /v1/surfaces/shape/solve: moves S(parameter) to `target`; the nearest reachable
 * target is asked for only without the control points (which reach every target). */
export function surfaceSolve(surface, parameter, target, methods) {
  const nearest = !methods.includes("control_points");
  return post("/v1/surfaces/shape/solve", { surface, parameter, target, methods, keep_domain: true, nearest });
}

/** POST /v1/surfaces/shape/regions: what each method reaches from S(parameter). */
export function surfaceRegions(surface, parameter, methods, budget = 0) {
  return post("/v1/surfaces/shape/regions", { surface, parameter, methods, keep_domain: true }, { budget });
}
