# Step light2-data: the light round's mix with photo-look clouds back in, all of it renderable by one session on
# two cores. The light round (steps/light.sh) gained on every clean validation split but lost 2.8 sAP on the
# photo look, because its photo-like Blender parts were lost with a machine; here the photo-look clouds are
# raster renders (`--textures photo`, ≈ 9 a minute on two cores against ≈ 2 in Blender), so a fresh machine makes
# the whole mix again. A third to a half of each light part keeps the render near an hour; validation first,
# then the training parts, each resumable.

# every_nth FILE N OUT: every N-th line of FILE (the first, then every N-th after it) -> OUT, written once.
every_nth() { [[ -s $3 ]] || awk -v n="$2" 'NR % n == 1' "$1" > "$3"; }

# mesh_names DIR OUT: the building names of a folder of .polyshape meshes -> OUT, written once.
mesh_names() { [[ -s $2 ]] || ls "$1" | sed -n 's/\.polyshape$//p' > "$2"; }

step_light2_data() {
  need_binary "$build_dir/tools/lc2wf-dataset" lc2wf-dataset
  [[ -f runs/general/meshes-gen/buildings.json && -d runs/general/ri-train-sub && -d runs/lod2-all ]] || general_meshes
  photo_lod2_links
  mkdir -p runs/light2 runs/light2/meshes-genphoto
  local g
  for g in $(ls runs/general/meshes-gen/*.polyshape | awk 'NR % 15 == 5'); do
    ln -sfn "$(realpath "$g")" "runs/light2/meshes-genphoto/photo_$(basename "$g")"
  done
  # Names: every real validation building; every 10th of them photo-look (the 42 the storey rule was chosen on).
  every_nth configs/splits/lod2/val.txt 10 runs/light2/photoval-src.txt
  [[ -s runs/light2/photoval-names.txt ]] || sed 's/^/photo_/' runs/light2/photoval-src.txt > runs/light2/photoval-names.txt
  mesh_names runs/general/meshes-genval runs/light2/genval-names.txt
  every_nth experiments/lists/light-real.txt 3 runs/light2/real-names.txt
  every_nth experiments/lists/photo-real.txt 2 runs/light2/realphoto-names.txt
  mesh_names runs/general/meshes-gen runs/light2/gen-all.txt
  every_nth runs/light2/gen-all.txt 4 runs/light2/gen-names.txt
  mesh_names runs/general/meshes-riaug runs/light2/riaug-all.txt
  every_nth runs/light2/riaug-all.txt 2 runs/light2/riaug-names.txt
  [[ -s runs/light2/ri-names.txt ]] || head -250 runs/general/ri-train-sub.txt | awk 'NR % 3 == 1' > runs/light2/ri-names.txt
  mesh_names runs/light2/meshes-genphoto runs/light2/genphoto-names.txt
  # Validation.
  [[ -s runs/general/rival-names.txt ]] || head -100 configs/splits/val.txt > runs/general/rival-names.txt
  local ri=("${fixed_size[@]}" --meshes "$meshes" --renderer blender --views 30 -j 2 -q)
  "$build_dir/tools/lc2wf-dataset" "${ri[@]}" --names runs/general/rival-names.txt --out runs/general/rival-blender > runs/general/rival.json || true
  render_part light2 runs/general/lod2-photo photoval --names runs/light2/photoval-names.txt --textures photo
  render_part light2 runs/lod2-all realval --names configs/splits/lod2/val.txt
  render_part light2 runs/general/meshes-genval genval --names runs/light2/genval-names.txt
  # Training: the photo look first (the part the light round lacked), then the clean parts.
  render_part light2 runs/general/lod2-photo realphoto --names runs/light2/realphoto-names.txt --textures photo
  render_part light2 runs/light2/meshes-genphoto genphoto --names runs/light2/genphoto-names.txt --textures photo
  render_part light2 runs/lod2-all real --names runs/light2/real-names.txt
  render_part light2 runs/general/meshes-gen gen --names runs/light2/gen-names.txt
  render_part light2 runs/general/meshes-riaug riaug --names runs/light2/riaug-names.txt
  render_part light2 "$meshes" ri --names runs/light2/ri-names.txt
  # Roof-Image in Blender, as the benchmark renders it: the light round's edge stage gained its Roof-Image sAP there.
  [[ -s runs/light2/ri-blender-names.txt ]] || sed -n '751,950p' runs/general/ri-train-sub.txt > runs/light2/ri-blender-names.txt
  "$build_dir/tools/lc2wf-dataset" "${ri[@]}" --names runs/light2/ri-blender-names.txt --out runs/light2/ri-blender > runs/light2/ri-blender.json || true
  general_list light2 runs/light2/train.txt light2/{realphoto,genphoto,real,gen,riaug,ri,ri-blender}
  general_list light2 runs/light2/val.txt general/rival-blender light2/{realval,genval,photoval}
  echo "light2-data: $(wc -l < runs/light2/train.txt) training and $(wc -l < runs/light2/val.txt) validation clouds in runs/light2/clouds"
}

# light2-train [FLAGS...]: experiments/configs/light2.json (the light round's schedule from models/general) on
# the light2 mix -> runs/light2-model, resumable.
step_light2_train() { train_mix light2 light2-model experiments/configs/light2.json "$@"; }

# light2-val WEIGHTS TAG [FLAGS...]: lc2wf-eval of WEIGHTS on each validation part of the light2 mix (real 414,
# Roof-Image 100 in Blender, generated 60, photo look 42) -> runs/light2-val/TAG/PART and a row of
# runs/light2-val/table.md (vAP / sAP / WED per part); a finished part is kept.
step_light2_val() {
  [[ $# -ge 2 ]] || die 2 "light2-val needs WEIGHTS and TAG"
  [[ -s runs/light2/val.txt ]] || die 3 "no light2 mix: run experiments/run.sh light2-data first"
  local weights=$1 tag=$2 part
  shift 2
  local out=runs/light2-val/$tag
  mkdir -p "$out"
  declare -A data=([real]=runs/light2/realval [ri]=runs/general/rival-blender [gen]=runs/light2/genval [photo]=runs/light2/photoval)
  declare -A names=([real]=configs/splits/lod2/val.txt [ri]=runs/general/rival-names.txt [gen]=runs/light2/genval-names.txt
    [photo]=runs/light2/photoval-names.txt)
  for part in real ri gen photo; do
    [[ -f $out/$part/metrics.json ]] || "$build_dir/infer/lc2wf-eval" --weights "$weights" --data "${data[$part]}/clouds" \
      --split "${names[$part]}" -o "$out/$part" -q --method "$tag" "$@" > /dev/null
  done
  metrics_row "$tag" "${*:--}" "$out"/{real,ri,gen,photo}/metrics.json >> runs/light2-val/table.md
  tail -1 runs/light2-val/table.md
}
