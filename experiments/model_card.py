#!/usr/bin/env python3
"""Writes the model card (README.md) of a published model folder from the records of its run.

    experiments/model_card.py --run runs/base --eval runs/base/test [--eval-release runs/base/test-release]
                        [--eval-raster runs/base/test-raster] [--dataset runs/dataset] -o models/base/README.md

Everything in the card is read from files the run wrote (config.json, log.jsonl and README.md of
lc2wf-train, metrics.json of lc2wf-eval --weights, summary.json of lc2wf-dataset) or from this machine
(CPU model, cores), so a card cannot claim numbers its model did not produce. Standard library only.
"""
import argparse
import json
import os
import platform
import sys

PAPER = {"vAP": 93.0, "sAP": 80.4, "wed_num": 5.301, "wed_dist": 27.33}


def fail(message):
    sys.exit(f"model_card.py: {message}")


def read_json(path, what):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read the {what}: {e}")


def log_records(run):
    path = os.path.join(run, "log.jsonl")
    try:
        with open(path, encoding="utf-8") as f:
            return [json.loads(line) for line in f if line.strip()]
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read the training log: {e}")


def training_time(records):
    """Wall and CPU hours of each stage's steps, plus validation and hand-off wall hours."""
    out = {}
    for r in records:
        stage = r.get("stage", "handoff" if r.get("type") == "handoff" else "?")
        t = out.setdefault(stage, {"wall": 0.0, "cpu": 0.0, "steps": 0, "kernels": {}})
        if r.get("type") == "epoch":
            # Epoch lines name the matrix products' precision and backend (not logged before 2026-12-03).
            kind = f"{r['precision']} products by {r.get('gemm', '?')}" if "precision" in r else "not recorded"
            t["kernels"][kind] = t["kernels"].get(kind, 0) + 1
        elif r.get("type") == "step":
            t["wall"] += r.get("seconds", 0.0)
            t["cpu"] += r.get("cpu_seconds", 0.0)
            t["steps"] += 1
        elif r.get("type") in ("val", "handoff"):
            t["wall"] += r.get("seconds", 0.0)
    return out


