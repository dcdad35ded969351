# Steps robust, edge-sound and merged-maps: the shipped models fine-tuned for other inputs or another junction
# selection (sourced by experiments/run.sh).

# The model for clouds made elsewhere: models/base fine-tuned on augmented clouds, scored on held-out
# buildings in each cloud style (and on the SfM-texture renders of the photo benchmark when they exist).
step_robust() {
  local resume
  resume_or_restore robust
  "$build_dir/train/lc2wf-train" experiments/configs/robust.json --out runs/robust "${resume[@]}"
  experiments/robustness.sh runs/robust bench/reconstruct/robustness-buildings.txt runs/robust/robustness
  if [[ -d runs/recon-bench/dataset/clouds ]]; then
    experiments/robustness.sh runs/robust bench/reconstruct/test-buildings.txt runs/robust/robustness-sfm \
      runs/recon-bench/dataset/clouds
  fi
}

# The shipped edge model fine-tuned on the junctions that inference gives it (offset screen 0.75 m, c > 0.05,
# NMS 0.5 m, loose seeds; base.json trains and validates it on the release's selection), beside the best
# junction model (models/rotate-loose, restored from the history); validated with that selection, so each
# epoch's score compares with lc2wf-eval's.
step_edge_sound() {
  local run=edge-sound junction=models/rotate-loose/junction.safetensors resume
  resume_or_restore "$run"
  mkdir -p "runs/$run"
  if [[ ! -f runs/$run/junction.safetensors ]]; then
    restore_model rotate-loose
    cp "$junction" "runs/$run/junction.safetensors"
  fi
  "$build_dir/train/lc2wf-train" "configs/$run.json" --stage edge --out "runs/$run" "${resume[@]}"
  score_on_val "runs/$run" "runs/$run/val-views"
}

# Merged line maps (Line3D++, LIMAP) are cut into staggered pieces at inference; the model fine-tuned on
# exactly that (cloud_augment.merged_map_prob), both stages from models/edge-sound (restored from the history).
step_merged_maps() {
  local run=merged-maps resume
  resume_or_restore "$run"
  restore_model edge-sound
  "$build_dir/train/lc2wf-train" "configs/$run.json" --out "runs/$run" "${resume[@]}"
  score_on_val "runs/$run" "runs/$run/val-views"
  experiments/robustness.sh "runs/$run" bench/reconstruct/robustness-buildings.txt "runs/$run/robustness"
}
