#!/usr/bin/env bash
# experiments/selection_table.py on fixtures: three lc2wf-eval metrics files with their selection recorded come out
# best sAP first (a tie broken by vAP), with the best row's flags last; a file without the selection and rows
# scored on different building counts are refused, naming the problem.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
write() {  # write TAG SAP VAP MIN_CONFIDENCE NMS MAX_OFFSET(null) [BUILDINGS]
  mkdir -p "$out/grid/$1"
  /usr/bin/python3 - "$out/grid/$1/metrics.json" "$@" <<'PY'
import json, sys
path, tag, sap, vap, c, nms, offset = sys.argv[1:8]
buildings = int(sys.argv[8]) if len(sys.argv) > 8 else 10
m = {"buildings": buildings, "vertex_avg": {"ap": float(vap)}, "edge_avg": {"ap": float(sap)},
     "wed": {"add_edge": 1, "del_edge": 2, "add_vertex": 3},
     "inference": {"min_confidence": float(c), "nms_radius_m": float(nms), "max_offset_m": json.loads(offset),
                   "pairs_per_building": 100.0, "seconds_per_building": 0.1}}
json.dump(m, open(path, "w"))
PY
}
write release 0.55 0.54 0.85 0.25 null
write screened 0.71 0.75 0.1 0.5 1.0
write screened_tighter 0.71 0.76 0.1 0.5 0.75
table=$(/usr/bin/python3 "$root/experiments/selection_table.py" "$out/grid")
order=$(grep -o '^| [a-z_]* |' <<<"$table" | tr -d '| ' | tr '\n' ' ')
[[ $order == "selection screened_tighter screened release " ]] || { echo "wrong order: $order"; echo "$table"; exit 1; }
grep -qF "| screened_tighter | 0.1 | 0.5 | 0.75 | 100 | 0.100 | 76.0 | 71.0 | 6.00 |" <<<"$table" || { echo "$table"; exit 1; }
grep -qF "| release | 0.85 | 0.25 | any |" <<<"$table" || { echo "$table"; exit 1; }
[[ $(tail -1 <<<"$table") == "Best: --min-confidence 0.1 --nms-radius 0.5 --max-offset 0.75" ]] || { echo "$table"; exit 1; }
# Different building counts are not comparable.
write few 0.9 0.9 0.1 0.5 null 3
if /usr/bin/python3 "$root/experiments/selection_table.py" "$out/grid" 2>"$out/err"; then echo "mixed building counts accepted"; exit 1; fi
grep -q "different numbers of buildings" "$out/err" || { cat "$out/err"; exit 1; }
rm -rf "$out/grid/few"
# A metrics file without the recorded selection is named.
mkdir -p "$out/grid/old" && echo '{"buildings": 10}' > "$out/grid/old/metrics.json"
if /usr/bin/python3 "$root/experiments/selection_table.py" "$out/grid" 2>"$out/err"; then echo "a file without the selection was accepted"; exit 1; fi
grep -q "old/metrics.json" "$out/err" || { cat "$out/err"; exit 1; }
echo ok
