#!/usr/bin/env bash
# The shared server: nginx (Debian's, installed by scripts/setup.sh) on 127.0.0.1:8080 in front of
# N `spinfold serve` replicas (default 2) that share one data directory. Ctrl-C stops them all.
#
#   scripts/front.sh [N]
#
# Environment: FRONT_PORT (8080), FRONT_HOST (127.0.0.1), REPLICA_BASE_PORT (8181: replicas listen
# on 127.0.0.1:8181, 8182, …), SPINFOLD_DATA (the shared data directory, default the per-user state
# directory), FRONT_DIR (nginx's runtime folder, default a temporary one), SPINFOLD_BIN (the binary,
# default build/spinfold, built if missing), FRONT_READY_FILE (written with the front's URL once
# every replica and nginx answer: for tests).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
replicas=${1:-2}
[[ $replicas =~ ^[1-9][0-9]?$ ]] || { echo "front.sh: N must be 1..99" >&2; exit 2; }
front_host=${FRONT_HOST:-127.0.0.1}
front_port=${FRONT_PORT:-8080}
base_port=${REPLICA_BASE_PORT:-8181}
data=${SPINFOLD_DATA:-${XDG_STATE_HOME:-$HOME/.local/state}/spinfold}
bin=${SPINFOLD_BIN:-$root/build/spinfold}
nginx_bin=$(command -v nginx || echo /usr/sbin/nginx)
[[ -x $nginx_bin ]] || { echo "front.sh: nginx is missing: run scripts/setup.sh" >&2; exit 2; }
if [[ ! -x $bin ]]; then
  bash "$root/scripts/setup.sh"
  cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build "$root/build" --target spinfold
fi

dir=${FRONT_DIR:-$(mktemp -d -t spinfold-front.XXXXXX)}
mkdir -p "$dir/tmp" "$dir/cache" "$data"
pids=()
declare -a replica_pids=()
stop() {
  trap - INT TERM EXIT
  for pid in "${pids[@]}" "${replica_pids[@]}"; do kill -TERM "$pid" 2> /dev/null || true; done
  wait 2> /dev/null || true
}
trap stop INT TERM EXIT

start_replica() {  # index
  local i=$1
  "$bin" serve --host 127.0.0.1 --port $((base_port + i)) --data-dir "$data" --trusted-proxy 127.0.0.1 \
    >> "$dir/replica-$i.log" 2>&1 &
  replica_pids[$i]=$!
  echo "$!" > "$dir/replica-$i.pid"
}
upstreams=""
for ((i = 0; i < replicas; ++i)); do
  start_replica "$i"
  # max_fails=1: a replica that refuses a connection is skipped for 5 s (its sessions move on).
  upstreams+="    server 127.0.0.1:$((base_port + i)) max_fails=1 fail_timeout=5s;"$'\n'
done

# Workers run as nobody when nginx starts as root; they need the temporary folders.
user_line=""
if [[ $(id -u) -eq 0 ]]; then
  user_line="user nobody nogroup;"
  chown -R nobody:nogroup "$dir/tmp" "$dir/cache"
fi
conf="$dir/nginx.conf"
awk -v prefix="$dir" -v listen="$front_host:$front_port" -v user="$user_line" -v ups="$upstreams" '
  /@UPSTREAMS@/ { printf "%s", ups; next }
  { gsub(/@PREFIX@/, prefix); gsub(/@LISTEN@/, listen); gsub(/@USER@/, user); print }
' "$root/deploy/nginx/spinfold.conf" > "$conf"
"$nginx_bin" -t -q -p "$dir" -c "$conf" -e "$dir/error.log"
# nginx starts once every replica answers (a refused first request would mark a replica down).
wait_for() {  # url…
  for _ in $(seq 1 200); do
    local ready=1 url
    for url in "$@"; do curl -sf "$url" > /dev/null || ready=0; done
    ((ready)) && return 0
    sleep 0.05
  done
  echo "front.sh: not ready: $* (logs in $dir)" >&2
  exit 1
}
replica_urls=()
for ((i = 0; i < replicas; ++i)); do replica_urls+=("http://127.0.0.1:$((base_port + i))/api/v1/health"); done
wait_for "${replica_urls[@]}"
"$nginx_bin" -p "$dir" -c "$conf" -e "$dir/error.log" &
nginx_pid=$!
pids+=("$nginx_pid")
wait_for "http://$front_host:$front_port/api/v1/health"

echo "Spinfold front on http://$front_host:$front_port/ ($replicas replicas on ports $base_port.., data $data, logs $dir)"
[[ -n ${FRONT_READY_FILE:-} ]] && echo "http://$front_host:$front_port $dir" > "$FRONT_READY_FILE"
# A supervisor, as a Deployment would be: a replica that dies is started again after a second (its
# sessions are served by the others meanwhile, from the shared store); if nginx ends, all stop.
while kill -0 "$nginx_pid" 2> /dev/null; do
  sleep 1
  for ((i = 0; i < replicas; ++i)); do
    if ! kill -0 "${replica_pids[$i]}" 2> /dev/null; then
      echo "front.sh: replica $i (port $((base_port + i))) ended; starting it again" >&2
      start_replica "$i"
    fi
  done
done
echo "front.sh: nginx ended; stopping (logs in $dir)" >&2
