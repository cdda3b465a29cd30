// The API client: one function per endpoint the editor uses. Each resolves to
// { ok: true, value } with the parsed answer, or { ok: false, problem } with a problem
// document (RFC 9457) — also for network failures — and never throws.

const API_KEY_STORAGE = "knotshape.apiKey";

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

async function post(path, body) {
  const headers = { "Content-Type": "application/json", Accept: "application/json" };
  const key = apiKey();
  if (key) {
    headers.Authorization = `Bearer ${key}`;
  }
  let response;
  try {
    response = await fetch(path, { method: "POST", headers, body: JSON.stringify(body) });
  } catch (error) {
    return failure({ title: "Network error", detail: `${path}: ${error.message}` });
  }
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

/** A problem as one readable line: title, detail and each field error's pointer. */
export function describeProblem(problem) {
  const parts = [problem.title, problem.detail].filter(Boolean);
  for (const error of problem.errors || []) {
    parts.push(`${error.pointer || "(body)"}: ${error.detail}`);
  }
  return parts.join(" — ");
}

/** POST /v1/curves/evaluate at given parameters. */
export function evaluateAt(curve, parameters) {
  return post("/v1/curves/evaluate", { curve, parameters });
}

/** POST /v1/curves/evaluate with `tolerance`: a polyline certified within it. */
export function evaluatePolyline(curve, tolerance) {
  return post("/v1/curves/evaluate", { curve, tolerance });
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

/** POST /v1/shape/regions: the regions' polygons of both sides at `parameter`. */
export function regions(curve, parameter) {
  return post("/v1/shape/regions", { curve, parameter, side: "both" });
}

/** POST /v1/shape/solve with `nearest`, the given methods and each solution's SVG path (so a
 * drag's preview needs no second request). */
export function solve(curve, parameter, target, methods) {
  return post("/v1/shape/solve", { curve, parameter, target, side: "both", nearest: true, methods, svg_paths: true });
}
