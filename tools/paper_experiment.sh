#!/usr/bin/env bash
# The paper's experiment (LC2WF Table 2) end to end on Roof-Image, one resumable step at a time:
#   tools/paper_experiment.sh dataset   Blender line clouds of all 3,583 buildings -> runs/dataset (train + val
#                                       first: `train` can run while the test clouds are made)
#   tools/paper_experiment.sh train     lc2wf-train configs/base.json -> runs/base (continues with --resume)
#   tools/paper_experiment.sh select    junction selections scored on the validation split with the trained
#                                       models, best first -> runs/base/selection/table.md (before eval)
#   tools/paper_experiment.sh eval      Table 2 on the 757 test buildings (sound, sound with the release's
#                                       junction selection, --release-quirks), plots, HTML report -> runs/base/test*
#   tools/paper_experiment.sh raster    the same model on raster-rendered test clouds (how much the renderer matters)
#   tools/paper_experiment.sh ship      the trained model -> models/base/ (weights, config, model card with
#                                       the test metrics; each file <= 20 MB), after eval (and raster)
#   tools/paper_experiment.sh all       dataset, train, eval, ship
#   tools/paper_experiment.sh local     next experiment: junction stage with local labels, scored on the
#                                       validation split with models/base's edge model
#   tools/paper_experiment.sh robust    configs/robust.json: models/base fine-tuned with the cloud augmentation
#                                       (fused and split fragments, drops, jitter, photo-like texture clutter),
#                                       then bench/robustness.sh on held-out buildings -> runs/robust
#   tools/paper_experiment.sh rotate    configs/rotate.json: models/base's junction stage fine-tuned with turns
#                                       about the vertical, scored on the validation split with models/base's
#                                       edge model (1 and 8 test-time views) -> runs/rotate
#   tools/paper_experiment.sh rotate-edge  then the edge stage of configs/rotate.json on that junction
#                                       model's hand-off, scored the same way -> runs/rotate/val-both-views*
#   tools/paper_experiment.sh loose-seeds  configs/loose-seeds.json: as rotate, with the junction stage's
#                                       patches sampled from loose density seeds -> runs/loose-seeds
#   tools/paper_experiment.sh junction-turns  configs/junction-turns.json: base.json's whole junction
#                                       schedule with turns and loose seeds, scored the same way
#   tools/paper_experiment.sh edge-sound  configs/edge-sound.json: models/base's edge model fine-tuned on
#                                       the junctions inference selects (offset screen, NMS 0.5 m, loose
#                                       seeds) beside models/rotate-loose's junction model -> runs/edge-sound
#   tools/paper_experiment.sh merged-maps  configs/merged-maps.json: models/edge-sound fine-tuned (both
#                                       stages) with half the training buildings made merged line maps and
#                                       cut as inference cuts them, scored on validation and with
#                                       bench/robustness.sh on held-out buildings -> runs/merged-maps
#   tools/paper_experiment.sh dense     the Blender clouds again from 30 views instead of 20 (≈ 1.2K lines per
#                                       building, the paper's ≈ 1.4K) -> runs/dataset-30v: test split first,
#                                       then validation, then training
#   tools/paper_experiment.sh edge-cheaper  evidence for a cheaper edge stage (issue: the schedule in 8 h):
#                                       base.json's edge stage on a quarter of the 30-view training clouds,
#                                       the paper's 512 pair patches (two seeds: the noise) against 256 patches
#                                       and against 32 lines per pair patch (two seeds), on models/base's hand-off ->
#                                       runs/edge-cheaper/table.md (best val sAP/vAP/WED and seconds per step)
#   tools/paper_experiment.sh fast-check  configs/fast.json's edge stage against base.json's at the full
#                                       schedule, both on the 30-view clouds from models/base's junction model
#                                       (fast first, ≈ 4 h; then the paper's, ≈ 8 h) -> runs/fast-check/table.md
#   tools/paper_experiment.sh dense-eval [WEIGHTS [TAG FLAGS...]]  WEIGHTS (default models/edge-sound) on the
#                                       30-view test clouds, 1 and 8 test-time views -> runs/dense-test/
#                                       <name>-views{1,8}; with TAG, the one setting FLAGS -> <name>-TAG
#   tools/paper_experiment.sh dense-select [WEIGHTS]  test-time settings of WEIGHTS (default
#                                       models/edge-sound) on the 30-view validation clouds, best first
#                                       -> runs/dense-select/<name>/table.md
#   tools/paper_experiment.sh dense-train  configs/dense.json: models/edge-sound fine-tuned (both stages) on
#                                       the 30-view clouds, scored on their validation split -> runs/dense
#   tools/paper_experiment.sh snapshot [RUN]  copy the training state of runs/RUN (default base: newest
#                                       checkpoint of each stage, best weights, log) to models/RUN-training/
#   tools/paper_experiment.sh restore [RUN]   put that state back into runs/RUN (train and local do it by
#                                       themselves when their run is missing), so a lost machine costs one session
# Every step can be killed and started again: the dataset skips finished buildings, training resumes from
# its last checkpoint, evaluation is redone. LC2WF_DATA_DIR (default ../shared/data) holds roof-image/;
# LC2WF_BUILD_DIR (default build/) the binaries.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${LC2WF_BUILD_DIR:-$root/build}
meshes=${LC2WF_DATA_DIR:-$root/../shared/data}/roof-image/res_building
cd "$root"

