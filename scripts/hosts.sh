#!/usr/bin/env bash
# Spinfold on several hosts, tested on one machine: Linux network namespaces (iproute2) as hosts,
# joined by veth pairs to a bridge in a namespace of its own, so that all traffic stays inside the
# namespaces. PostgreSQL on host `db`, replicas on `r1`…`rN` (`spinfold serve --store postgresql://…`),
# nginx on `front` (deploy/nginx/spinfold.conf: consistent hashing on the session id), and a host
# `client` for tests. Needs root (namespaces); Debian's postgresql, nginx and iproute2 (setup.sh).
#
#   scripts/hosts.sh up [N]            # N replicas (default 3): prints the front's URL
#   scripts/hosts.sh down              # stops everything, removes the namespaces and the state
#   scripts/hosts.sh kill-replica I    # SIGKILL every process of host rI (a host lost)
#   scripts/hosts.sh start-replica I   # starts rI's replica again, waits until it answers
#   scripts/hosts.sh db-down | db-up   # stops / starts the database (its data kept)
#   scripts/hosts.sh exec HOST CMD…    # runs CMD on a host (client, front, db, r1…)
#   scripts/hosts.sh status            # each host's processes
#
# Environment: HOSTS_STATE (state folder, default /tmp/spinfold-hosts), SPINFOLD_BIN (build/spinfold),
# HOSTS_NET (the /24's first three numbers, default 10.251.0), HOSTS_FRONT_RATE (the front's requests
# per second per address, default deploy/nginx/spinfold.conf's 100: a soak from one address raises it),
# HOSTS_SERVE_ARGS (more `spinfold serve` options for every replica, e.g. --requests-per-second 0).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
state=${HOSTS_STATE:-/tmp/spinfold-hosts}
bin=${SPINFOLD_BIN:-$root/build/spinfold}
net=${HOSTS_NET:-10.251.0}
prefix=spf
db_ip=$net.2 front_ip=$net.3 client_ip=$net.4
replica_ip() { echo "$net.$((10 + $1))"; }
port=8181 front_port=8080
pg_bin=$(ls -d /usr/lib/postgresql/*/bin 2> /dev/null | sort -V | tail -n 1)

die() { echo "hosts.sh: $*" >&2; exit 1; }
[[ $(id -u) -eq 0 ]] || die "needs root (network namespaces)"
in_host() { local host=$1; shift; ip netns exec "$prefix-$host" "$@"; }
url() { echo "postgresql://spinfold:$(cat "$state/db-password")@$db_ip:5432/spinfold"; }

# A host: a namespace with loopback and eth0, a veth whose other end is on the bridge.
add_host() {  # name address
  local ns=$prefix-$1
  ip netns add "$ns"
  ip link add "v-$1" type veth peer name eth0 netns "$ns"
  ip link set "v-$1" netns "$prefix-net"
  in_host net ip link set "v-$1" master br0 up
  in_host "$1" ip link set lo up
  in_host "$1" ip addr add "$2/24" dev eth0
  in_host "$1" ip link set eth0 up
  echo "$1" >> "$state/hosts"
}

wait_http() {  # host url
  for _ in $(seq 1 300); do
    in_host "$1" curl -sf -o /dev/null "$2" && return 0
    sleep 0.05
  done
  die "no answer from $2 on host $1 (logs in $state)"
}

db() {  # pg_ctl action…
  in_host db runuser -u postgres -- "$pg_bin/pg_ctl" -D "$state/pg" -l "$state/pg-run/db.log" -w -t 30 "$@" > /dev/null
}

start_replica() {  # index
  local i=$1
  # setsid: its own process group, so kill-replica can end the host's processes.
  SPINFOLD_STORE=$(url) in_host "r$i" setsid "$bin" serve --host "$(replica_ip "$i")" --port "$port" \
    --trusted-proxy "$front_ip" ${HOSTS_SERVE_ARGS:-} >> "$state/r$i.log" 2>&1 < /dev/null &
  wait_http client "http://$(replica_ip "$i"):$port/api/v1/health"
}

up() {
  local n=${1:-3}
  [[ $n =~ ^[1-9]$ ]] || die "N must be 1..9"
  [[ -x $bin ]] || die "no binary at $bin (build it: cmake --build build)"
  [[ -x $pg_bin/initdb ]] || die "PostgreSQL is missing: run scripts/setup.sh"
  [[ -e $state/hosts ]] && die "already up (scripts/hosts.sh down first)"
  ip netns list | grep -q "^$prefix-net" && die "the namespaces of another run are up (scripts/hosts.sh down)"
  mkdir -p "$state/nginx/tmp" "$state/nginx/cache"
  : > "$state/hosts"
  echo "$n" > "$state/replicas"
  ip netns add "$prefix-net"
  in_host net ip link add br0 type bridge
  in_host net ip link set br0 up
  in_host net ip link set lo up
  add_host db "$db_ip"
  add_host front "$front_ip"
  add_host client "$client_ip"
  for ((i = 1; i <= n; ++i)); do add_host "r$i" "$(replica_ip "$i")"; done

  # The database host: a cluster owned by `postgres`, a password for the replicas' role.
  head -c 18 /dev/urandom | base64 | tr -d '/+=' > "$state/db-password"
  chmod 600 "$state/db-password"
  install -d -o postgres "$state/pg" "$state/pg-run"
  local pwfile; pwfile=$(mktemp); cat "$state/db-password" > "$pwfile"; chmod 644 "$pwfile"
  runuser -u postgres -- "$pg_bin/initdb" -D "$state/pg" -U spinfold --pwfile="$pwfile" -A scram-sha-256 \
    -E UTF8 > "$state/initdb.log"
  rm -f "$pwfile"
  echo "host spinfold spinfold $net.0/24 scram-sha-256" >> "$state/pg/pg_hba.conf"
  echo "listen_addresses = '$db_ip'" >> "$state/pg/postgresql.conf"
  echo "unix_socket_directories = '$state/pg-run'" >> "$state/pg/postgresql.conf"
  db start
  PGPASSWORD=$(cat "$state/db-password") in_host db "$pg_bin/psql" -q -h "$state/pg-run" -U spinfold -d postgres \
    -c "CREATE DATABASE spinfold"

  for ((i = 1; i <= n; ++i)); do start_replica "$i"; done

  # The front: the same nginx configuration as scripts/front.sh, upstreams on the replica hosts.
  local upstreams=""
  for ((i = 1; i <= n; ++i)); do
    upstreams+="    server $(replica_ip "$i"):$port max_fails=1 fail_timeout=5s;"$'\n'
  done
  chown -R nobody:nogroup "$state/nginx/tmp" "$state/nginx/cache"
  awk -v prefix="$state/nginx" -v listen="$front_ip:$front_port" -v user="user nobody nogroup;" \
    -v ups="$upstreams" '
    /@UPSTREAMS@/ { printf "%s", ups; next }
    { gsub(/@PREFIX@/, prefix); gsub(/@LISTEN@/, listen); gsub(/@USER@/, user);
      if (rate != "") gsub(/rate=100r\/s/, "rate=" rate "r/s"); print }
  ' rate="${HOSTS_FRONT_RATE:-}" "$root/deploy/nginx/spinfold.conf" > "$state/nginx/nginx.conf"
  in_host front setsid nginx -p "$state/nginx" -c "$state/nginx/nginx.conf" -e "$state/nginx/error.log" \
    > /dev/null 2>&1 < /dev/null &
  wait_http client "http://$front_ip:$front_port/api/v1/health"
  echo "http://$front_ip:$front_port"
}

kill_host() {  # host
  local pids
  pids=$(ip netns pids "$prefix-$1" || true)
  [[ -n $pids ]] && kill -KILL $pids 2> /dev/null || true
  for _ in $(seq 1 100); do [[ -z $(ip netns pids "$prefix-$1") ]] && return 0; sleep 0.02; done
}

down() {
  [[ -d $state/pg ]] && { db stop -m fast 2> /dev/null || true; }
  # Every namespace of ours, also those a run that was killed left behind.
  local ns
  for ns in $(ip netns list | awk '{print $1}' | grep "^$prefix-" || true); do
    kill_host "${ns#"$prefix"-}"
    ip netns del "$ns" 2> /dev/null || true
  done
  rm -rf "$state"
}

case ${1:-} in
  up) up "${2:-3}" ;;
  down) down ;;
  kill-replica) kill_host "r${2:?replica number}" ;;
  start-replica) start_replica "${2:?replica number}" ;;
  db-down) db stop -m fast ;;
  db-up) db start ;;
  exec) shift; host=$1; shift; in_host "$host" "$@" ;;
  status) while read -r host; do echo "$host: $(ip netns pids "$prefix-$host" | tr '\n' ' ')"; done < "$state/hosts" ;;
  *) sed -n '2,20p' "$0"; exit 2 ;;
esac
