#!/usr/bin/env bash
# The scale search (model/scale_search.h) on buildings of 3-60 m with a scale unknown to it: real LoD2
# buildings and generated ones are rendered into labelled line clouds (raster, 30 views), moved into random
# frames and given to lc2wf-infer. Usage: bench/reconstruct/scale_search_bench.sh OUT [WEIGHTS] [N_REAL] [N_GENERATED]
# Writes OUT/keep-up/summary.md (z kept up: the scale search alone) and OUT/auto/summary.md (random rotation:
# up from the lines, then the search). TEXTURES=photo renders the photo look (windows by storey, clutter), whose
# storeys give the scale before the search does (dataset/photo/storey_scale.h); default: the paper look.
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${1:?usage: scale_search_bench.sh OUT [WEIGHTS] [N_REAL] [N_GENERATED]}
WEIGHTS=${2:-models/dense}
N_REAL=${3:-10}
N_GEN=${4:-12}
TEXTURES=${TEXTURES:-paper}
LOD2=../shared/data/lod2/cityjson/cjseq__3dbag_b2.city.jsonl   # 3D BAG (2 buildings)
LOD2B=../shared/data/lod2/cityjson/cjdb__vienna.jsonl           # Vienna
mkdir -p "$OUT"
if [ ! -d "$OUT/gen-meshes" ]; then
  build/dataset/lc2wf-make-buildings --count "$N_GEN" --seed 7 -o "$OUT/gen-meshes" -q
fi
[ -d "$OUT/gen-clouds/clouds" ] || nice -n 5 build/tools/lc2wf-dataset --meshes "$OUT/gen-meshes" --out "$OUT/gen-clouds" --renderer raster --textures "$TEXTURES" --views 30 -j 1 -q || true
if [ -f "$LOD2" ]; then
  [ -d "$OUT/lod2-clouds/clouds" ] || nice -n 5 build/tools/lc2wf-dataset --meshes "$LOD2" --limit "$N_REAL" --out "$OUT/lod2-clouds" --renderer raster --textures "$TEXTURES" --views 30 -j 1 -q || true
  [ -d "$OUT/lod2b-clouds/clouds" ] || nice -n 5 build/tools/lc2wf-dataset --meshes "$LOD2B" --limit "$N_REAL" --out "$OUT/lod2b-clouds" --renderer raster --textures "$TEXTURES" --views 30 -j 1 -q || true
fi
CLOUDS=$(ls "$OUT"/gen-clouds/clouds/*.lcloud "$OUT"/lod2-clouds/clouds/*.lcloud "$OUT"/lod2b-clouds/clouds/*.lcloud 2>/dev/null)
for mode in keep-up auto; do
  nice -n 5 python3 bench/reconstruct/scale_search_bench.py --infer build/infer/lc2wf-infer --convert build/dataset/lc2wf-cloud-convert \
    --weights "$WEIGHTS" --out "$OUT/$mode" $([ $mode = keep-up ] && echo --keep-up) $CLOUDS
done
