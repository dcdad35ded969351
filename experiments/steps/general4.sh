# Step general4-data: general2's mix with its large buildings rendered again at lc2wf-dataset's default pixel
# rule (finer images for buildings whose diagonal is over 32 m; experiments/README.md, "Real buildings: where
# the junctions go"): the real, generated and augmented Roof-Image buildings of the mix and of its validation
# split whose mesh diagonal is over 30 m. The other clouds are the ones general2-data made (byte-identical at
# the default rule). Needs general-data's and general2-data's clouds.

# The names of a mesh folder's buildings whose bounding-box diagonal is over 30 m (polyshape raw units / 20).
large_meshes() {
  python3 - "$1" <<'PY'
import glob, math, os, sys
for f in sorted(glob.glob(os.path.join(sys.argv[1], '*.polyshape'))):
    pts = []
    for line in open(f):
        p = line.strip().split(',')
        if len(p) == 3:
            try: pts.append([float(x) for x in p])
            except ValueError: pass
    if pts and math.dist([min(q[i] for q in pts) for i in range(3)], [max(q[i] for q in pts) for i in range(3)]) / 20 > 30:
        print(os.path.basename(f)[:-len('.polyshape')])
PY
}

# The real buildings of a name list whose footprint and height (configs/splits/lod2/buildings.csv) span over 30 m.
large_real() {
  python3 - configs/splits/lod2/buildings.csv "$1" <<'PY'
import csv, math, sys
names = set(open(sys.argv[2]).read().split())
for r in csv.DictReader(open(sys.argv[1])):
    if r['name'] in names and math.hypot(float(r['footprint_long_m']), float(r['footprint_short_m']), float(r['height_m'])) > 30:
        print(r['name'])
PY
}

step_general4_data() {
  local dataset=$build_dir/tools/lc2wf-dataset
  need_binary "$dataset" lc2wf-dataset
  [[ -s runs/general2/train.txt ]] || die 3 "no general2 mix: run experiments/run.sh general2-data first"
  mkdir -p runs/general4
  if [[ ! -f runs/general4/real-large.txt ]]; then
    sort runs/general/real-train-sub.txt runs/general2/real-train-add.txt > runs/general4/all-real.txt
    large_real runs/general4/all-real.txt > runs/general4/real-large.txt
  fi
  [[ -f runs/general4/realval-large.txt ]] || large_real runs/general2/realval-names.txt > runs/general4/realval-large.txt
  [[ -f runs/general4/gen-large.txt ]] || large_meshes runs/general/meshes-gen > runs/general4/gen-large.txt
  [[ -f runs/general4/genval-large.txt ]] || large_meshes runs/general/meshes-genval > runs/general4/genval-large.txt
  [[ -f runs/general4/riaug-large.txt ]] || large_meshes runs/general/meshes-riaug > runs/general4/riaug-large.txt
  local common=(--renderer raster --views 30 -j 2 -q)
  "$dataset" --meshes runs/lod2-all --names runs/general4/real-large.txt --out runs/general4/real-fine "${common[@]}" > runs/general4/real-fine.json || true
  "$dataset" --meshes runs/lod2-all --names runs/general4/realval-large.txt --out runs/general4/realval-fine "${common[@]}" > runs/general4/realval-fine.json || true
  "$dataset" --meshes runs/general/meshes-genval --names runs/general4/genval-large.txt --out runs/general4/genval-fine "${common[@]}" > runs/general4/genval-fine.json || true
  "$dataset" --meshes runs/general/meshes-gen --names runs/general4/gen-large.txt --out runs/general4/gen-fine "${common[@]}" > runs/general4/gen-fine.json || true
  "$dataset" --meshes runs/general/meshes-riaug --names runs/general4/riaug-large.txt --out runs/general4/riaug-fine "${common[@]}" > runs/general4/riaug-fine.json || true
  # The fine parts come last, so their links replace the 640 x 480 clouds of the same names.
  general_list general4 runs/general4/train.txt general/{gen-raster,real-raster,riaug-raster,ri-raster,photo-blender} \
    general2/{real-raster,ri-blender,photo-blender} general4/{real-fine,gen-fine,riaug-fine}
  general_list general4 runs/general4/val.txt general/{genval-raster,rival-blender} general2/realval-raster general4/{realval-fine,genval-fine}
  echo "general4-data: $(wc -l < runs/general4/train.txt) training and $(wc -l < runs/general4/val.txt) validation clouds in runs/general4/clouds"
}
