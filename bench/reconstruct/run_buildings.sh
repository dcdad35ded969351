#!/usr/bin/env bash
# Photos -> wireframe on held-out buildings (reconstruct/README.md, "End to end"; bench/README.md, "reconstruct"):
#   1. renders with photo-like textures (lc2wf-dataset --keep-views); the labelled clouds it builds with the
#      known cameras are the baseline;
#   2. the images alone -> lc2wf-reconstruct (COLMAP poses), and the same with the render cameras given
#      (--cameras), each aligned to the render cameras by a similarity for scoring;
#   3. lc2wf-eval of the three against the GT and against the part of it the cameras saw (--gt-seen-by 2), the
#      share of predicted edge length near a GT edge, the scale error and the per-stage seconds of every run
#      (summarise.py).
# usage: bench/reconstruct/run_buildings.sh WEIGHTS NAMES_FILE OUT [MESHES]
# e.g.   bench/reconstruct/run_buildings.sh models/base bench/reconstruct/test-buildings.txt runs/recon-bench
#        CAPTURE=street-2 TEXTURES=photo bench/reconstruct/run_buildings.sh models/dense \
#          bench/reconstruct/real-test-buildings.txt runs/recon-real-street2 runs/real-test-meshes
# MESHES: a folder of Roof-Image <name>.polyshape files (default ../shared/data/roof-image/res_building; the
# named ones are linked into OUT/meshes) or of city models (CityJSON, CityJSONSeq, CityGML, read in place;
# names <file stem>__<building id>, dataset/README.md).
# TEXTURES=sfm|photo|paper (default sfm), CAPTURE=orbit|street-1|street-2|walk (default orbit),
# RENDERER=blender|raster (default blender): lc2wf-dataset's --textures, --capture, --renderer.
# POSES_FROM=DIR reuses the poses of an earlier run (DIR/recon-photos/<name>/cameras.json, already in the
# output frame) instead of running COLMAP again: same cloud and frame, new weights, no COLMAP seconds.
# RECONSTRUCT_FLAGS="--max-features 1000" adds options to every lc2wf-reconstruct run.
# MODES="given-cameras" runs only the render cameras' reconstruction (no COLMAP; default "photos given-cameras").
# The COLMAP-pose run gets the renders' focal length (--focal-35mm), as real photos' EXIF gives it;
# GUESS_FOCAL=1 leaves it out (the default 35 mm, refined by COLMAP: photos without EXIF).
# GPS_NOISE_M=1.5 gives the photos a drone's GPS: JPEGs whose EXIF holds each render camera's centre with that
# much horizontal receiver noise (GPS_VERTICAL_NOISE_M, default 0.5, vertically; geotag_views.py, seeded by the
# building's name), so the COLMAP-pose run takes its scale and up from GPS. Unset: the PNGs, no GPS.
set -euo pipefail
weights=$1 names=$2 out=$3
meshes=${4:-../shared/data/roof-image/res_building}
bin=${BUILD_DIR:-build}
threads=${THREADS:-2}
read -r -a user_flags <<< "${RECONSTRUCT_FLAGS:-}"

# Roof-Image meshes are linked by name (the folder holds thousands); city models are read where they are.
gt=$meshes
first=$(grep -m1 . "$names")
if [ -e "$meshes/$first.polyshape" ]; then
  gt=$out/meshes
  mkdir -p "$gt"
  while read -r n; do
    [ -n "$n" ] && ln -sf "$(realpath "$meshes/$n.polyshape")" "$gt/$n.polyshape"
  done < "$names"
fi

"$bin/tools/lc2wf-dataset" --meshes "$gt" --names "$names" --out "$out/dataset" --renderer "${RENDERER:-blender}" \
  --textures "${TEXTURES:-sfm}" --capture "${CAPTURE:-orbit}" --keep-views -j 1 -q > /dev/null \
  || [ $? -eq 1 ]  # 1: some buildings failed (named on stderr); the others go on

