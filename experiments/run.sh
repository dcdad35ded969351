#!/usr/bin/env bash
# The paper's experiment (LC2WF Table 2) and the experiments after it, on Roof-Image, one resumable step at a
# time: experiments/run.sh STEP [ARGS]. Each step lives in experiments/steps/<family>.sh.
#
# The paper's run (steps/clouds.sh, steps/paper.sh):
#   dataset       Blender line clouds of all 3,583 buildings -> runs/dataset (train + val first: `train` can
#                 run while the test clouds are made)
#   train         lc2wf-train configs/base.json -> runs/base (continues with --resume)
#   select        junction selections scored on the validation split with the trained models, best first
#                 -> runs/base/selection/table.md (before eval)
#   eval          Table 2 on the 757 test buildings (sound, sound with the release's junction selection,
#                 --release-quirks), plots, HTML report -> runs/base/test*
#   raster        the same model on raster-rendered test clouds (how much the renderer matters)
#   ship          the trained model -> models/base/ (weights, config, model card with the test metrics;
#                 each file <= 20 MB), after eval (and raster)
#   all           dataset, train, eval, ship
# Junction stages, scored beside models/base's edge model on the validation split (steps/junction.sh):
#   local         junction stage with local labels (experiments/configs/local-labels.json)
#   rotate        experiments/configs/rotate.json: models/base's junction stage fine-tuned with turns about the vertical
#                 (1 and 8 test-time views) -> runs/rotate
#   rotate-edge   then the edge stage of experiments/configs/rotate.json on that junction model's hand-off, scored the
#                 same way -> runs/rotate/val-both-views*
#   loose-seeds   experiments/configs/loose-seeds.json: as rotate, with the junction stage's patches sampled from loose
#                 density seeds -> runs/loose-seeds
#   junction-turns  experiments/configs/junction-turns.json: base.json's whole junction schedule with turns and loose
#                 seeds, scored the same way
# Fine-tuned models (steps/finetune.sh):
#   robust        experiments/configs/robust.json: models/base fine-tuned with the cloud augmentation (fused and split
#                 fragments, drops, jitter, photo-like texture clutter), then experiments/robustness.sh on
#                 held-out buildings -> runs/robust
#   edge-sound    experiments/configs/edge-sound.json: models/base's edge model fine-tuned on the junctions inference
#                 selects (offset screen, NMS 0.5 m, loose seeds) beside models/rotate-loose's junction
#                 model -> runs/edge-sound
#   merged-maps   experiments/configs/merged-maps.json: models/edge-sound fine-tuned (both stages) with half the training
#                 buildings made merged line maps and cut as inference cuts them, scored on validation and
#                 with experiments/robustness.sh on held-out buildings -> runs/merged-maps
# Denser clouds (steps/clouds.sh, steps/dense.sh):
#   dense         the Blender clouds again from 30 views instead of 20 (≈ 1.2K lines per building, the
#                 paper's ≈ 1.4K) -> runs/dataset-30v: test split first, then validation, then training
#   dense-eval [WEIGHTS [TAG FLAGS...]]  WEIGHTS (default models/edge-sound) on the 30-view test clouds,
#                 1 and 8 test-time views -> runs/dense-test/<name>-views{1,8}; with TAG, the one setting
#                 FLAGS -> <name>-TAG
#   dense-select [WEIGHTS]  test-time settings of WEIGHTS (default models/edge-sound) on the 30-view
#                 validation clouds, best first -> runs/dense-select/<name>/table.md
#   dense-train   experiments/configs/dense.json: models/edge-sound fine-tuned (both stages) on the 30-view clouds,
#                 scored on their validation split -> runs/dense
# A cheaper edge stage (steps/edge_cost.sh):
#   edge-cheaper  base.json's edge stage on a quarter of the 30-view training clouds, the paper's 512 pair
#                 patches (two seeds: the noise) against 256 patches and against 32 lines per pair patch
#                 (two seeds), on models/base's hand-off -> runs/edge-cheaper/table.md (best val
#                 sAP/vAP/WED and seconds per step)
#   fast-check    configs/fast.json's edge stage against base.json's at the full schedule, both on the
#                 30-view clouds from models/base's junction model (fast first, ≈ 4 h; then the paper's,
#                 ≈ 8 h) -> runs/fast-check/table.md
# One model for real buildings (steps/general.sh; configs/splits/lod2/ and dataset/README.md, the generator):
#   general-data  raster 30-view clouds of the mix: 600 generated LoD2 buildings, 800 real LoD2 training
#                 buildings (all Vienna, 250 3D BAG, 475 NRW), 250 Roof-Image and 200 height/footprint-augmented
#                 Roof-Image training buildings, 123 of them also photo-like (Blender); validation 60 generated, 150 real (raster), 100 Roof-Image
#                 (Blender) -> runs/general
#   general-train configs/general.json: models/dense fine-tuned on it -> runs/general-model
#   general-eval [MODEL...]  the real test split's raster clouds (lc2wf-dataset's default pixel rule, and 640 x 480
#                 for every building as before it) and Roof-Image's 30-view test clouds, each model (default
#                 models/general, models/dense) scored by default and with 8 test-time views, the real split per
#                 source, roof kind and height band -> runs/general-eval/MODEL-ttN/{real,real-fixed,ri}
#   general2-data  general-data's mix plus the real training buildings of the kinds general failed on (every 3D
#                 BAG, Vienna and >= 10 m one, NRW's rarer roofs), 1 in 10 of them also photo-like (Blender), and
#                 300 Roof-Image training buildings as 30-view Blender clouds; validation with the whole real
#                 validation split (414) -> runs/general2
#   general2-train experiments/configs/general2.json: models/general fine-tuned on it -> runs/general2-model
#   general2-val WEIGHTS TAG [FLAGS...]  WEIGHTS with lc2wf-infer FLAGS on general2's validation clouds (real per
#                 group, Roof-Image, generated) -> runs/general2-val/TAG and a row of runs/general2-val/table.md
#   general4-data  general2's mix with its buildings over 22 m across (real, generated, augmented Roof-Image; train
#                 and validation) rendered again at lc2wf-dataset's default pixel rule -> runs/general4
#   general4-train [FLAGS...]  experiments/configs/general4.json: models/general fine-tuned on it at a low lr
#                 (FLAGS to lc2wf-train, e.g. --stage junction) -> runs/general4-model
#   general4-val WEIGHTS TAG [FLAGS...]  as general2-val, on general4's validation clouds -> runs/general4-val/TAG
# Photo-like clouds and the rounds trained on them (steps/photo.sh, steps/photo_rounds.sh):
#   photo-data     Blender photo-like renders (30 views, default pixel rule) of every 4th real and generated
#                 training building of the mix not yet rendered so, and of every 7th real validation building
#                 -> runs/photo
#   photo5-data    a fine-tuning mix: every photo-like training cloud photo-data has made and every 3rd cloud of
#                 general4's mix; validation: the 60 photo-like and every 3rd of general4's validation clouds
#                 -> runs/photo5 (the photo part's names in experiments/lists/photo5-photo.txt)
#   photo5-train [FLAGS...]  experiments/configs/photo5.json: models/general fine-tuned on it -> runs/photo5-model
#                 (scored with general4-val, whose last column is the photo-like validation set)
#   photo6-data    as photo5-data with every photo-like training cloud made by then and every 4th cloud of
#                 general4's mix (a larger photo share), sampled by endpoint count -> runs/photo6 (photo part's
#                 names in experiments/lists/photo6-photo.txt; the same validation clouds as photo5)
#   photo6-train [FLAGS...]  experiments/configs/photo6.json: photo5's schedule on it -> runs/photo6-model
# Today's rasteriser (steps/light.sh):
#   light-data     general4's mix with every raster cloud rendered again at lc2wf-dataset's defaults (the ambient
#                 light dims with the viewing angle, so walls in shade show their corners) and its Roof-Image
#                 parts in Blender -> runs/light
#   light-train [FLAGS...]  experiments/configs/light.json: models/general fine-tuned on it -> runs/light-model
#   light-val WEIGHTS TAG [FLAGS...]  general4-val's table on its validation clouds -> runs/light-val/TAG
# The light round with photo-look raster clouds (steps/light2.sh):
#   light2-data    a third to a half of each light part again, the photo look as raster renders (real and generated
#                 training buildings, every 10th real validation building) -> runs/light2
#   light2-train [FLAGS...]  experiments/configs/light2.json: light.json's schedule on it -> runs/light2-model
#   light2-val WEIGHTS TAG [FLAGS...]  vAP / sAP / WED on its four validation parts -> runs/light2-val/TAG
# Walks along the street in the mix (steps/street.sh):
#   street-data    walks (eye height, along one facade) of light2's photo-look training buildings, light2's photo
#                 orbits and every 3rd of its clean clouds; validation: light2's and the validation walks -> runs/street
#   street-train [FLAGS...]  experiments/configs/street.json: light2's schedule on it -> runs/street-model
#   street2-data   the street mix's walks and photo-look orbits beside all of light2's clean clouds -> runs/street2
#   street2-train [FLAGS...]  experiments/configs/street2.json's edge stage beside models/general's junction model
#                 -> runs/street2-model
#   street-val WEIGHTS TAG [FLAGS...]  light2-val's parts and the validation walks (vAP / sAP / WED, the share of the
#                 drawn length on the building) -> runs/light2-val/TAG and a row of runs/street/table.md
# The height model that scales photo clouds and line maps nothing else scales (steps/height.sh):
#   height-model  more photo-look raster clouds of training buildings, then lc2wf-fit-height on them and the
#                 light2 mix's real and generated training clouds -> runs/height/height.json
#   map-frame-val INFER WEIGHTS TAG [FLAGS...]  validation clouds as line OBJ maps in random frames (rotation,
#                 scale, shift), up and scale found by the INFER binary with WEIGHTS: photo-look orbits (42),
#                 street captures (42), walks along the street (42), every 20th clean real (21), every 3rd generated
#                 (20) -> runs/map-frame-val/TAG
# Photo benchmark runs with other flags (steps/photo_rerun.sh):
#   photo-rerun RUN MESHES TAG [FLAGS...]  a run_buildings.sh run's reconstructions again with lc2wf-reconstruct
#                 FLAGS on its renders and cameras (POSES=DIR: an earlier run's COLMAP poses; WEIGHTS=DIR: a model
#                 other than models/general), scored against
#                 MESHES -> runs/photo-rerun/<RUN's name>-TAG
# Training state (steps/snapshots.sh):
#   snapshot [RUN]  copy the training state of runs/RUN (default base: newest checkpoint of each stage,
#                 best weights, log) to models/RUN-training/
#   restore [RUN]   put that state back into runs/RUN (the training steps do it by themselves when their
#                 run is missing), so a lost machine costs one session
#
# Every step can be killed and started again: the dataset skips finished buildings, training resumes from
# its last checkpoint, evaluation is redone. A model folder that left the tree (models/edge-sound,
# models/rotate-loose, models/*-training) is restored from the git history when a step needs it
# (experiments/README.md). LC2WF_DATA_DIR (default ../shared/data) holds roof-image/; LC2WF_BUILD_DIR
# (default build/) the binaries. -h / --help prints this text.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }

