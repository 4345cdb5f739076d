#!/bin/bash
# The Slurm recipe (deploy/slurm/sweep.sbatch) run for real: Debian's slurm-wlm and munge as a
# one-node cluster on localhost (munged, slurmctld and slurmd started here, configured in a temp
# directory, stopped on exit), a job array of 4 tasks and the merge job after it (afterany); the
# merged rows must be those of the same sweep in one process (timing column and command lines
# aside). Then a shard is lost: the merge names it and fails, a re-run of that task alone
# (--array=2) and the merge again give the same rows.
#
#   scripts/slurm_sweep_test.sh [path/to/spinfold]     (default: build/spinfold)
#
# A ctest (slurm_sweep, ~20 s: the scheduler starts a dependent job on its next pass). Needs root (the daemons run as root here) and slurm-wlm and munge
# (scripts/setup.sh); otherwise it exits 77, which ctest reports as skipped. Prints its run time.
set -euo pipefail
if [[ $(id -u) -ne 0 ]]; then
  echo "slurm_sweep_test: skipped: needs root to run munged, slurmctld and slurmd" >&2
  exit 77
fi
root=$(cd "$(dirname "$0")/.." && pwd)
spinfold=$(realpath "${1:-$root/build/spinfold}")
start=$(date +%s.%N)

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  echo "slurm_sweep_test: skipped: slurm-wlm and munge are not installed (scripts/setup.sh)" >&2
  exit 77
fi

tmp=$(mktemp -d /tmp/spinfold-slurm.XXXXXX)
chmod 755 "$tmp"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [[ ${KEEP:-0} != 1 ]]; then rm -rf "$tmp"; else echo "kept $tmp"; fi
}
trap cleanup EXIT
fail() {
  echo "slurm_sweep_test: $*" >&2
  for log in "$tmp"/*.log; do echo "--- $log" >&2; tail -20 "$log" >&2; done
  exit 1
}

# munge: its own key, socket and files here.
mkdir -m 711 "$tmp/munge"  # the socket needs x for all
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/munge/munge.key"
munged --foreground --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/socket" \
  --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/seed" --log-file="$tmp/munged.log" \
  >"$tmp/munged.out" 2>&1 &
pids+=($!)

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
host=$(hostname -s)
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/out"
export SLURM_CONF=$tmp/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=spinfold-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
MailProg=/bin/true
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$(($(awk '/MemTotal/ {print $2}' /proc/meminfo) / 2048)) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

# Wait until munge answers before the daemons need it.
for _ in $(seq 50); do
  [[ -S $tmp/munge/socket ]] && munge --socket="$tmp/munge/socket" -n </dev/null >/dev/null 2>&1 && break
  sleep 0.1
done
slurmctld -D -i -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 150); do
  state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
  [[ $state == idle ]] && break
  sleep 0.2
done
[[ ${state:-} == idle ]] || fail "the node did not come up (state '${state:-}')"
up=$(date +%s.%N)

sweep_args="spinning_rigid_sphere --set initial.r=0.4:1.6:6 --set integrator.name=dop853,gauss6,auto --t-end 20 --every 1 --fields t,r,phi,energy_error,drift.p_phi"
export SPINFOLD=$spinfold SWEEP_ARGS=$sweep_args OUT_DIR=$tmp/out SHARDS=4
# Waits for jobs to leave the queue (polled: sbatch --wait looks only every few seconds).
wait_jobs() {
  for _ in $(seq 600); do
    [[ -z $(squeue -h -j "$1" -o %i 2>/dev/null) ]] && return 0
    sleep 0.1
  done
  fail "jobs $1 still queued after 60 s"
}
completed() { scontrol -o show job "$1" | grep -c 'JobState=COMPLETED'; }

# The recipe as README says it: the array, then the merge as a job that depends on it (afterany).
job=$(sbatch --parsable --array=0-3 --output="$tmp/task-%a.log" "$root/deploy/slurm/sweep.sbatch") ||
  fail "sbatch refused the job array"
merge=$(sbatch --parsable --dependency=afterany:"$job" --output="$tmp/merge-1.log" \
  "$root/deploy/slurm/merge.sbatch") || fail "sbatch refused the merge job"
wait_jobs "$job,$merge"
[[ $(completed "$job") == 4 ]] ||
  fail "the job array's tasks did not all complete: $(scontrol -o show job "$job" | grep -o 'JobState=[A-Z_]*' | sort | uniq -c)"
[[ $(completed "$merge") == 1 ]] || fail "the merge job did not complete"
# shellcheck disable=SC2086  # a list of arguments
"$spinfold" sweep $sweep_args --quiet --out "$tmp/single.csv"

# The same rows: all but the last column (seconds) and the header's command lines (the merge adds one).
strip() { grep -v -e '^# command:' -e '^# merge:' "$1" | sed 's/,[^,]*$//'; }
same_as_single() {
  diff <(strip "$tmp/single.csv") <(strip "$1") >"$tmp/diff.log" || fail "$2 differ from the single-process sweep"
}
same_as_single "$tmp/out/sweep.csv" "the merged shards"
rows=$(grep -vc '^#' "$tmp/out/sweep.csv")
[[ $rows == 19 ]] || fail "expected 18 rows and a header, got $rows lines"

# A lost shard: the merge names it and fails; re-running that one task (--array=2: index 2, still
# of 4 shards) and the merge again gives the same rows.
rm "$tmp/out/shard-2.csv" "$tmp/out/sweep.csv"
merge=$(sbatch --parsable --output="$tmp/merge-2.log" "$root/deploy/slurm/merge.sbatch")
wait_jobs "$merge"
[[ $(completed "$merge") == 0 ]] || fail "the merge ran with a shard missing"
grep -q 'shards missing: 2 of 4; re-run them with sbatch --array=2' "$tmp/merge-2.log" ||
  fail "the merge did not name the missing shard: $(cat "$tmp/merge-2.log")"
again=$(sbatch --parsable --array=2 --output="$tmp/rerun-%a.log" "$root/deploy/slurm/sweep.sbatch")
merge=$(sbatch --parsable --dependency=afterany:"$again" --output="$tmp/merge-3.log" \
  "$root/deploy/slurm/merge.sbatch")
wait_jobs "$again,$merge"
[[ $(completed "$merge") == 1 ]] || fail "the merge after the re-run did not complete"
same_as_single "$tmp/out/sweep.csv" "the shards merged after a re-run of one task"
end=$(date +%s.%N)
printf 'slurm_sweep_test: ok: 4 array tasks and a dependent merge = single process; a lost shard named, re-run alone and merged again; cluster up in %.1f s, %.1f s in all\n' \
  "$(awk "BEGIN{print $up - $start}")" "$(awk "BEGIN{print $end - $start}")"
