#!/usr/bin/env bash
# Runs the LPT workloads of bench/nn/lpt_bench and bench/torch_lpt.py side by side (alternating, one
# process per workload so peak RSS is per workload) and prints time and memory ratios.
#
#   bench/compare.sh [--build DIR] [--workloads "junction_train edge_train junction_infer edge_infer"]
#                    (also junction_train_bf16, edge_train_bf16, junction_infer_bf16, edge_infer_bf16: ours
#                    with bf16 operands against PyTorch's fp32)
#                    [--train-iters N] [--infer-iters N] [--threads N]
#
# PyTorch runs at its best setting on this machine (OPENBLAS_CORETYPE=SkylakeX: OpenBLAS's fastest kernels here).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
build="$here/../build-nn"
workloads="junction_train edge_train junction_infer edge_infer"
train_iters=3
infer_iters=10
threads=2

usage() { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --workloads) workloads="$2"; shift 2 ;;
    --train-iters) train_iters="$2"; shift 2 ;;
    --infer-iters) infer_iters="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "compare.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

bench="$build/bench/nn/lpt_bench"
[[ -x "$bench" ]] || { echo "compare.sh: $bench not found; build the lpt_bench target first" >&2; exit 1; }
py=/usr/bin/python3
"$py" -c "import torch" 2>/dev/null || { echo "compare.sh: $py has no torch (apt-get install python3-torch)" >&2; exit 1; }

export OMP_NUM_THREADS=$threads OPENBLAS_NUM_THREADS=$threads OPENBLAS_CORETYPE=SkylakeX

# *_bf16: our step with bf16 GEMM operands against PyTorch's fp32 step (Debian's PyTorch cannot autocast
# this model to bf16 on the CPU).
declare -A filter=([junction_train]=BM_JunctionTrainStep/fused:1/bf16:0/recompute:0 [edge_train]=BM_EdgeTrainStep/fused:1/bf16:0/recompute:0
                   [junction_train_bf16]=BM_JunctionTrainStep/fused:1/bf16:1/recompute:0 [edge_train_bf16]=BM_EdgeTrainStep/fused:1/bf16:1/recompute:0
                   [junction_infer]=BM_JunctionInference/bf16:0 [edge_infer]=BM_EdgeInference/bf16:0
                   [junction_infer_bf16]=BM_JunctionInference/bf16:1 [edge_infer_bf16]=BM_EdgeInference/bf16:1)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Ratios only mean something next to the CPU they were measured on.
cpu_model=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
simd_flags=$(grep -m1 '^flags' /proc/cpuinfo | tr ' ' '\n' | grep -E '^(avx|avx2|fma|f16c|avx512f|avx512bw|avx512vl|avx512_bf16|amx_bf16|amx_tile)$' | sort | tr '\n' ' ')
echo "CPU: $cpu_model, $(nproc) cores; SIMD flags: ${simd_flags:-none}"
printf '%-15s %10s %10s %8s %10s %10s %8s\n' workload ours_s torch_s speedup ours_MB torch_MB rss_ratio
for w in $workloads; do
  [[ -n "${filter[$w]:-}" ]] || { echo "compare.sh: unknown workload '$w'" >&2; exit 2; }
  iters=$infer_iters
  [[ $w == *_train* ]] && iters=$train_iters
  # Our benchmark fixes its iteration counts; it prints the mean seconds and the peak RSS counter.
  "$bench" --benchmark_filter="^${filter[$w]}/" --benchmark_format=json > "$tmp/ours.json"
  read -r ours_s ours_mb < <("$py" -c '
import json, sys
b = json.load(open(sys.argv[1]))["benchmarks"][0]
scale = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}[b["time_unit"]]
print(b["real_time"] * scale, b["peak_rss_MB"])' "$tmp/ours.json")
  line=$("$py" "$here/torch_lpt.py" "${w%_bf16}" --iters "$iters" --threads "$threads")
  torch_s=$(sed -n 's/.*median_s=\([0-9.]*\).*/\1/p' <<<"$line")
  torch_mb=$(sed -n 's/.*peak_rss_MB=\([0-9.]*\).*/\1/p' <<<"$line")
  awk -v w="$w" -v a="$ours_s" -v b="$torch_s" -v c="$ours_mb" -v d="$torch_mb" \
    'BEGIN { printf "%-15s %10.3f %10.3f %7.2fx %10.0f %10.0f %8.2f\n", w, a, b, b / a, c, d, c / d }'
done
echo "(speedup = torch/ours time; rss_ratio = ours/torch peak RSS; load average: $(cut -d' ' -f1-3 /proc/loadavg))"
