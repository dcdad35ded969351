# Steps edge-cheaper and fast-check: is a cheaper edge stage as good as the paper's? (sourced by
# experiments/run.sh; the evidence is in experiments/README.md, "A cheaper edge stage", and edge-cheaper/).

# The edge stage of $1/config.json from models/base's junction model, resumed where it stopped.
run_edge_stage() {
  local resume=()
  [[ -f $1/junction.safetensors ]] || cp models/base/junction.safetensors "$1/junction.safetensors"
  [[ -d $1/checkpoints ]] && resume=(--resume)
  "$build_dir/train/lc2wf-train" "$1/config.json" --stage edge --out "$1" -q "${resume[@]}"
}

# Best validation scores and step cost of every run folder under $1 (an edge stage each) -> $1/table.md.
edge_runs_table() {
  /usr/bin/python3 - "$1" <<'PY' | tee "$1/table.md"
import json, statistics, sys
from pathlib import Path
print("| variant | best val sAP avg | its vAP avg | its WED | median s per step |")
print("|---|---|---|---|---|")
for run in sorted(p for p in Path(sys.argv[1]).iterdir() if (p / "log.jsonl").exists()):
    records = [json.loads(line) for line in open(run / "log.jsonl")]
    val = [r for r in records if r.get("type") == "val" and r.get("stage") == "edge"]
    steps = [r["seconds"] for r in records if r.get("type") == "step" and r.get("stage") == "edge" and "seconds" in r]
    if not val:
        continue
    best = max(val, key=lambda r: r["sAP_mean"])
    step = f"{statistics.median(steps):.2f}" if steps else "-"
    print(f"| {run.name} | {100 * best['sAP_mean']:.1f} | {100 * best['vAP_mean']:.1f} | {best['wed_total']:.2f} | {step} |")
PY
}

# The edge stage is two thirds of base.json's wall time; is half of it as good? Each variant is base.json's
# edge stage (milestones scaled to the shorter schedule) on models/base's junction model, trained on every
# 4th training building of the 30-view clouds and validated on the whole validation split.
step_edge_cheaper() {
  local out=runs/edge-cheaper
  mkdir -p "$out"
  awk 'NR % 4 == 1' configs/splits/train.txt > "$out/train.txt"
  local variant
  for variant in p512-s1 p256-s1 p512-s2 l32-s1 l32-s2; do  # the cheaper variant right after the first reference
    local dir=$out/$variant
    mkdir -p "$dir"
    /usr/bin/python3 - configs/base.json "$dir/config.json" "$variant" "$out/train.txt" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
variant, train = sys.argv[3], sys.argv[4]
config["seed"] = 1555 + int(variant.split("-s")[1])
config["data"].update(dir="runs/dataset-30v/clouds", train_split=train)
edge = config["edge"]
edge["epochs"], edge["optim"]["milestones"] = 8, [4, 7]
edge["val_every"] = 2  # after epochs 2, 4, 6, 8: a validation pass costs half an epoch here
if variant.startswith("p256"):
    edge["net"]["lpt"]["patches"], edge["max_static_pairs"] = 256, 128  # half the pairs, the same GT share
if variant.startswith("l32"):
    edge["net"]["lpt"]["lines_per_patch"] = 32  # 16 lines around each junction of a pair
json.dump(config, open(sys.argv[2] + ".tmp", "w"), indent=2)
PY
    mv "$dir/config.json.tmp" "$dir/config.json"
    run_edge_stage "$dir"
  done
  edge_runs_table "$out"
}

# Does configs/fast.json (32 lines per pair patch) keep the paper's edge quality at the full schedule? Each
# run is the edge stage of its config on the 30-view clouds from models/base's junction model; only
# edge.net.lpt.lines_per_patch differs.
step_fast_check() {
  local out=runs/fast-check run
  for run in fast base; do
    local dir=$out/$run
    mkdir -p "$dir"
    # The config as resolved (its "extends" merged), so the copy stands alone in its run folder.
    "$build_dir/train/lc2wf-train" "configs/$run.json" --print-config > "$dir/config.json.resolved"
    /usr/bin/python3 - "$dir/config.json.resolved" "$dir/config.json" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
config["data"]["dir"] = "runs/dataset-30v/clouds"
json.dump(config, open(sys.argv[2] + ".tmp", "w"), indent=2)
PY
    mv "$dir/config.json.tmp" "$dir/config.json"
    rm -f "$dir/config.json.resolved"
    run_edge_stage "$dir"
  done
  edge_runs_table "$out"
}
