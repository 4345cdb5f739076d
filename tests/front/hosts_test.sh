#!/usr/bin/env bash
# Brings the hosts of scripts/hosts.sh up (PostgreSQL, three replicas, nginx, a client), runs
# tests/front/hosts_test.py on the client host, and takes everything down. Exit 77 (skipped) without
# root or PostgreSQL. Measured: about 35 s on 2 cores (README, "Several hosts").
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
export SPINFOLD_BIN=${1:-$root/build/spinfold}
export HOSTS_STATE=${HOSTS_STATE:-/tmp/spinfold-hosts-test-$$}
[[ $(id -u) -eq 0 ]] || { echo "hosts_test.sh: skipped: needs root (network namespaces)"; exit 77; }
ls /usr/lib/postgresql/*/bin/initdb > /dev/null 2>&1 || { echo "hosts_test.sh: skipped: no PostgreSQL"; exit 77; }
# One set of hosts at a time on a machine: the namespaces' names are fixed.
exec 9> /tmp/spinfold-hosts.lock
flock 9
bash "$root/scripts/hosts.sh" down > /dev/null 2>&1 || true
trap 'bash "$root/scripts/hosts.sh" down' EXIT
front=$(bash "$root/scripts/hosts.sh" up 3 | tail -n 1)
bash "$root/scripts/hosts.sh" exec client python3 "$root/tests/front/hosts_test.py" "$front" "$root/scripts/hosts.sh"
