#!/usr/bin/env bash
# Photos -> wireframe on held-out Roof-Image buildings (reconstruct/README.md, "End to end"):
#   1. Blender renders with the SfM textures (lc2wf-dataset --keep-views); the labelled clouds it builds
#      with the known cameras are the baseline;
#   2. the images alone -> lc2wf-reconstruct (COLMAP poses), and the same with the render cameras given
#      (--cameras), each aligned to the render cameras by a similarity for scoring;
#   3. lc2wf-eval of the three against the GT meshes, and the per-stage seconds of every run.
# usage: bench/reconstruct/run_buildings.sh WEIGHTS NAMES_FILE OUT [MESHES_DIR]
# e.g.   bench/reconstruct/run_buildings.sh models/base bench/reconstruct/test-buildings.txt runs/recon-bench
# POSES_FROM=DIR reuses the poses of an earlier run (DIR/recon-photos/<name>/cameras.json, already in the
# output frame) instead of running COLMAP again: same cloud and frame, new weights, no COLMAP seconds.
# RECONSTRUCT_FLAGS="--max-features 1000" adds options to every lc2wf-reconstruct run.
set -euo pipefail
weights=$1 names=$2 out=$3
meshes=${4:-../shared/data/roof-image/res_building}
bin=${BUILD_DIR:-build}
threads=${THREADS:-2}
read -r -a user_flags <<< "${RECONSTRUCT_FLAGS:-}"

mkdir -p "$out/meshes"
while read -r n; do
  [ -n "$n" ] && ln -sf "$(realpath "$meshes/$n.polyshape")" "$out/meshes/$n.polyshape"
done < "$names"

"$bin/tools/lc2wf-dataset" --meshes "$out/meshes" --out "$out/dataset" --renderer blender --textures sfm --keep-views \
  -j 1 -q

mkdir -p "$out/pred-photos" "$out/pred-given-cameras" "$out/logs"
while read -r n; do
  [ -n "$n" ] || continue
  views="$out/dataset/views/$n"
  # The photo folder holds the images only: the cameras are thrown away.
  mkdir -p "$out/photos/$n"
  for f in "$views"/view_*.png; do ln -sf "$(realpath "$f")" "$out/photos/$n/"; done
  for mode in photos given-cameras; do
    extra=()
    [ "$mode" = given-cameras ] && extra=(--cameras "$views/cameras.json")
    [ "$mode" = photos ] && [ -n "${POSES_FROM:-}" ] && extra=(--cameras "$POSES_FROM/recon-photos/$n/cameras.json")
    rm -rf "$out/recon-$mode/$n"
    code=0
    "$bin/reconstruct/lc2wf-reconstruct" "$out/photos/$n" --weights "$weights" -o "$out/recon-$mode/$n" \
      --reference-cameras "$views/cameras.json" -j "$threads" "${extra[@]}" "${user_flags[@]}" 2> "$out/logs/$mode-$n.log" || code=$?
    echo "$mode $n exit $code" | tee -a "$out/logs/exit-codes.txt"
    if [ -f "$out/recon-$mode/$n/wireframe_aligned.obj" ]; then
      cp "$out/recon-$mode/$n/wireframe_aligned.obj" "$out/pred-$mode/$n.obj"
      cp "$out/recon-$mode/$n/wireframe_aligned.json" "$out/pred-$mode/$n.json"
    fi
  done
done < "$names"

"$bin/infer/lc2wf-eval" --weights "$weights" --data "$out/dataset/clouds" --split "$names" --out "$out/eval-known-clouds" \
  --method "known-camera clouds" --quiet > /dev/null
for mode in photos given-cameras; do
  "$bin/infer/lc2wf-eval" --pred "$out/pred-$mode" --gt "$out/meshes" --split "$names" --out "$out/eval-$mode" \
    --method "reconstruct ($mode)" --quiet > /dev/null || [ $? -eq 1 ]  # 1: failed reconstructions, scored as empty
done
python3 "$(dirname "$0")/summarise.py" "$out" "$names" | tee "$out/summary.md"
