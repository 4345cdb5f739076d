#!/usr/bin/env bash
# Hunts flaky tests: the whole ctest run of an existing build, RUNS times in a row with -j2 while a
# CPU hog (Debian's stress-ng) keeps every core busy, then once with -j4 (more tests than cores).
# A test that fails under load is a bug in the test or the code: this prints each failure and
# exits non-zero if there was any. Usage: scripts/flake_hunt.sh [BUILD_DIR] [RUNS]
# (defaults: build, 5). Takes about RUNS+1 times a loaded ctest run (docs/performance.md).
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-5}
[[ -f $build/CTestTestfile.cmake ]] || { echo "flake_hunt: no ctest build in $build (scripts/test.sh makes one)"; exit 2; }
command -v stress-ng > /dev/null || { echo "flake_hunt: stress-ng is missing (scripts/setup.sh installs it)"; exit 2; }

log=$build/flake_hunt
mkdir -p "$log"
stress-ng --cpu "$(nproc)" --timeout 0 --quiet &
hog=$!
trap 'kill $hog 2> /dev/null' EXIT

failures=0
round() {  # round NAME JOBS
  local started=$SECONDS
  ctest --test-dir "$build" -j "$2" --output-on-failure > "$log/$1.log" 2>&1
  local failed
  failed=$(sed -n 's/^[[:space:]]*[0-9]\+ - \(.*\) (.*)$/\1/p' "$log/$1.log" | sort -u | tr '\n' ' ')
  local summary
  summary=$(grep -E '^[0-9]+% tests passed' "$log/$1.log" || echo "no summary (see $log/$1.log)")
  echo "flake_hunt: $1 (-j$2, $(nproc) cores busy): $summary in $((SECONDS - started)) s${failed:+; failed: $failed}"
  grep -qE '^100% tests passed' "$log/$1.log" || failures=$((failures + 1))
}
for i in $(seq 1 "$runs"); do round "loaded-$i" 2; done
round "loaded-j4" 4
echo "flake_hunt: $failures of $((runs + 1)) loaded runs had a failure (logs in $log/)"
((failures == 0))
