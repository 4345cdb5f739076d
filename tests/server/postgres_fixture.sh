#!/usr/bin/env bash
# A PostgreSQL server of its own for the store tests: Debian's binaries, a cluster in DIR, listening
# only on a Unix socket in DIR (no TCP port to collide with), run as an unprivileged user (the
# `postgres` account when started as root; PostgreSQL refuses to run as root).
#
#   postgres_fixture.sh start DIR   # a new cluster in DIR (what was there is removed), started
#   postgres_fixture.sh down DIR    # stops the server (connections end), keeping its data
#   postgres_fixture.sh up DIR      # starts it again
#   postgres_fixture.sh stop DIR    # stops it and removes DIR
#   postgres_fixture.sh url DIR     # the URL of its `postgres` database
set -euo pipefail
action=$1
dir=$(realpath -m "$2")  # absolute: the server resolves its socket folder from its data folder
port=54329
bin=$(ls -d /usr/lib/postgresql/*/bin 2> /dev/null | sort -V | tail -n 1)
[[ -x $bin/initdb ]] || { echo "postgres_fixture.sh: PostgreSQL is missing: run scripts/setup.sh" >&2; exit 1; }
as_owner=()
[[ $(id -u) -eq 0 ]] && as_owner=(runuser -u postgres --)
ctl() { "${as_owner[@]}" "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 30 "$@" > /dev/null; }

case $action in
  start)
    if [[ -d $dir/data ]]; then ctl stop -m immediate 2> /dev/null || true; fi
    rm -rf "$dir"
    mkdir -p "$dir"
    [[ $(id -u) -eq 0 ]] && chown postgres "$dir"
    "${as_owner[@]}" "$bin/initdb" -D "$dir/data" -A trust -U spinfold -E UTF8 --no-sync > "$dir/initdb.log"
    ctl -o "-k $dir -c listen_addresses='' -p $port" start
    ;;
  down) ctl stop -m fast ;;
  up) ctl -o "-k $dir -c listen_addresses='' -p $port" start ;;
  stop)
    if [[ -d $dir/data ]]; then ctl stop -m fast || true; fi
    rm -rf "$dir"
    ;;
  url) echo "postgresql:///postgres?host=$dir&port=$port&user=spinfold" ;;
  *) echo "postgres_fixture.sh: start|down|up|stop|url DIR" >&2; exit 2 ;;
esac
