#!/usr/bin/env bash
# tools/plots/ on fixtures: a hand-made training log and a small evaluation's metrics.json; each script must
# write a non-trivial PNG. Exit 77 (CTest: skipped) when Debian's python3-matplotlib is missing.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
if ! /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  echo "skipped: /usr/bin/python3 has no matplotlib (apt-get install python3-matplotlib, tools/setup-deps.sh)"
  exit 77
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$root/tools/plots/plot_training.py" "$here/log.jsonl" --out "$out/training.png"
mkdir -p "$out/eval" && cp "$here/metrics.json" "$out/eval/"
"$root/tools/plots/plot_eval.py" "$out/eval"
for png in "$out/training.png" "$out/eval/plots/errors.png"; do
  size=$(stat -c %s "$png")
  [[ $(head -c 8 "$png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a && $size -gt 20000 ]] ||
    { echo "bad PNG $png ($size bytes)"; exit 1; }
done
# Errors name the argument.
if "$root/tools/plots/plot_eval.py" "$out/eval" --eta 0.3 2>"$out/err"; then echo "bad --eta accepted"; exit 1; fi
grep -q -- "--eta" "$out/err"
echo "ok"
