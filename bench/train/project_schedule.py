#!/usr/bin/env python3
"""Projects the wall time of a full lc2wf-train schedule from a short measured run.

Usage: project_schedule.py CONFIG.json LOG.jsonl [--config-name NAME] [--train N] [--val M] [--skip-first K] [--cpu-threads T]

CONFIG is the schedule to project, as lc2wf-train CONFIG --print-config resolves it (a config that
"extends" another holds only its differences): epochs, batch sizes, val_every, drop_last.
LOG is the log.jsonl of a short run at the same network sizes and batch sizes on the same kind of data
(e.g. the config with max_steps_per_epoch: 3). Split sizes default to the config's split files.
Measured per stage: the median seconds of an optimiser step (the first K steps are skipped: warm-up),
the seconds of a validation pass scaled to the full validation split, and the hand-off's buildings/s.
With --cpu-threads T a step costs its logged process CPU seconds divided by T instead of its wall
seconds: what the step would take with T fully used cores, the estimate to use when the log was written
on a machine shared with other jobs (it ignores imperfect parallel scaling, so it is a lower bound).
Prints a Markdown table and the total in hours.
"""
import argparse
import json
import math
import statistics
import sys
from pathlib import Path


def read_log(path):
    lines = []
    for number, text in enumerate(Path(path).read_text().splitlines(), 1):
        if not text.strip():
            continue
        try:
            lines.append(json.loads(text))
        except json.JSONDecodeError as e:
            sys.exit(f"{path}:{number}: not JSON ({e})")
    return lines


def count_names(path):
    return sum(1 for line in Path(path).read_text().splitlines() if line.strip())


def stage_numbers(log, stage, skip_first, cpu_threads=None):
    records = [l for l in log if l.get("stage") == stage and l.get("type") == "step"][skip_first:]
    if cpu_threads:
        # Logs written before cpu_seconds existed lack it on their early steps: those are left out.
        steps = [l["cpu_seconds"] / cpu_threads for l in records if "cpu_seconds" in l]
    else:
        steps = [l["seconds"] for l in records]
    vals = [l for l in log if l.get("stage") == stage and l.get("type") == "val"]
    if not steps:
        sys.exit(f"the log has no {stage} steps after skipping {skip_first}")
    val_seconds_per_building = None
    if vals:
        per = [v["seconds"] / max(1, v.get("buildings", 1)) for v in vals]
        val_seconds_per_building = statistics.median(per)
    return statistics.median(steps), val_seconds_per_building


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("config")
    ap.add_argument("--config-name", help="the config's name in the table's title (default: CONFIG)")
    ap.add_argument("log")
    ap.add_argument("--train", type=int, help="training buildings (default: the config's train split)")
    ap.add_argument("--val", type=int, help="validation buildings (default: the config's val split)")
    ap.add_argument("--skip-first", type=int, default=1, help="warm-up steps per stage left out (default 1)")
    ap.add_argument("--cpu-threads", type=int, help="step cost = logged CPU seconds / this many cores")
    args = ap.parse_args()

    config = json.loads(Path(args.config).read_text())
    log = read_log(args.log)
    n_train = args.train if args.train is not None else count_names(config["data"]["train_split"])
    n_val = args.val if args.val is not None else count_names(config["data"]["val_split"])

    rows, total = [], 0.0
    for stage in ("junction", "edge"):
        c = config[stage]
        step_s, val_s = stage_numbers(log, stage, args.skip_first, args.cpu_threads)
        batches = n_train // c["batch_size"] if c["drop_last"] else math.ceil(n_train / c["batch_size"])
        epochs = c["epochs"]
        validations = len({e for e in range(1, epochs + 1) if e % c["val_every"] == 0 or e == epochs})
        train_h = epochs * batches * step_s / 3600
        val_h = validations * n_val * (val_s or 0.0) / 3600
        kind = f" (CPU s / {args.cpu_threads})" if args.cpu_threads else ""
        rows.append((f"{stage} training", f"{epochs} epochs × {batches} steps × {step_s:.2f} s{kind}", train_h))
        rows.append((f"{stage} validation", f"{validations} × {n_val} buildings × {(val_s or 0):.3f} s", val_h))
        total += train_h + val_h
        if stage == "junction":
            handoff = [l for l in log if l.get("type") == "handoff"]
            if handoff:
                rate = handoff[-1]["buildings_per_s"]
                h = (n_train + n_val) / rate / 3600
                rows.append(("hand-off", f"{n_train + n_val} buildings at {rate:.2f}/s", h))
                total += h

    print(f"Projection of {args.config_name or args.config} from {args.log} ({n_train} train / {n_val} val buildings)\n")
    print("| part | from | hours |\n|---|---|---|")
    for name, how, hours in rows:
        print(f"| {name} | {how} | {hours:.2f} |")
    print(f"| **total** | | **{total:.2f}** |")


if __name__ == "__main__":
    main()
