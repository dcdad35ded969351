#!/usr/bin/env bash
# bf16 against fp32 in training: the junction stage of configs/base.json (the paper's network) on a real
# subset — every 9th building of the train split (292) and every 2nd of the val split (100) — for 10 epochs
# (lr 1e-3, 1e-4 from epoch 8), three runs: fp32 and bf16 from the same seed, and fp32 from another seed
# (the run-to-run noise to compare the bf16 difference with). Runs one after the other and resumes
# (lc2wf-train --resume), so a killed study continues where it stopped. train/README.md has the results.
#   experiments/bf16_study.sh [OUT_DIR=runs/bf16-study] [BUILD_DIR=build]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-runs/bf16-study}
build=${2:-build}
mkdir -p "$out"
awk 'NR % 9 == 1' "$root/configs/splits/train.txt" > "$out/train.txt"
awk 'NR % 2 == 1' "$root/configs/splits/val.txt" > "$out/val.txt"
for run in fp32-s1555:fp32:1555 bf16-s1555:bf16:1555 fp32-s1556:fp32:1556; do
  IFS=: read -r name precision seed <<<"$run"
  /usr/bin/python3 - "$root/configs/base.json" "$out" "$name" "$precision" "$seed" <<'PY'
import json, sys
base, out, name, precision, seed = sys.argv[1:]
c = json.load(open(base))
c["seed"], c["precision"], c["out"] = int(seed), precision, f"{out}/{name}"
c["data"]["train_split"], c["data"]["val_split"] = f"{out}/train.txt", f"{out}/val.txt"
c["junction"]["epochs"] = 10
c["junction"]["optim"]["milestones"] = [8]
json.dump(c, open(f"{out}/{name}.json", "w"), indent=2)
PY
  resume=()
  [[ -d "$out/$name/checkpoints" ]] && resume=(--resume)
  "$build/train/lc2wf-train" "$out/$name.json" --stage junction -q "${resume[@]}"
  echo "$name done"
done
/usr/bin/python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
print("| run | val vAP mean per epoch | last | best | CPU-s per step (median) |")
print("|---|---|---|---|---|")
for name in ["fp32-s1555", "bf16-s1555", "fp32-s1556"]:
    rows = [json.loads(l) for l in open(f"{out}/{name}/log.jsonl")]
    vap = [r for r in rows if r.get("type") == "val"]
    steps = sorted(r["cpu_seconds"] for r in rows if r.get("type") == "step")
    key = next(k for k in vap[-1] if "vap" in k.lower() and "mean" in k.lower())
    series = [100 * r[key] for r in vap]
    print(f"| {name} | {' '.join(f'{v:.1f}' for v in series)} | {series[-1]:.1f} | {max(series):.1f} | {steps[len(steps) // 2]:.2f} |")
PY
