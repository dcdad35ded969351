#!/usr/bin/env python3
"""Runs the adversarial cases (cases.py) through every command and checks the promises of RELIABILITY.md:
no crash (signal), no hang (timeout), no file written outside the output folder, peak RSS within
max(256 MB, 4 x the hostile input's size), and every error naming the file (or the flag) and a field,
line, byte or value. Prints a summary, writes WORK/report.json and exits 1 on any violation.

  run.py --bin BUILD_DIR [--work DIR] [--cases N] [--per-file K] [--seed S] [--keep]
  --cases N keeps a deterministic sample of N cases spread over every family (the CTest sample)."""
import argparse
import json
import os
import random
import re
import resource
import shutil
import signal
import stat
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cases as casebook  # noqa: E402
from fixtures import Fixtures  # noqa: E402

COMMANDS = ["lc2wf-infer", "lc2wf-eval", "lc2wf-dataset", "lc2wf-train", "lc2wf-reconstruct", "lc2wf-cloud-convert",
            "lc2wf-make-splits", "lc2wf-colmap-poses", "lc2wf-synthetic-data", "lc2wf-adversarial-weights"]
MB = 1 << 20
# Something that locates the problem: a line, a byte offset, a quoted value or key, a flag, a named field,
# or, for the file as a whole, why it cannot be read (missing, a folder, a FIFO, too large).
LOCATOR = re.compile(rb":\d+:|\bline \d+|\bbyte \d+|'[^']*'|\"[^\"]*\"|--[a-z]|\b[a-z0-9]+_[a-z0-9_]+\b|\[\d+\]|"
                     rb"\b(?:entry|camera|segment|image|vertex|face|tensor|key|field|header|version|count|shape|dtype|offset|"
                     rb"size|name|junction|edge|quaternion|translation|parameter|width|height|format|FIFO|directory|"
                     rb"regular file|exist|empty|JSON|UTF-8|bytes|limit|number|open|folder|directory|symbolic link|no building)")


def find_executables(build):
    found = {}
    for name in COMMANDS:
        hits = [p for p in Path(build).rglob(name) if p.is_file() and os.access(p, os.X_OK)]
        if hits:
            found[name] = str(hits[0].resolve())
    return found


def expand(text, c, fx, esc, exe):
    text = text.replace("{C}", c).replace("{F}", fx).replace("{ESC}", esc)
    return re.sub(r"\{X:([a-z0-9-]+)\}", lambda m: exe[m.group(1)], text)