# Every step and the function that runs it (step_<name>, dashes as underscores).
steps=(dataset train select eval raster ship all local rotate rotate-edge loose-seeds junction-turns robust
       edge-sound merged-maps dense dense-eval dense-select dense-train edge-cheaper fast-check general-data
       general-train general-eval general2-data general2-train general2-val general4-data general4-train general4-val photo-data photo5-data photo5-train photo6-data photo6-train light-data light-train light-val light2-data light2-train light2-val street-data street-train street2-data street2-train street-val height-model map-frame-val photo-rerun snapshot restore)

step=${1:-}
case $step in
  -h|--help) usage; exit 0 ;;
  '') usage; exit 2 ;;
esac
if [[ " ${steps[*]} " != *" $step "* ]]; then
  echo "experiments/run.sh: unknown step '$step'; the steps are: ${steps[*]} (experiments/run.sh --help)" >&2
  exit 2
fi
shift

source "$here/common.sh"
for family in "$here"/steps/*.sh; do source "$family"; done

step_all() { step_dataset && step_train && step_eval && step_ship; }

cd "$root"
[[ -x "$build_dir/train/lc2wf-train" ]] || LC2WF_WITH_RENDER_TOOLS=1 LC2WF_BUILD_TESTS=OFF LC2WF_BUILD_BENCH=OFF "$root/tools/build.sh"
"step_${step//-/_}" "$@"
