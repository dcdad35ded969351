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
  [[ -f runs/general/meshes-gen/buildings.json ]] || "$make" --count 900 --seed 11 -o runs/general/meshes-gen -q
  if [[ ! -f runs/general/meshes-genval/buildings.json ]]; then
    "$make" --count 60 --seed 12 -o runs/general/meshes-genval -q
    (cd runs/general/meshes-genval && for f in gen_*.polyshape; do mv "$f" "val$f"; done)
  fi
  # Roof-Image training buildings: 300 as they are, 300 others with height, footprint and turn augmented.
  if [[ ! -d runs/general/ri-train-sub ]]; then
    shuf -n 1100 --random-source=<(yes) configs/splits/train.txt | sort > runs/general/ri-train-sub.txt
    mkdir -p runs/general/ri-train-sub runs/general/ri-aug-src
    local n
    head -300 runs/general/ri-train-sub.txt | while read -r n; do ln -sfn "$(realpath "$meshes/$n.polyshape")" runs/general/ri-train-sub/; done
    sed -n '551,850p' runs/general/ri-train-sub.txt | while read -r n; do ln -sfn "$(realpath "$meshes/$n.polyshape")" runs/general/ri-aug-src/; done
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

# general-data: the raster clouds of the mix, then the training folder (links) and its split lists.
step_general_data() {
  local dataset=$build_dir/tools/lc2wf-dataset
  need_binary "$dataset" lc2wf-dataset
  general_meshes
  local common=(--renderer raster --views 30 -j 2 -q)
  "$dataset" --meshes runs/general/meshes-gen --out runs/general/gen-raster "${common[@]}" > runs/general/gen.json || true
  "$dataset" --meshes runs/general/meshes-genval --out runs/general/genval-raster "${common[@]}" > runs/general/genval.json || true
  "$dataset" --meshes runs/lod2-all --names runs/general/real-train-sub.txt --out runs/general/real-raster "${common[@]}" \
    > runs/general/real.json || true
  "$dataset" --meshes runs/general/meshes-riaug --out runs/general/riaug-raster "${common[@]}" > runs/general/riaug.json || true
  "$dataset" --meshes runs/general/ri-train-sub --out runs/general/ri-raster "${common[@]}" > runs/general/ri.json || true
  # Validation: generated (raster), real (the Blender clouds of lc2wf-dataset on configs/splits/lod2/val.txt,
  # 150 of them) and Roof-Image (its validation split's 30-view Blender clouds, 100 of them).
  mkdir -p runs/general/clouds
  : > runs/general/train.txt
  local part
  for part in gen-raster real-raster riaug-raster ri-raster; do
    for f in runs/general/$part/clouds/*.lcloud; do ln -sfn "$(realpath "$f")" runs/general/clouds/; basename "$f" .lcloud; done >> runs/general/train.txt
  done
  : > runs/general/val.txt
  for f in runs/general/genval-raster/clouds/*.lcloud; do ln -sfn "$(realpath "$f")" runs/general/clouds/; basename "$f" .lcloud; done >> runs/general/val.txt
  for f in $(ls runs/lod2-30v/clouds/*.lcloud 2>/dev/null | head -150) $(ls runs/dataset-30v/clouds/*.lcloud 2>/dev/null | grep -F -f <(sed 's/$/.lcloud/' configs/splits/val.txt) | head -100); do
    ln -sfn "$(realpath "$f")" runs/general/clouds/; basename "$f" .lcloud
  done >> runs/general/val.txt
  sort -o runs/general/train.txt runs/general/train.txt
  sort -o runs/general/val.txt runs/general/val.txt
  echo "general-data: $(wc -l < runs/general/train.txt) training and $(wc -l < runs/general/val.txt) validation clouds in runs/general/clouds"
}

# general-train: configs/general.json (models/dense fine-tuned on the mix), resumable.
step_general_train() {
  need_binary "$build_dir/train/lc2wf-train" lc2wf-train
  [[ -s runs/general/train.txt ]] || die 3 "no training list: run experiments/run.sh general-data first"
  local resume=()
  [[ -d runs/general-model/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" configs/general.json "${resume[@]}"
}
