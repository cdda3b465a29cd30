-- wrk script for benches/load.sh: optional JSON POST body, and one
-- machine-readable summary line at the end of the run.
--
-- Environment:
--   KNOTSHAPE_BENCH_BODY  path of a JSON file; when set, every request is a
--                         POST of that body with Content-Type application/json,
--                         otherwise a plain GET.

local body_path = os.getenv("KNOTSHAPE_BENCH_BODY")
if body_path ~= nil and body_path ~= "" then
  local f = assert(io.open(body_path, "rb"))
  wrk.method = "POST"
  wrk.body = f:read("*a")
  f:close()
  wrk.headers["Content-Type"] = "application/json"
end

-- summary.errors.status counts responses with status >= 400 (the service
-- sends no 1xx/3xx, so that is every non-2xx); the rest are socket errors.
-- Latencies are in microseconds.
function done(summary, latency, requests)
  local e = summary.errors
  io.write(string.format(
    "KNOTSHAPE_RESULT requests=%d duration_us=%d p50_us=%d p99_us=%d max_us=%d "
      .. "status_errors=%d connect_errors=%d read_errors=%d write_errors=%d timeouts=%d\n",
    summary.requests, summary.duration,
    latency:percentile(50), latency:percentile(99), latency.max,
    e.status, e.connect, e.read, e.write, e.timeout))
end
