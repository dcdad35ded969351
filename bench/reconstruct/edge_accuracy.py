#!/usr/bin/python3
"""How much of a predicted wireframe lies on the ground truth: the share of its edge length within a distance of
a GT edge, for captures that see only part of a building (vAP/sAP charge the unseen sides as misses).

GT edges come from the labelled line cloud lc2wf-dataset wrote (its header holds the GT wireframe in the frame of
its cameras, the frame wireframe_aligned.obj of lc2wf-reconstruct --reference-cameras is written in).
usage: edge_accuracy.py PRED.obj CLOUD.lcloud [TOLERANCE_M]   prints length_m, share_within
       edge_accuracy.py PRED_DIR CLOUD_DIR [TOLERANCE_M]      every <name>.obj of PRED_DIR against CLOUD_DIR/<name>.lcloud:
                                                              prints drawn length, pooled and median share, empty wireframes
"""
import os
import json
import sys

import numpy as np


def read_obj_wireframe(path):
    """Junctions (n x 3) and edges (pairs of 0-based indices) of an OBJ with 'v' and 'l' lines."""
    vertices, edges = [], []
    for line in open(path):
        f = line.split()
        if not f:
            continue
        if f[0] == "v":
            vertices.append([float(x) for x in f[1:4]])
        elif f[0] == "l":
            ids = [int(x.split("/")[0]) - 1 for x in f[1:]]
            edges += list(zip(ids, ids[1:]))
    return np.array(vertices, dtype=float).reshape(-1, 3), edges


def read_lcloud_wireframe(path):
    """The GT wireframe in the header of our line-cloud file (binary or JSON variant; dataset/README.md)."""
    data = open(path, "rb").read()
    if data.startswith(b"LC2WF-LINECLOUD"):
        first = data.index(b"\n")
        size = int(data[:first].split()[2])
        header = json.loads(data[first + 1:first + 1 + size])
    else:
        header = json.loads(data)
    wf = header["wireframe"]
    return np.array(wf["junctions"], dtype=float).reshape(-1, 3), [tuple(e) for e in wf["edges"]]


def distance_to_segments(points, a, b):
    """Distance of every point (m x 3) to the nearest segment a[k]-b[k] (k x 3 each)."""
    ab = b - a
    length2 = np.maximum((ab * ab).sum(1), 1e-300)
    t = np.clip(((points[:, None, :] - a[None]) * ab[None]).sum(2) / length2[None], 0.0, 1.0)
    nearest = a[None] + t[..., None] * ab[None]
    return np.sqrt(((points[:, None, :] - nearest) ** 2).sum(2)).min(1)


def share_within(pred, gt, tolerance=0.5, step=0.05):
    """(predicted edge length, share of it within `tolerance` of a GT edge), points every `step` metres."""
    (pv, pe), (gv, ge) = pred, gt
    if not pe:
        return 0.0, float("nan")
    ga, gb = gv[[e[0] for e in ge]], gv[[e[1] for e in ge]]
    total = near = 0.0
    for i, j in pe:
        p, q = pv[i], pv[j]
        length = float(np.linalg.norm(q - p))
        n = max(1, int(np.ceil(length / step)))
        samples = p + ((np.arange(n) + 0.5) / n)[:, None] * (q - p)  # midpoints of n equal pieces
        if ge:
            near += length * float((distance_to_segments(samples, ga, gb) <= tolerance).mean())
        total += length
    return total, near / total if total > 0 else float("nan")


def folder_shares(pred_dir, cloud_dir, tolerance):
    """(drawn length, pooled share, median share over buildings with edges, buildings without an edge)."""
    total = near = 0.0
    shares, empty = [], 0
    for name in sorted(f[:-4] for f in os.listdir(pred_dir) if f.endswith(".obj")):
        length, share = share_within(read_obj_wireframe(os.path.join(pred_dir, name + ".obj")),
                                     read_lcloud_wireframe(os.path.join(cloud_dir, name + ".lcloud")), tolerance)
        if length <= 0:
            empty += 1
            continue
        total += length
        near += length * share
        shares.append(share)
    return total, near / total if total > 0 else float("nan"), float(np.median(shares)) if shares else float("nan"), empty


if __name__ == "__main__":
    tolerance = float(sys.argv[3]) if len(sys.argv) > 3 else 0.5
    if os.path.isdir(sys.argv[1]):
        length, pooled, median, empty = folder_shares(sys.argv[1], sys.argv[2], tolerance)
        print(f"{length:.1f} m drawn, {100 * pooled:.1f} % within {tolerance} m of a GT edge (median {100 * median:.1f} %), "
              f"{empty} without an edge")
    else:
        length, share = share_within(read_obj_wireframe(sys.argv[1]), read_lcloud_wireframe(sys.argv[2]), tolerance)
        print(f"{length:.3f} {share:.4f}")
