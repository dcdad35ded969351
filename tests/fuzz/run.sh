#!/usr/bin/env bash
# Runs every built fuzz target for SECONDS each (default 60) from the seed corpus in tests/fuzz/corpus.
# New inputs go to WORK/<target>/ (default build-fuzz/fuzz-work), never into the repository's seeds;
# a crash, leak, timeout or over-limit allocation leaves its reproducer in WORK and a non-zero exit.
#   tests/fuzz/run.sh [BUILD_DIR] [SECONDS]     e.g. tests/fuzz/run.sh build-fuzz 600  (release check)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-build-fuzz}"
seconds="${2:-60}"
work="${WORK:-$build/fuzz-work}"
status=0
for bin in "$build"/tests/fuzz/fuzz_*; do
  [ -x "$bin" ] || continue
  name="$(basename "$bin")"
  seeds="$here/corpus/${name#fuzz_}"
  mkdir -p "$work/$name"
  echo "== $name ($seconds s)"
  # rss_limit / malloc_limit: the memory promise (max(256 MB, 4 x input)) with headroom for ASan.
  if ! "$bin" "$work/$name" "$seeds" -max_total_time="$seconds" -rss_limit_mb=2048 -malloc_limit_mb=512 \
       -timeout=10 -max_len=65536 -artifact_prefix="$work/$name/" -print_final_stats=1 2>"$work/$name.log"; then
    echo "   FAILED: see $work/$name.log"
    status=1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|cov: " "$work/$name.log" | tail -3 | sed 's/^/   /'
done
exit $status
