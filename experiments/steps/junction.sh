# Steps local, rotate, loose-seeds, junction-turns and rotate-edge: junction stages of their own, scored
# beside a shipped edge model on the validation split (sourced by experiments/run.sh).

# The junction stage again with local patch labels (experiments/configs/local-labels.json: base.json with
# junction.positive_radius_m 1.0), scored on the validation split with the shipped edge model.
step_local() {
  local resume
  need_binary "$build_dir/experiments/lc2wf_oracle_junctions" lc2wf_oracle_junctions  # before hours of training
  resume_or_restore local-labels
  "$build_dir/train/lc2wf-train" experiments/configs/local-labels.json --stage junction --out runs/local-labels "${resume[@]}"
  "$build_dir/experiments/lc2wf_oracle_junctions" --weights models/base --junctions predicted \
    --junction-weights runs/local-labels/junction.safetensors --data runs/dataset/clouds \
    --split configs/splits/val.txt -o runs/local-labels/val-with-base-edge --precision auto
  cat runs/local-labels/val-with-base-edge/metrics.md
}

# A junction stage of its own (configs/RUN.json -> runs/RUN: a fine-tune of models/base or a whole schedule),
# scored on the validation split beside the shipped edge model at 1 and 8 test-time views.
junction_variant() {
  local run=$1 resume
  resume_or_restore "$run"
  "$build_dir/train/lc2wf-train" "configs/$run.json" --stage junction --out "runs/$run" "${resume[@]}"
  # The fine-tuned junction model beside the shipped edge model, as one weights folder.
  mkdir -p "runs/$run/with-base-edge"
  ln -sfn ../junction.safetensors "runs/$run/with-base-edge/junction.safetensors"
  ln -sfn "$root/models/base/edge.safetensors" "runs/$run/with-base-edge/edge.safetensors"
  score_on_val "runs/$run/with-base-edge" "runs/$run/val-views"
}

# The junction model's answers depend on the building's orientation (8 test-time views: +4 vAP on val): the
# junction stage once more with turns about the vertical (models/rotate).
step_rotate() { junction_variant rotate; }

# The same with the loose density seeds in training, so the junction model learns on the patches that
# inference samples by default.
step_loose_seeds() { junction_variant loose-seeds; }

# The paper's whole junction schedule (41 epochs from scratch) with turns and loose seeds from the start.
step_junction_turns() { junction_variant junction-turns; }

# The edge model fine-tuned with the same turns, on the hand-off of the turned junction model.
step_rotate_edge() {
  [[ -f runs/rotate/junction.safetensors ]] || step_rotate
  "$build_dir/train/lc2wf-train" experiments/configs/rotate.json --stage edge --out runs/rotate --resume
  score_on_val runs/rotate runs/rotate/val-both-views
}
