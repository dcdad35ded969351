"""The adversarial cases: every command fed hostile files (from hostile.py), special files (FIFO, folder,
/dev/zero, >4 GiB sparse file, symlink loop, missing), hostile file names and hostile flag values.

A case lists the files to create under its folder C (bytes, or a Special), the command line, the files
an error must name and, for flag cases, the flag. "{C}" (the case folder), "{F}" (fixtures) and "{ESC}"
(a folder no command may write to) are replaced in the command line and in file contents."""
from dataclasses import dataclass, field
from pathlib import Path

import hostile


@dataclass
class Special:
    kind: str  # fifo | dir | devzero | sparse | loop | missing | null (a device node like /dev/null)


@dataclass
class Case:
    family: str
    argv: list
    files: dict = field(default_factory=dict)  # path under C -> bytes | Special
    names: list = field(default_factory=list)  # paths under C an error message must name (any one)
    flag: str = ""                             # a flag case: the error must name this flag
    allowed: list = field(default_factory=lambda: ["out"])  # folders under C the command may write to
    # Exit codes that keep the convention (0 done, 1 partly failed, 2 usage, 3 data or I/O error): a hostile
    # file is never a usage error; empty means {0, 1, 3} for files and {0, 1, 2, 3} for flag values.
    exits: tuple = ()
    also_named: list = field(default_factory=list)  # other words that name the problem well enough
    timeout: float = 30
    id: str = ""


SPECIALS = [Special("fifo"), Special("dir"), Special("devzero"), Special("sparse"), Special("loop"), Special("missing"), b""]
# File names a command must not trip over (stem used for outputs): newline, non-UTF-8, dots, dash, quotes.
HOSTILE_STEMS = [b"a\nb", b"\xff\xfe", b"caf\xc3\xa9", b".", b"..", b"-x", b" sp ace ", b"q'\"$(x)`", b"x" * 200, b"\\..\\e"]


def stems(seed_name, ext):
    return [(s + ext, s) for s in HOSTILE_STEMS] + [(b"ok" + ext, b"ok")]


def mutated(seed, rng, count):
    return hostile.variants(seed, rng, count)


def exe(name):
    return "{X:%s}" % name


def file_cases(family, rel, seed, rng, count, argv, extra_files=None, **kw):
    """`count` hostile versions of one input file plus every special file in its place."""
    out = []
    for data in mutated(seed, rng, count) + SPECIALS:
        files = dict(extra_files or {})
        files[rel] = data
        out.append(Case(family, argv, files, [rel], **kw))
    return out


def name_cases(family, folder, ext, seed, argv_of, **kw):
    """A valid input under every hostile file name; argv_of(path under C) gives the command line."""
    out = []
    for fname, _ in stems(b"", ext.encode()):
        rel = folder + "/" + fname.decode("utf-8", "surrogateescape")
        out.append(Case(family, argv_of(rel), {rel: seed}, [rel], **kw))
    return out


def convert(fx, rng, n):
    cases = []
    for seed in ("lcloud_bin", "lcloud_json"):
        for to in ("line3dpp", "obj"):
            argv = [exe("lc2wf-cloud-convert"), "{C}/in/cloud.lcloud", "-o", "{C}/out/cloud.txt", "--to", to]
            cases += file_cases("convert/" + seed, "in/cloud.lcloud", fx.seeds[seed], rng, n, argv)
    cases += name_cases("convert/names", "in", ".lcloud", fx.seeds["lcloud_bin"],
                        lambda rel: [exe("lc2wf-cloud-convert"), "{C}/" + rel, "-o", "{C}/out/c.txt"])
    return cases


INFER_FORMATS = {"lcloud_bin": ("lc2wf", ".lcloud"), "lcloud_json": ("lc2wf", ".json"), "release": ("release", ".json"),
                 "line3dpp": ("line3dpp", ".txt"), "line3dpp_small": ("line3dpp", ".txt"), "line_obj": ("obj", ".obj")}


def infer_argv(path, fmt):
    return [exe("lc2wf-infer"), "--weights", "{F}/weights", path, "-o", "{C}/out", "--format", fmt, "--threads", "1", "--quiet"]


