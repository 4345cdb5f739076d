#!/usr/bin/env bash
# What the durable session store costs, in one run: advance and GET requests per second with wrk
# against a memory-only server and a server with a store (a commit per acknowledged change, a
# version SELECT per request), then the start-up restore time of N stored sessions.
# Usage: bench/store_bench.sh [BUILD_DIR] (default build); DATA_DIR_PARENT (default the build
# directory: a real disk, not a tmpfs, so that fsync costs what it costs); SESSIONS (default 64),
# UNTIL (each restored session's time, default 100). Needs wrk and curl (scripts/setup.sh).
set -euo pipefail
build=${1:-build}
duration=${DURATION:-5s}
sessions=${SESSIONS:-64}
until_t=${UNTIL:-100}
work=$(mktemp -d "${DATA_DIR_PARENT:-$build}/store_bench.XXXXXX")
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$work"' EXIT

start() {  # NAME ARGS… → sets port_NAME; the server's stdout/stderr in $work/NAME.log
  local name=$1
  shift
  "$build/spinfold" serve --port 0 --requests-per-second 0 "$@" > "$work/$name.log" 2>&1 &
  pids+=($!)
  local port=""
  for _ in $(seq 100); do
    port=$(grep -o 'serving on http://127.0.0.1:[0-9]*' "$work/$name.log" | grep -o '[0-9]*$' || true)
    [[ -n $port ]] && break
    sleep 0.1
  done
  printf -v "port_$name" '%s' "$port"
}
session() {  # PORT BODY [CLIENT] → a new session's id (CLIENT: the address it is made for)
  curl -sf -X POST -H 'Content-Type: application/json' -H "X-Forwarded-For: ${3:-127.0.0.1}" -d "$2" \
    "http://127.0.0.1:$1/api/v1/sessions" |
    sed 's/^{"id":"\([^"]*\)".*/\1/'
}
cat > "$work/advance.lua" <<'LUA'
wrk.method = "POST"
wrk.body = '{"steps": 1}'
wrk.headers["Content-Type"] = "application/json"
LUA
rps() {  # URL CONNECTIONS [LUA_SCRIPT] → requests per second
  local extra=() t=2
  [[ $# -ge 3 ]] && extra=(-s "$3")
  (($2 < t)) && t=$2
  wrk -t$t -c"$2" -d"$duration" "${extra[@]}" "$1" | awk '/Requests\/sec/ {print $2}'
}

start memory --no-store
start stored --data-dir "$work/data"
scene='{"preset": "spinning_rigid_sphere"}'
memory_id=$(session "$port_memory" "$scene")
stored_id=$(session "$port_stored" "$scene")
memory="http://127.0.0.1:$port_memory/api/v1/sessions/$memory_id"
stored="http://127.0.0.1:$port_stored/api/v1/sessions/$stored_id"

echo "| request | connections | memory only req/s | with the store req/s | ratio |"
echo "| --- | --- | --- | --- | --- |"
for c in 1 16; do
  a=$(rps "$memory/advance" $c "$work/advance.lua")
  b=$(rps "$stored/advance" $c "$work/advance.lua")
  awk -v a="$a" -v b="$b" -v c=$c 'BEGIN {printf "| POST advance {\"steps\": 1} (a commit each) | %d | %.0f | %.0f | %.2f |\n", c, a, b, b / a}'
done
a=$(rps "$memory" 16)
b=$(rps "$stored" 16)
awk -v a="$a" -v b="$b" 'BEGIN {printf "| GET /sessions/{id} (a version SELECT each) | 16 | %.0f | %.0f | %.2f |\n", a, b, b / a}'

# Restore: SESSIONS sessions at t = UNTIL (a parameter change at half way), then kill -9 and restart.
kill "${pids[@]}"
wait 2> /dev/null || true
pids=()
rm -rf "$work/data"
# As many clients as sessions (through X-Forwarded-For), within the quota of sessions per client.
start filler --data-dir "$work/data" --trusted-proxy 127.0.0.1
for i in $(seq $((sessions - 1))); do
  id=$(session "$port_filler" "$scene" "10.0.0.$i")
  curl -sf -X POST -H 'Content-Type: application/json' -d "{\"until\": $((until_t / 2))}" \
    "http://127.0.0.1:$port_filler/api/v1/sessions/$id/advance" > /dev/null
  curl -sf -X PATCH -H 'Content-Type: application/json' -d '{"body": {"mass": 2}}' \
    "http://127.0.0.1:$port_filler/api/v1/sessions/$id" > /dev/null
  curl -sf -X POST -H 'Content-Type: application/json' -d "{\"until\": $until_t}" \
    "http://127.0.0.1:$port_filler/api/v1/sessions/$id/advance" > /dev/null
done
kill -9 "${pids[@]}"
wait 2> /dev/null || true
pids=()
begin=$(date +%s%N)
start restored --data-dir "$work/data"
up_ms=$((($(date +%s%N) - begin) / 1000000))
echo
grep -o 'restored .*' "$work/restored.log" | sed "s/^/start-up: /; s/\$/ (t = $until_t each; serving after $up_ms ms)/"