def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def metric_row(label, m):
    w = m["wed"]
    return (f"| {label} | {100 * m['vertex_avg']['ap']:.1f} / {100 * m['vertex_avg']['recall']:.1f} | "
            f"{100 * m['edge_avg']['ap']:.1f} / {100 * m['edge_avg']['recall']:.1f} | "
            f"{w['total_num']:.3f} / {w['total_dist']:.2f} |")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--run", required=True, help="lc2wf-train output folder")
    p.add_argument("--eval", required=True, help="lc2wf-eval --weights output folder (sound post-processing)")
    p.add_argument("--eval-release", help="the same with --release-quirks")
    p.add_argument("--eval-raster", help="the same model on raster-rendered clouds")
    p.add_argument("--dataset", help="lc2wf-dataset output folder of the training clouds")
    p.add_argument("--name", default="base")
    p.add_argument("-o", "--out", required=True)
    a = p.parse_args()

    config = read_json(os.path.join(a.run, "config.json"), "run's config")
    records = log_records(a.run)
    evals = [("lc2wf, sound post-processing", read_json(os.path.join(a.eval, "metrics.json"), "test metrics"))]
    if a.eval_release:
        evals.append(("lc2wf, `--release-quirks`", read_json(os.path.join(a.eval_release, "metrics.json"), "test metrics")))
    if a.eval_raster:
        evals.append(("lc2wf on raster-rendered clouds", read_json(os.path.join(a.eval_raster, "metrics.json"), "test metrics")))
    main_eval = evals[0][1]
    dataset = read_json(os.path.join(a.dataset, "summary.json"), "dataset summary") if a.dataset else None
    times = training_time(records)
    kept = {r["stage"]: r for r in records if r.get("type") == "val" and r.get("best")}

    lines = [f"# models/{a.name} — LC2WF trained with `configs/{a.name}.json`", ""]
    lines += [
        "The paper's two networks (junction and edge Line-Patch Transformers) trained with its schedule on "
        "Blender-rendered line clouds of the Roof-Image buildings, by lc2wf itself.", "",
        "```sh",
        f"build/infer/lc2wf-infer --weights models/{a.name} CLOUD.lcloud -o OUT        # OUT/<name>.obj + scores",
        f"build/infer/lc2wf-eval --weights models/{a.name} --data CLOUDS --split SPLIT -o OUT",
        "```", "",
        "## Licence", "",
        "Trained on data derived from the Roof-Image dataset (Ren et al., *Intuitive and Efficient Roof Modeling "
        "for Reconstruction and Synthesis*, SIGGRAPH Asia 2021), licensed **CC BY-NC 4.0**. These weights are "
        "derived from it: **non-commercial use only**, with attribution to the Roof-Image authors.", "",
        "## Results on the 757 test buildings", "",
        f"`lc2wf-eval --weights models/{a.name}` on `configs/splits/test.txt` ({main_eval['buildings']} buildings), "
        "release metric definitions (every polyshape vertex and unique polygon edge as GT; vAP at η = 0.15/0.25/0.35 m, "
        "sAP at 0.25/0.35/0.50 m, WED total mean over buildings).", "",
        "| | vAP avg / vRecall avg | sAP avg / sRecall avg | WED total (Num / Dist m) |",
        "|---|---|---|---|",
        f"| LC2WF paper, Table 2 | {PAPER['vAP']} | {PAPER['sAP']} | {PAPER['wed_num']} / {PAPER['wed_dist']} |",
    ]
    lines += [metric_row(label, m) for label, m in evals]
    timing = main_eval.get("inference")
    if timing:
        lines += ["", f"Inference: {timing['seconds_per_building']:.3f} s per building on average "
                  f"({timing['threads']} threads; junction model {timing['junction_seconds_per_building']:.3f} s, edge model "
                  f"{timing['edge_seconds_per_building']:.3f} s for {timing['pairs_per_building']:.0f} pairs, "
                  f"post-processing {timing['post_seconds_per_building']:.3f} s) on {cpu_model()}."]
        if "min_confidence" in timing:  # metrics written before the selection was recorded lack it
            offsets = timing.get("max_offset_m")
            lines += ["", f"Junction selection of these scores: confidence > {timing['min_confidence']:g} after point NMS "
                      f"{timing['nms_radius_m']:g} m, "
                      + (f"candidates regressed at most {offsets:g} m from their sample point"
                         if offsets is not None else "every candidate") + "."]

    lines += ["", "## Training", ""]
    # A card may be written while the run continues (an interim model): say so rather than imply the schedule ran.
    for stage in ("junction", "edge"):
        done = max((r["epoch"] for r in records if r.get("stage") == stage and r.get("type") == "epoch"), default=0)
        if done < config[stage]["epochs"]:
            lines.append(f"- **unfinished**: the {stage} stage had run {done} of its {config[stage]['epochs']} epochs "
                         "when this card was written; the weights are the best so far.")
    for stage in ("junction", "edge"):
        t = times.get(stage)
        k = kept.get(stage)
        if not t:
            continue
        metric = "vAP mean" if stage == "junction" else "sAP mean"
        best = f", kept epoch {k['epoch']} of {config[stage]['epochs']} ({metric} {100 * k['score']:.1f} % on the validation split)" if k else ""
        kernels = "; ".join(f"{n} epoch(s): {kind}" for kind, n in t["kernels"].items())
        lines.append(f"- {stage}: {t['steps']} steps of {config[stage]['batch_size']} buildings, "
                     f"{t['wall'] / 3600:.1f} h wall ({t['cpu'] / 3600:.1f} CPU-h in steps){best}"
                     + (f"; {kernels}." if kernels else "."))
    if "handoff" in times:
        lines.append(f"- hand-off: {times['handoff']['wall'] / 3600:.2f} h.")
    lines.append(f"- machine of the last session: {cpu_model()}, {os.cpu_count()} cores, `threads: {config.get('threads')}`; "
                 "the run continued over several sessions with `--resume` (exact resume: the same losses as one run), "
                 "possibly on other machines (the stages' lines above say what their products ran in).")
    lines.append("- config: `config.json` here (configs/base.json as resolved); the card of the run, with its "
                 "lc2wf commit, is `training-card.md`; the learning curves are `learning_curves.png`.")
    if dataset:
        lines.append(f"- line clouds: `lc2wf-dataset --renderer {dataset.get('renderer')}` (textures "
                     f"`{dataset.get('textures')}`, commit {dataset.get('commit')}), "
                     f"{dataset['segments_per_building']['mean']:.0f} 3D segments per building on average.")
    lines += ["", "## Reproduce", "", "```sh",
              "experiments/run.sh dataset   # Blender line clouds of all 3,583 buildings",
              "experiments/run.sh train     # lc2wf-train configs/base.json (resumable)",
              "experiments/run.sh select    # junction selections scored on the validation split",
              "experiments/run.sh eval      # Table 2 on the 757 test buildings",
              "experiments/run.sh ship      # this folder", "```", ""]

    tmp = a.out + ".tmp"
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(tmp, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