[[ -x "$build_dir/train/lc2wf-train" ]] || LC2WF_WITH_RENDER_TOOLS=1 LC2WF_BUILD_TESTS=OFF LC2WF_BUILD_BENCH=OFF "$root/tools/build.sh"

# Links the meshes of the named split lists into DIR (lc2wf-dataset renders every mesh of one folder).
# The meshes' absolute folder is resolved once: a subshell per name took minutes at low priority.
link_meshes() {
  local dir=$1 from
  shift
  from=$(cd "$meshes" && pwd)
  mkdir -p "$dir"
  cat "$@" | while read -r name; do
    [[ -n "$name" ]] && ln -sfn "$from/$name.polyshape" "$dir/$name.polyshape"
  done
}

step_dataset() {
  LC2WF_WITH_RENDER_TOOLS=1 "$root/tools/setup-deps.sh"
  # Train + validation first, so that `train` can start (or resume after a lost machine) before the test
  # clouds exist; summary.json describes the training clouds (the model card quotes it).
  link_meshes runs/trainval-meshes configs/splits/train.txt configs/splits/val.txt
  "$build_dir/tools/lc2wf-dataset" --meshes runs/trainval-meshes --out runs/dataset --renderer blender -j 2 \
    > runs/dataset-summary-trainval.json
  link_meshes runs/test-meshes configs/splits/test.txt
  "$build_dir/tools/lc2wf-dataset" --meshes runs/test-meshes --out runs/dataset --renderer blender -j 2 \
    > runs/dataset-summary-test.json
  cp runs/dataset-summary-trainval.json runs/dataset/summary.json.tmp && mv runs/dataset/summary.json.tmp runs/dataset/summary.json
  cp runs/dataset-summary-test.json runs/dataset/summary-test.json
}

# More views give the junction model the walls' feet it misses (bench/README.md, "Denser clouds"): the same
# renders from 30 views. The test split first, so the shipped models can be scored on it while the
# validation and training clouds are made.
step_dense() {
  LC2WF_WITH_RENDER_TOOLS=1 "$root/tools/setup-deps.sh"
  link_meshes runs/test-meshes configs/splits/test.txt
  "$build_dir/tools/lc2wf-dataset" --meshes runs/test-meshes --out runs/dataset-30v --renderer blender --views 30 -j 2 \
    > runs/dataset-30v-summary-test.json
  # The validation split next (200 buildings): test-time options are chosen on it while the training
  # clouds are made; the train + val pass below skips its finished buildings.
  link_meshes runs/val-meshes configs/splits/val.txt
  "$build_dir/tools/lc2wf-dataset" --meshes runs/val-meshes --out runs/dataset-30v --renderer blender --views 30 \
    -j 2 > runs/dataset-30v-summary-val.json
  link_meshes runs/trainval-meshes configs/splits/train.txt configs/splits/val.txt
  "$build_dir/tools/lc2wf-dataset" --meshes runs/trainval-meshes --out runs/dataset-30v --renderer blender --views 30 \
    -j 2 > runs/dataset-30v-summary-trainval.json
  cp runs/dataset-30v-summary-trainval.json runs/dataset-30v/summary.json.tmp
  mv runs/dataset-30v/summary.json.tmp runs/dataset-30v/summary.json
  cp runs/dataset-30v-summary-test.json runs/dataset-30v/summary-test.json
}

