# Step street-data: the light2 mix with walks along the street in it. Every model so far saw whole-building orbits
# and the street arcs only; a walk at eye height along one facade (lc2wf-dataset --capture walk) gives it a
# facade, trees in front and no roof, and it draws the trees (bench/README.md, "A walk down the street"). Walks
# of the light2 mix's photo-look real and generated training buildings (raster, photo look, 20 views, ≈ 25 min
# on two cores), beside light2's photo-look orbits and every 3rd cloud of its clean parts; validation: light2's
# validation clouds and the walks of the photo-look validation buildings (runs/height/photoval-walk).

# link_clouds FROM TO N PREFIX: every N-th cloud of FROM/clouds (the first, then every N-th after it) linked into
# TO/clouds as PREFIX<name>, so general_list can take TO as a part.
link_clouds() {
  local from=$1 to=$2 n=$3 prefix=$4 f
  mkdir -p "$to/clouds"
  ls "$from/clouds" | awk -v n="$n" 'NR % n == 1 % n' | while read -r f; do
    ln -sfn "$(realpath "$from/clouds/$f")" "$to/clouds/$prefix$f"
  done
}

step_street_data() {
  need_binary "$build_dir/tools/lc2wf-dataset" lc2wf-dataset
  [[ -s runs/light2/train.txt ]] || step_light2_data
  mkdir -p runs/street/meshes-walk
  # Walk clouds need names of their own beside the same buildings' orbits: the meshes linked again as walk_*.
  local g
  for g in runs/general/lod2-photo/* runs/light2/meshes-genphoto/*; do
    ln -sfn "$(realpath "$g")" "runs/street/meshes-walk/walk_$(basename "$g")"
  done
  [[ -s runs/street/walk-names.txt ]] || cat runs/light2/realphoto-names.txt runs/light2/genphoto-names.txt | sed 's/^/walk_/' \
    > runs/street/walk-names.txt
  render_part street runs/street/meshes-walk walk --names runs/street/walk-names.txt --textures photo --views 20 --capture walk
  [[ -d runs/height/photoval-walk/clouds ]] || step_height_model
  local clean=() part
  for part in real gen riaug ri ri-blender; do
    link_clouds "runs/light2/$part" "runs/street/light2-$part" 3 ""
    clean+=("street/light2-$part")
  done
  general_list street runs/street/train.txt street/walk light2/{realphoto,genphoto} "${clean[@]}"
  # The validation walks are named as the same buildings' photo-look orbits: linked again as walk_*.
  link_clouds runs/height/photoval-walk runs/street/walkval 1 walk_
  general_list street runs/street/val.txt general/rival-blender light2/{realval,genval,photoval} street/walkval
  echo "street-data: $(wc -l < runs/street/train.txt) training and $(wc -l < runs/street/val.txt) validation clouds in runs/street/clouds"
}

# street-train [FLAGS...]: experiments/configs/street.json (light2's schedule from models/general) on the street mix
# -> runs/street-model, resumable.
step_street_train() { train_mix street street-model experiments/configs/street.json "$@"; }

# street-val WEIGHTS TAG [FLAGS...]: light2-val's four parts, then the 42 validation walks: vAP / sAP / WED and the
# share of the drawn length within 0.5 m of a GT edge (bench/reconstruct/edge_accuracy.py) -> runs/light2-val/TAG
# and a row of runs/street/table.md.
step_street_val() {
  [[ $# -ge 2 ]] || die 2 "street-val needs WEIGHTS and TAG"
  local weights=$1 tag=$2
  shift 2
  step_light2_val "$weights" "$tag" "$@"
  local out=runs/light2-val/$tag/walk
  [[ -f $out/metrics.json ]] || "$build_dir/infer/lc2wf-eval" --weights "$weights" --data runs/height/photoval-walk/clouds \
    --split runs/height/photoval-walk-names.txt -o "$out" -q --method "$tag" "$@" > /dev/null
  local row on
  row=$(metrics_row "$tag" "${*:--}" runs/light2-val/"$tag"/{real,ri,gen,photo,walk}/metrics.json)
  on=$(/usr/bin/python3 bench/reconstruct/edge_accuracy.py "$out/predictions" runs/height/photoval-walk/clouds)
  echo "$row $on |" >> runs/street/table.md
  tail -1 runs/street/table.md
}

# street2-data: the street mix's walks and photo-look orbits beside all of light2's clean clouds (the street round
# kept a third of them and lost 1.7–2.2 sAP on the clean validation parts) -> runs/street2.
step_street2_data() {
  [[ -s runs/street/train.txt ]] || step_street_data
  general_list street2 runs/street2/train.txt street/walk light2/{realphoto,genphoto,real,gen,riaug,ri,ri-blender}
  general_list street2 runs/street2/val.txt general/rival-blender light2/{realval,genval,photoval} street/walkval
  echo "street2-data: $(wc -l < runs/street2/train.txt) training and $(wc -l < runs/street2/val.txt) validation clouds in runs/street2/clouds"
}

# street2-train [FLAGS...]: the edge stage alone (experiments/configs/street2.json, light2's schedule) beside
# models/general's junction model, whose hand-off it trains on (the street round's photo gain was its edge
# model's: experiments/README.md, "Walks in the mix") -> runs/street2-model, resumable.
step_street2_train() {
  mkdir -p runs/street2-model
  [[ -f runs/street2-model/junction.safetensors ]] || cp models/general/junction.safetensors runs/street2-model/
  train_mix street2 street2-model experiments/configs/street2.json --stage edge "$@"
}
