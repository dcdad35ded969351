#!/usr/bin/python3
"""Per-building error distribution of an lc2wf-eval run, from OUT/metrics.json: histograms of the release WED
(total Dist, m) and of edge precision / recall at one threshold, and the ten worst buildings by WED.

  tools/plots/plot_eval.py OUT [--eta 0.35] [--out PNG]     (default: OUT/plots/errors.png)
Run before lc2wf-eval --html (or re-run the evaluation) to have the report show it; it links whatever PNGs
are in OUT/plots/.
"""
import argparse
import json
import os
import statistics
import sys

import plot_style
from plot_style import BLUE, ORANGE, RED, GREY, plt


def plot(metrics, eta_index):
    plot_style.apply()
    rows = metrics["per_building"]
    eta = metrics["options"]["edge_thresholds_m"][eta_index]
    wed = [b["wed"]["total_dist"] for b in rows]
    precision = [b["edge_tp"][eta_index] / b["pred_edges"] for b in rows if b["pred_edges"] > 0]
    recall = [b["edge_tp"][eta_index] / b["gt_edges"] for b in rows if b["gt_edges"] > 0]

    fig, (wed_ax, pr_ax, worst_ax) = plt.subplots(1, 3, figsize=(15, 4.2), gridspec_kw={"width_ratios": [1, 1, 1.15]})
    bins = min(40, max(8, len(rows) // 8))
    wed_ax.hist(wed, bins=bins, color=BLUE, alpha=0.85, edgecolor="white", linewidth=0.5)
    median = statistics.median(wed) if wed else 0
    wed_ax.axvline(median, color=RED, linewidth=1.4, linestyle="--")
    wed_ax.annotate("median %.1f m" % median, (median, wed_ax.get_ylim()[1] * 0.92), xytext=(5, 0),
                    textcoords="offset points", color=RED, fontsize=9)
    wed_ax.set_title("WED per building (release, total Dist)")
    wed_ax.set_xlabel("WED total Dist (m)")
    wed_ax.set_ylabel("buildings")

    edges = [k / 20 for k in range(21)]
    pr_ax.hist(recall, bins=edges, histtype="stepfilled", color=ORANGE, alpha=0.35, label="recall (%d)" % len(recall))
    pr_ax.hist(recall, bins=edges, histtype="step", color=ORANGE, linewidth=1.5)
    pr_ax.hist(precision, bins=edges, histtype="step", color=BLUE, linewidth=1.8,
               label="precision (%d with a prediction)" % len(precision))
    pr_ax.set_title("Edge precision / recall per building, η = %.2f m" % eta)
    pr_ax.set_xlabel("fraction of edges")
    pr_ax.set_ylabel("buildings")
    pr_ax.set_xlim(0, 1)
    pr_ax.legend(loc="upper left")

    worst = sorted(rows, key=lambda b: b["wed"]["total_dist"], reverse=True)[:10]
    names = [("%s (no pred.)" % b["name"]) if b["prediction_missing"] else b["name"] for b in worst][::-1]
    values = [b["wed"]["total_dist"] for b in worst][::-1]
    bars = worst_ax.barh(range(len(values)), values, color=[GREY if "(no pred.)" in n else RED for n in names], alpha=0.85)
    worst_ax.set_yticks(range(len(values)), names, fontsize=8.5)
    worst_ax.set_title("Ten worst buildings by WED")
    worst_ax.set_xlabel("WED total Dist (m)")
    worst_ax.grid(axis="y", visible=False)
    for bar, value in zip(bars, values):
        worst_ax.text(bar.get_width(), bar.get_y() + bar.get_height() / 2, " %.1f" % value, va="center", fontsize=8)
    worst_ax.set_xlim(0, max(values + [1]) * 1.15)
    fig.suptitle("%s: %d buildings" % (metrics.get("method", "evaluation"), len(rows)), fontsize=12)
    fig.tight_layout()
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("eval_dir", help="lc2wf-eval --out folder (holding metrics.json)")
    parser.add_argument("--eta", type=float, default=0.35, help="edge threshold (m) for precision/recall (0.35)")
    parser.add_argument("--out", help="PNG to write (default: EVAL_DIR/plots/errors.png)")
    args = parser.parse_args()
    path = os.path.join(args.eval_dir, "metrics.json")
    if not os.path.isfile(path):
        parser.error("eval_dir: %s not found" % path)
    with open(path) as f:
        metrics = json.load(f)
    thresholds = metrics["options"]["edge_thresholds_m"]
    matches = [k for k, t in enumerate(thresholds) if abs(t - args.eta) < 1e-9]
    if not matches:
        parser.error("--eta: %g is not one of the evaluated edge thresholds %s" % (args.eta, thresholds))
    if not metrics["per_building"]:
        print("plot_eval: %s has no buildings" % path, file=sys.stderr)
        return 1
    out = args.out or os.path.join(args.eval_dir, "plots", "errors.png")
    plot_style.save(plot(metrics, matches[0]), out)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
