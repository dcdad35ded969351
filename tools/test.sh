#!/usr/bin/env bash
# The test command: installs missing dependencies (Blender too, for the end-to-end render test, and
# Chromium for the HTML report's browser test), builds, and runs the default CTest suite, then the
# sanitizer stage (tools/sanitize.sh: ASan/UBSan reader tests and a short run of every fuzz target;
# LC2WF_SKIP_SANITIZE=1 skips it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
LC2WF_WITH_RENDER_TOOLS=${LC2WF_WITH_RENDER_TOOLS:-1} LC2WF_WITH_BROWSER=${LC2WF_WITH_BROWSER:-1} \
  "$root/tools/build.sh" "$@"
cd "${LC2WF_BUILD_DIR:-$root/build}"
# Tests write their scratch files under the system temp folder: one folder per run, removed afterwards,
# so repeated runs leave nothing behind in /tmp.
TMPDIR=$(mktemp -d "${TMPDIR:-/tmp}/lc2wf-test.XXXXXX")
export TMPDIR
trap 'rm -rf "$TMPDIR"' EXIT
ctest --output-on-failure -j "$(nproc)"
"$root/tools/sanitize.sh"
