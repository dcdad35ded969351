#!/usr/bin/env bash
# How one model serves clouds of other statistics (issue: robust to the cloud's statistics). For the
# buildings of SPLIT, makes five kinds of cloud with lc2wf-cloud-styles (our own; the same segments through
# the Line3D++ .txt path; every GT edge as 2-5 long noisy fragments plus clutter, in our format and as a
# Line3D++ .txt, which the default cuts into pieces; only our lines on GT edges; ours plus photo-like
# texture lines on faces and ground), scores WEIGHTS on each with lc2wf-eval and prints Markdown tables
# (vAP/sAP avg, WED, mean junctions/edges; which clouds the default would cut if read from a line map).
#
#   experiments/robustness.sh WEIGHTS SPLIT OUT [CLOUDS] [-- LC2WF_EVAL_FLAGS...]
#   CLOUDS: labelled clouds (default runs/dataset/clouds); flags after -- go to every lc2wf-eval (e.g.
#   --test-time-views 8)
#
# Run it on held-out buildings (e.g. configs/splits/test.txt or a subset) for each model to compare.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${LC2WF_BUILD_DIR:-$root/build}
[[ $# -ge 3 ]] || { sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
weights=$1 split=$2 out=$3 clouds=$root/runs/dataset/clouds
shift 3
if [[ $# -gt 0 && $1 != -- ]]; then clouds=$1; shift; fi
[[ ${1:-} == -- ]] && shift
eval_flags=("$@")

[[ -x $build/experiments/lc2wf-cloud-styles ]] ||
  { echo "robustness.sh: $build/experiments/lc2wf-cloud-styles is missing: cmake --build $build --target lc2wf-cloud-styles" >&2; exit 3; }
"$build/experiments/lc2wf-cloud-styles" --data "$clouds" --split "$split" -o "$out/clouds"
eval_as() {  # eval_as ROW STYLE [extra lc2wf-eval flags]
  local row=$1 style=$2
  shift 2
  "$build/infer/lc2wf-eval" --weights "$weights" --data "$out/clouds/$style" --split "$split" --out "$out/$row" \
    --method "$row" --quiet "$@" ${eval_flags[@]+"${eval_flags[@]}"} >/dev/null
}
eval_as own own
eval_as line3dpp line3dpp --format line3dpp --gt "$out/clouds/gt"
eval_as long long
eval_as long-cut long-line3dpp --format line3dpp --gt "$out/clouds/gt"
eval_as edges edges
eval_as photo photo

/usr/bin/python3 - "$out" <<'PY'
import csv, json, statistics, sys
from pathlib import Path
out = Path(sys.argv[1])
labels = {"own": "our clouds (lc2wf-dataset)", "line3dpp": "same segments via Line3D++ .txt",
          "long": "long fragments from the GT + clutter (our file format: not cut)",
          "long-cut": "the same as a Line3D++ .txt: a merged line map, cut at 1.5 m by default",
          "edges": "our clouds, only the lines on a GT edge",
          "photo": "our clouds + texture lines on faces and ground (photo-like)"}
print("| clouds | vAP avg | sAP avg | WED total (Dist) | junctions / building | edges / building |")
print("|---|---|---|---|---|---|")
for style, label in labels.items():
    m = json.load(open(out / style / "metrics.json"))
    rows = list(csv.DictReader(open(out / style / "per_building.csv")))
    def mean_of(key):
        return statistics.mean(float(r[key]) for r in rows) if rows else float("nan")
    print(f"| {label} | {100 * m['vertex_avg']['ap']:.1f} | {100 * m['edge_avg']['ap']:.1f} | {m['wed']['total_dist']:.3f} | "
          f"{mean_of('pred_vertices'):.1f} | {mean_of('pred_edges'):.1f} |")
PY
