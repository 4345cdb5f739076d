#!/usr/bin/env bash
# One server under the soak (`spinfold-bench soak`: 8 clients creating, changing, reading and
# deleting sessions, frames and streams), its RSS sampled every 30 s, for docs/performance.md's
# memory figures. Two of these side by side (two builds) compare under the same load.
# Usage: bench/soak.sh OUT_DIR MINUTES [BUILD_DIR] [NAME=VALUE …]   (e.g. SPINFOLD_GL=osmesa)
# Writes OUT_DIR/rss.txt ("seconds RSS-KiB" lines) and OUT_DIR/soak.txt (the bench's report).
set -euo pipefail
out=$1 minutes=$2 build=${3:-build}
shift $(($# < 3 ? $# : 3))
mkdir -p "$out"
port=$((18800 + RANDOM % 100))
data=$(mktemp -d)
env "$@" "$build/spinfold" serve --port "$port" --requests-per-second 0 --data-dir "$data" > "$out/server.log" 2>&1 &
pid=$!
trap 'kill $pid 2> /dev/null; rm -rf "$data"' EXIT
for _ in $(seq 50); do curl -s -o /dev/null "http://127.0.0.1:$port/api/v1/health" && break; sleep 0.2; done
(
  t0=$SECONDS
  while kill -0 "$pid" 2> /dev/null; do
    echo "$((SECONDS - t0)) $(awk '/VmRSS/{print $2}' "/proc/$pid/status")"
    sleep 30
  done
) > "$out/rss.txt" &
"$build/bench/spinfold-bench" soak --minutes "$minutes" --clients 8 --url "http://127.0.0.1:$port" --pid "$pid" \
  > "$out/soak.txt" 2>&1
tail -1 "$out/soak.txt"
