#!/usr/bin/env bash
# What the durable session store costs, in one run: advance and GET requests per second with wrk
# against a memory-only server, a server with the SQLite store and one with the PostgreSQL store (a
# commit per acknowledged change, a version SELECT per request), then the start-up restore time of N
# stored sessions from each store. PostgreSQL is a server of the bench's own (tests/server/
# postgres_fixture.sh: Debian's, a Unix socket, default settings: synchronous_commit on, fsync on).
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
root=$(cd "$(dirname "$0")/.." && pwd)
pg() { bash "$root/tests/server/postgres_fixture.sh" "$1" "$work/pg"; }
trap 'kill "${pids[@]}" 2>/dev/null || true; pg stop > /dev/null 2>&1 || true; rm -rf "$work"' EXIT
[[ $(id -u) -eq 0 ]] && chmod 755 "$work"  # the postgres account reaches its folder inside
pg start

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

pg_url=$(pg url)
start memory --no-store
start stored --data-dir "$work/data"
start postgres --store "$pg_url"
scene='{"preset": "spinning_rigid_sphere"}'
memory_id=$(session "$port_memory" "$scene")
stored_id=$(session "$port_stored" "$scene")
postgres_id=$(session "$port_postgres" "$scene")
memory="http://127.0.0.1:$port_memory/api/v1/sessions/$memory_id"
stored="http://127.0.0.1:$port_stored/api/v1/sessions/$stored_id"
postgres="http://127.0.0.1:$port_postgres/api/v1/sessions/$postgres_id"

echo "| request | connections | memory only req/s | SQLite req/s | PostgreSQL req/s | SQLite / memory | PostgreSQL / memory |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
row() {  # LABEL CONNECTIONS A B C
  awk -v l="$1" -v c="$2" -v a="$3" -v b="$4" -v p="$5" \
    'BEGIN {printf "| %s | %d | %.0f | %.0f | %.0f | %.2f | %.2f |\n", l, c, a, b, p, b / a, p / a}'
}
for c in 1 16; do
  a=$(rps "$memory/advance" $c "$work/advance.lua")
  b=$(rps "$stored/advance" $c "$work/advance.lua")
  p=$(rps "$postgres/advance" $c "$work/advance.lua")
  row 'POST advance {"steps": 1} (a commit each)' $c "$a" "$b" "$p"
done
a=$(rps "$memory" 16)
b=$(rps "$stored" 16)
p=$(rps "$postgres" 16)
row 'GET /sessions/{id} (a version SELECT each)' 16 "$a" "$b" "$p"

# Restore: SESSIONS sessions at t = UNTIL (a parameter change at half way), then kill -9 and restart.
kill "${pids[@]}"
wait 2> /dev/null || true
pids=()
rm -rf "$work/data"
pg start > /dev/null
echo
for store in sqlite postgres; do
  args=(--data-dir "$work/data")
  [[ $store == postgres ]] && args=(--store "$pg_url")
  # As many clients as sessions (through X-Forwarded-For), within the quota of sessions per client.
  start filler "${args[@]}" --trusted-proxy 127.0.0.1
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
  start restored "${args[@]}"
  up_ms=$((($(date +%s%N) - begin) / 1000000))
  grep -o 'restored .*' "$work/restored.log" | sed "s/^/start-up ($store): /; s/\$/ (t = $until_t each; serving after $up_ms ms)/"
  kill "${pids[@]}"
  wait 2> /dev/null || true
  pids=()
done
