#!/usr/bin/env python3
"""Markdown table comparing lc2wf-dataset summaries (e.g. --renderer raster vs blender on the same shard).

usage: compare_summaries.py NAME=OUT_DIR/summary.json [NAME=...]
"""
import json
import sys


def row(label, values):
    return "| " + label + " | " + " | ".join(values) + " |"


def main(argv):
    if len(argv) < 2 or any("=" not in a for a in argv[1:]):
        sys.exit(__doc__)
    names, sums = [], []
    for a in argv[1:]:
        name, path = a.split("=", 1)
        with open(path) as f:
            sums.append(json.load(f))
        names.append(name)
    out = [row("", names), "|---|" + "---|" * len(names)]
    out.append(row("buildings done / failed", [f"{s['done']} / {len(s['failed'])}" for s in sums]))
    out.append(row("2D segments per building (mean)", [f"{s['segments_2d_per_building']['mean']:.0f}" for s in sums]))
    out.append(row("3D segments per building (mean / median)",
                   [f"{s['segments_per_building']['mean']:.0f} / {s['segments_per_building']['median']:.0f}" for s in sums]))
    out.append(row("share f=1 (pooled / per-building mean)",
                   [f"{100 * s['positive_share']['pooled']:.1f}% / {100 * s['positive_share']['mean']:.1f}%" for s in sums]))
    out.append(row("shorter than the mean GT edge (pooled)",
                   [f"{100 * s['shorter_than_mean_gt_edge_share']['pooled']:.1f}%" for s in sums]))
    out.append(row("GT edges covered by an f=1 segment (mean)",
                   [f"{100 * s['gt_edge_coverage_by_positives']['mean']:.1f}%" for s in sums]))
    if all("positive_edge_distance_m" in s for s in sums):
        out.append(row("f=1 distance to their GT edge, m (median / p90)",
                       [f"{s['positive_edge_distance_m']['median']:.3f} / {s['positive_edge_distance_m']['p90']:.3f}" for s in sums]))
    if all("triangulation_per_building" in s for s in sums):
        for key, label in [("with_hypothesis", "with a hypothesis"), ("with_two_target_views", "with hypotheses from >= 2 views"),
                           ("scored", "with a score > 0"), ("kept", "kept (score above thresholds)")]:
            out.append(row(f"2D segments {label} (mean)", [f"{s['triangulation_per_building'][key]:.0f}" for s in sums]))
    for i, b in enumerate(sums[0]["length_histogram"]):
        lo = "0" if i == 0 else sums[0]["length_histogram"][i - 1]["below_x_mean_gt_edge"]
        out.append(row(f"length in [{lo}, {b['below_x_mean_gt_edge']}) x mean GT edge",
                       [f"{100 * s['length_histogram'][i]['share']:.1f}%" for s in sums]))
    for stage in ["render", "lsd", "triangulation", "labelling"]:
        out.append(row(f"seconds per building: {stage}", [f"{s['seconds_per_building'].get(stage, 0):.2f}" for s in sums]))
    print("\n".join(out))


if __name__ == "__main__":
    main(sys.argv)