def infer(fx, rng, n):
    cases = []
    for seed, (fmt, ext) in INFER_FORMATS.items():
        rel = "in/cloud" + ext
        for f in ("auto", fmt):
            cases += file_cases("infer/" + seed, rel, fx.seeds[seed], rng, n, infer_argv("{C}/" + rel, f))
    # LIMAP: a finaltracks/ folder of three tracks, one of them hostile.
    for k in range(2 * n):
        files = {"in/run/finaltracks/track_%d.txt" % i: fx.seeds["limap_track"] for i in range(3)}
        rel = "in/run/finaltracks/track_%d.txt" % (k % 3)
        files[rel] = mutated(fx.seeds["limap_track"], rng, 1)[0] if k < 2 * n - len(SPECIALS) else SPECIALS[k % len(SPECIALS)]
        cases.append(Case("infer/limap", infer_argv("{C}/in/run", "limap" if k % 2 else "auto"), files, [rel]))
    # Weights: one of the two safetensors files hostile.
    for which in ("junction", "edge"):
        rel = "in/w/%s.safetensors" % which
        other = "in/w/%s.safetensors" % ("edge" if which == "junction" else "junction")
        argv = [exe("lc2wf-infer"), "--weights", "{C}/in/w", "{F}/synth/clouds/synth_0000.lcloud", "-o", "{C}/out", "--threads", "1", "--quiet"]
        cases += file_cases("infer/weights", rel, fx.seeds[which + "_weights"], rng, n, argv,
                            extra_files={other: fx.seeds[("edge" if which == "junction" else "junction") + "_weights"]})
    cases += name_cases("infer/names", "in", ".lcloud", fx.seeds["lcloud_bin"], lambda rel: infer_argv("{C}/" + rel, "auto"))
    # Names inside the file must never become output paths.
    for inner in (b"../../escape", b"{ESC}/abs", b"", b"a\\u0000b", b".", b"..", b"/", b"x/../../y"):
        data = fx.seeds["lcloud_json"].replace(b'"name":"t"', b'"name":"' + inner + b'"')
        cases.append(Case("infer/inner_names", infer_argv("{C}/in/c.json", "auto"), {"in/c.json": data}, ["in/c.json"]))
    return cases


