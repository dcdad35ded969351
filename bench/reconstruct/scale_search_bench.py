#!/usr/bin/env python3
"""The scale search on line clouds of known scale: each labelled cloud (metres, z up) is written as a line OBJ
moved into a random frame (scale log-uniform in [0.05, 20] map units per metre, a random rotation unless
--keep-up, a random shift), lc2wf-infer finds up and scale, and the recovered scale is compared with the truth.

  scale_search_bench.py --infer BIN --convert BIN --weights DIR --out OUT [--keep-up] [--seed S] [--infer-arg A]... CLOUD...

Writes OUT/results.csv (one row per cloud) and OUT/summary.md (median / p90 scale error, per measure over the
search's curve, and the up error). Standard library only.
"""
import argparse, csv, json, math, os, random, subprocess, sys


def random_rotation(rng):
    # Uniform on SO(3) from a random unit quaternion.
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in q))
    w, x, y, z = (v / n for v in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def matvec(R, p):
    return [sum(R[r][c] * p[c] for c in range(3)) for r in range(3)]


def percentile(values, q):
    v = sorted(values)
    if not v:
        return float("nan")
    k = min(len(v) - 1, max(0, int(round(q * (len(v) - 1)))))
    return v[k]


def write_rows(path, rows):
    # Every column any row has: clouds scaled before the search have no curve, and no error per measure.
    fields = []
    for r in rows:
        fields += [k for k in r if k not in fields]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--infer", required=True)
    ap.add_argument("--convert", required=True)
    ap.add_argument("--weights", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--keep-up", action="store_true", help="z stays up (--up z): the scale search alone")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--infer-arg", action="append", default=[], help="one more lc2wf-infer argument (repeatable)")
    ap.add_argument("clouds", nargs="+")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rng = random.Random(a.seed)
    rows = []
    for cloud in a.clouds:
        name = os.path.splitext(os.path.basename(cloud))[0]
        metric_obj = os.path.join(a.out, name + ".metric.obj")
        subprocess.run([a.convert, cloud, "-o", metric_obj, "--to", "obj", "-q"], check=True)
        s = math.exp(rng.uniform(math.log(0.05), math.log(20)))  # map units per metre
        R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]] if a.keep_up else random_rotation(rng)
        t = [rng.uniform(-100, 100) for _ in range(3)]
        moved = os.path.join(a.out, name + ".obj")
        with open(metric_obj) as f, open(moved, "w") as g:
            for line in f:
                if line.startswith("v "):
                    p = [float(x) for x in line.split()[1:4]]
                    q = matvec(R, p)
                    g.write("v %.9g %.9g %.9g\n" % tuple(s * q[i] + t[i] for i in range(3)))
                else:
                    g.write(line)
        os.remove(metric_obj)
        pred = os.path.join(a.out, "pred")
        cmd = [a.infer, "--weights", a.weights, moved, "-o", pred, "-q", "--no-surfaces"]
        if a.keep_up:
            cmd += ["--up", "z"]
        cmd += a.infer_arg
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        frame = json.load(open(os.path.join(pred, name + ".frame.json")))
        found = frame["to_metric"]["scale"]  # metres per map unit; the truth is 1 / s
        up = frame["up_input"]
        true_up = [R[r][2] for r in range(3)]
        up_err = math.degrees(math.acos(max(-1.0, min(1.0, sum(up[i] * true_up[i] for i in range(3))))))
        search = frame.get("scale_search", {})
        curve = search.get("curve", [])
        true_height = frame["height_m"] / (found * s)  # the cloud's height in true metres
        row = {"name": name, "true_height_m": true_height, "map_units_per_metre": s, "found_height_m": frame["height_m"],
               "scale_error": found * s - 1, "up_error_deg": up_err, "ratio": search.get("best_over_runner_up", 0),
               "scale_source": frame["scale_source"], "storeys": frame.get("storeys", {}).get("storeys", 0),
               "true_up": " ".join("%.6f" % x for x in true_up)}
        for measure in ("edge_evidence", "edge_confidence", "confident_junctions", "junction_mean"):
            if curve:
                best = max(curve, key=lambda c: (c[measure], -c["height_m"]))
                row["error_" + measure] = best["height_m"] / true_height - 1
        rows.append(row)
        write_rows(os.path.join(a.out, "results.csv"), rows)  # after every cloud: a cut run keeps its rows
        print("%s: true %.1f m, found %.1f m (%+.1f %%, %s), up error %.1f deg" % (name, true_height, frame["height_m"], 100 * row["scale_error"],
              frame["scale_source"], up_err), file=sys.stderr)
    write_rows(os.path.join(a.out, "results.csv"), rows)
    def stats(key, subset=rows):
        e = [abs(r[key]) for r in subset if key in r]
        return "%.1f %% / %.1f %%" % (100 * percentile(e, 0.5), 100 * percentile(e, 0.9)) if e else "-"
    lines = ["| clouds | n | scale error median / p90 | within 15 % | up error median / max (deg) |", "|---|---|---|---|---|"]
    within = sum(abs(r["scale_error"]) <= 0.15 for r in rows)
    ups = [r["up_error_deg"] for r in rows]
    lines.append("| all | %d | %s | %d | %.1f / %.1f |" % (len(rows), stats("scale_error"), within, percentile(ups, 0.5), max(ups)))
    for source in sorted({r["scale_source"] for r in rows}):
        subset = [r for r in rows if r["scale_source"] == source]
        lines.append("| scale from %s | %d | %s | %d | |" % (source, len(subset), stats("scale_error", subset),
                                                          sum(abs(r["scale_error"]) <= 0.15 for r in subset)))
    lines += ["", "Per measure, the best height of the curve (the search's tries; refined around the default measure's best):", "",
              "| measure | error median / p90 |", "|---|---|"]
    for measure in ("edge_evidence", "edge_confidence", "confident_junctions", "junction_mean"):
        lines.append("| %s | %s |" % (measure, stats("error_" + measure)))
    open(os.path.join(a.out, "summary.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
