#!/usr/bin/python3
"""Tables of run_buildings.sh results: scores of the three variants, how much of each predicted wireframe lies on
the GT (street captures see one or two sides, so vAP/sAP count the unseen ones as misses), the scale error,
pose/scale recovery and per-stage seconds."""
import json
import math
import statistics
import sys
from pathlib import Path

from edge_accuracy import read_lcloud_wireframe, read_obj_wireframe, share_within

out, names_file = Path(sys.argv[1]), sys.argv[2]
names = [n.strip() for n in open(names_file) if n.strip()]
TOLERANCE_M = 0.5

dataset_summary = out / "dataset" / "summary.json"
if dataset_summary.exists():
    d = json.load(open(dataset_summary))
    print(f"renders: capture {d.get('capture', 'orbit')}, textures {d.get('textures')}, renderer {d.get('renderer')}, "
          f"{d.get('done')} of {d.get('buildings')} buildings done")
    print()


def metrics(run):
    m = json.load(open(out / run / "metrics.json"))
    return m["vertex_avg"]["ap"] * 100, m["edge_avg"]["ap"] * 100, m["edge_avg"]["recall"] * 100


print("| clouds | vAP avg | sAP avg | sRecall avg | the seen part of the GT: vAP / sAP / sRecall |")
print("|---|---|---|---|---|")
for run, label in [("eval-known-clouds", "lc2wf-dataset, known cameras"), ("eval-given-cameras", "lc2wf-reconstruct --cameras (known)"),
                   ("eval-photos", "lc2wf-reconstruct, COLMAP poses")]:
    seen = "–"  # runs before the seen part was scored, or none succeeded
    if (out / f"{run}-seen" / "metrics.json").exists():
        seen = " / ".join(f"{x:.1f}" for x in metrics(f"{run}-seen"))
    if (out / run / "metrics.json").exists():
        v, s, r = metrics(run)
        print(f"| {label} | {v:.1f} | {s:.1f} | {r:.1f} | {seen} |")
    else:
        print(f"| {label} | – | – | – | {seen} |")  # no run succeeded (logs/exit-codes.txt)

print()
print("| building | registered | 3D lines (kept) | junctions | edges | scale from | scale / true | rotation err (deg) | exit | colmap s | lsd s | triangulation s | scale search s | inference s | total s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
totals = {}
for n in names:
    p = out / "recon-photos" / n / "report.json"
    if not p.exists():
        print(f"| {n} | not run or failed (see logs/) | | | | | | | | | | | | | |")
        continue
    r = json.load(open(p))
    sec = r["seconds"]
    ref = r.get("reference", {})
    sec.setdefault("scale search", 0.0)  # the search runs the networks itself; absent when the scale was given
    for k in ("cameras", "lsd", "triangulation", "scale search", "inference", "total"):
        totals.setdefault(k, []).append(sec[k])
    print(f"| {n} | {r['cameras']['registered']}/{r['images']['read']} | {r['lines_3d']} ({r['lines_3d'] - r.get('lines_unconfirmed', 0)}) | {r['junctions']} | {r['edges']} | {r.get('frame', {}).get('scale_source', '–')} | "
          f"{ref.get('scale_to_reference', float('nan')):.3f} | {ref.get('rotation_error_deg_median', float('nan')):.3f} | {r['exit_code']} | "
          f"{sec['cameras']:.1f} | {sec['lsd']:.2f} | {sec['triangulation']:.2f} | {sec['scale search']:.1f} | {sec['inference']:.2f} | {sec['total']:.1f} |")
if totals:
    print("| **median** | | | | | | | | | " + " | ".join(f"{statistics.median(totals[k]):.2f}" for k in ("cameras", "lsd", "triangulation", "scale search", "inference", "total")) + " |")


def on_gt(mode, name):
    """(predicted edge length, share within TOLERANCE_M of a GT edge) of a run's aligned wireframe, or None."""
    pred, cloud = out / f"pred-{mode}" / f"{name}.obj", out / "dataset" / "clouds" / f"{name}.lcloud"
    if not pred.exists() or not cloud.exists():
        return None
    return share_within(read_obj_wireframe(pred), read_lcloud_wireframe(cloud), TOLERANCE_M)


def scale_error(name):
    """|estimated / true size - 1| of the COLMAP-pose run: report.json's reference.scale_to_reference maps our
    frame onto the render cameras' (1 = the scale estimate was exact)."""
    p = out / "recon-photos" / name / "report.json"
    if not p.exists():
        return None
    s = json.load(open(p)).get("reference", {}).get("scale_to_reference")
    return abs(1.0 / s - 1.0) if s else None


def number(v, fmt):
    return "–" if v is None or math.isnan(v) else format(v, fmt)


def percent(v):
    return "–" if v is None or math.isnan(v) else f"{v * 100:.1f} %"


print()
print(f"Predicted edge length within {TOLERANCE_M} m of a GT edge (aligned wireframes) and the scale error of the COLMAP-pose run:")
print()
print("| building | COLMAP poses: edge length m | on GT | known cameras: edge length m | on GT | scale error |")
print("|---|---|---|---|---|---|")
shares = {"photos": [], "given-cameras": []}
errors = []
for n in names:
    row = [n]
    for mode in ("photos", "given-cameras"):
        length, share = on_gt(mode, n) or (None, None)
        row += [number(length, ".1f"), percent(share)]
        if share is not None and not math.isnan(share):
            shares[mode].append(share)
    e = scale_error(n)
    if e is not None:
        errors.append(e)
    row.append(percent(e))
    print("| " + " | ".join(row) + " |")
median = lambda v: statistics.median(v) if v else None
print(f"| **median** | | {percent(median(shares['photos']))} | | {percent(median(shares['given-cameras']))} | {percent(median(errors))} |")
