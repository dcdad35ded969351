"""The valid inputs the hostile cases start from, made once per run in WORK/fixtures: tiny weights,
synthetic line clouds with their predictions, six rendered views of a gable box with their cameras (JSON,
COLMAP text and binary), a tiny training config, and the seeds of tests/fuzz/corpus."""
import json
import os
import shutil
import struct
import subprocess
from pathlib import Path

CORPUS = Path(__file__).resolve().parent.parent / "corpus"


def quaternion(R):
    import math
    tr = R[0][0] + R[1][1] + R[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [0.25 * s, (R[2][1] - R[1][2]) / s, (R[0][2] - R[2][0]) / s, (R[1][0] - R[0][1]) / s]
    i = max(range(3), key=lambda k: R[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + R[i][i] - R[j][j] - R[k][k]) * 2
    q = [0.0] * 4
    q[0] = (R[k][j] - R[j][k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (R[j][i] + R[i][j]) / s
    q[1 + k] = (R[k][i] + R[i][k]) / s
    return q


def colmap_models(cams, names):
    """Our cameras (JSON entries: K, R row-major, t) as COLMAP text and binary models (one PINHOLE camera, id 1)."""
    K, width, height = cams[0]["K"], cams[0]["width"], cams[0]["height"]
    params = [K[0], K[4], K[2] + 0.5, K[5] + 0.5]  # COLMAP's pixel origin is the corner, ours the centre
    cam_txt = "# Camera list\n1 PINHOLE %d %d %s\n" % (width, height, " ".join(repr(p) for p in params))
    img_txt = "# Image list\n"
    cam_bin = struct.pack("<QIiQQ", 1, 1, 1, width, height) + struct.pack("<4d", *params)
    img_bin = struct.pack("<Q", len(cams))
    for i, (c, name) in enumerate(zip(cams, names)):
        R = [c["R"][0:3], c["R"][3:6], c["R"][6:9]]
        q, t = quaternion(R), c["t"]
        img_txt += "%d %s %s 1 %s\n\n" % (i + 1, " ".join(repr(v) for v in q), " ".join(repr(v) for v in t), name)
        img_bin += struct.pack("<I4d3dI", i + 1, *q, *t, 1) + name.encode() + b"\x00" + struct.pack("<Q", 0)
    return cam_txt.encode(), img_txt.encode(), cam_bin, img_bin


def tiny_config(data_dir, train_split, val_split):
    lpt = lambda dim, patches: {"input_dim": dim, "lines_per_patch": 8, "patches": patches, "mlp_dims": [8, 16], "hidden_dim": 16,
                                "num_heads": 2, "ffn_dim": 16, "dropout": 0.1, "attn_dropout": 0.1, "line_layers": 1,
                                "patch_layers": 1, "pool": "mean_all"}
    optim = {"optimizer": "adamw", "lr": 0.001, "milestones": [5], "gamma": 0.1}
    return {"seed": 1, "threads": 1, "loader_workers": 1, "out": "out",
            "data": {"format": "lc2wf", "dir": data_dir, "train_split": train_split, "val_split": val_split},
            "junction": {"net": {"lpt": lpt(7, 16), "head": {"dims": [8]}}, "optim": optim, "epochs": 1, "batch_size": 2,
                         "max_steps_per_epoch": 1, "val_every": 1},
            "edge": {"net": {"lpt": lpt(6, 16), "head": {"dims": [8]}, "num_classes": 5}, "optim": optim, "epochs": 1,
                     "batch_size": 2, "max_steps_per_epoch": 1, "val_every": 1, "max_static_pairs": 16, "top_k": 8}}


class Fixtures:
    def __init__(self, root, exe):
        self.root = Path(root)
        self.exe = exe
        self.seeds = {}  # name -> bytes of a valid input

    def path(self, *parts):
        return str(self.root.joinpath(*parts))

    def _run(self, *argv):
        subprocess.run([str(a) for a in argv], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    def make(self):
        r = self.root
        r.mkdir(parents=True, exist_ok=True)
        self._run(self.exe["lc2wf-adversarial-weights"], r / "weights")
        self._run(self.exe["lc2wf-synthetic-data"], "--out", r / "synth", "--count", "4", "--val", "1", "--test", "1", "--quiet")
        (r / "one.txt").write_text("synth_0000\n")
        self._run(self.exe["lc2wf-infer"], "--weights", r / "weights", r / "synth/clouds/synth_0000.lcloud", "-o", r / "pred",
                  "--threads", "1", "--quiet")
        self._run(self.exe["lc2wf-eval"], "--pred", r / "pred", "--data", r / "synth/clouds", "--split", r / "one.txt",
                  "--out", r / "eval", "--quiet")
        self._run(self.exe["lc2wf-cloud-convert"], r / "synth/clouds/synth_0000.lcloud", "-o", r / "synth_0000.txt")
        self._run(self.exe["lc2wf-cloud-convert"], r / "synth/clouds/synth_0000.lcloud", "-o", r / "synth_0000.obj", "--to", "obj")
        # A GT mesh folder for --gt: the gable box as b.polyshape and b.obj's prediction.
        (r / "pred_b").mkdir(exist_ok=True)
        (r / "pred_b/b.obj").write_bytes((CORPUS / "obj/wireframe.obj").read_bytes())
        (r / "meshes").mkdir(exist_ok=True)
        (r / "meshes/b.polyshape").write_bytes((CORPUS / "polyshape/gable_box.seed").read_bytes())
        # Six rendered views of the gable box and their exact cameras: what lc2wf-reconstruct runs on.
        self._run(self.exe["lc2wf-dataset"], "--meshes", r / "meshes", "--out", r / "rendered", "--views", "6", "--size", "160x120",
                  "-j", "1", "--quiet", "--keep-views")
        names = sorted(p.name for p in (r / "rendered/views/b").glob("*.png"))
        shutil.copytree(r / "rendered/views/b", r / "images", ignore=shutil.ignore_patterns("*.json"))
        shutil.copy(r / "rendered/views/b/cameras.json", r / "cameras.json")
        cams = json.loads((r / "cameras.json").read_text())
        cam_txt, img_txt, cam_bin, img_bin = colmap_models(cams, names)
        for folder, files in (("model_txt", {"cameras.txt": cam_txt, "images.txt": img_txt, "points3D.txt": b""}),
                              ("model_bin", {"cameras.bin": cam_bin, "images.bin": img_bin})):
            (r / folder).mkdir(exist_ok=True)
            for n, data in files.items():
                (r / folder / n).write_bytes(data)
        config = tiny_config(self.path("synth/clouds"), self.path("synth/train.txt"), self.path("synth/val.txt"))
        (r / "config.json").write_text(json.dumps(config))
        read = lambda p: Path(p).read_bytes()
        self.seeds = {
            "lcloud_bin": read(r / "synth/clouds/synth_0000.lcloud"),
            "lcloud_json": read(CORPUS / "lcloud/two_segments.json"),
            "release": read(CORPUS / "release_json/small.json"),
            "line3dpp": read(r / "synth_0000.txt"),
            "line3dpp_small": read(CORPUS / "line3dpp/three_lines.txt"),
            "line_obj": read(r / "synth_0000.obj"),
            "limap_track": read(CORPUS / "limap_track/track_0.txt"),
            "polyshape": read(CORPUS / "polyshape/gable_box.seed"),
            "obj_wireframe": read(CORPUS / "obj/wireframe.obj"),
            "obj_mesh": read(CORPUS / "obj/mesh.obj"),
            "pred_obj": read(r / "pred/synth_0000.obj"),
            "pred_json": read(r / "pred/synth_0000.json"),
            "split": read(r / "synth/train.txt"),
            "metrics": read(r / "eval/metrics.json"),
            "config": json.dumps(config, indent=1).encode(),
            "junction_weights": read(r / "weights/junction.safetensors"),
            "edge_weights": read(r / "weights/edge.safetensors"),
            "cameras_json": read(r / "cameras.json"),
            "colmap_cameras_txt": cam_txt, "colmap_images_txt": img_txt,
            "colmap_cameras_bin": cam_bin, "colmap_images_bin": img_bin,
            "png": read(r / "images" / names[1]),
        }
        return self
