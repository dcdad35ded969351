#!/usr/bin/env python3
"""Proves that the adversarial checks of run.py can fail: each deliberately broken command below runs
through the same harness as the real cases and must be flagged for the reason it was built for, and a
well-behaved one must pass. A CTest next to the sample of the corpus.

  selfcheck.py WORK_DIR"""
import os
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import run  # noqa: E402
from cases import Case  # noqa: E402

PY = sys.executable
INPUT = "in/c.lcloud"
# (name, command line, what the harness must report: a problem or unclear-message text; "" = must pass)
CASES = [
    ("segfault", [PY, "-c", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)"], "crash: signal 11"),
    ("abort", [PY, "-c", "import os; os.abort()"], "crash: signal 6"),
    ("hang", ["/bin/sleep", "30"], "hang"),
    ("escape", ["/bin/sh", "-c", "echo x > {ESC}/x"], "wrote outside the output folder"),
    ("overwrites_its_input", ["/bin/sh", "-c", "echo x >> {C}/" + INPUT], "wrote outside the output folder"),
    ("memory", [PY, "-c", "b = b'x' * (400 << 20)"], "memory: peak RSS"),
    ("usage_error_for_a_file", ["/bin/sh", "-c", "echo 'c.lcloud: line 1: bad' >&2; exit 2"], "exit 2, expected 0 or 1 or 3"),
    ("exit_code_off_the_convention", ["/bin/sh", "-c", "echo 'c.lcloud: line 1: bad' >&2; exit 4"], "exit 4"),
    ("names_no_file", ["/bin/sh", "-c", "echo 'bad input' >&2; exit 3"], "does not name c.lcloud"),
    ("locates_nothing", ["/bin/sh", "-c", "echo 'c.lcloud failed' >&2; exit 3"], "names no field"),
    ("well_behaved", ["/bin/sh", "-c", "mkdir -p out && echo ok > out/x && echo 'c.lcloud: line 3: num_segments is -1' >&2; exit 3"],
     ""),
]


def main():
    work = Path(sys.argv[1] if len(sys.argv) > 1 else "adversarial-selfcheck").resolve()
    shutil.rmtree(work, ignore_errors=True)
    for sub in ("escaped", "fixtures", "cases"):
        (work / sub).mkdir(parents=True)
    env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "LANG": "C.UTF-8"}
    wrong = 0
    for name, argv, wanted in CASES:
        case = Case("selfcheck", argv, {INPUT: b"valid"}, [INPUT], timeout=1 if name == "hang" else 30, id=name)
        record, problems, unclear = run.run_case(case, work, work / "fixtures", {}, env)
        found = problems + ([unclear] if unclear else [])
        ok = not found if not wanted else any(wanted in f for f in found)
        print("%-30s %s  %s" % (name, "ok  " if ok else "WRONG", "; ".join(found) or "passed"))
        wrong += not ok
    if wrong:
        print("selfcheck: %d of %d deliberately broken commands were judged wrongly" % (wrong, len(CASES)))
        return 1
    print("selfcheck: every broken command was caught, the well-behaved one passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
