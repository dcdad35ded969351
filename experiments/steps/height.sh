# Step height-model: the height model of models/general (dataset/photo/line_height.h), which scales photo
# clouds and line maps nothing else scales. Its training clouds are the light2 mix's metric clouds of real and
# generated training buildings, clean and photo-look, plus the other half of the photo-look real training
# buildings and 40 more generated ones in the photo look, and street captures of real training buildings in
# the photo look (two facades: the light2 photo half; one facade: every other of the other half; a walk along
# the street: the rest of that half), ≈ 70 min of raster renders on two cores; the street captures and walks of
# the photo-look validation buildings to validate on;
# then lc2wf-fit-height (a second) -> runs/height/height.json, copied to models/general/height.json by hand
# after validation (experiments/README.md, "Height from line statistics").

step_height_model() {
  need_binary "$build_dir/tools/lc2wf-dataset" lc2wf-dataset
  need_binary "$build_dir/train/lc2wf-fit-height" lc2wf-fit-height
  [[ -d runs/light2/realphoto && -d runs/light2/real && -d runs/light2/gen && -d runs/light2/genphoto ]] || step_light2_data
  mkdir -p runs/height runs/height/meshes-genphoto2
  local g
  for g in $(ls runs/general/meshes-gen/*.polyshape | awk 'NR % 15 == 10'); do
    ln -sfn "$(realpath "$g")" "runs/height/meshes-genphoto2/photo_$(basename "$g")"
  done
  [[ -s runs/height/realphoto2-names.txt ]] || awk 'NR % 2 == 0' experiments/lists/photo-real.txt > runs/height/realphoto2-names.txt
  mesh_names runs/height/meshes-genphoto2 runs/height/genphoto2-names.txt
  render_part height runs/general/lod2-photo realphoto2 --names runs/height/realphoto2-names.txt --textures photo
  render_part height runs/height/meshes-genphoto2 genphoto2 --names runs/height/genphoto2-names.txt --textures photo
  # Street captures see one or two facades: their statistics are not an orbit's (20 views, as a phone's photos).
  [[ -s runs/height/photoval-street2-names.txt ]] || cp runs/light2/photoval-names.txt runs/height/photoval-street2-names.txt
  [[ -s runs/height/realstreet2-names.txt ]] || cp runs/light2/realphoto-names.txt runs/height/realstreet2-names.txt
  [[ -s runs/height/realstreet1-names.txt ]] || awk 'NR % 2 == 0' runs/height/realphoto2-names.txt > runs/height/realstreet1-names.txt
  local part capture
  # A walk along the street (one straight line at eye height): the other half of realphoto2, and the validation
  # buildings (experiments/README.md, "Walks in the height model").
  [[ -s runs/height/realwalk-names.txt ]] || awk 'NR % 2 == 1' runs/height/realphoto2-names.txt > runs/height/realwalk-names.txt
  [[ -s runs/height/photoval-walk-names.txt ]] || cp runs/light2/photoval-names.txt runs/height/photoval-walk-names.txt
  for part in photoval-street2:street-2 realstreet2:street-2 realstreet1:street-1 photoval-walk:walk realwalk:walk; do
    capture=${part#*:} part=${part%%:*}
    render_part height runs/general/lod2-photo "$part" --names "runs/height/$part-names.txt" --textures photo --views 20 --capture "$capture"
  done
  # k = 7: on the street captures of the validation buildings 7.3 % median error against 8.9 % with 5 (the
  # cross-validation's pick), the orbits within 0.2 points (experiments/README.md, "Height from line statistics").
  "$build_dir/train/lc2wf-fit-height" -o runs/height/height.json --ks 7 runs/light2/{realphoto,genphoto,real,gen}/clouds \
    runs/height/{realphoto2,genphoto2,realstreet2,realstreet1,realwalk}/clouds
}

# map-frame-val INFER WEIGHTS TAG [FLAGS...]: lc2wf-infer's frame for maps without cameras (up, ground and scale
# from the lines alone) on validation clouds moved into random frames (bench/reconstruct/scale_search_bench.py,
# seed 3) -> runs/map-frame-val/TAG/PART and one row per part in runs/map-frame-val/table.md (experiments/README.md,
# "Up from the lines").
step_map_frame_val() {
  [[ $# -ge 3 ]] || die 2 "map-frame-val needs INFER, WEIGHTS and TAG"
  local infer=$1 weights=$2 tag=$3 part a
  shift 3
  local extra=()
  for a in "$@"; do extra+=("--infer-arg=$a"); done
  declare -A clouds=([photo]="runs/light2/photoval/clouds/*.lcloud" [street]="runs/height/photoval-street2/clouds/*.lcloud"
                      [walk]="runs/height/photoval-walk/clouds/*.lcloud")
  mkdir -p "runs/map-frame-val/$tag"
  for part in photo street walk clean gen; do
    local list
    case $part in
      clean) list=$(grep -v '^#' runs/s11-ss-clouds.txt) ;;
      gen) list=$(ls runs/light2/genval/clouds/*.lcloud | awk 'NR % 3 == 1') ;;
      *) list=$(ls ${clouds[$part]}) ;;
    esac
    # shellcheck disable=SC2086  # one path per word
    [[ -f runs/map-frame-val/$tag/$part/summary.md ]] || /usr/bin/python3 bench/reconstruct/scale_search_bench.py --infer "$infer" \
      --convert "$build_dir/dataset/lc2wf-cloud-convert" --weights "$weights" --out "runs/map-frame-val/$tag/$part" --seed 3 \
      "${extra[@]}" $list > "runs/map-frame-val/$tag/$part.log" 2>&1
    /usr/bin/python3 - "$tag" "$part" "runs/map-frame-val/$tag/$part/results.csv" >> runs/map-frame-val/table.md <<'PY'
import csv, sys
tag, part, path = sys.argv[1:]
rows = list(csv.DictReader(open(path)))
up = [float(r["up_error_deg"]) for r in rows]
scale = sorted(abs(float(r["scale_error"])) for r in rows)
print(f"| {tag} | {part} | {len(rows)} | {sum(e < 10 for e in up)} | {sum(e > 170 for e in up)} | "
      f"{100 * scale[len(scale) // 2]:.1f} % | {sum(e <= 0.15 for e in scale)} |")
PY
  done
  tail -4 runs/map-frame-val/table.md
}
