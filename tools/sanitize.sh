#!/usr/bin/env bash
# CI's sanitizer stage (run by tools/test.sh after the default suite): in its own folder (build-sanitize),
# an ASan/UBSan build with clang of the reader tests and of every libFuzzer target, then those tests and a
# short fuzz run of every target from the seed corpus. Fails on a test failure, a sanitizer report or a
# fuzz finding. -O0: this stage is bounded by its build time, not by how fast the code runs.
#   LC2WF_SKIP_SANITIZE=1           skip the stage (local runs)
#   LC2WF_FUZZ_SECONDS=N            seconds per fuzz target (default 4)
#   LC2WF_SANITIZE_BUILD_DIR=DIR    build folder (default build-sanitize)
set -euo pipefail
if [[ "${LC2WF_SKIP_SANITIZE:-0}" == 1 ]]; then
  echo "sanitize: skipped (LC2WF_SKIP_SANITIZE=1)"
  exit 0
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=${LC2WF_SANITIZE_BUILD_DIR:-$root/build-sanitize}
seconds=${LC2WF_FUZZ_SECONDS:-4}
start=$SECONDS
LC2WF_WITH_SANITIZERS=1 "$root/tools/setup-deps.sh"

# Only the fuzz targets and the reader tests are built, from the reader sources they link
# (tests/fuzz/CMakeLists.txt); core is the smallest module to configure.
generator=()
[[ ! -f "$build/CMakeCache.txt" ]] && command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DCMAKE_CXX_COMPILER=clang++ \
  -DLC2WF_FUZZ=ON -DLC2WF_BUILD_TESTS=ON -DLC2WF_BUILD_BENCH=OFF -DLC2WF_ONLY=core >/dev/null
cmake --build "$build" -j "$(nproc)" --target lc2wf_fuzzers lc2wf_reader_tests
echo "sanitize: built in $((SECONDS - start)) s"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The labelling and synthetic-cloud tests share a file with the reader tests but read nothing: at -O0 under
# ASan they took 45 of the 50 s.
(cd "$build" && ./tests/fuzz/lc2wf_reader_tests --gtest_brief=1 --gtest_filter=-Labelling.*:SyntheticCloud.*)
echo "sanitize: tests passed at $((SECONDS - start)) s"
WORK="$build/fuzz-work" "$root/tests/fuzz/run.sh" "$build" "$seconds"
echo "sanitize: done in $((SECONDS - start)) s"
