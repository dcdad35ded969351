#!/usr/bin/env bash
# Installs every Debian package lc2wf needs. Idempotent: returns at once when all are present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libopenblas0-pthread             # fp32 GEMM tiles, loaded at run time (core/blas_backend.h); Eigen without it
  libopencv-dev libopencv-contrib-dev
  libsqlite3-dev                   # tools/ reads the SIFT descriptors from COLMAP's database
  zlib1g-dev                       # dataset/ reads gzip-compressed CityGML (.gml.gz)
  python3-numpy
  python3-jsonschema               # tests: the CityJSON output against the official CityJSON 2.0 schema
  libjs-three python3-matplotlib   # lc2wf-eval --html inlines three.js; tools/plots/ draws the PNGs
  libopenmpi-dev openmpi-bin       # mpirun -np N lc2wf-train (data-parallel); its tests run 2 local ranks
  time                             # GNU time: peak memory of each command in tests/fuzz/adversarial
)
# Rendering and pose tools are only needed by the dataset generator (tools/), so they are opt-in.
if [[ "${LC2WF_WITH_RENDER_TOOLS:-0}" == 1 ]]; then
  packages+=(blender colmap python3-pil)  # python3-pil: the photo benchmark's GPS-tagged JPEGs (bench/reconstruct)
fi
# clang with libFuzzer and the ASan/UBSan runtimes for the sanitizer stage (tools/sanitize.sh).
if [[ "${LC2WF_WITH_SANITIZERS:-0}" == 1 ]]; then
  packages+=(clang)
fi
# Headless Chromium for the HTML report's browser test; tools/test.sh asks for it.
if [[ "${LC2WF_WITH_BROWSER:-0}" == 1 ]]; then
  packages+=(chromium)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "setup-deps: installing ${missing[*]}" >&2
sudo_cmd=()
[[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
