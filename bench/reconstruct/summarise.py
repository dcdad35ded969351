#!/usr/bin/env python3
"""Table of run_buildings.sh results: scores of the three variants, pose/scale recovery, per-stage seconds."""
import json
import statistics
import sys
from pathlib import Path

out, names_file = Path(sys.argv[1]), sys.argv[2]
names = [n.strip() for n in open(names_file) if n.strip()]


def metrics(run):
    m = json.load(open(out / run / "metrics.json"))
    return m["vertex_avg"]["ap"] * 100, m["edge_avg"]["ap"] * 100, m["edge_avg"]["recall"] * 100


print("| clouds | vAP avg | sAP avg | sRecall avg |")
print("|---|---|---|---|")
for run, label in [("eval-known-clouds", "lc2wf-dataset, known cameras"), ("eval-given-cameras", "lc2wf-reconstruct --cameras (known)"),
                   ("eval-photos", "lc2wf-reconstruct, COLMAP poses")]:
    if (out / run / "metrics.json").exists():
        v, s, r = metrics(run)
        print(f"| {label} | {v:.1f} | {s:.1f} | {r:.1f} |")

print()
print("| building | registered | 3D lines (kept) | junctions | edges | scale / true | rotation err (deg) | exit | colmap s | lsd s | triangulation s | inference s | total s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
totals = {}
for n in names:
    p = out / "recon-photos" / n / "report.json"
    if not p.exists():
        print(f"| {n} | not run or failed (see logs/) | | | | | | | | | | | |")
        continue
    r = json.load(open(p))
    sec = r["seconds"]
    ref = r.get("reference", {})
    for k in ("cameras", "lsd", "triangulation", "inference", "total"):
        totals.setdefault(k, []).append(sec[k])
    print(f"| {n} | {r['cameras']['registered']}/{r['images']['read']} | {r['lines_3d']} ({r['lines_3d'] - r.get('lines_unconfirmed', 0)}) | {r['junctions']} | {r['edges']} | "
          f"{ref.get('scale_to_reference', float('nan')):.3f} | {ref.get('rotation_error_deg_median', float('nan')):.3f} | {r['exit_code']} | "
          f"{sec['cameras']:.1f} | {sec['lsd']:.2f} | {sec['triangulation']:.2f} | {sec['inference']:.2f} | {sec['total']:.1f} |")
if totals:
    print("| **median** | | | | | | | | " + " | ".join(f"{statistics.median(totals[k]):.2f}" for k in ("cameras", "lsd", "triangulation", "inference", "total")) + " |")
