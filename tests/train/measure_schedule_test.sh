#!/usr/bin/env bash
# bench/train/measure_schedule.sh end to end on generated buildings with the demo's network sizes: a few real
# steps of each stage, then the projection of the config's whole schedule (its epochs, its split sizes, a
# validation per val_every epochs, the hand-off); bad arguments are refused naming the argument.
# Usage: measure_schedule_test.sh BUILD_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:?usage: measure_schedule_test.sh BUILD_DIR}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$build/train/lc2wf-synthetic-data" -o "$out/data" --count 30 --val 4 --test 2 -q
# The demo's sizes (configs/demo.json as lc2wf-train resolves it); 24 training buildings, a validation every
# 5th epoch over 4 buildings.
"$build/train/lc2wf-train" "$root/configs/demo.json" --print-config > "$out/demo.json"
/usr/bin/python3 - "$out/demo.json" "$out" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
out = sys.argv[2]
config["data"].update(dir=f"{out}/data/clouds", train_split=f"{out}/data/train.txt", val_split=f"{out}/data/val.txt")
config["threads"] = 2
json.dump(config, open(f"{out}/config.json", "w"))
PY
[[ $(wc -l < "$out/data/train.txt") == 24 ]] || fail "expected 24 training buildings"

bench=$root/bench/train/measure_schedule.sh
"$bench" "$out/config.json" -o "$out/m" --steps 2 --val-buildings 2 --build "$build" > "$out/stdout"
table=$out/m/projection.md
[[ -f $table ]] || fail "no projection.md"
cmp -s "$table" "$out/stdout" || fail "stdout is not the table"
# The short run used 3 batches of the larger batch size (4) and the first 2 validation names.
[[ $(wc -l < "$out/m/train.txt") == 12 && $(wc -l < "$out/m/val.txt") == 2 ]] || fail "short splits"
# Projected over the config itself: 60 junction epochs of 24 // 4 = 6 steps, 40 edge epochs of 6 steps,
# validations after every 5th epoch (12 and 8) over the 4 validation buildings, a hand-off of 28.
grep -qE '^\| junction training \| 60 epochs × 6 steps × [0-9.]+ s \| [0-9.]+ \|$' "$table" || { cat "$table"; fail "junction row"; }
grep -qE '^\| junction validation \| 12 × 4 buildings × [0-9.]+ s \|' "$table" || { cat "$table"; fail "junction val row"; }
grep -qE '^\| hand-off \| 28 buildings at [0-9.]+/s \|' "$table" || { cat "$table"; fail "hand-off row"; }
grep -qE '^\| edge training \| 40 epochs × 6 steps × [0-9.]+ s \|' "$table" || { cat "$table"; fail "edge row"; }
grep -qE '^\| edge validation \| 8 × 4 buildings × [0-9.]+ s \|' "$table" || { cat "$table"; fail "edge val row"; }
total=$(sed -n 's/^| \*\*total\*\* | | \*\*\([0-9.]*\)\*\* |$/\1/p' "$table")
/usr/bin/python3 -c "import sys; sys.exit(0 if float('$total') > 0 else 1)" || fail "total $total"
# Both stages really trained: their logs hold steps and a validation each.
for stage in junction edge; do
  grep -q "\"stage\":\"$stage\".*\"type\":\"step\"\|\"type\":\"step\".*\"stage\":\"$stage\"" "$out/m/log.jsonl" ||
    fail "no $stage steps in the log"
done

# A given junction model is the one the edge stage starts from.
"$bench" "$out/config.json" -o "$out/given" --steps 1 --val-buildings 1 --build "$build" \
  --junction-weights "$out/m/junction/junction.safetensors" > /dev/null
cmp -s "$out/m/junction/junction.safetensors" "$out/given/edge/junction.safetensors" || fail "--junction-weights not used"

# Refusals name what is wrong.
refused() {  # refused PATTERN ARGS...
  local pattern=$1
  shift
  if "$bench" "$@" > /dev/null 2> "$out/err"; then fail "accepted: $*"; fi
  grep -q -- "$pattern" "$out/err" || { cat "$out/err"; fail "message without '$pattern'"; }
}
refused "lists 24 buildings, 84 needed" "$out/config.json" -o "$out/x" --steps 20 --build "$build"
refused "no such file" "$out/missing.json" --build "$build"
refused "--steps" "$out/config.json" --steps 0 --build "$build"
refused "--frobnicate" "$out/config.json" --frobnicate
refused "--junction-weights" "$out/config.json" --junction-weights "$out/none.safetensors" --build "$build"
echo ok
