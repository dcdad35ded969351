#!/usr/bin/env bash
# Runs every built fuzz target, one after the other, from the seed corpus in tests/fuzz/corpus for SECONDS
# each (0 = no time limit) and at most RUNS executions each (0 = no limit); prints one table row per target.
# New inputs go to WORK/<target>/ (default BUILD_DIR/fuzz-work), never into the repository's seeds; a crash,
# leak, timeout or over-limit allocation leaves its reproducer there and makes the exit status 1.
#   tests/fuzz/run.sh [BUILD_DIR] [SECONDS] [RUNS]   e.g. tests/fuzz/run.sh build-fuzz 5 (CI), build-fuzz 0 10000000
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-build-fuzz}"
seconds="${2:-60}"
runs="${3:-0}"
work="${WORK:-$build/fuzz-work}"
status=0
limits=()
[[ "$seconds" != 0 ]] && limits+=(-max_total_time="$seconds")
[[ "$runs" != 0 ]] && limits+=(-runs="$runs")
printf '%-22s %12s %9s %8s %8s %9s %s\n' target executions exec/s edges corpus peak_MB result
for bin in "$build"/tests/fuzz/fuzz_*; do
  [ -x "$bin" ] || continue
  name="$(basename "$bin")"
  seeds="$here/corpus/${name#fuzz_}"
  mkdir -p "$work/$name"
  result=ok
  # rss_limit / malloc_limit: the memory promise (max(256 MB, 4 x input)) with headroom for ASan.
  if ! "$bin" "$work/$name" "$seeds" "${limits[@]}" -rss_limit_mb=2048 -malloc_limit_mb=512 -timeout=10 -max_len=65536 \
       -artifact_prefix="$work/$name/" -print_final_stats=1 2>"$work/$name.log"; then
    result="FAILED: see $work/$name.log"
    status=1
  fi
  stat() { grep -m1 "^stat::$1:" "$work/$name.log" | awk '{print $2}'; }
  edges=$(grep -oE "cov: [0-9]+" "$work/$name.log" | tail -1 | awk '{print $2}')
  corpus=$(grep -oE "corp: [0-9]+" "$work/$name.log" | tail -1 | awk '{print $2}')
  printf '%-22s %12s %9s %8s %8s %9s %s\n' "$name" "$(stat number_of_executed_units)" "$(stat average_exec_per_sec)" \
    "${edges:-?}" "${corpus:-?}" "$(stat peak_rss_mb)" "$result"
done
exit $status