def materialise(case, cdir, fx, esc):
    size = 0
    for rel, data in case.files.items():
        p = Path(cdir) / rel  # surrogate-escaped names become their raw bytes
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(data, casebook.Special):
            if data.kind == "fifo":
                os.mkfifo(p)
            elif data.kind == "dir":
                p.mkdir()
            elif data.kind == "devzero":
                os.symlink("/dev/zero", p)
            elif data.kind == "sparse":
                with open(p, "wb") as f:
                    f.truncate((5 << 30) + 7)  # over the 4 GiB input limit, no disk used
            elif data.kind == "loop":
                os.symlink(p.name, p)
            elif data.kind == "null":
                try:  # the device numbers of /dev/null; a FIFO when not allowed to make devices
                    os.mknod(p, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
                except PermissionError:
                    os.mkfifo(p)
            continue
        data = data.replace(b"{C}", os.fsencode(str(cdir))).replace(b"{F}", fx.encode()).replace(b"{ESC}", esc.encode())
        p.write_bytes(data)
        if rel in case.names:
            size += len(data)
    return size


def snapshot(*roots, shallow=()):
    """Every path under roots (and directly in the shallow folders) with (type, size, mtime): what changed."""
    seen = {}
    for folder in shallow:
        for n in os.listdir(os.fsencode(str(folder))):
            p = os.path.join(os.fsencode(str(folder)), n)
            seen[p] = (stat.S_IFMT(os.lstat(p).st_mode), 0, 0)
    for root in roots:
        for dirpath, dirnames, filenames in os.walk(os.fsencode(str(root))):
            for n in dirnames + filenames:
                p = os.path.join(dirpath, n)
                try:
                    st = os.lstat(p)
                except FileNotFoundError:
                    continue
                seen[p] = (stat.S_IFMT(st.st_mode), st.st_size if stat.S_ISREG(st.st_mode) else 0, st.st_mtime_ns)
    return seen


def run_limited(argv, cwd, env, timeout, out_path, err_path, address_limit):
    """Runs argv under GNU time: a fork of this (large) Python process would count our own pages in the
    command's peak RSS, a fork of `time` does not. time exits 128 + N when the command dies of signal N."""
    rss_path = str(err_path) + ".rss"
    argv = [b"/usr/bin/time", b"-f", b"%M", b"-o", os.fsencode(rss_path)] + argv

    def limits():
        resource.setrlimit(resource.RLIMIT_AS, (address_limit, address_limit))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))

    start = time.monotonic()
    with open(out_path, "wb") as out, open(err_path, "wb") as err:
        pid = os.fork()
        if pid == 0:
            try:
                os.setsid()
                limits()
                os.chdir(cwd)
                os.dup2(os.open(os.devnull, os.O_RDONLY), 0)
                os.dup2(out.fileno(), 1)
                os.dup2(err.fileno(), 2)
                os.execve(argv[0], argv, env)
            finally:
                os._exit(127)
    timed_out = False
    while True:
        got, status, usage = os.wait4(pid, os.WNOHANG)
        if got:
            break
        if time.monotonic() - start > timeout:
            timed_out = True
            os.killpg(pid, signal.SIGKILL)
            got, status, usage = os.wait4(pid, 0)
            break
        time.sleep(0.005)
    try:
        with open(rss_path) as f:
            rss_kb = int(f.read().split()[-1])
        os.unlink(rss_path)
    except (OSError, ValueError, IndexError):
        rss_kb = 0  # killed before time could write it (a timeout)
    return {"exit": os.waitstatus_to_exitcode(status), "timed_out": timed_out, "rss_mb": rss_kb / 1024,
            "seconds": round(time.monotonic() - start, 3)}


def check(case, result, stderr, created, size):
    problems = []
    if result["timed_out"]:
        problems.append("hang: killed after %.0f s" % case.timeout)
    elif result["exit"] < 0:
        problems.append("crash: signal %d" % -result["exit"])
    elif result["exit"] >= 128:  # GNU time's 128 + N for a command killed by signal N
        problems.append("crash: signal %d" % (result["exit"] - 128))
    if created:
        problems.append("wrote outside the output folder: " + ", ".join(os.fsdecode(p) for p in sorted(created)[:3]))
    bound = max(256, 4 * size / MB)
    if result["rss_mb"] > bound:
        problems.append("memory: peak RSS %.0f MB > %.0f MB" % (result["rss_mb"], bound))
    expected = case.exits or ((0, 1, 2, 3) if case.flag else (0, 1, 3))
    if not result["timed_out"] and 0 <= result["exit"] < 128 and result["exit"] not in expected:
        problems.append("exit %d, expected %s" % (result["exit"], " or ".join(map(str, expected))))
    unclear = ""
    # lc2wf-reconstruct's exit 1 is "done, with warnings" (its --help); every other non-zero exit is an error.
    warned = result["exit"] == 1 and case.argv[0] == "{X:lc2wf-reconstruct}"
    if result["exit"] > 0 and not warned and not result["timed_out"] and result["exit"] < 128:
        wanted = [os.fsencode(case.flag)] if case.flag else [os.fsencode(os.path.basename(n)) for n in case.names]
        # A missing file found by listing a folder can only be reported through the folder.
        wanted += [os.fsencode(os.path.basename(os.path.dirname(n))) for n in case.names
                   if isinstance(case.files.get(n), casebook.Special) and case.files[n].kind == "missing"]
        wanted = [w for w in wanted if w] + [os.fsencode(w) for w in case.also_named]
        if wanted and not any(w in stderr for w in wanted):
            unclear = "does not name " + " or ".join(os.fsdecode(w) for w in wanted)
        elif not LOCATOR.search(stderr):
            unclear = "names no field, line, byte, flag or value"
    return problems, unclear


