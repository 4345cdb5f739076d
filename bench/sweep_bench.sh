#!/bin/bash
# The sweep's figures (docs/performance.md, "Sweeps"), ratios from one run each:
#  1. 400 short runs (T = 100, dop853) as one `spinfold sweep --jobs 1` against the same 400 as
#     `spinfold simulate` processes one after another (what a shell loop does), for the full
#     binary and for the compute-only one (-DSPINFOLD_COMPUTE_ONLY=ON) when given;
#  2. a sweep with --jobs 2 against --jobs 1 (longer runs: T = 1000);
#  3. 400 runs with a summary and one event (--summary r --event r:up:1.3) against the same 400
#     without them, for dop853, rk4 and the closed form (the best of 3, interleaved).
#
#   bench/sweep_bench.sh [build/spinfold] [build-compute/spinfold]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
full=$(realpath "${1:-$root/build/spinfold}")
compute=${2:-}
[[ -n $compute ]] && compute=$(realpath "$compute")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

now() { date +%s.%N; }
seconds() { awk "BEGIN{printf \"%.2f\", $2 - $1}"; }
ratio() { awk "BEGIN{printf \"%.1f\", $1 / $2}"; }

runs=400
base=spinning_rigid_sphere
set_r="initial.r=0.1:3:$runs"
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"

# The same 400 scenes as files, written by the sweep's own values (not timed).
"$full" sweep $base --set "$set_r" --t-end 0 --fields t --quiet --out "$tmp/values.csv"
python3 - "$tmp" "$root/assets/scenes/$base.json" <<'EOF'
import csv, json, sys
tmp, scene_file = sys.argv[1:]
scene = json.load(open(scene_file))
rows = [r for r in csv.reader(line for line in open(f"{tmp}/values.csv") if not line.startswith("#"))]
header, rows = rows[0], rows[1:]
for row in rows:
    scene["initial"]["r"] = float(row[header.index("initial_r")])  # dots written _
    json.dump(scene, open(f"{tmp}/scene_{row[0]}.json", "w"))
EOF

t0=$(now)
"$full" sweep $base --set "$set_r" --set integrator.name=dop853 --t-end 100 --every 1 --jobs 1 --quiet \
  --out "$tmp/sweep.csv"
t1=$(now)
sweep_s=$(seconds "$t0" "$t1")
echo "sweep, 400 runs, --jobs 1:                  ${sweep_s} s"

loop() {
  local binary=$1
  local start
  start=$(now)
  for ((i = 0; i < runs; ++i)); do
    "$binary" simulate "$tmp/scene_$i.json" --integrator dop853 --t-end 100 --every 1 >"$tmp/sim.jsonl"
  done
  seconds "$start" "$(now)"
}
loop_s=$(loop "$full")
echo "400 simulate processes (full binary):       ${loop_s} s   sweep is $(ratio "$loop_s" "$sweep_s")x faster"
if [[ -n $compute ]]; then
  loop_c=$(loop "$compute")
  echo "400 simulate processes (compute-only):      ${loop_c} s   sweep is $(ratio "$loop_c" "$sweep_s")x faster"
fi

# --jobs 2 against --jobs 1, and as a control of what the machine gives two processes now (it is
# shared): the same sweep as two shard processes side by side (each --jobs 1).
long="$base --set initial.r=0.1:3:200 --set integrator.name=dop853 --t-end 5000 --every 10 --quiet"
# shellcheck disable=SC2086  # a list of arguments
{
  t0=$(now)
  "$full" sweep $long --jobs 1 --out "$tmp/j1.csv"
  t1=$(now)
  "$full" sweep $long --jobs 2 --out "$tmp/j2.csv"
  t2=$(now)
  "$full" sweep $long --jobs 1 --shard 0/2 --out "$tmp/s0.csv" &
  "$full" sweep $long --jobs 1 --shard 1/2 --out "$tmp/s1.csv"
  wait
  t3=$(now)
}
j1=$(seconds "$t0" "$t1")
j2=$(seconds "$t1" "$t2")
p2=$(seconds "$t2" "$t3")
echo "sweep, 200 runs of T = 5000, --jobs 1:      ${j1} s"
echo "the same, --jobs 2:                         ${j2} s   speed-up $(ratio "$j1" "$j2")x"
echo "control: 2 processes of 100 runs each:      ${p2} s   speed-up $(ratio "$j1" "$p2")x (what the machine gives now)"

# Summaries and events against none: the same sweep, the best of 3 each, interleaved.
best() { sort -n | head -1; }
for integrator in dop853 rk4 exact; do
  plain=() watched=()
  for _ in 1 2 3; do
    for mode in plain watched; do
      extra=()
      [[ $mode == watched ]] && extra=(--summary r --event r:up:1.3)
      t0=$(now)
      "$full" sweep separable_radial_abc --set initial.phi=0:1:400 --set integrator.name=$integrator \
        --t-end 100 --every 1 --jobs 1 --quiet "${extra[@]}" --out "$tmp/m.csv"
      t1=$(now)
      if [[ $mode == plain ]]; then plain+=("$(seconds "$t0" "$t1")"); else watched+=("$(seconds "$t0" "$t1")"); fi
    done
  done
  p=$(printf '%s\n' "${plain[@]}" | best)
  w=$(printf '%s\n' "${watched[@]}" | best)
  echo "400 runs of W5 to T = 100, $integrator: ${p} s; with --summary r --event r:up:1.3: ${w} s   $(awk "BEGIN{printf \"%.2f\", $w / $p}")x"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
