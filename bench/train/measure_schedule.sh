#!/usr/bin/env bash
# How long would CONFIG's whole schedule take on this machine? Trains a few optimiser steps of each stage at
# the config's own sizes on its own data, times a validation pass over a sample of its validation split and
# the hand-off, then projects every epoch of the schedule with bench/train/project_schedule.py.
#
# Usage: bench/train/measure_schedule.sh CONFIG.json [-o OUT] [--steps N] [--val-buildings M]
#                                        [--junction-weights FILE] [--build DIR] [-j THREADS]
#   -o, --out OUT             work folder (default runs/measure-<config name>); OUT/projection.md is the result
#   --steps N                 timed steps per stage (default 10; one more runs first as the warm-up)
#   --val-buildings M         validation buildings timed per stage (default 50; scaled to the whole split)
#   --junction-weights FILE   junction model the edge stage starts from (default: the one this script
#                             trains for a few steps). Its junctions set how many pairs validation scores, so
#                             pass a trained one (models/base/junction.safetensors for configs/base.json)
#                             for a representative edge validation time
#   --build DIR               build folder holding train/lc2wf-train (default build)
#   -j, --threads T           compute threads (default: the config's)
# The machine should be otherwise idle: the projection is this machine's wall time.
set -euo pipefail
usage() { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; }
die() { echo "measure_schedule: $*" >&2; exit 2; }
root=$(cd "$(dirname "$0")/../.." && pwd)
config="" out="" steps=10 val_buildings=50 junction_weights="" build="$root/build" threads=()
while (($#)); do
  case $1 in
    -h | --help) usage; exit 0 ;;
    -o | --out) out=${2:?"-o needs a folder"}; shift 2 ;;
    --steps) steps=${2:?"--steps needs a number"}; shift 2 ;;
    --val-buildings) val_buildings=${2:?"--val-buildings needs a number"}; shift 2 ;;
    --junction-weights) junction_weights=${2:?"--junction-weights needs a file"}; shift 2 ;;
    --build) build=${2:?"--build needs a folder"}; shift 2 ;;
    -j | --threads) threads=(--threads "${2:?"--threads needs a number"}"); shift 2 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [[ -z $config ]] || die "one CONFIG only, got $config and $1"; config=$1; shift ;;
  esac
done
[[ -n $config ]] || { usage >&2; exit 2; }
[[ -f $config ]] || die "CONFIG $config: no such file"
[[ $steps =~ ^[1-9][0-9]*$ ]] || die "--steps must be a positive whole number, got $steps"
[[ $val_buildings =~ ^[1-9][0-9]*$ ]] || die "--val-buildings must be a positive whole number, got $val_buildings"
[[ -z $junction_weights || -f $junction_weights ]] || die "--junction-weights $junction_weights: no such file"
train_exe=$build/train/lc2wf-train
[[ -x $train_exe ]] || die "--build $build: no train/lc2wf-train in it (tools/build.sh builds it)"
out=${out:-runs/measure-$(basename "$config" .json)}
mkdir -p "$out"
# The config as lc2wf-train reads it ("extends" merged, every key present); a bad config stops here.
"$train_exe" "$config" --print-config > "$out/resolved.json" || die "CONFIG $config: not an lc2wf-train config"

# The short run: the config itself with one epoch per stage, as many training buildings as steps + 1
# batches need and the first val_buildings validation names, every other key (sizes, batches, precision) as is.
/usr/bin/python3 - "$config" "$out" "$steps" "$val_buildings" <<'PY'
import json, sys
from pathlib import Path
config_path, out, steps, val_buildings = sys.argv[1], Path(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
try:
    config = json.loads((out / "resolved.json").read_text())
    data = config["data"]
    batches = [config[stage]["batch_size"] for stage in ("junction", "edge")]
except (json.JSONDecodeError, KeyError, TypeError) as e:
    sys.exit(f"measure_schedule: {config_path}: not an lc2wf-train config ({e})")

def names(key, count):
    path = Path(data.get(key, ""))
    if not path.is_file():
        sys.exit(f"measure_schedule: {config_path}: data.{key} {path}: no such file")
    listed = [n for n in path.read_text().split() if n]
    if len(listed) < count:
        sys.exit(f"measure_schedule: {config_path}: data.{key} lists {len(listed)} buildings, {count} needed")
    return listed[:count]

(out / "train.txt").write_text("\n".join(names("train_split", (steps + 1) * max(batches))) + "\n")
(out / "val.txt").write_text("\n".join(names("val_split", val_buildings)) + "\n")
data.update(train_split=str(out / "train.txt"), val_split=str(out / "val.txt"))
for stage in ("junction", "edge"):
    config[stage].update(epochs=1, max_steps_per_epoch=steps + 1, val_every=1)
config["init_weights"] = ""
(out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
PY

# Each stage in its own folder, so a given junction model never mixes with the one trained here.
rm -rf "$out/junction" "$out/edge"
"$train_exe" "$out/config.json" --stage junction --out "$out/junction" -q "${threads[@]}"
mkdir -p "$out/edge"
cp "${junction_weights:-$out/junction/junction.safetensors}" "$out/edge/junction.safetensors"
"$train_exe" "$out/config.json" --stage edge --out "$out/edge" -q "${threads[@]}"
cat "$out/junction/log.jsonl" "$out/edge/log.jsonl" > "$out/log.jsonl"
/usr/bin/python3 "$root/bench/train/project_schedule.py" "$out/resolved.json" "$out/log.jsonl" --config-name "$config" --skip-first 1 \
  | tee "$out/projection.md.tmp"
mv "$out/projection.md.tmp" "$out/projection.md"
