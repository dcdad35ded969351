# Steps dense-eval, dense-select and dense-train: models on the 30-view clouds of `dense` (runs/dataset-30v;
# sourced by experiments/run.sh). models/edge-sound, their default weights, is restored from the history.

# dense-eval [WEIGHTS [TAG FLAGS...]]: WEIGHTS on the 30-view test clouds at 1 and 8 test-time views, or with
# a TAG and flags (e.g. the setting dense-select chose) that one setting.
step_dense_eval() {
  local weights=${1:-models/edge-sound}
  local name
  name=$(basename "$weights")
  restore_weights "$weights"
  if [[ $# -ge 2 ]]; then
    local tag=$2
    shift 2
    "$build_dir/infer/lc2wf-eval" --weights "$weights" --data runs/dataset-30v/clouds \
      --split configs/splits/test.txt --method "$weights, 30-view clouds, $tag" -q -o "runs/dense-test/$name-$tag" "$@"
    cat "runs/dense-test/$name-$tag/metrics.md"
    return
  fi
  local views
  for views in 1 8; do
    "$build_dir/infer/lc2wf-eval" --weights "$weights" --data runs/dataset-30v/clouds \
      --split configs/splits/test.txt --test-time-views "$views" --method "$weights, 30-view clouds" \
      -q -o "runs/dense-test/$name-views$views"
    cat "runs/dense-test/$name-views$views/metrics.md"
  done
}

# dense-select [WEIGHTS]: test-time settings for the 30-view clouds, chosen on their validation split
# (junction views, sampling passes, edge views, NMS radius and confidence cut around the default); each
# finished cell is kept.
step_dense_select() {
  local weights=${1:-models/edge-sound}
  local dir
  dir=runs/dense-select/$(basename "$weights")
  restore_weights "$weights"
  local cells=("views1:" "views8:--test-time-views 8"
               "views8_edge4:--test-time-views 8 --edge-test-time-views 4"
               "views8_passes2:--test-time-views 8 --sampling-passes 2"
               "views8_passes2_edge4:--test-time-views 8 --sampling-passes 2 --edge-test-time-views 4"
               "views8_nms0.35:--test-time-views 8 --nms-radius 0.35"
               "views8_c0.02:--test-time-views 8 --min-confidence 0.02")
  score_cells "$weights" runs/dataset-30v/clouds "$dir" "${cells[@]}"
}

# The shipped models fine-tuned on the 30-view clouds (after `dense` has made the training clouds).
step_dense_train() {
  local run=dense resume
  resume_or_restore "$run"
  restore_model edge-sound
  "$build_dir/train/lc2wf-train" "configs/$run.json" --out "runs/$run" "${resume[@]}"
  local views
  for views in 1 8; do
    "$build_dir/infer/lc2wf-eval" --weights "runs/$run" --data runs/dataset-30v/clouds \
      --split configs/splits/val.txt --test-time-views "$views" -q -o "runs/$run/val-views$views"
    cat "runs/$run/val-views$views/metrics.md"
  done
}
