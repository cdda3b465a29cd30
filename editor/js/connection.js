// The service's reachability as the page shows it. When a request gets no answer, the state
// says "unreachable" (the banner) and `GET /healthz` is probed every few seconds — or at
// once with the banner's Retry button — until the service answers; then the committed
// curve is drawn again if its drawing was missing. A 503 being retried shows as "retrying".

import * as api from "./api.js";
import * as store from "./store.js";

/** Seconds between probes while the service does not answer. */
const PROBE_SECONDS = 3;

let probeTimer = null;
let whenBack = () => {};

function show(connection) {
  const state = store.get();
  if (state.connection.state === connection.state && state.connection.seconds === connection.seconds) return;
  store.set({ ...state, connection });
}

function scheduleProbe() {
  if (probeTimer === null) {
    probeTimer = setTimeout(probe, PROBE_SECONDS * 1000);
  }
}

/** Asks /healthz now; back to "ok" when it answers, else tries again later. */
export async function probe() {
  clearTimeout(probeTimer);
  probeTimer = null;
  if (await api.healthy()) {
    if (store.get().connection.state !== "ok") {
      show({ state: "ok" });
      whenBack();
    }
  } else {
    scheduleProbe();
  }
}

/** Follows the API client's reports; `onBack` runs when the service answers again. */
export function watch(onBack) {
  whenBack = onBack;
  api.onConnection((event) => {
    if (event.state === "unreachable") {
      show({ state: "unreachable" });
      scheduleProbe();
    } else if (event.state === "retrying") {
      show({ state: "retrying", seconds: event.seconds });
    } else if (store.get().connection.state !== "ok") {
      const wasUnreachable = store.get().connection.state === "unreachable";
      show({ state: "ok" });
      if (wasUnreachable) whenBack();
    }
  });
}
