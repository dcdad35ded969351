# Photo benchmark runs again with other lc2wf-reconstruct flags (experiments/README.md, "Lines along a street").

# photo-rerun RUN MESHES TAG [FLAGS...]: the reconstructions of a bench/reconstruct/run_buildings.sh run RUN
# again on its renders with models/general (WEIGHTS=DIR: another model), with the render cameras (POSES=DIR: the COLMAP poses DIR/recon-photos/<name>/cameras.json
# of an earlier run, so COLMAP's run-to-run spread stays out of the comparison) and FLAGS, aligned to the render
# cameras and scored against the GT in MESHES -> runs/photo-rerun/<RUN's name>-TAG (eval/metrics.md).
step_photo_rerun() {
  [[ $# -ge 3 ]] || die 2 "photo-rerun needs RUN, MESHES and TAG"
  local run=$1 meshes=$2 tag=$3 n
  shift 3
  local out
  out=runs/photo-rerun/$(basename "$run")-$tag
  rm -rf "$out"
  mkdir -p "$out/pred"
  ls "$run/photos" > "$out/names.txt"
  while read -r n; do
    local views=$run/dataset/views/$n cams=$run/dataset/views/$n/cameras.json
    [[ -n ${POSES:-} ]] && cams=$POSES/recon-photos/$n/cameras.json
    # A building COLMAP did not register in POSES has no cameras: it is scored as empty.
    [[ -f $cams ]] || continue
    "$build_dir/reconstruct/lc2wf-reconstruct" "$run/photos/$n" --weights "${WEIGHTS:-models/general}" -o "$out/recon/$n" --cameras "$cams" \
      --reference-cameras "$views/cameras.json" -j 2 -q "$@" 2> "$out/$n.log" || true
    if [[ -f $out/recon/$n/wireframe_aligned.obj ]]; then
      cp "$out/recon/$n/wireframe_aligned.obj" "$out/pred/$n.obj"
      cp "$out/recon/$n/wireframe_aligned.json" "$out/pred/$n.json"
    fi
  done < "$out/names.txt"
  "$build_dir/infer/lc2wf-eval" --pred "$out/pred" --gt "$meshes" --split "$out/names.txt" --out "$out/eval" --method "$tag" \
    --quiet > /dev/null || [[ $? -eq 1 ]]
}
