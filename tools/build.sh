#!/usr/bin/env bash
# Configures and builds lc2wf in build/ (Release). LC2WF_BUILD_TESTS / LC2WF_BUILD_BENCH (ON|OFF) choose
# whether tests and benchmarks are built; extra arguments go to cmake's configure step.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${LC2WF_BUILD_DIR:-$root/build}
"$root/tools/setup-deps.sh"
generator=()
[[ ! -f "$build_dir/CMakeCache.txt" ]] && command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DLC2WF_BUILD_TESTS="${LC2WF_BUILD_TESTS:-ON}" -DLC2WF_BUILD_BENCH="${LC2WF_BUILD_BENCH:-ON}" "$@" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
