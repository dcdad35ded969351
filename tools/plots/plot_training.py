#!/usr/bin/python3
"""Learning curves of an lc2wf-train run, from its log.jsonl (format in train/README.md): training loss per
epoch (and per step, faint) and the validation metric per epoch (junction stage: vAP, edge stage: sAP and vAP,
means over the three thresholds), best epochs marked.

  tools/plots/plot_training.py RUN_DIR [--out PNG]     (default: RUN_DIR/plots/training.png)
"""
import argparse
import json
import os
import sys

import plot_style
from plot_style import BLUE, ORANGE, GREEN, plt

STAGE_COLOUR = {"junction": BLUE, "edge": ORANGE}


def read_log(path):
    lines = []
    with open(path) as f:
        for number, text in enumerate(f, 1):
            if text.strip():
                try:
                    lines.append(json.loads(text))
                except json.JSONDecodeError as e:
                    raise SystemExit("plot_training: %s:%d: %s" % (path, number, e))
    return lines


def plot(lines, title):
    plot_style.apply()
    fig, (loss_ax, val_ax) = plt.subplots(1, 2, figsize=(11, 4))
    for stage, colour in STAGE_COLOUR.items():
        steps = [l for l in lines if l.get("stage") == stage and l.get("type") == "step"]
        epochs = [l for l in lines if l.get("stage") == stage and l.get("type") == "epoch"]
        if steps:  # steps drawn at fractional epochs so they line up with the epoch means
            per_epoch = {}
            for l in steps:
                per_epoch.setdefault(l["epoch"], []).append(l["loss"])
            xs, ys = [], []
            for e, losses in sorted(per_epoch.items()):
                xs += [e - 1 + (k + 1) / len(losses) for k in range(len(losses))]
                ys += losses
            loss_ax.plot(xs, ys, color=colour, alpha=0.3, linewidth=0.8, label="%s stage (per step)" % stage)
        if epochs:
            loss_ax.plot([l["epoch"] for l in epochs], [l["train_loss"] for l in epochs], "o-", color=colour,
                         markersize=3.5, linewidth=1.6, label="%s stage (epoch mean)" % stage)
        # The validation loss keeps showing progress when the validation metric is flat or noisy.
        vals = [l for l in lines if l.get("stage") == stage and l.get("type") == "val" and l.get("loss", 0) > 0]
        if vals:
            loss_ax.plot([l["epoch"] for l in vals], [l["loss"] for l in vals], "s--", color=colour, markersize=3,
                         linewidth=1.2, label="%s stage (validation)" % stage)
    loss_ax.set_title("Training and validation loss")
    loss_ax.set_xlabel("epoch (of its stage)")
    loss_ax.set_ylabel("loss")
    all_losses = [l["loss"] for l in lines if l.get("type") == "step" and l.get("loss", 0) > 0]
    if all_losses and max(all_losses) / min(all_losses) > 20:
        loss_ax.set_yscale("log")
    elif len(all_losses) > 50:
        # The first steps' loss (10x the rest at paper size) would flatten every curve: they go off the top.
        means = [l.get("train_loss", 0) for l in lines if l.get("type") == "epoch"]
        means += [l.get("loss", 0) for l in lines if l.get("type") == "val"]
        top = 1.15 * max([sorted(all_losses)[int(0.98 * (len(all_losses) - 1))]] + means)
        if max(all_losses) > top:
            loss_ax.set_ylim(0, top)
            loss_ax.annotate("first steps above the top", xy=(0.02, 0.97), xycoords="axes fraction", fontsize=8,
                             va="top", color="0.4")
    if loss_ax.get_legend_handles_labels()[0]:
        loss_ax.legend(loc="upper right", fontsize=9)

    # The junction stage scores raw candidates (after point NMS), the edge stage post-processed wireframes.
    series = [("junction", "vAP_mean", BLUE, "-", "junction stage: vAP, raw candidates"),
              ("edge", "sAP_mean", ORANGE, "-", "edge stage: sAP, wireframes"),
              ("edge", "vAP_mean", GREEN, "--", "edge stage: vAP, wireframes")]
    for stage, key, colour, style, label in series:
        val = [l for l in lines if l.get("stage") == stage and l.get("type") == "val" and key in l]
        if not val:
            continue
        xs, ys = [l["epoch"] for l in val], [100 * l[key] for l in val]
        val_ax.plot(xs, ys, style, marker="o", markersize=3.5, color=colour, linewidth=1.6, label=label)
        if key == {"junction": "vAP_mean", "edge": "sAP_mean"}[stage]:
            best = [l for l in val if l.get("best")]
            if best:
                b = best[-1]
                val_ax.plot([b["epoch"]], [100 * b[key]], "*", color=colour, markersize=12, markeredgecolor="white")
                val_ax.annotate("best %.1f" % (100 * b[key]), (b["epoch"], 100 * b[key]), textcoords="offset points",
                                xytext=(6, 6), fontsize=9, color=colour)
    val_ax.set_title("Validation (mean over the three thresholds)")
    val_ax.set_xlabel("epoch (of its stage)")
    val_ax.set_ylabel("%")
    top = max([l.get(k, 0) for l in lines if l.get("type") == "val" for k in ("vAP_mean", "sAP_mean")] + [0.5])
    val_ax.set_ylim(0, min(105, 100 * top + 10))  # headroom for the "best" labels
    if val_ax.get_legend_handles_labels()[0]:
        val_ax.legend(loc="best", fontsize=9, frameon=True, facecolor="white", edgecolor="none", framealpha=0.9)
    else:
        val_ax.text(0.5, 0.5, "no validation lines yet", ha="center", va="center", transform=val_ax.transAxes, color="#888")
    for ax in (loss_ax, val_ax):
        ax.xaxis.get_major_locator().set_params(integer=True)
    fig.suptitle(title, fontsize=12)
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="training output folder (holding log.jsonl) or the log.jsonl itself")
    parser.add_argument("--out", help="PNG to write (default: RUN/plots/training.png)")
    args = parser.parse_args()
    log = args.run if os.path.isfile(args.run) else os.path.join(args.run, "log.jsonl")
    if not os.path.isfile(log):
        parser.error("run: %s not found" % log)
    run_dir = os.path.dirname(os.path.abspath(log))
    out = args.out or os.path.join(run_dir, "plots", "training.png")
    lines = read_log(log)
    if not any(l.get("type") in ("step", "epoch", "val") for l in lines):
        print("plot_training: %s has no training lines yet" % log, file=sys.stderr)
        return 1
    plot_style.save(plot(lines, "lc2wf training: " + os.path.basename(run_dir)), out)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