read -r -a modes <<< "${MODES:-photos given-cameras}"
for mode in "${modes[@]}"; do
  [ "$mode" = photos ] || [ "$mode" = given-cameras ] || { echo "MODES: unknown mode '$mode' (photos, given-cameras)" >&2; exit 2; }
done
mkdir -p "$out/logs"
for mode in "${modes[@]}"; do mkdir -p "$out/pred-$mode"; done
while read -r n; do
  [ -n "$n" ] || continue
  views="$out/dataset/views/$n"
  [ -f "$views/cameras.json" ] || { echo "$n: no renders (lc2wf-dataset failed on it)" | tee -a "$out/logs/exit-codes.txt"; continue; }
  # The photo folder holds the images only: the cameras are thrown away.
  rm -rf "$out/photos/$n"
  mkdir -p "$out/photos/$n"
  if [ -n "${GPS_NOISE_M:-}" ]; then
    /usr/bin/python3 "$(dirname "$0")/geotag_views.py" "$views" "$out/photos/$n" --noise-m "$GPS_NOISE_M" \
      --vertical-noise-m "${GPS_VERTICAL_NOISE_M:-0.5}" --seed "$(printf %s "$n" | cksum | cut -d' ' -f1)"
  else
    for f in "$views"/view_*.png; do ln -sf "$(realpath "$f")" "$out/photos/$n/"; done
  fi
  # The renders' focal length, as a real photo's EXIF gives it (GUESS_FOCAL=1: left out, COLMAP refines a guess).
  focal=$(/usr/bin/python3 -c 'import json,sys; c=json.load(open(sys.argv[1]))[0]; print(c["K"][0] * 36 / max(c["width"], c["height"]))' "$views/cameras.json")
  for mode in "${modes[@]}"; do
    extra=()
    [ "$mode" = given-cameras ] && extra=(--cameras "$views/cameras.json")
    [ "$mode" = photos ] && [ "${GUESS_FOCAL:-0}" != 1 ] && extra=(--focal-35mm "$focal")
    [ "$mode" = photos ] && [ -n "${POSES_FROM:-}" ] && extra=(--cameras "$POSES_FROM/recon-photos/$n/cameras.json")
    rm -rf "$out/recon-$mode/$n" "$out/pred-$mode/$n.obj" "$out/pred-$mode/$n.json"  # nothing left from an earlier run
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
  --method "known-camera clouds" --quiet > /dev/null || [ $? -eq 1 ]
# score PRED EVAL METHOD GT_ARGS...: lc2wf-eval of a folder of predictions into OUT/EVAL. Exit 1: failed
# reconstructions, scored as empty; 3: every one failed, nothing to score (the summary says so).
score() {
  local pred=$1 eval=$2 method=$3 code=0
  shift 3
  rm -rf "${out:?}/$eval"
  "$bin/infer/lc2wf-eval" --pred "$pred" "$@" --split "$names" --out "$out/$eval" --method "$method" --quiet > /dev/null || code=$?
  [ $code -eq 0 ] || [ $code -eq 1 ] || [ $code -eq 3 ] || exit $code
}
# Each run against the whole GT and against the part of it the capture saw (edges >= 2 render cameras had in
# view; lc2wf-eval --gt-seen-by): a street capture is then scored on its facades, not on the sides nobody
# photographed.
seen=(--data "$out/dataset/clouds" --gt-seen-by 2)
score "$out/eval-known-clouds/predictions" eval-known-clouds-seen "known-clouds, seen part" "${seen[@]}"
for mode in "${modes[@]}"; do
  score "$out/pred-$mode" "eval-$mode" "reconstruct ($mode)" --gt "$gt"
  score "$out/pred-$mode" "eval-$mode-seen" "reconstruct ($mode), seen part" "${seen[@]}"
done
/usr/bin/python3 "$(dirname "$0")/summarise.py" "$out" "$names" | tee "$out/summary.md"
