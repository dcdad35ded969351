#!/usr/bin/env bash
# The main command: installs what is missing, builds, and runs the demo on the embedded default data.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${LC2WF_BUILD_DIR:-$root/build}
LC2WF_BUILD_TESTS=OFF "$root/tools/build.sh"
# Until the full pipeline lands, the demo is the engine's smallest real job: train a small MLP.
exec "$build_dir/train/lc2wf-mlp-demo" "$@"
