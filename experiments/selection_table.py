#!/usr/bin/env python3
"""Rank junction selections by their validation scores.

Reads DIR/*/metrics.json (each from `lc2wf-eval --weights ... -o DIR/<tag>` with some selection flags),
prints a Markdown table best first (sAP avg, then vAP avg, then fewer pairs) and, last, the flags of the
best row. The selection of each row is read from the metrics file itself (its "inference" block), so a
row always says what produced it.

    experiments/selection_table.py runs/base/selection > runs/base/selection/table.md
"""
import argparse
import glob
import json
import math
import os
import sys


def fail(message):
    print(f"selection_table.py: {message}", file=sys.stderr)
    sys.exit(2)


def row_of(path):
    try:
        with open(path) as f:
            m = json.load(f)
        inf = m["inference"]
        wed = m["wed"]
        offset = inf.get("max_offset_m")
        return {
            "tag": os.path.basename(os.path.dirname(path)),
            "min_confidence": inf["min_confidence"],
            "nms_radius_m": inf["nms_radius_m"],
            "max_offset_m": math.inf if offset is None else offset,
            "pairs": inf["pairs_per_building"],
            "seconds": inf["seconds_per_building"],
            "vap": 100 * m["vertex_avg"]["ap"],
            "sap": 100 * m["edge_avg"]["ap"],
            "wed": wed["add_edge"] + wed["del_edge"] + wed["add_vertex"],
            "buildings": m["buildings"],
        }
    except (OSError, ValueError, KeyError, TypeError) as e:
        fail(f"{path}: not an lc2wf-eval --weights metrics file with the selection recorded ({e})")


def flags(r):
    out = f"--min-confidence {r['min_confidence']:g} --nms-radius {r['nms_radius_m']:g}"
    return out + (f" --max-offset {r['max_offset_m']:g}" if math.isfinite(r["max_offset_m"]) else "")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("dir", help="folder of lc2wf-eval outputs, one sub-folder per selection")
    a = p.parse_args()
    paths = sorted(glob.glob(os.path.join(a.dir, "*", "metrics.json")))
    if not paths:
        fail(f"{a.dir}: no */metrics.json")
    rows = [row_of(path) for path in paths]
    if len({r["buildings"] for r in rows}) != 1:
        fail(f"{a.dir}: the rows were scored on different numbers of buildings")
    rows.sort(key=lambda r: (-round(r["sap"], 1), -round(r["vap"], 1), r["pairs"], r["tag"]))
    print(f"{len(rows)} selections on {rows[0]['buildings']} buildings, best sAP avg first (then vAP avg, fewer pairs).\n")
    print("| selection | confidence > | NMS m | offsets <= m | pairs per building | s per building | vAP avg | sAP avg | WED total Num |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        offset = f"{r['max_offset_m']:g}" if math.isfinite(r["max_offset_m"]) else "any"
        print(f"| {r['tag']} | {r['min_confidence']:g} | {r['nms_radius_m']:g} | {offset} | {r['pairs']:.0f} | "
              f"{r['seconds']:.3f} | {r['vap']:.1f} | {r['sap']:.1f} | {r['wed']:.2f} |")
    print(f"\nBest: {flags(rows[0])}")


if __name__ == "__main__":
    main()