def run_case(case, work, fixtures, exe, env):
    """Runs one case in WORK/cases/ID and checks it: (record, problems, unclear message)."""
    cdir = work / "cases" / case.id
    (cdir / "tmp").mkdir(parents=True)
    size = materialise(case, cdir, str(fixtures), str(work / "escaped"))
    roots, shallow = (cdir, work / "fixtures", work / "escaped"), (work, work / "cases")
    before = snapshot(*roots, shallow=shallow)
    argv = [os.fsencode(expand(a, str(cdir), str(fixtures), str(work / "escaped"), exe)) for a in case.argv]
    run_env = dict(env, TMPDIR=str(cdir / "tmp"), HOME=str(cdir / "tmp"))
    err_path, out_path = work / "cases" / (case.id + ".stderr"), work / "cases" / (case.id + ".stdout")
    result = run_limited(argv, str(cdir), run_env, case.timeout, out_path, err_path, (4 << 30) + 8 * size)
    # Messages go to stderr; lc2wf-dataset reports failed buildings in its summary on stdout.
    err, out = err_path.read_bytes(), out_path.read_bytes()
    stderr = err + b"\n" + out
    after = snapshot(*roots, shallow=shallow)
    logs = [os.fsencode(str(p)) for p in (err_path, out_path, str(err_path) + ".rss")]
    allowed = [os.fsencode(str(cdir / a)) for a in case.allowed + ["tmp"]] + logs
    created = {p for p, v in after.items() if before.get(p) != v and not any(p == a or p.startswith(a + b"/") for a in allowed)}
    # A folder that holds an allowed path changes its mtime when that path is replaced (an atomic rename): not a write.
    created = {p for p in created if not (stat.S_ISDIR(after[p][0]) and before.get(p, (None,))[0] == after[p][0] and
                                          any(a.startswith(p + b"/") for a in allowed))}
    problems, message = check(case, result, stderr, created, size)
    record = {"id": case.id, "argv": [os.fsdecode(a) for a in argv], "result": result,
              "stderr": err.decode("utf-8", "replace")[-600:], "stdout": out.decode("utf-8", "replace")[-200:]}
    return record, problems, message


def forget_case(work, case):
    """Removes a passing case's folder and logs."""
    shutil.rmtree(work / "cases" / case.id, ignore_errors=True)
    for ext in (".stderr", ".stdout"):
        (work / "cases" / (case.id + ext)).unlink(missing_ok=True)


