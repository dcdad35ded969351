#!/usr/bin/env python3
"""Projects the step time and scaling efficiency of data-parallel lc2wf-train on N machines.

Usage: project_scaling.py --step-seconds 1:1.5,2:2.6,4:4.9,16:18.4 --batch 16 --grad-bytes 6.2e6
                          [--ranks 4,8,16,32,64] [--gbps 10,25,100] [--latency-us 30] [--small-sums 32]
                          [--check RANKS:STEP_S:ALLREDUCE_S:COMPUTE_S:LATENCY_S]

Model (one rank per machine, all of the machine's cores for its compute threads):
  step(N) = compute(ceil(B / N)) + allreduce(N) + small_sums * ceil(log2 N) * latency
  compute(b)   the measured step seconds of one process at local batch b (linear between the measured b)
  allreduce(N) ring sum of the gradients: 2 (N - 1) / N * bytes / bandwidth + 2 (N - 1) * latency,
               none of it hidden by the backward pass (the trainer starts buckets early, so this is an
               upper bound)
  small sums   the per-step sums of a few numbers (loss terms, dropout stream, replica check, and with
               synchronised BatchNorm two per BatchNorm layer and pass), latency-bound
Efficiency = step(1) / (N * step(N)) with step(1) = compute(B): the speed-up per machine against one
machine. Ranks beyond B get no buildings, so N > B adds nothing.
--check compares the model with a measured run on one machine: N ranks, the measured step seconds of a
rank, the measured gradient sum seconds and small-sum latency (allreduce_bench on that machine) and the
measured step seconds of one process doing one rank's share alone with one rank's threads; prints the
prediction and the error. On a machine shared with other jobs use CPU seconds (cpu_seconds in the log)
for both steps: wall seconds then measure the share of the machine a run got, not its work.
"""
import argparse
import math


def parse_points(text):
    points = {}
    for item in text.split(","):
        b, s = item.split(":")
        points[int(b)] = float(s)
    return dict(sorted(points.items()))


def compute_seconds(points, b):
    keys = list(points)
    if b in points:
        return points[b]
    if b < keys[0] or b > keys[-1]:
        raise SystemExit(f"local batch {b} is outside the measured range {keys[0]}..{keys[-1]}")
    for lo, hi in zip(keys, keys[1:]):
        if lo <= b <= hi:
            return points[lo] + (points[hi] - points[lo]) * (b - lo) / (hi - lo)


def allreduce_seconds(n, grad_bytes, gbps, latency):
    if n == 1:
        return 0.0
    return 2 * (n - 1) / n * grad_bytes / (gbps * 1e9 / 8) + 2 * (n - 1) * latency


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--step-seconds", required=True, help="local batch:seconds of one machine, comma-separated")
    ap.add_argument("--batch", type=int, required=True, help="the config's global batch_size")
    ap.add_argument("--grad-bytes", type=float, required=True, help="bytes summed per step (4 per parameter)")
    ap.add_argument("--ranks", default="4,8,16,32,64")
    ap.add_argument("--gbps", default="10,25,100")
    ap.add_argument("--latency-us", type=float, default=30.0, help="per-message latency of the network (TCP: 20-50)")
    ap.add_argument("--small-sums", type=int, default=32, help="latency-bound sums per step")
    ap.add_argument("--check", help="ranks:measured_step_s:allreduce_s:compute_s:latency_s of a run on one machine")
    args = ap.parse_args()

    points = parse_points(args.step_seconds)
    latency = args.latency_us * 1e-6
    one = compute_seconds(points, args.batch)
    print(f"one machine: {one:.2f} s per step of {args.batch} buildings\n")
    print("| machines | local batch | " + " | ".join(f"{g:g} Gb/s: step s / speed-up / efficiency" for g in map(float, args.gbps.split(","))) + " |")
    print("|---|---|" + "---|" * len(args.gbps.split(",")))
    for n in map(int, args.ranks.split(",")):
        local = math.ceil(args.batch / n)
        cells = []
        for g in map(float, args.gbps.split(",")):
            step = compute_seconds(points, local) + allreduce_seconds(n, args.grad_bytes, g, latency) + \
                args.small_sums * math.ceil(math.log2(n)) * latency
            cells.append(f"{step:.3f} / {one / step:.1f}x / {100 * one / (n * step):.0f} %")
        print(f"| {n} | {local} | " + " | ".join(cells) + " |")

    if args.check:
        n, measured, allreduce, compute, small = args.check.split(":")
        predicted = float(compute) + float(allreduce) + args.small_sums * math.ceil(math.log2(int(n))) * float(small)
        print(f"\ncheck: {n} ranks on one machine, predicted {predicted:.3f} s per step, measured {float(measured):.3f} s "
              f"({100 * (float(measured) - predicted) / predicted:+.1f} %)")


if __name__ == "__main__":
    main()
