# Steps general-data and general-train: one model for real buildings of every roof kind and size, fine-tuned
# from models/dense on a mix of generated LoD2 buildings, real LoD2 training buildings and Roof-Image buildings
# (plain and with their heights and footprints augmented), all rendered by the raster renderer from 30 views
# (sourced by experiments/run.sh).

general_lod2=${LC2WF_DATA_DIR:-$root/../shared/data}/lod2

# The mix's meshes and name lists under runs/general (each part resumable by lc2wf-dataset).
general_meshes() {
  local make=$build_dir/dataset/lc2wf-make-buildings
  need_binary "$make" lc2wf-make-buildings
  mkdir -p runs/general runs/lod2-all
  local f
  for f in "$general_lod2"/cityjson/* "$general_lod2"/citygml/nrw/* "$general_lod2"/citygml/plateau/*; do
    ln -sfn "$(realpath "$f")" "runs/lod2-all/$(basename "$f")"
  done
  [[ -f runs/general/meshes-gen/buildings.json ]] || "$make" --count 600 --seed 11 -o runs/general/meshes-gen -q
  if [[ ! -f runs/general/meshes-genval/buildings.json ]]; then
    "$make" --count 60 --seed 12 -o runs/general/meshes-genval -q
    (cd runs/general/meshes-genval && for f in gen_*.polyshape; do mv "$f" "val$f"; done)
  fi
  # Roof-Image training buildings: 250 as they are, 200 others with height, footprint and turn augmented.
  if [[ ! -d runs/general/ri-train-sub ]]; then
    shuf -n 1100 --random-source=<(yes) configs/splits/train.txt | sort > runs/general/ri-train-sub.txt
    mkdir -p runs/general/ri-train-sub runs/general/ri-aug-src
    local n
    head -250 runs/general/ri-train-sub.txt | while read -r n; do ln -sfn "$(realpath "$meshes/$n.polyshape")" runs/general/ri-train-sub/; done
    sed -n '551,750p' runs/general/ri-train-sub.txt | while read -r n; do ln -sfn "$(realpath "$meshes/$n.polyshape")" runs/general/ri-aug-src/; done
    "$make" --augment runs/general/ri-aug-src -o runs/general/meshes-riaug --seed 5 -q
  fi
  # Real training buildings: every Vienna one, 250 of 3D BAG, 475 of North Rhine-Westphalia (seeded).
  [[ -f runs/general/real-train-sub.txt ]] || python3 - configs/splits/lod2/buildings.csv runs/general/real-train-sub.txt <<'PY'
import csv, random, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r['split'] == 'train']
by = {}
for r in rows: by.setdefault(r['source'], []).append(r['name'])
rng = random.Random(7)
pick = by.get('vienna', []) + rng.sample(by['3dbag'], 250) + rng.sample(by['nrw'], 475)
open(sys.argv[2], 'w').write('\n'.join(sorted(pick)) + '\n')
PY
}

# Every real building file linked again as photo_<file> in runs/general/lod2-photo, so a building's photo-like
# cloud is named apart from its raster one.
photo_lod2_links() {
  mkdir -p runs/general/lod2-photo
  local g
  for g in runs/lod2-all/*; do ln -sfn "$(realpath "$g")" "runs/general/lod2-photo/photo_$(basename "$g")"; done
}

# general-data: the raster clouds of the mix, then the training folder (links) and its split lists.
step_general_data() {
  local dataset=$build_dir/tools/lc2wf-dataset
  need_binary "$dataset" lc2wf-dataset
  general_meshes
  local common=(--renderer raster "${constant_ambient[@]}" --views 30 -j 2 -q)
  "$dataset" "${fixed_size[@]}" --meshes runs/general/meshes-gen --out runs/general/gen-raster "${common[@]}" > runs/general/gen.json || true
  "$dataset" "${fixed_size[@]}" --meshes runs/general/meshes-genval --out runs/general/genval-raster "${common[@]}" > runs/general/genval.json || true
  "$dataset" "${fixed_size[@]}" --meshes runs/lod2-all --names runs/general/real-train-sub.txt --out runs/general/real-raster "${common[@]}" \
    > runs/general/real.json || true
  "$dataset" "${fixed_size[@]}" --meshes runs/general/meshes-riaug --out runs/general/riaug-raster "${common[@]}" > runs/general/riaug.json || true
  "$dataset" "${fixed_size[@]}" --meshes runs/general/ri-train-sub --out runs/general/ri-raster "${common[@]}" > runs/general/ri.json || true
  # Photo-like clouds (Blender, --textures photo: facades with windows, clutter, sun, camera noise), so photo
  # clutter is in the training distribution: every 10th generated and every 13th real training building,
  # named photo_* (links with that prefix) beside their raster clouds.
  if [[ ! -f runs/general/photo-names.txt ]]; then
    mkdir -p runs/general/meshes-photo
    local g
    for g in $(ls runs/general/meshes-gen/*.polyshape | awk 'NR % 10 == 1'); do
      ln -sfn "$(realpath "$g")" "runs/general/meshes-photo/photo_$(basename "$g")"
    done
    photo_lod2_links
    awk 'NR % 13 == 1 { print "photo_" $0 }' runs/general/real-train-sub.txt > runs/general/photo-names.txt
  fi
  "$dataset" "${fixed_size[@]}" --meshes runs/general/meshes-photo --out runs/general/photo-blender --renderer blender --textures photo \
    --views 30 -j 2 -q > runs/general/photo-gen.json || true
  "$dataset" "${fixed_size[@]}" --meshes runs/general/lod2-photo --names runs/general/photo-names.txt --out runs/general/photo-blender \
    --renderer blender --textures photo --views 30 -j 2 -q > runs/general/photo-real.json || true
  # Validation: generated, real (the first 150 of configs/splits/lod2/val.txt) and Roof-Image (100 of its
  # validation split, 30-view Blender clouds as in the paper's benchmark).
  [[ -f runs/general/realval-names.txt ]] || head -150 configs/splits/lod2/val.txt > runs/general/realval-names.txt
  "$dataset" "${fixed_size[@]}" --meshes runs/lod2-all --names runs/general/realval-names.txt --out runs/general/realval-raster "${common[@]}" \
    > runs/general/realval.json || true
  [[ -f runs/general/rival-names.txt ]] || head -100 configs/splits/val.txt > runs/general/rival-names.txt
  "$dataset" "${fixed_size[@]}" --meshes "$meshes" --names runs/general/rival-names.txt --out runs/general/rival-blender --renderer blender \
    --views 30 -j 2 -q > runs/general/rival.json || true
  general_list general runs/general/train.txt general/{gen-raster,real-raster,riaug-raster,ri-raster,photo-blender}
  general_list general runs/general/val.txt general/{genval-raster,realval-raster,rival-blender}
  echo "general-data: $(wc -l < runs/general/train.txt) training and $(wc -l < runs/general/val.txt) validation clouds in runs/general/clouds"
}

# general-train: configs/general.json (models/dense fine-tuned on the mix), resumable.
step_general_train() { train_mix general general-model configs/general.json; }

# general-eval [MODEL...]: the test clouds (real LoD2 test split, raster: at lc2wf-dataset's default pixel rule
# in runs/lod2-raster-fine, and at 640 x 480 for every building, as before that rule, in runs/lod2-raster;
# Roof-Image test split, 30-view Blender) and the scores of each model (default models/general models/dense), by
# default and with 8 test-time views: the real split per source, roof kind and height band
# (bench/real/score_groups.sh; real-fixed/ for the 640 x 480 clouds), Roof-Image with lc2wf-eval.
step_general_eval() {
  local dataset=$build_dir/tools/lc2wf-dataset
  need_binary "$dataset" lc2wf-dataset
  general_meshes
  "$dataset" --meshes runs/lod2-all --names configs/splits/lod2/test.txt --out runs/lod2-raster-fine --renderer raster \
    "${constant_ambient[@]}" --views 30 -j 2 -q > runs/lod2-raster-fine-summary.json || true
  "$dataset" "${fixed_size[@]}" --meshes runs/lod2-all --names configs/splits/lod2/test.txt --out runs/lod2-raster --renderer raster \
    "${constant_ambient[@]}" --views 30 -j 2 -q > runs/lod2-raster-summary.json || true
  dense_test_clouds || true  # steps/clouds.sh; a failed building is named and left out
  local models=("$@") model views tag
  [[ ${#models[@]} -gt 0 ]] || models=(models/general models/dense)
  for model in "${models[@]}"; do
    for views in 1 8; do
      tag=$(basename "$model")-tt$views
      bench/real/score_groups.sh "$model" runs/lod2-raster-fine/clouds test "runs/general-eval/$tag/real" --test-time-views "$views"
      bench/real/score_groups.sh "$model" runs/lod2-raster/clouds test "runs/general-eval/$tag/real-fixed" --test-time-views "$views"
      [[ -f runs/general-eval/$tag/ri/metrics.json ]] ||
        "$build_dir/infer/lc2wf-eval" --weights "$model" --data runs/dataset-30v/clouds --split configs/splits/test.txt \
          --test-time-views "$views" -o "runs/general-eval/$tag/ri" -q --method "$tag"
    done
  done
}