step_dense_eval() {
  local weights=${1:-models/edge-sound}
  local name
  name=$(basename "$weights")
  # A TAG and flags after the weights: that one setting (e.g. the one dense-select chose) instead of 1 and 8 views.
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

# Test-time settings for the 30-view clouds, chosen on their validation split (junction views, sampling
# passes, edge views, NMS radius and confidence cut around the default); each finished cell is kept.
step_dense_select() {
  local weights=${1:-models/edge-sound}
  local dir
  dir=runs/dense-select/$(basename "$weights")
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
  local run=dense
  [[ ! -e runs/$run && -f models/$run-training/config.json ]] && step_restore "$run"
  local resume=()
  [[ -d runs/$run/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" "configs/$run.json" --out "runs/$run" "${resume[@]}"
  local views
  for views in 1 8; do
    "$build_dir/infer/lc2wf-eval" --weights "runs/$run" --data runs/dataset-30v/clouds \
      --split configs/splits/val.txt --test-time-views "$views" -q -o "runs/$run/val-views$views"
    cat "runs/$run/val-views$views/metrics.md"
  done
}

# A run's resumable state is committed as models/<run>-training (runs/base -> models/base-training).
step_snapshot() {
  local run=${1:-base}
  local src=runs/$run snap=models/$run-training
  [[ -f $src/config.json ]] || { echo "paper_experiment.sh: no training run in $src" >&2; exit 3; }
  local tmp=$snap.tmp
  rm -rf "$tmp" && mkdir -p "$tmp/checkpoints"
  cp "$src/config.json" "$src/log.jsonl" "$tmp/"
  for stage in junction edge; do
    [[ -f $src/$stage.safetensors ]] && cp "$src/$stage.safetensors" "$tmp/"
    # The newest complete slot: its weights and optimiser state are written together.
    local newest
    newest=$(ls -t "$src"/checkpoints/${stage}_last_?.safetensors 2>/dev/null | head -1 || true)
    [[ -n "$newest" && -f "${newest%.safetensors}.optim.safetensors" ]] || continue
    cp "$newest" "$tmp/checkpoints/${stage}_last_0.safetensors"
    cp "${newest%.safetensors}.optim.safetensors" "$tmp/checkpoints/${stage}_last_0.optim.safetensors"
  done
  # The hand-off is the edge stage's input: kept, or a restored run would predict it again and drop the edge
  # stage's log lines. In parts of 19 MB: a committed file may have 20 MB at most.
  [[ -f $src/predicted_junctions/manifest.json ]] &&
    tar -C "$src" -czf - predicted_junctions | split -b 19m -d - "$tmp/predicted_junctions.tar.gz.part"
  local step=$run
  case $run in base) step=train ;; local-labels) step=local ;; dense) step=dense-train ;; esac
  sed "s|@RUN@|$run|g; s|@STEP@|$step|g" tools/paper_experiment-snapshot.md > "$tmp/README.md"
  # The learning curves so far, shown in the top README (skipped without matplotlib).
  /usr/bin/python3 tools/plots/plot_training.py "$src" --out "$tmp/learning_curves.png" >/dev/null ||
    echo "paper_experiment.sh: no learning curves (tools/setup-deps.sh installs python3-matplotlib)" >&2
  rm -rf "$snap" && mv "$tmp" "$snap"
  echo "Training state of $src copied to $snap ($(du -sh "$snap" | cut -f1))"
}

step_restore() {
  local run=${1:-base}
  local dst=runs/$run snap=models/$run-training
  [[ -f $snap/config.json ]] || { echo "paper_experiment.sh: no $snap to restore" >&2; exit 3; }
  [[ ! -e $dst ]] || { echo "paper_experiment.sh: $dst exists; move it away to restore" >&2; exit 3; }
  mkdir -p "$dst.tmp"
  cp -r "$snap"/. "$dst.tmp/"
  rm -f "$dst.tmp/README.md" "$dst.tmp"/predicted_junctions.tar.gz.part* "$dst.tmp/learning_curves.png"
  if compgen -G "$snap/predicted_junctions.tar.gz.part*" >/dev/null; then
    cat "$snap"/predicted_junctions.tar.gz.part* | tar -C "$dst.tmp" -xzf -
  fi
  mv "$dst.tmp" "$dst"
  echo "$dst restored from $snap"
}

