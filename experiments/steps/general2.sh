# Steps general2-data and general2-train: models/general fine-tuned on its own mix plus what its scores said it
# lacked (experiments/README.md, "General model: the whole mix"): real training buildings of the kinds it
# failed on (every 3D BAG, Vienna and >= 10 m one, NRW's complex, multi-level flat and hipped roofs, 100 of its
# mixed ones; raster), Roof-Image training buildings as 30-view Blender clouds (its edge stage had learnt the
# raster look) and more photo-like clouds. Validation: the whole real validation split (414 buildings,
# raster: with Vienna, 3D BAG and buildings over 20 m) besides general's generated and Roof-Image validation
# clouds (sourced by experiments/run.sh; needs general-data's clouds).

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
  local common=(--renderer raster "${constant_ambient[@]}" --views 30 -j 2 -q)
  "$dataset" "${fixed_size[@]}" --meshes runs/lod2-all --names runs/general2/real-train-add.txt --out runs/general2/real-raster "${common[@]}" \
    > runs/general2/real.json || true
  [[ -f runs/general2/realval-names.txt ]] || cp configs/splits/lod2/val.txt runs/general2/realval-names.txt
  "$dataset" "${fixed_size[@]}" --meshes runs/lod2-all --names runs/general2/realval-names.txt --out runs/general2/realval-raster "${common[@]}" \
    > runs/general2/realval.json || true
  # 300 Roof-Image training buildings not in general's mix, as the paper's benchmark renders them.
  if [[ ! -f runs/general2/ri-blender-names.txt ]]; then
    sed -n '751,1050p' runs/general/ri-train-sub.txt > runs/general2/ri-blender-names.txt
  fi
  link_meshes runs/general2/ri-meshes configs/splits/train.txt
  "$dataset" "${fixed_size[@]}" --meshes runs/general2/ri-meshes --names runs/general2/ri-blender-names.txt --out runs/general2/ri-blender \
    --renderer blender --views 30 -j 2 -q > runs/general2/ri.json || true
  # Photo-like clouds of every 10th added real building with the textures COLMAP registers (76b1407): general's
  # 108 were 5 % of its mix and of the textures before.
  [[ -f runs/general2/photo-names.txt ]] || awk 'NR % 10 == 1 { print "photo_" $0 }' runs/general2/real-train-add.txt \
    > runs/general2/photo-names.txt
  "$dataset" "${fixed_size[@]}" --meshes runs/general/lod2-photo --names runs/general2/photo-names.txt --out runs/general2/photo-blender \
    --renderer blender --textures photo --views 30 -j 2 -q > runs/general2/photo.json || true
  general_list general2 runs/general2/train.txt general/{gen-raster,real-raster,riaug-raster,ri-raster,photo-blender} \
    general2/{real-raster,ri-blender,photo-blender}
  general_list general2 runs/general2/val.txt general/{genval-raster,rival-blender} general2/realval-raster
  echo "general2-data: $(wc -l < runs/general2/train.txt) training and $(wc -l < runs/general2/val.txt) validation clouds in runs/general2/clouds"
}

# general2-train: experiments/configs/general2.json, resumable.
step_general2_train() { train_mix general2 general2-model experiments/configs/general2.json; }

# general2-val WEIGHTS TAG [FLAGS...]: WEIGHTS with lc2wf-infer FLAGS on general2's validation clouds -> runs/general2-val/TAG:
# real/ (414 real buildings, per source, roof kind and height band), ri/ (100 Roof-Image, Blender), gen/ (60
# generated), and one row of runs/general2-val/table.md (a finished part is kept, so a killed run resumes).
step_general2_val() {
  [[ $# -ge 2 ]] || die 2 "general2-val needs WEIGHTS and TAG"
  score_validation runs/general2-val runs/general2/realval-raster/clouds runs/general/genval-raster/clouds "$@"
}