def sample(all_cases, count):
    """A deterministic sample spread over every family: round robin over the families' case lists."""
    by_family = {}
    for c in all_cases:
        by_family.setdefault(c.family, []).append(c)
    picked, queues = [], [list(v) for v in by_family.values()]
    step = {id(q): max(1, len(q) * len(queues) // max(count, 1)) for q in queues}
    # Each family starts at a different offset, so a small sample mixes truncations, flips, numbers, names.
    positions = {id(q): (37 * k) % len(q) for k, q in enumerate(queues)}
    taken = {id(q): 0 for q in queues}
    while len(picked) < count and any(taken[id(q)] < len(q) for q in queues):
        for q in queues:
            if taken[id(q)] < len(q) and len(picked) < count:
                picked.append(q[positions[id(q)] % len(q)])
                positions[id(q)] += step[id(q)]
                taken[id(q)] += step[id(q)]
    return picked


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True, help="build folder holding the commands")
    ap.add_argument("--work", default=None, help="scratch folder (default BUILD/adversarial)")
    ap.add_argument("--cases", type=int, default=0, help="run a spread sample of this many cases (0 = all)")
    ap.add_argument("--per-file", type=int, default=105, help="hostile versions of each input file")
    ap.add_argument("--seed", type=int, default=14)
    ap.add_argument("--family", default="", help="only families starting with this")
    ap.add_argument("--keep", action="store_true", help="keep every case folder (default: only failing ones)")
    args = ap.parse_args()

    exe = find_executables(args.bin)
    missing = [c for c in COMMANDS if c not in exe]
    if missing:
        sys.exit("adversarial: not built in %s: %s" % (args.bin, ", ".join(missing)))
    work = Path(args.work or Path(args.bin) / "adversarial").resolve()
    shutil.rmtree(work, ignore_errors=True)
    (work / "escaped").mkdir(parents=True)
    fx = Fixtures(work / "fixtures", exe).make()
    rng = random.Random(args.seed)
    todo = [c for c in casebook.all_cases(fx, rng, args.per_file) if c.family.startswith(args.family)]
    if args.cases:
        todo = sample(todo, args.cases)
    env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "OMP_NUM_THREADS": "1", "LANG": "C.UTF-8"}
    fixture_state = snapshot(work / "fixtures")
    failures, unclear, families = [], [], {}
    t0 = time.monotonic()
    for k, case in enumerate(todo):
        record, problems, message = run_case(case, work, fx.root, exe, env)
        result = record["result"]
        fam = families.setdefault(case.family, {"cases": 0, "failed": 0, "unclear": 0, "exit0": 0, "max_rss_mb": 0, "seconds": 0})
        fam["cases"] += 1
        fam["exit0"] += result["exit"] == 0
        fam["max_rss_mb"] = max(fam["max_rss_mb"], round(result["rss_mb"]))
        fam["seconds"] = round(fam["seconds"] + result["seconds"], 1)
        if problems:
            fam["failed"] += 1
            failures.append(dict(record, problems=problems))
        if message:
            fam["unclear"] += 1
            unclear.append(dict(record, unclear=message))
        if not problems and not message and not args.keep:
            forget_case(work, case)
        if (k + 1) % 250 == 0:
            print("adversarial: %d / %d cases, %d failed, %.0f s" % (k + 1, len(todo), len(failures), time.monotonic() - t0), flush=True)
    changed = {p for p, v in snapshot(work / "fixtures").items() if fixture_state.get(p) != v}
    if changed:
        failures.append({"id": "fixtures", "problems": ["fixtures changed: " + ", ".join(os.fsdecode(p) for p in sorted(changed)[:5])]})
    report = {"cases": len(todo), "failed": len(failures), "unclear_messages": len(unclear), "seconds": round(time.monotonic() - t0),
              "families": families, "failures": failures, "unclear": unclear}
    (work / "report.json").write_text(json.dumps(report, indent=1))
    print("%-34s %6s %6s %7s %7s %8s %8s" % ("family", "cases", "exit0", "failed", "unclear", "maxRSS", "seconds"))
    for name, f in sorted(families.items()):
        print("%-34s %6d %6d %7d %7d %7dM %8.0f" % (name, f["cases"], f["exit0"], f["failed"], f["unclear"], f["max_rss_mb"], f["seconds"]))
    for f in failures[:20]:
        print("FAILED %s: %s\n  %s\n  %s" % (f["id"], "; ".join(f["problems"]), " ".join(f.get("argv", [])), f.get("stderr", "")[-300:]))
    for u in unclear[:20]:
        print("UNCLEAR %s: %s\n  %s" % (u["id"], u["unclear"], u["stderr"][-300:].strip()))
    print("adversarial: %d cases, %d failed, %d unclear messages, %d s; report: %s" % (
        len(todo), len(failures), len(unclear), report["seconds"], work / "report.json"))
    return 1 if failures or unclear else 0


if __name__ == "__main__":
    sys.exit(main())