step_train() {
  [[ ! -e runs/base && -f models/base-training/config.json ]] && step_restore base
  local resume=()
  [[ -d runs/base/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" configs/base.json --out runs/base "${resume[@]}"
  /usr/bin/python3 tools/plots/plot_training.py runs/base --out runs/base/plots/training.png
}

evaluate() {  # evaluate CLOUDS OUT METHOD [extra lc2wf-eval flags]
  local clouds=$1 out=$2 method=$3
  shift 3
  "$build_dir/infer/lc2wf-eval" --weights runs/base --data "$clouds" --split configs/splits/test.txt --out "$out" \
    --method "$method" "$@"
}

# score_cells WEIGHTS CLOUDS DIR CELL...: lc2wf-eval of WEIGHTS on the validation split of CLOUDS once per
# "tag:flags" cell into DIR/tag (a finished cell is kept, so a killed run resumes), then the table, best first.
score_cells() {
  local weights=$1 clouds=$2 dir=$3 cell
  shift 3
  mkdir -p "$dir"
  for cell in "$@"; do
    local tag=${cell%%:*} flags=${cell#*:}
    [[ -f $dir/$tag/metrics.json ]] && continue
    # shellcheck disable=SC2086  # flags are words
    "$build_dir/infer/lc2wf-eval" --weights "$weights" --data "$clouds" --split configs/splits/val.txt \
      --out "$dir/$tag.tmp" --method "$tag" --quiet $flags
    rm -rf "${dir:?}/$tag" && mv "$dir/$tag.tmp" "$dir/$tag"
  done
  /usr/bin/python3 tools/selection_table.py "$dir" > "$dir/table.md"
  cat "$dir/table.md"
}

# The junction selection is chosen on the validation split: each cell of the grid once (a finished cell is
# kept, so the step resumes), then the table, best first. Every candidate (no offset limit) is left out:
# with a low cut it classifies thousands of pairs per building (bench/README.md has its rows).
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
  "$build_dir/tools/lc2wf-dataset" --meshes runs/raster-test-meshes --out runs/raster-test --renderer raster -j 2
  evaluate runs/raster-test/clouds runs/base/test-raster "lc2wf on raster clouds"
}

step_ship() {
  local out=models/base tmp=models/base.tmp extra=()
  for f in runs/base/junction.safetensors runs/base/edge.safetensors runs/base/test/metrics.json; do
    [[ -f $f ]] || { echo "paper_experiment.sh: $f is missing: run train and eval first" >&2; exit 3; }
  done
  rm -rf "$tmp" && mkdir -p "$tmp"
  cp runs/base/junction.safetensors runs/base/edge.safetensors runs/base/config.json "$tmp/"
  [[ -f runs/base/README.md ]] && cp runs/base/README.md "$tmp/training-card.md"
  /usr/bin/python3 tools/plots/plot_training.py runs/base --out "$tmp/learning_curves.png" >/dev/null || true
  [[ -f runs/base/test-release/metrics.json ]] && extra+=(--eval-release runs/base/test-release)
  [[ -f runs/base/test-raster/metrics.json ]] && extra+=(--eval-raster runs/base/test-raster)
  [[ -f runs/dataset/summary.json ]] && extra+=(--dataset runs/dataset)
  /usr/bin/python3 tools/model_card.py --run runs/base --eval runs/base/test "${extra[@]}" -o "$tmp/README.md"
  # The repository keeps every file under 20 MB.
  local big
  big=$(find "$tmp" -type f -size +20M)
  [[ -z $big ]] || { echo "paper_experiment.sh: over 20 MB: $big" >&2; exit 3; }
  rm -rf "$out" && mv "$tmp" "$out"
  echo "Model published in $out ($(du -sh "$out" | cut -f1)); commit it."
}

# The next experiment: the junction stage again with local patch labels (configs/local-labels.json:
# base.json with junction.positive_radius_m 1.0), scored on the validation split with the shipped edge model.
step_local() {
  [[ ! -e runs/local-labels && -f models/local-labels-training/config.json ]] && step_restore local-labels
  local resume=()
  [[ -d runs/local-labels/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" configs/local-labels.json --stage junction --out runs/local-labels "${resume[@]}"
  "$build_dir/bench/infer/lc2wf_oracle_junctions" --weights models/base --junctions predicted \
    --junction-weights runs/local-labels/junction.safetensors --data runs/dataset/clouds \
    --split configs/splits/val.txt -o runs/local-labels/val-with-base-edge --precision auto
  cat runs/local-labels/val-with-base-edge/metrics.md
}

# The model for clouds made elsewhere: models/base fine-tuned on augmented clouds, scored on held-out
# buildings in each cloud style (and on the SfM-texture renders of the photo benchmark when they exist).
step_robust() {
  [[ ! -e runs/robust && -f models/robust-training/config.json ]] && step_restore robust
  local resume=()
  [[ -d runs/robust/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" configs/robust.json --out runs/robust "${resume[@]}"
  bench/robustness.sh runs/robust bench/reconstruct/robustness-buildings.txt runs/robust/robustness
  if [[ -d runs/recon-bench/dataset/clouds ]]; then
    bench/robustness.sh runs/robust bench/reconstruct/test-buildings.txt runs/robust/robustness-sfm \
      runs/recon-bench/dataset/clouds
  fi
}

# score_on_val WEIGHTS PREFIX: lc2wf-eval of WEIGHTS on the validation split at 1 and 8 test-time views
# -> PREFIX1, PREFIX8 (metrics printed).
score_on_val() {
  local views
  for views in 1 8; do
    "$build_dir/infer/lc2wf-eval" --weights "$1" --data runs/dataset/clouds \
      --split configs/splits/val.txt --test-time-views "$views" -q -o "$2$views"
    cat "$2$views/metrics.md"
  done
}

# A junction stage of its own (configs/RUN.json -> runs/RUN: a fine-tune of models/base or a whole schedule),
# scored on the validation split beside the shipped edge model at 1 and 8 test-time views.
junction_variant() {
  local run=$1
  [[ ! -e runs/$run && -f models/$run-training/config.json ]] && step_restore "$run"
  local resume=()
  [[ -d runs/$run/checkpoints ]] && resume=(--resume)
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
  "$build_dir/train/lc2wf-train" configs/rotate.json --stage edge --out runs/rotate --resume
  score_on_val runs/rotate runs/rotate/val-both-views
}

# The shipped edge model fine-tuned on the junctions that inference gives it (offset screen 0.75 m, c > 0.05,
# NMS 0.5 m, loose seeds; base.json trains and validates it on the release's selection), beside the best
# junction model; validated with that selection, so each epoch's score compares with lc2wf-eval's.
step_edge_sound() {
  local run=edge-sound junction=models/rotate-loose/junction.safetensors
  [[ ! -e runs/$run && -f models/$run-training/config.json ]] && step_restore "$run"
  mkdir -p "runs/$run"
  [[ -f runs/$run/junction.safetensors ]] || cp "$junction" "runs/$run/junction.safetensors"
  local resume=()
  [[ -d runs/$run/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" "configs/$run.json" --stage edge --out "runs/$run" "${resume[@]}"
  score_on_val "runs/$run" "runs/$run/val-views"
}

# Merged line maps (Line3D++, LIMAP) are cut into staggered pieces at inference; the model fine-tuned on
# exactly that (cloud_augment.merged_map_prob), both stages from models/edge-sound.
step_merged_maps() {
  local run=merged-maps
  [[ ! -e runs/$run && -f models/$run-training/config.json ]] && step_restore "$run"
  local resume=()
  [[ -d runs/$run/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" "configs/$run.json" --out "runs/$run" "${resume[@]}"
  score_on_val "runs/$run" "runs/$run/val-views"
  bench/robustness.sh "runs/$run" bench/reconstruct/robustness-buildings.txt "runs/$run/robustness"
}

# The edge stage of $1/config.json from models/base's junction model, resumed where it stopped.
run_edge_stage() {
  local resume=()
  [[ -f $1/junction.safetensors ]] || cp models/base/junction.safetensors "$1/junction.safetensors"
  [[ -d $1/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" "$1/config.json" --stage edge --out "$1" -q "${resume[@]}"
}

# Best validation scores and step cost of every run folder under $1 (an edge stage each) -> $1/table.md.
edge_runs_table() {
  /usr/bin/python3 - "$1" <<'PY' | tee "$1/table.md"
import json, statistics, sys
from pathlib import Path
print("| variant | best val sAP avg | its vAP avg | its WED | median s per step |")
print("|---|---|---|---|---|")
for run in sorted(p for p in Path(sys.argv[1]).iterdir() if (p / "log.jsonl").exists()):
    records = [json.loads(line) for line in open(run / "log.jsonl")]
    val = [r for r in records if r.get("type") == "val" and r.get("stage") == "edge"]
    steps = [r["seconds"] for r in records if r.get("type") == "step" and r.get("stage") == "edge" and "seconds" in r]
    if not val:
        continue
    best = max(val, key=lambda r: r["sAP_mean"])
    step = f"{statistics.median(steps):.2f}" if steps else "-"
    print(f"| {run.name} | {100 * best['sAP_mean']:.1f} | {100 * best['vAP_mean']:.1f} | {best['wed_total']:.2f} | {step} |")
PY
}

# The edge stage is two thirds of base.json's wall time; is half of it as good? Each variant is base.json's
# edge stage (milestones scaled to the shorter schedule) on models/base's junction model, trained on every
# 4th training building of the 30-view clouds and validated on the whole validation split.
step_edge_cheaper() {
  local out=runs/edge-cheaper
  mkdir -p "$out"
  awk 'NR % 4 == 1' configs/splits/train.txt > "$out/train.txt"
  local variant
  for variant in p512-s1 p256-s1 p512-s2 l32-s1 l32-s2; do  # the cheaper variant right after the first reference
    local dir=$out/$variant
    mkdir -p "$dir"
    /usr/bin/python3 - configs/base.json "$dir/config.json" "$variant" "$out/train.txt" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
variant, train = sys.argv[3], sys.argv[4]
config["seed"] = 1555 + int(variant.split("-s")[1])
config["data"].update(dir="runs/dataset-30v/clouds", train_split=train)
edge = config["edge"]
edge["epochs"], edge["optim"]["milestones"] = 8, [4, 7]
edge["val_every"] = 2  # after epochs 2, 4, 6, 8: a validation pass costs half an epoch here
if variant.startswith("p256"):
    edge["net"]["lpt"]["patches"], edge["max_static_pairs"] = 256, 128  # half the pairs, the same GT share
if variant.startswith("l32"):
    edge["net"]["lpt"]["lines_per_patch"] = 32  # 16 lines around each junction of a pair
json.dump(config, open(sys.argv[2] + ".tmp", "w"), indent=2)
PY
    mv "$dir/config.json.tmp" "$dir/config.json"
    run_edge_stage "$dir"
  done
  edge_runs_table "$out"
}

# Does configs/fast.json (32 lines per pair patch) keep the paper's edge quality at the full schedule? Each
# run is the edge stage of its config on the 30-view clouds from models/base's junction model; only
# edge.net.lpt.lines_per_patch differs.
step_fast_check() {
  local out=runs/fast-check run
  for run in fast base; do
    local dir=$out/$run
    mkdir -p "$dir"
    /usr/bin/python3 - "configs/$run.json" "$dir/config.json" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
config["data"]["dir"] = "runs/dataset-30v/clouds"
json.dump(config, open(sys.argv[2] + ".tmp", "w"), indent=2)
PY
    mv "$dir/config.json.tmp" "$dir/config.json"
    run_edge_stage "$dir"
  done
  edge_runs_table "$out"
}

case "${1:-}" in
  dataset) step_dataset ;;
  train) step_train ;;
  select) step_select ;;
  eval) step_eval ;;
  raster) step_raster ;;
  snapshot) step_snapshot "${2:-base}" ;;
  restore) step_restore "${2:-base}" ;;
  ship) step_ship ;;
  local) step_local ;;
  robust) step_robust ;;
  rotate) step_rotate ;;
  rotate-edge) step_rotate_edge ;;
  loose-seeds) step_loose_seeds ;;
  junction-turns) step_junction_turns ;;
  edge-sound) step_edge_sound ;;
  merged-maps) step_merged_maps ;;
  dense) step_dense ;;
  dense-select) step_dense_select "${2:-}" ;;
  dense-eval) shift; step_dense_eval "$@" ;;
  dense-train) step_dense_train ;;
  edge-cheaper) step_edge_cheaper ;;
  fast-check) step_fast_check ;;
  all) step_dataset && step_train && step_eval && step_ship ;;
  *) sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 2 ;;
esac
