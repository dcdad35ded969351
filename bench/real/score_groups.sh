#!/usr/bin/env bash
# Scores one model on the real LoD2 buildings of a split, whole and per source, roof kind and height band
# (the README's real-building rows): predicts once, then lc2wf-eval --pred on each group's name list.
#   bench/real/score_groups.sh WEIGHTS CLOUDS SPLIT OUT [lc2wf-infer flags...]
# WEIGHTS: a model folder; CLOUDS: lc2wf-dataset's clouds/ of the split's buildings; SPLIT: val or test
# (configs/splits/lod2/SPLIT.txt); OUT: a new or resumed folder. Groups come from configs/splits/lod2/buildings.csv.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${LC2WF_BUILD_DIR:-$root/build}
[[ $# -ge 4 ]] || { sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
weights=$1 clouds=$2 split=$3 out=$4
shift 4
list=$root/configs/splits/lod2/$split.txt
[[ -f $list ]] || { echo "score_groups.sh: no split '$split' ($list)" >&2; exit 2; }
[[ -d $clouds ]] || { echo "score_groups.sh: no cloud folder $clouds" >&2; exit 2; }
mkdir -p "$out/groups"
# The split's buildings that have a cloud (a building whose render failed is named, not scored).
comm -12 <(sort "$list") <(ls "$clouds" | sed -n 's/\.lcloud$//p' | sort) > "$out/groups/all.txt"
missing=$(comm -23 <(sort "$list") "$out/groups/all.txt" | wc -l)
[[ $missing -eq 0 ]] || echo "score_groups.sh: $missing building(s) of $split have no cloud in $clouds" >&2
if [[ ! -f $out/predictions.done ]]; then
  "$build/infer/lc2wf-infer" --weights "$weights" $(sed "s#^#$clouds/#; s#\$#.lcloud#" "$out/groups/all.txt") \
    -o "$out/predictions" -q "$@" > /dev/null
  touch "$out/predictions.done"
fi
# Group lists: source, roof kind, height band (csv columns: name,source,file,split,x,y,height,long,short,kind,...).
python3 - "$root/configs/splits/lod2/buildings.csv" "$out/groups" <<'PY'
import csv, os, sys
csv_path, groups = sys.argv[1], sys.argv[2]
present = set(open(os.path.join(groups, 'all.txt')).read().split())
bands = [(0, 5, 'height <5 m'), (5, 10, 'height 5-10 m'), (10, 20, 'height 10-20 m'), (20, 1e9, 'height >=20 m')]
lists = {}
for r in csv.DictReader(open(csv_path)):
    if r['name'] not in present: continue
    h = float(r['height_m'])
    band = next(b[2] for b in bands if b[0] <= h < b[1])
    for key in ('source ' + r['source'], 'roof ' + r['roof_kind'], band):
        lists.setdefault(key, []).append(r['name'])
for key, names in lists.items():
    with open(os.path.join(groups, key.replace(' ', '_').replace('>=', 'ge').replace('<', 'lt') + '.txt'), 'w') as f:
        f.write('\n'.join(sorted(names)) + '\n')
PY
printf '| group | buildings | vAP | sAP | WED |\n|---|---|---|---|---|\n' > "$out/table.md"
for g in "$out"/groups/*.txt; do
  name=$(basename "$g" .txt)
  "$build/infer/lc2wf-eval" --pred "$out/predictions" --data "$clouds" --split "$g" -o "$out/eval/$name" -q --method "$name" \
    > /dev/null 2>&1 || true
  python3 - "$out/eval/$name/metrics.json" "$name" "$(wc -l < "$g")" >> "$out/table.md" <<'PY'
import json, sys
try:
    m = json.load(open(sys.argv[1]))
    print(f"| {sys.argv[2].replace('_', ' ')} | {sys.argv[3]} | {100*m['vertex_avg']['ap']:.1f} | {100*m['edge_avg']['ap']:.1f} | {m['wed']['total_num']:.2f} |")
except Exception as e:
    print(f"| {sys.argv[2]} | {sys.argv[3]} | - | - | - |")
PY
done
cat "$out/table.md"
