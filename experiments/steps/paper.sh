# Steps train, select, eval, raster and ship: the paper's run (configs/base.json -> runs/base -> models/base;
# sourced by experiments/run.sh).

step_train() {
  local resume
  resume_or_restore base
  "$build_dir/train/lc2wf-train" configs/base.json --out runs/base "${resume[@]}"
  /usr/bin/python3 tools/plots/plot_training.py runs/base --out runs/base/plots/training.png
}

evaluate() {  # evaluate CLOUDS OUT METHOD [extra lc2wf-eval flags]
  local clouds=$1 out=$2 method=$3
  shift 3
  "$build_dir/infer/lc2wf-eval" --weights runs/base --data "$clouds" --split configs/splits/test.txt --out "$out" \
    --method "$method" "$@"
}

# The junction selection is chosen on the validation split: each cell of the grid once (a finished cell is
# kept, so the step resumes), then the table, best first. Every candidate (no offset limit) is left out:
# with a low cut it classifies thousands of pairs per building (experiments/README.md has its rows).
step_select() {
  local dir=runs/base/selection
  local cells=("release:--min-confidence 0.85 --nms-radius 0.25")
  for offset in 1.25 1 0.75 0.5; do
    for c in 0.85 0.5 0.3 0.1 0.05; do
      cells+=("c${c}_offset${offset}:--min-confidence $c --nms-radius 0.5 --max-offset $offset")
    done
  done
  # Around the best cell of the grid above (offsets 0.75 m, c > 0.05, NMS 0.5 m on the 2026-12-03 run).
  cells+=("c0.02_offset0.75:--min-confidence 0.02 --nms-radius 0.5 --max-offset 0.75"
          "c0_offset0.75:--min-confidence 0 --nms-radius 0.5 --max-offset 0.75"
          "c0.05_offset0.75_nms0.35:--min-confidence 0.05 --nms-radius 0.35 --max-offset 0.75"
          "c0.05_offset0.75_nms0.75:--min-confidence 0.05 --nms-radius 0.75 --max-offset 0.75")
  score_cells runs/base runs/dataset/clouds "$dir" "${cells[@]}"
}

step_eval() {
  evaluate runs/dataset/clouds runs/base/test-release "lc2wf, release post-processing" --release-quirks --quiet
  evaluate runs/dataset/clouds runs/base/test-release-selection "lc2wf, release selection" \
    --max-offset 0 --min-confidence 0.85 --nms-radius 0.25 --quiet
  evaluate runs/dataset/clouds runs/base/test "lc2wf"
  /usr/bin/python3 tools/plots/plot_eval.py runs/base/test >/dev/null
  "$build_dir/infer/lc2wf-eval" --pred runs/base/test/predictions --data runs/dataset/clouds \
    --split configs/splits/test.txt --out runs/base/test --method "lc2wf" --html \
    --html-compare runs/base/test-release --quiet >/dev/null
  echo "Report: $root/runs/base/test/report.html"
}

step_raster() {
  # Only the test buildings are rendered (the model is the Blender-trained one).
  link_meshes runs/raster-test-meshes configs/splits/test.txt
  "$build_dir/tools/lc2wf-dataset" "${fixed_size[@]}" --meshes runs/raster-test-meshes --out runs/raster-test --renderer raster \
    "${constant_ambient[@]}" -j 2
  evaluate runs/raster-test/clouds runs/base/test-raster "lc2wf on raster clouds"
}

step_ship() {
  local out=models/base tmp=models/base.tmp extra=()
  for f in runs/base/junction.safetensors runs/base/edge.safetensors runs/base/test/metrics.json; do
    [[ -f $f ]] || die 3 "$f is missing: run train and eval first"
  done
  rm -rf "$tmp" && mkdir -p "$tmp"
  cp runs/base/junction.safetensors runs/base/edge.safetensors runs/base/config.json "$tmp/"
  [[ -f runs/base/README.md ]] && cp runs/base/README.md "$tmp/training-card.md"
  /usr/bin/python3 tools/plots/plot_training.py runs/base --out "$tmp/learning_curves.png" >/dev/null || true
  [[ -f runs/base/test-release/metrics.json ]] && extra+=(--eval-release runs/base/test-release)
  [[ -f runs/base/test-raster/metrics.json ]] && extra+=(--eval-raster runs/base/test-raster)
  [[ -f runs/dataset/summary.json ]] && extra+=(--dataset runs/dataset)
  /usr/bin/python3 experiments/model_card.py --run runs/base --eval runs/base/test "${extra[@]}" -o "$tmp/README.md"
  # The repository keeps every file under 20 MB.
  local big
  big=$(find "$tmp" -type f -size +20M)
  [[ -z $big ]] || die 3 "over 20 MB: $big"
  rm -rf "$out" && mv "$tmp" "$out"
  echo "Model published in $out ($(du -sh "$out" | cut -f1)); commit it."
}
