#!/usr/bin/env bash
# Live frames, one run: frame misses with 1 and 8 concurrent clients (wrk; each request a new frame
# of one of 8 sessions, so nothing is served from the cache), then the browser and viewer figures
# of bench/live_bench.mjs (headless Chromium, the UI's web/live.js). Prints JSON lines.
# Usage: bench/live_bench.sh [BUILD_DIR] [SECONDS] [PRESET] (default build, 5, the default scene: the
# live view's scene, e.g. spin_vs_geodesic_torus); needs wrk, curl, chromium,
# web/node_modules (scripts/setup.sh).
set -euo pipefail
build=${1:-build}
seconds=${2:-5}
port=18191
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT

"$build/spinfold" serve --port $port --requests-per-second 0 --no-store > "$work/serve.log" 2>&1 &
for _ in $(seq 50); do curl -sf "http://127.0.0.1:$port/api/v1/health" > /dev/null && break; sleep 0.1; done
base="http://127.0.0.1:$port/api/v1/sessions"
ids=()
for _ in $(seq 8); do
  ids+=("$(curl -sf -X POST -H 'Content-Type: application/json' -d '{}' "$base" | sed 's/.*"id":"\([^"]*\)".*/\1/')")
done
# Every request another session (round robin) and another scale: a new ETag, a render.
{
  echo "paths = {"
  for id in "${ids[@]}"; do echo "  \"/api/v1/sessions/$id/frame.png\","; done
  echo "}"
  cat <<'LUA'
counter = 0
request = function()
  counter = counter + 1
  return wrk.format("GET", paths[counter % #paths + 1] .. "?scale=" .. (0.2 + counter * 1e-9))
end
LUA
} > "$work/miss.lua"
misses() { wrk -t"$(( $1 < 2 ? $1 : 2 ))" -c"$1" -d"${seconds}s" -s "$work/miss.lua" "http://127.0.0.1:$port/" | awk '/Requests\/sec/ {print $2}'; }
one=$(misses 1)
eight=$(misses 8)
awk -v a="$one" -v b="$eight" 'BEGIN {printf "{\"frame_misses_per_s\": {\"clients_1\": %.1f, \"clients_8\": %.1f, \"ratio\": %.2f}}\n", a, b, b / a}'
node "$(dirname "$0")/live_bench.mjs" "http://127.0.0.1:$port" "$seconds" 16 ${3:+"$3"}
