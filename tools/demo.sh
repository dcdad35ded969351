#!/usr/bin/env bash
# The main command: installs what is missing, builds, and runs the demo on the embedded default data.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${LC2WF_BUILD_DIR:-$root/build}
LC2WF_BUILD_TESTS=OFF LC2WF_BUILD_BENCH=OFF "$root/tools/build.sh"
# The demo: the project's own synthetic buildings as line clouds (no external data needed), a small model
# trained with configs/demo.json on 2 threads, then inference + Table-2 metrics on held-out buildings.
# Deterministic: same files and numbers on every run. Outputs under runs/ (git-ignored).
cd "$root"
data=runs/demo-data
out=runs/demo
rm -rf "$data" "$out"
"$build_dir/train/lc2wf-synthetic-data" --out "$data" --count 64 --val 4 --test 6 --seed 1555
"$build_dir/train/lc2wf-train" configs/demo.json --out "$out"
echo
echo "== Held-out test buildings, sound post-processing (default) =="
"$build_dir/infer/lc2wf-eval" --weights "$out" --data "$data/clouds" --split "$data/test.txt" \
  --out "$out/eval" --previews --method "lc2wf demo"
echo
echo "== Same buildings, the release's post-processing (--release-quirks) =="
"$build_dir/infer/lc2wf-eval" --weights "$out" --data "$data/clouds" --split "$data/test.txt" \
  --out "$out/eval-release-quirks" --release-quirks --method "lc2wf demo, release quirks" --quiet
# Plots (PNG) and the HTML report with both runs' tables; scoring the saved predictions again needs no inference.
/usr/bin/python3 "$root/tools/plots/plot_training.py" "$out" --out "$out/eval/plots/training.png" >/dev/null
/usr/bin/python3 "$root/tools/plots/plot_eval.py" "$out/eval" >/dev/null
"$build_dir/infer/lc2wf-eval" --pred "$out/eval/predictions" --data "$data/clouds" --split "$data/test.txt" \
  --out "$out/eval" --method "lc2wf demo" --html --html-compare "$out/eval-release-quirks" --quiet >/dev/null
echo
echo "Report (open in a browser; tables, buildings worst first, 3D viewer, plots): $root/$out/eval/report.html"
echo "Wireframes (.obj + scores .json): $root/$out/eval/predictions/"
echo "Previews (grey: line cloud, red: prediction, green: ground truth): $root/$out/eval/previews/"
echo "Metrics: $root/$out/eval/metrics.md (also metrics.json, per_building.csv); training log: $root/$out/log.jsonl"
echo
echo "The demo model knows only its 64 toy buildings. For your own buildings use the shipped general model:"
echo "  $build_dir/infer/lc2wf-infer --weights models/general CLOUD -o OUT --preview OUT/preview.png"
echo "  $build_dir/reconstruct/lc2wf-reconstruct PHOTOS/ --weights models/general -o OUT"
