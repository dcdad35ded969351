#!/usr/bin/env bash
# experiments/model_card.py on fixtures: a training log with kept epochs, the resolved base config and a test
# evaluation; the card must carry the licence, the test metrics as read from metrics.json, the inference
# time, the training time summed from the log and each stage's matrix-product precision (or that it was
# not recorded), and a missing metrics file must be named.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mkdir -p "$out/run" "$out/test"
cp "$root/configs/base.json" "$out/run/config.json"
cat > "$out/run/log.jsonl" <<'LOG'
{"stage":"junction","type":"step","epoch":1,"step":1,"loss":2.0,"seconds":1800.0,"cpu_seconds":3600.0}
{"stage":"junction","type":"val","epoch":1,"step":1,"score":0.5,"best":true,"seconds":1800.0}
{"stage":"junction","type":"epoch","epoch":1,"step":1,"train_loss":2.0,"seconds":1800.0}
{"stage":"handoff","type":"handoff","step":0,"seconds":360.0}
{"stage":"edge","type":"step","epoch":1,"step":1,"loss":1.0,"seconds":7200.0,"cpu_seconds":14400.0}
{"stage":"edge","type":"val","epoch":1,"step":1,"score":0.25,"best":true,"seconds":0.0}
{"stage":"edge","type":"epoch","epoch":1,"step":1,"train_loss":1.0,"seconds":7200.0,"precision":"bf16","gemm":"openblas (SkylakeX)"}
LOG
/usr/bin/python3 - "$root/tests/tools/plots/metrics.json" "$out/test/metrics.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["inference"] = {"buildings": m["buildings"], "threads": 2, "seconds_per_building": 0.5, "junction_seconds_per_building": 0.1,
                  "edge_seconds_per_building": 0.3, "post_seconds_per_building": 0.1, "max_seconds": 1.0,
                  "pairs_per_building": 210.0, "empty_wireframes": 0, "min_confidence": 0.1, "nms_radius_m": 0.5,
                  "max_offset_m": 0.75}
json.dump(m, open(sys.argv[2], "w"))
PY
/usr/bin/python3 "$root/experiments/model_card.py" --run "$out/run" --eval "$out/test" -o "$out/model/README.md"
card="$out/model/README.md"
vap=$(/usr/bin/python3 -c "import json; m = json.load(open('$out/test/metrics.json')); print(f\"{100 * m['vertex_avg']['ap']:.1f}\")")
for want in "CC BY-NC 4.0" "non-commercial use only" "Roof-Image" "| LC2WF paper, Table 2 | 93.0 | 80.4 | 5.301 / 27.33 |" \
            "| lc2wf, sound post-processing | $vap / " "0.500 s per building" "210 pairs" \
            "confidence > 0.1 after point NMS 0.5 m, candidates regressed at most 0.75 m from their sample point" \
            "junction: 1 steps of 16 buildings, 1.0 h wall (1.0 CPU-h in steps), kept epoch 1 of 41 (vAP mean 50.0 %" \
            "edge: 1 steps of 32 buildings, 2.0 h wall" "hand-off: 0.10 h" \
            "1 epoch(s): not recorded." "1 epoch(s): bf16 products by openblas (SkylakeX)." \
            "**unfinished**: the junction stage had run 1 of its 41 epochs" "the edge stage had run 1 of its 31 epochs"; do
  grep -qF -- "$want" "$card" || { echo "model card lacks: $want"; cat "$card"; exit 1; }
done
# A run whose stages ran all their epochs is not called unfinished.
/usr/bin/python3 - "$out/run/config.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["junction"]["epochs"] = c["edge"]["epochs"] = 1
json.dump(c, open(sys.argv[1], "w"))
PY
/usr/bin/python3 "$root/experiments/model_card.py" --run "$out/run" --eval "$out/test" -o "$out/done/README.md"
if grep -q "unfinished" "$out/done/README.md"; then echo "a finished run was called unfinished"; exit 1; fi
# A missing evaluation is named, and nothing is written.
if /usr/bin/python3 "$root/experiments/model_card.py" --run "$out/run" --eval "$out/nowhere" -o "$out/bad/README.md" 2>"$out/err"; then
  echo "a missing metrics.json was accepted"; exit 1
fi
grep -q "nowhere/metrics.json" "$out/err" || { echo "error does not name the file:"; cat "$out/err"; exit 1; }
[[ ! -e "$out/bad/README.md" ]] || { echo "a card was written without metrics"; exit 1; }
echo "ok"
