# Step light-data: general4's mix rebuilt from what one session can render: every raster part again by today's
# rasteriser, whose paper look dims the ambient light with the angle a surface is seen at (lc2wf-dataset
# --view-light, default 0.8; experiments/README.md, "Where the real score is lost": without retraining it lifts
# the real validation split 44.5 / 30.9 -> 45.8 / 32.8, and no model has yet seen such clouds), general2's 300
# Roof-Image training buildings and general's 100 Roof-Image validation buildings in Blender (30 views, as the
# paper's benchmark), and the photo-like Blender parts of the earlier mixes where they still exist (hours of
# Blender: not rendered again here). Validation first, then the training parts, each resumable.

step_light_data() {
  need_binary "$build_dir/tools/lc2wf-dataset" lc2wf-dataset
  # The raster parts need only the meshes (seconds) and the committed list of the mix's real training buildings
  # (experiments/lists/light-real.txt, general4's all-real.txt), so a fresh machine renders them without the
  # earlier mixes.
  [[ -f runs/general/meshes-gen/buildings.json && -d runs/general/ri-train-sub && -d runs/lod2-all ]] || general_meshes
  mkdir -p runs/light
  render_part light runs/lod2-all realval --names configs/splits/lod2/val.txt
  render_part light runs/general/meshes-genval genval
  render_part light runs/lod2-all real --names experiments/lists/light-real.txt
  render_part light runs/general/meshes-gen gen
  render_part light runs/general/meshes-riaug riaug
  render_part light runs/general/ri-train-sub ri
  # The Roof-Image parts in Blender (≈ 2 s per building): general2's training and general's validation choice.
  [[ -s runs/general2/ri-blender-names.txt ]] || { mkdir -p runs/general2 && sed -n '751,1050p' runs/general/ri-train-sub.txt > runs/general2/ri-blender-names.txt; }
  [[ -s runs/general/rival-names.txt ]] || head -100 configs/splits/val.txt > runs/general/rival-names.txt
  local ri=("${fixed_size[@]}" --meshes "$meshes" --renderer blender --views 30 -j 2 -q)
  "$build_dir/tools/lc2wf-dataset" "${ri[@]}" --names runs/general/rival-names.txt --out runs/general/rival-blender > runs/general/rival.json || true
  "$build_dir/tools/lc2wf-dataset" "${ri[@]}" --names runs/general2/ri-blender-names.txt --out runs/general2/ri-blender > runs/general2/ri.json || true
  local photo=() part
  for part in general/photo-blender general2/photo-blender; do [[ -d runs/$part/clouds ]] && photo+=("$part"); done
  general_list light runs/light/train.txt light/{gen,real,riaug,ri} general2/ri-blender "${photo[@]}"
  general_list light runs/light/val.txt general/rival-blender light/{genval,realval}
  echo "light-data: $(wc -l < runs/light/train.txt) training and $(wc -l < runs/light/val.txt) validation clouds in runs/light/clouds"
}

# light-val WEIGHTS TAG [FLAGS...]: general4-val's table on the light mix's validation clouds -> runs/light-val/TAG
# and a row of runs/light-val/table.md.
step_light_val() {
  [[ $# -ge 2 ]] || die 2 "light-val needs WEIGHTS and TAG"
  [[ -s runs/light/val.txt ]] || die 3 "no light mix: run experiments/run.sh light-data first"
  score_validation runs/light-val runs/light/clouds runs/light/clouds "$@"
}

# light-train [FLAGS...]: experiments/configs/light.json (photo5's schedule: two junction and two edge epochs, 5e-5
# then 5e-6, from models/general) on the light mix -> runs/light-model, resumable.
step_light_train() { train_mix light light-model experiments/configs/light.json "$@"; }
