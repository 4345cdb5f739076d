#!/usr/bin/env bash
# Painted frames/s of the page at 1920×1080, paced and full size (bench/projector_bench.mjs).
# Usage: bench/projector_bench.sh [BUILD_DIR] [SECONDS] [PRESET]; with `busy` as a 4th argument,
# stress-ng keeps one core busy meanwhile (the issue's "the machine's other core busy").
set -euo pipefail
build=${1:-build}
seconds=${2:-10}
preset=${3:-spin_vs_geodesic_torus}
port=18291
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
"$build/spinfold" serve --port $port --no-store > "$work/serve.log" 2>&1 &
for _ in $(seq 50); do curl -sf "http://127.0.0.1:$port/api/v1/health" > /dev/null && break; sleep 0.1; done
if [ "${4:-}" = busy ]; then stress-ng --cpu 1 --timeout 600s > /dev/null 2>&1 & fi
node "$(dirname "$0")/projector_bench.mjs" "http://127.0.0.1:$port/" "$seconds" "$preset"
