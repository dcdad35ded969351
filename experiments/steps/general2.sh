# Steps general2-data and general2-train: models/general fine-tuned on its own mix plus what its scores said it
# lacked: real training buildings
# (every 3D BAG, Vienna and >= 10 m one, NRW's complex, multi-level flat and hipped roofs, 100 of its mixed ones; raster), and Roof-Image training buildings as 30-view Blender clouds (its edge stage had learnt the raster
# look, experiments/README.md "General model: the whole mix"). Validation: the whole real validation split
# (414 buildings, raster: with Vienna, 3D BAG and buildings over 20 m) besides general's generated and
# Roof-Image validation clouds (sourced by experiments/run.sh; needs general-data's clouds).

# general2-data: the added clouds, then runs/general2/{clouds,train.txt,val.txt}.
step_general2_data() {
  local dataset=$build_dir/tools/lc2wf-dataset
  need_binary "$dataset" lc2wf-dataset
  [[ -s runs/general/train.txt ]] || die 3 "no general mix: run experiments/run.sh general-data first"
  mkdir -p runs/general2
  [[ -f runs/general2/real-train-add.txt ]] || python3 - configs/splits/lod2/buildings.csv runs/general/real-train-sub.txt \
    runs/general2/real-train-add.txt <<'PY'
import csv, random, sys
used = set(open(sys.argv[2]).read().split())
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r['split'] == 'train' and r['name'] not in used]
rng = random.Random(8)
rare = {'complex', 'flat-multi', 'hipped'}
pick = [r['name'] for r in rows if r['source'] != 'nrw' or float(r['height_m']) >= 10 or r['roof_kind'] in rare]
pick += rng.sample([r['name'] for r in rows if r['name'] not in pick and r['roof_kind'] == 'mixed'], 100)
open(sys.argv[3], 'w').write('\n'.join(sorted(pick)) + '\n')
PY
  local common=(--renderer raster --views 30 -j 2 -q)
  "$dataset" --meshes runs/lod2-all --names runs/general2/real-train-add.txt --out runs/general2/real-raster "${common[@]}" \
    > runs/general2/real.json || true
  [[ -f runs/general2/realval-names.txt ]] || cp configs/splits/lod2/val.txt runs/general2/realval-names.txt
  "$dataset" --meshes runs/lod2-all --names runs/general2/realval-names.txt --out runs/general2/realval-raster "${common[@]}" \
    > runs/general2/realval.json || true
  # 300 Roof-Image training buildings not in general's mix, as the paper's benchmark renders them.
  if [[ ! -f runs/general2/ri-blender-names.txt ]]; then
    sed -n '751,1050p' runs/general/ri-train-sub.txt > runs/general2/ri-blender-names.txt
  fi
  link_meshes runs/general2/ri-meshes configs/splits/train.txt
  "$dataset" --meshes runs/general2/ri-meshes --names runs/general2/ri-blender-names.txt --out runs/general2/ri-blender \
    --renderer blender --views 30 -j 2 -q > runs/general2/ri.json || true
  mkdir -p runs/general2/clouds
  local f
  for f in runs/general/clouds/*.lcloud runs/general2/{real-raster,realval-raster,ri-blender}/clouds/*.lcloud; do
    ln -sfn "$(realpath "$f")" runs/general2/clouds/
  done
  { cat runs/general/train.txt
    for f in runs/general2/{real-raster,ri-blender}/clouds/*.lcloud; do basename "$f" .lcloud; done; } | sort -u > runs/general2/train.txt
  { grep -v -x -F -f runs/general/realval-names.txt runs/general/val.txt
    for f in runs/general2/realval-raster/clouds/*.lcloud; do basename "$f" .lcloud; done; } | sort -u > runs/general2/val.txt
  echo "general2-data: $(wc -l < runs/general2/train.txt) training and $(wc -l < runs/general2/val.txt) validation clouds in runs/general2/clouds"
}

# general2-train: experiments/configs/general2.json, resumable.
step_general2_train() {
  need_binary "$build_dir/train/lc2wf-train" lc2wf-train
  [[ -s runs/general2/train.txt ]] || die 3 "no training list: run experiments/run.sh general2-data first"
  local resume=()
  [[ -d runs/general2-model/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" experiments/configs/general2.json "${resume[@]}"
}
