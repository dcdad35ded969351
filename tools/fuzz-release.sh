#!/usr/bin/env bash
# Release check: the long fuzz run. Builds the libFuzzer targets (clang, ASan/UBSan) in build-fuzz and runs
# each one until it has RUNS executions in all (default 10^7, the release target), one target at a time, in
# slices of at most SLICE seconds. Every slice adds its executions to WORK/<target>.executions, so a killed
# run resumes where it stopped and loses at most one slice; the corpora in WORK carry on as well.
# Prints one row per slice (tests/fuzz/run.sh's columns) and a final table of the totals for tests/fuzz/README.md.
#   tools/fuzz-release.sh [RUNS] [SLICE_SECONDS]     e.g. tools/fuzz-release.sh 10000000 600
#   LC2WF_FUZZ_BUILD_DIR=DIR (default build-fuzz); LC2WF_FUZZ_ONLY=fuzz_obj runs one target;
#   LC2WF_FUZZ_NICE=N (default 10; 0 when the machine is free); LC2WF_FUZZ_NO_BUILD=1 skips the build.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-10000000}
slice=${2:-600}
build=${LC2WF_FUZZ_BUILD_DIR:-$root/build-fuzz}
niceness=${LC2WF_FUZZ_NICE:-10}
work="$build/fuzz-work"
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz-release.sh: RUNS must be a positive integer, got '$runs'" >&2; exit 2; }
[[ "$slice" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz-release.sh: SLICE_SECONDS must be a positive integer, got '$slice'" >&2; exit 2; }
if [[ -z "${LC2WF_FUZZ_NO_BUILD:-}" ]]; then
  LC2WF_WITH_SANITIZERS=1 "$root/tools/setup-deps.sh"
  generator=()
  [[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null && generator=(-G Ninja)
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DLC2WF_FUZZ=ON -DLC2WF_BUILD_TESTS=OFF -DLC2WF_BUILD_BENCH=OFF -DLC2WF_ONLY=core >/dev/null
  nice -n "$niceness" cmake --build "$build" -j "$(nproc)" --target lc2wf_fuzzers
fi
mkdir -p "$work"
total_of() { local f="$work/$1.executions"; [[ -f "$f" ]] && cat "$f" || echo 0; }
status=0
targets=()
for bin in "$build"/tests/fuzz/fuzz_*; do
  [[ -x "$bin" ]] || continue
  name=$(basename "$bin")
  [[ -n "${LC2WF_FUZZ_ONLY:-}" && "$name" != "$LC2WF_FUZZ_ONLY" ]] && continue
  targets+=("$name")
done
[[ ${#targets[@]} -gt 0 ]] || { echo "fuzz-release.sh: no fuzz target ${LC2WF_FUZZ_ONLY:-} in $build/tests/fuzz" >&2; exit 3; }
for name in "${targets[@]}"; do
  # run.sh runs every fuzz_* in its folder: give it a folder holding only this one.
  only="$build/fuzz-only/tests/fuzz"
  rm -rf "$build/fuzz-only" && mkdir -p "$only" && ln -s "$build/tests/fuzz/$name" "$only/"
  while (( $(total_of "$name") < runs )); do
    left=$(( runs - $(total_of "$name") ))
    set +e
    row=$(WORK="$work" nice -n "$niceness" "$root/tests/fuzz/run.sh" "$build/fuzz-only" "$slice" "$left" | tail -1)
    code=$?
    set -e
    echo "$row"
    done_now=$(awk '{print $2}' <<<"$row")
    [[ "$done_now" =~ ^[0-9]+$ ]] || done_now=0
    echo $(( $(total_of "$name") + done_now )) > "$work/$name.executions.tmp"
    mv "$work/$name.executions.tmp" "$work/$name.executions"
    if (( code != 0 )); then status=1; break; fi
    (( done_now > 0 )) || { echo "fuzz-release.sh: $name made no progress" >&2; status=1; break; }
  done
done
echo
printf '%-22s %14s\n' target total_executions
for name in "${targets[@]}"; do printf '%-22s %14s\n' "$name" "$(total_of "$name")"; done
exit $status
