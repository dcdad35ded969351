# Step light-data: general4's mix with every raster cloud rendered again by today's rasteriser, whose paper look
# dims the ambient light with the angle a surface is seen at (lc2wf-dataset --view-light, default 0.8;
# experiments/README.md, "Where the real score is lost"): without retraining it lifts the real validation split
# 44.5 / 30.9 -> 45.8 / 32.8, and no model has yet seen such clouds. Same buildings as general4's mix, at
# lc2wf-dataset's defaults (pixel rule and light); the Blender clouds of the mix (Roof-Image, photo-like) are
# linked as they are. Validation first (real, generated), then the training parts, each resumable.

# render_light MESHES OUT [NAMES]: one raster part at lc2wf-dataset's defaults -> runs/light/OUT.
render_light() {
  local names=()
  [[ $# -ge 3 ]] && names=(--names "$3")
  "$build_dir/tools/lc2wf-dataset" --meshes "$1" "${names[@]}" --out "runs/light/$2" --renderer raster --views 30 -j 2 -q \
    > "runs/light/$2.json" || true
}

step_light_data() {
  need_binary "$build_dir/tools/lc2wf-dataset" lc2wf-dataset
  # The raster parts need only the meshes (seconds) and the committed list of the mix's real training buildings
  # (experiments/lists/light-real.txt, general4's all-real.txt), so a fresh machine renders them without the
  # earlier mixes; linking the mix needs general4-data's lists and Blender clouds.
  [[ -f runs/general/meshes-gen/buildings.json && -d runs/general/ri-train-sub && -d runs/lod2-all ]] || general_meshes
  mkdir -p runs/light
  render_light runs/lod2-all realval configs/splits/lod2/val.txt
  render_light runs/general/meshes-genval genval
  render_light runs/lod2-all real experiments/lists/light-real.txt
  render_light runs/general/meshes-gen gen
  render_light runs/general/meshes-riaug riaug
  render_light runs/general/ri-train-sub ri
  [[ -s runs/general4/train.txt && -s runs/general4/val.txt ]] || die 3 "light-data: rendered; linking the mix needs general4-data's lists and Blender clouds"
  general_list light runs/light/train.txt general/photo-blender general2/{ri-blender,photo-blender} light/{gen,real,riaug,ri}
  general_list light runs/light/val.txt general/rival-blender light/{genval,realval}
  cmp -s runs/light/train.txt runs/general4/train.txt && cmp -s runs/light/val.txt runs/general4/val.txt ||
    die 3 "light-data: the lists differ from general4's (a part failed to render? see runs/light/*.json)"
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
