#!/usr/bin/env bash
# Requests per second with wrk against Spinfold's state and frame endpoints and, in the same run,
# against a bare cpp-httplib server returning bodies of the same sizes. Prints a Markdown table.
# Usage: bench/http_bench.sh [BUILD_DIR] (default build); needs wrk and curl (scripts/setup.sh).
set -euo pipefail
build=${1:-build}
port=18181; bare_port=18182
duration=${DURATION:-5s}; connections=${CONNECTIONS:-16}; threads=2
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT

"$build/spinfold" serve --port $port --threads 8 --requests-per-second 0 > "$work/serve.log" &
for _ in $(seq 50); do curl -sf "http://127.0.0.1:$port/api/v1/health" > /dev/null && break; sleep 0.1; done
id=$(grep -o 'sessions/[A-Za-z0-9_-]*' "$work/serve.log" | head -1 | cut -d/ -f2)
base="http://127.0.0.1:$port/api/v1/sessions/$id"
curl -sf -X POST -H 'Content-Type: application/json' -d '{"until": 3}' "$base/advance" > /dev/null
curl -sf "$base" > "$work/state.json"
curl -sf "$base/frame.png" > "$work/frame.png"

"$build/bench/bare-http-server" $bare_port "$(stat -c %s "$work/state.json")" "$work/frame.png" &
for _ in $(seq 50); do curl -sf "http://127.0.0.1:$bare_port/state" > /dev/null && break; sleep 0.1; done

rps() {  # URL CONNECTIONS [LUA_SCRIPT] → requests per second
  local extra=() t=$threads
  [[ $# -ge 3 ]] && extra=(-s "$3")
  (( $2 < t )) && t=$2
  wrk -t$t -c"$2" -d$duration "${extra[@]}" "$1" | awk '/Requests\/sec/ {print $2}'
}
# Every request a different scale: a different ETag, a cache miss, a render.
cat > "$work/miss.lua" <<'LUA'
counter = 0
request = function()
  counter = counter + 1
  return wrk.format("GET", wrk.path .. "?scale=" .. (0.2 + counter * 1e-9))
end
LUA

state=$(rps "$base" $connections); bare_state=$(rps "http://127.0.0.1:$bare_port/state" $connections)
hit=$(rps "$base/frame.png" $connections); bare_frame=$(rps "http://127.0.0.1:$bare_port/frame" $connections)
miss=$(rps "$base/frame.png" 1 "$work/miss.lua")

# The bare render + encode of the same 640x480 frame, measured now (bench/bare_render_loop.cpp).
bare_frame_ms=$("$build/bench/spinfold-bench" render --frames 15 | awk -F'|' '/640x480 \| all layers/ {print $10 + $11}')

echo "| request | Spinfold req/s | bare cpp-httplib req/s (same body size) | ratio |"
echo "| --- | --- | --- | --- |"
awk -v a="$state" -v b="$bare_state" 'BEGIN {printf "| GET /sessions/{id} (state JSON, %d connections) | %.0f | %.0f | %.2f |\n", '"$connections"', a, b, a / b}'
awk -v a="$hit" -v b="$bare_frame" 'BEGIN {printf "| GET frame.png, cache hit (%d connections) | %.0f | %.0f | %.2f |\n", '"$connections"', a, b, a / b}'
awk -v a="$miss" -v b="$bare_frame_ms" 'BEGIN {printf "| GET frame.png, miss: render + encode + serve, 640x480 (1 connection) | %.1f (%.2f ms each) | bare render + encode %.2f ms | %.2f× the bare time |\n", a, 1000 / a, b, (1000 / a) / b}'
