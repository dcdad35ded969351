# Step general4-data: general2's mix with its large buildings rendered again at lc2wf-dataset's default pixel
# rule (finer images for buildings whose bounding-box diagonal is over 32 m; experiments/README.md, "Real
# buildings: where the junctions go"): the real, generated and augmented Roof-Image buildings of the mix and of
# its validation split over 22 m across (footprint sides and height, so every building the rule can enlarge,
# whatever its turn: the rule measures the axis-aligned box, and 32 m / sqrt 2 < 23 m). The other clouds are
# the ones general2-data made (byte-identical at the default rule). Needs general-data's and general2-data's clouds.

# The buildings of a building CSV (configs/splits/lod2/buildings.csv, or lc2wf-list-buildings' output for a mesh
# folder: the same name, height_m and footprint columns) over 22 m across (footprint sides and height), limited to
# the names of NAMES when given.
large_buildings() {
  python3 - "$@" <<'PY'
import csv, math, sys
names = set(open(sys.argv[2]).read().split()) if len(sys.argv) > 2 else None
for r in csv.DictReader(open(sys.argv[1])):
    if (names is None or r['name'] in names) and r.get('status', 'ok') == 'ok' and \
            math.hypot(float(r['footprint_long_m']), float(r['footprint_short_m']), float(r['height_m'])) > 22:
        print(r['name'])
PY
}

# large_meshes FOLDER: the large buildings of a mesh folder (lc2wf-list-buildings facts).
large_meshes() {
  "$build_dir/dataset/lc2wf-list-buildings" "$1" -o "runs/general4/$(basename "$1").csv" -q -j 2 || true
  large_buildings "runs/general4/$(basename "$1").csv"
}

step_general4_data() {
  need_binary "$build_dir/tools/lc2wf-dataset" lc2wf-dataset
  [[ -s runs/general2/train.txt ]] || die 3 "no general2 mix: run experiments/run.sh general2-data first"
  mkdir -p runs/general4
  if [[ ! -f runs/general4/real-large.txt ]]; then
    sort runs/general/real-train-sub.txt runs/general2/real-train-add.txt > runs/general4/all-real.txt
    large_buildings configs/splits/lod2/buildings.csv runs/general4/all-real.txt > runs/general4/real-large.txt
  fi
  [[ -f runs/general4/realval-large.txt ]] ||
    large_buildings configs/splits/lod2/buildings.csv runs/general2/realval-names.txt > runs/general4/realval-large.txt
  [[ -f runs/general4/gen-large.txt ]] || large_meshes runs/general/meshes-gen > runs/general4/gen-large.txt
  [[ -f runs/general4/genval-large.txt ]] || large_meshes runs/general/meshes-genval > runs/general4/genval-large.txt
  [[ -f runs/general4/riaug-large.txt ]] || large_meshes runs/general/meshes-riaug > runs/general4/riaug-large.txt
  render_part general4 runs/lod2-all real-fine --names runs/general4/real-large.txt "${constant_ambient[@]}"
  render_part general4 runs/lod2-all realval-fine --names runs/general4/realval-large.txt "${constant_ambient[@]}"
  render_part general4 runs/general/meshes-genval genval-fine --names runs/general4/genval-large.txt "${constant_ambient[@]}"
  render_part general4 runs/general/meshes-gen gen-fine --names runs/general4/gen-large.txt "${constant_ambient[@]}"
  render_part general4 runs/general/meshes-riaug riaug-fine --names runs/general4/riaug-large.txt "${constant_ambient[@]}"
  # The fine parts come last, so their links replace the 640 x 480 clouds of the same names.
  general_list general4 runs/general4/train.txt general/{gen-raster,real-raster,riaug-raster,ri-raster,photo-blender} \
    general2/{real-raster,ri-blender,photo-blender} general4/{real-fine,gen-fine,riaug-fine}
  general_list general4 runs/general4/val.txt general/{genval-raster,rival-blender} general2/realval-raster \
    general4/{realval-fine,genval-fine}
  echo "general4-data: $(wc -l < runs/general4/train.txt) training and $(wc -l < runs/general4/val.txt)" \
    "validation clouds in runs/general4/clouds"
}

# general4-train: experiments/configs/general4.json (models/general fine-tuned on the mix at a low lr, since
# general2's 5e-5 moved it off its minimum), resumable; `--stage junction` first, scored as a hybrid with
# general4-val before the edge stage runs.
step_general4_train() { train_mix general4 general4-model experiments/configs/general4.json "$@"; }

# general4-val WEIGHTS TAG [FLAGS...]: as general2-val, on general4's validation clouds (the large buildings at the
# default pixel rule) -> runs/general4-val/TAG and a row of runs/general4-val/table.md.
step_general4_val() {
  [[ $# -ge 2 ]] || die 2 "general4-val needs WEIGHTS and TAG"
  [[ -s runs/general4/val.txt ]] || die 3 "no general4 mix: run experiments/run.sh general4-data first"
  score_validation runs/general4-val runs/general4/clouds runs/general4/clouds "$@"
}