def eval_cases(fx, rng, n):
    ev = exe("lc2wf-eval")
    cases = []
    base = [ev, "--data", "{F}/synth/clouds", "--split", "{F}/one.txt", "--out", "{C}/out", "--quiet"]
    cases += file_cases("eval/pred_obj", "in/pred/synth_0000.obj", fx.seeds["pred_obj"], rng, 2 * n, base + ["--pred", "{C}/in/pred"],
                        extra_files={"in/pred/synth_0000.json": fx.seeds["pred_json"]})
    cases += file_cases("eval/pred_json", "in/pred/synth_0000.json", fx.seeds["pred_json"], rng, 2 * n, base + ["--pred", "{C}/in/pred"],
                        extra_files={"in/pred/synth_0000.obj": fx.seeds["pred_obj"]})
    gt = [ev, "--pred", "{F}/pred_b", "--gt", "{C}/in/gt", "--out", "{C}/out", "--quiet"]
    cases += file_cases("eval/gt_polyshape", "in/gt/b.polyshape", fx.seeds["polyshape"], rng, n, gt)
    cases += file_cases("eval/gt_obj", "in/gt/b.obj", fx.seeds["obj_mesh"], rng, n, gt)
    cases += file_cases("eval/gt_obj_yup", "in/gt/b.obj", fx.seeds["obj_wireframe"], rng, n // 2, gt + ["--gt-y-up", "--units", "raw"])
    data = [ev, "--pred", "{F}/pred", "--data", "{C}/in/data", "--split", "{F}/one.txt", "--out", "{C}/out", "--quiet"]
    cases += file_cases("eval/data_lcloud", "in/data/synth_0000.lcloud", fx.seeds["lcloud_bin"], rng, n, data)
    cases += file_cases("eval/data_release", "in/data/synth_0000.json", fx.seeds["release"], rng, n // 2, data)
    split = [ev, "--pred", "{F}/pred", "--data", "{F}/synth/clouds", "--split", "{C}/in/split.txt", "--out", "{C}/out", "--quiet"]
    cases += file_cases("eval/split", "in/split.txt", fx.seeds["split"], rng, n, split)
    cmp_ = [ev, "--pred", "{F}/pred", "--data", "{F}/synth/clouds", "--split", "{F}/one.txt", "--out", "{C}/out", "--quiet",
            "--html", "--html-compare", "{C}/in/cmp"]
    cases += file_cases("eval/html_compare", "in/cmp/metrics.json", fx.seeds["metrics"], rng, n // 2, cmp_)
    weights = [ev, "--weights", "{F}/weights", "--data", "{C}/in/data", "--split", "{F}/one.txt", "--out", "{C}/out", "--quiet"]
    cases += file_cases("eval/weights_data", "in/data/synth_0000.lcloud", fx.seeds["lcloud_bin"], rng, n // 2, weights)
    return cases


def dataset(fx, rng, n):
    argv = [exe("lc2wf-dataset"), "--meshes", "{C}/in/meshes", "--out", "{C}/out", "--views", "6", "--size", "128x96", "-j", "1",
            "--quiet"]
    cases = file_cases("dataset/polyshape", "in/meshes/b.polyshape", fx.seeds["polyshape"], rng, n, argv, timeout=60)
    cases += name_cases("dataset/names", "in/meshes", ".polyshape", fx.seeds["polyshape"], lambda rel: argv, timeout=60)
    return cases


def train(fx, rng, n):
    argv = [exe("lc2wf-train"), "{C}/in/config.json", "--out", "{C}/out", "--quiet"]
    cases = file_cases("train/config", "in/config.json", fx.seeds["config"], rng, 2 * n, argv, timeout=60)
    # A hostile cloud or split list among the training data.
    cfg = fx.seeds["config"].replace(fx.path("synth/clouds").encode(), b"{C}/in/data").replace(fx.path("synth/train.txt").encode(),
                                                                                                 b"{C}/in/train.txt")
    clouds = {"in/data/synth_%04d.lcloud" % i: open(fx.path("synth/clouds/synth_%04d.lcloud" % i), "rb").read() for i in range(4)}
    files = dict(clouds, **{"in/config.json": cfg, "in/train.txt": fx.seeds["split"]})
    cases += file_cases("train/cloud", "in/data/synth_0001.lcloud", clouds["in/data/synth_0001.lcloud"], rng, n, argv, extra_files=files,
                        timeout=60)
    cases += file_cases("train/split", "in/train.txt", fx.seeds["split"], rng, n // 2, argv, extra_files=files, timeout=60)
    return cases


def fixture_images(fx, folder):
    """The rendered views, copied under `folder` of the case."""
    return {folder + "/" + p.name: p.read_bytes() for p in sorted(Path(fx.path("images")).glob("*.png"))}


def reconstruct(fx, rng, n):
    rc = [exe("lc2wf-reconstruct"), "{F}/images", "--weights", "{F}/weights", "-o", "{C}/out", "--quiet", "--threads", "1", "--cameras"]
    cases = []
    for kind, first, second in (("txt", "cameras.txt", "images.txt"), ("bin", "cameras.bin", "images.bin")):
        files = {"in/model/" + first: fx.seeds["colmap_cameras_" + kind], "in/model/" + second: fx.seeds["colmap_images_" + kind]}
        for rel in ("in/model/" + first, "in/model/" + second):
            for case in file_cases("reconstruct/colmap_" + kind, rel, files[rel], rng, n, rc + ["{C}/in/model"], extra_files=files,
                                   timeout=60):
                case.names.append("in/model")  # image names that match no image are reported for the model as a whole
                cases.append(case)
    cases += file_cases("reconstruct/cameras_json", "in/cameras.json", fx.seeds["cameras_json"], rng, n, rc + ["{C}/in/cameras.json"],
                        timeout=60)
    cases += file_cases("reconstruct/reference", "in/ref.json", fx.seeds["cameras_json"], rng, n // 2,
                        rc + ["{F}/cameras.json", "--reference-cameras", "{C}/in/ref.json"], timeout=60)
    images = fixture_images(fx, "in/images")
    argv = [exe("lc2wf-reconstruct"), "{C}/in/images", "--weights", "{F}/weights", "-o", "{C}/out", "--quiet", "--threads", "1",
            "--cameras", "{F}/cameras.json"]
    cases += file_cases("reconstruct/image", "in/images/view_001.png", fx.seeds["png"], rng, n // 2, argv, extra_files=images, timeout=60)
    return cases


def make_splits(fx, rng, n):
    argv = [exe("lc2wf-make-splits"), "--meshes", "{C}/in/meshes", "-o", "{C}/out", "--test", "1", "--val", "1"]
    cases = name_cases("make_splits/names", "in/meshes", ".polyshape", fx.seeds["polyshape"], lambda rel: argv)
    for case in cases:  # two more buildings, so one test and one validation building can be drawn
        case.files.update({"in/meshes/b1.polyshape": fx.seeds["polyshape"], "in/meshes/b2.polyshape": fx.seeds["polyshape"]})
    # Too few buildings for the split: the error names the folder and the flags.
    cases.append(Case("make_splits/names", argv[:-4] + ["--test", "2", "--val", "1"], {"in/meshes/b.polyshape": fx.seeds["polyshape"]},
                      ["in/meshes"]))
    return cases


def colmap_poses(fx, rng, n):
    images = fixture_images(fx, "in/views")
    argv = [exe("lc2wf-colmap-poses"), "{C}/in/views", "--colmap", "/bin/false", "--threads", "1"]
    # /bin/false stands in for COLMAP: a cameras.json that is accepted ends in "COLMAP ... failed", named.
    cases = file_cases("colmap_poses/cameras_json", "in/views/cameras.json", fx.seeds["cameras_json"], rng, n // 2, argv,
                       extra_files=images, allowed=["in/views"], also_named=["COLMAP"])
    # cameras.json is optional: without it the intrinsics must come from --intrinsics, so its absence is a
    # usage error (exit 2) whose message names both.
    for case in cases:
        if case.files["in/views/cameras.json"] == Special("missing"):
            case.exits = (2,)
    return cases


# Flag values a command line must refuse by name (exit 2) or accept: NaN, Inf, overflow, empty, junk.
BAD_VALUES = ["nan", "inf", "-inf", "1e400", "-1", "0", "99999999999999999999", "", "x", "1,2", "\udcff", "0x10", "1e9"]


def flags(fx, rng, n):
    cloud = "{F}/synth/clouds/synth_0000.lcloud"
    commands = {
        "lc2wf-infer": ([exe("lc2wf-infer"), "--weights", "{F}/weights", cloud, "-o", "{C}/out", "--quiet"],
                        ["--threads", "--units", "--format", "--height-model"]),  # --preview's value is an output path by design
        "lc2wf-eval": ([exe("lc2wf-eval"), "--pred", "{F}/pred", "--data", "{F}/synth/clouds", "--split", "{F}/one.txt", "--out",
                        "{C}/out", "--quiet"], ["--ties", "--units", "--method", "--format"]),
        "lc2wf-dataset": ([exe("lc2wf-dataset"), "--meshes", "{F}/meshes", "--out", "{C}/out", "--quiet", "-j", "1"],
                          ["--views", "--size", "--supersample", "--blur", "--seed", "--shard", "--limit", "--lsd-scale", "--min-score",
                           "--max-segments", "--sigma-p", "--neighbours", "--threads"]),
        "lc2wf-reconstruct": ([exe("lc2wf-reconstruct"), "{F}/images", "--weights", "{F}/weights", "-o", "{C}/out", "--quiet",
                               "--cameras", "{F}/cameras.json"],
                              ["--intrinsics", "--focal-35mm", "--scale", "--up", "--known-distance", "--min-score", "--threads",
                               "--max-features", "--matcher", "--height-model", "--init-min-inliers", "--abs-pose-min-inliers"]),
        "lc2wf-cloud-convert": ([exe("lc2wf-cloud-convert"), cloud, "-o", "{C}/out/c.txt"], ["--to"]),
        "lc2wf-train": ([exe("lc2wf-train"), "{F}/config.json", "--out", "{C}/out", "--quiet"], ["--stage"]),
        "lc2wf-synthetic-data": ([exe("lc2wf-synthetic-data"), "--out", "{C}/out", "--quiet"], ["--count", "--val", "--test", "--seed"]),
        "lc2wf-make-splits": ([exe("lc2wf-make-splits"), "--meshes", "{F}/meshes", "-o", "{C}/out", "--test", "0", "--val", "0"],
                              ["--seed", "--test", "--val"]),
    }
    extra = {"--size": ["0x0", "100000x100000", "96x", "x72", "-5x5", "1e3x1e3"], "--shard": ["3/2", "0/0", "-1/2", "1/99999999999999999999"],
             "--intrinsics": ["nan,1,1,1", "1,1,1", "1,1,1,inf", "0,0,0,0"], "--up": ["nan,0,0", "0,0,0", "inf,1,1"],
             "--known-distance": ["view_000.png,view_001.png,nan", "a,b,1", "view_000.png,view_000.png,1", "view_000.png,view_001.png,-1"]}
    cases = []
    for name, (argv, names) in commands.items():
        for f in names:
            for v in BAD_VALUES + extra.get(f, []):
                cases.append(Case("flags/" + name, argv + [f, v], flag=f, timeout=60))
        # Output paths that cannot be folders: under a file, a device (a node like /dev/null made in the case
        # folder, so a command that replaces it harms nothing), /proc. cloud-convert's -o names a file, so
        # overwriting in/file is what it was asked to do.
        for v in ("{C}/in/file", "{C}/in/file/sub", "{C}/in/null", "/proc/version"):
            out = [a if a != "{C}/out" and a != "{C}/out/c.txt" else v for a in argv]
            convert_onto_file = name == "lc2wf-cloud-convert" and v == "{C}/in/file"
            cases.append(Case("flags/" + name, out, {"in/file": b"x", "in/null": Special("null")}, flag="", timeout=60,
                              allowed=["out", "in/file"] if convert_onto_file else ["out"], exits=(0,) if convert_onto_file else (3,)))
    return cases


FAMILIES = {"convert": convert, "infer": infer, "eval": eval_cases, "dataset": dataset, "train": train,
            "reconstruct": reconstruct, "make_splits": make_splits, "colmap_poses": colmap_poses, "flags": flags}


def all_cases(fx, rng, per_file):
    cases = []
    for name, make in FAMILIES.items():
        for i, case in enumerate(make(fx, rng, per_file)):
            case.id = "%s-%04d" % (case.family.replace("/", "-"), i)
            cases.append(case)
    return cases
