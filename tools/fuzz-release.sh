#!/usr/bin/env bash
# Release check: the long fuzz run. Builds the libFuzzer targets (clang, ASan/UBSan) in build-fuzz and runs
# each one after the other for RUNS executions (default 10^7, the release target), at low priority, then
# prints executions, exec/s, coverage and peak memory per target. Record the table in tests/fuzz/README.md.
#   tools/fuzz-release.sh [RUNS] [MAX_SECONDS_PER_TARGET]     e.g. tools/fuzz-release.sh 10000000 0
#   LC2WF_FUZZ_BUILD_DIR=DIR (default build-fuzz); LC2WF_FUZZ_ONLY=fuzz_obj runs one target.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-10000000}
seconds=${2:-0}
build=${LC2WF_FUZZ_BUILD_DIR:-$root/build-fuzz}
LC2WF_WITH_SANITIZERS=1 "$root/tools/setup-deps.sh"
generator=()
[[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DLC2WF_FUZZ=ON -DLC2WF_BUILD_TESTS=OFF -DLC2WF_BUILD_BENCH=OFF -DLC2WF_ONLY=core >/dev/null
nice -n 10 cmake --build "$build" -j "$(nproc)" --target lc2wf_fuzzers
if [[ -n "${LC2WF_FUZZ_ONLY:-}" ]]; then
  # run.sh runs every fuzz_* in its folder: give it a folder holding only the chosen one.
  only="$build/fuzz-only/tests/fuzz"
  rm -rf "$build/fuzz-only" && mkdir -p "$only" && ln -s "$build/tests/fuzz/$LC2WF_FUZZ_ONLY" "$only/"
  WORK="$build/fuzz-work" exec nice -n 10 "$root/tests/fuzz/run.sh" "$build/fuzz-only" "$seconds" "$runs"
fi
WORK="$build/fuzz-work" exec nice -n 10 "$root/tests/fuzz/run.sh" "$build" "$seconds" "$runs"
