"""Where does the CPU time of `make test` go? (the suite's budget is its CPU time, not its wall time)

`make test` is one pytest run over tests/, book/, exercises/ and solutions/ on pytest-xdist
workers (Makefile: TEST_WORKERS, `--dist loadgroup`). Every notebook is executed once, by its own
test item; the tests that look at a notebook (figure standard, exercises, quiet outputs, browser)
read the record of that execution (tests/nbrun.py). Each run leaves its record in
build/nbrun/run-*/: seconds and tests per test file (by-file.json), per worker (workers.json) and
one line per execution of a notebook (executions.jsonl). This script times one `make test`
(set-up first, not counted) and prints the table from that record:

    .venv/bin/python benchmarks/suite_time.py               # make test, then the table
    .venv/bin/python benchmarks/suite_time.py --last        # the table of the latest run only
    .venv/bin/python benchmarks/suite_time.py --args "-m 'not browser'"   # PYTEST_ARGS
    .venv/bin/python benchmarks/suite_time.py --direct   # pytest without make (shared venv)

The CPU seconds of every process of the run are the number to compare between runs; before and
after the run it times 10^7 Python additions, because this machine's speed varies with its load.

"seconds" are summed over the workers (setup + call + teardown of every test in the group); the
workers share the cores, so a test's seconds include its waits for the CPU. Figure checks run in
the notebooks' kernels, so they count in the "notebooks ..." rows.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import shlex
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RUNS = ROOT / "build" / "nbrun"
#: the suite's CPU seconds (every process of `make test`) before House round 3 (issue 34): keep
#: it within 15 % of this unless a new test earns it
BASELINE_CPU_S = 675.0

#: rows of the table: a name and what belongs to it (first match wins, by file category)
GROUPS = [
    ("notebooks: book (executed + figure checks)", lambda c: c == "notebooks book"),
    ("notebooks: exercises (executed + checks)", lambda c: c == "notebooks exercises"),
    ("notebooks: solutions (executed + checks)", lambda c: c == "notebooks solutions"),
    ("readers of the record", lambda c: c in ("tests/test_figure_standard.py", "tests/test_exercises.py",
                                              "tests/test_notebook_outputs.py")),
    ("browser (JupyterLab + Chromium)", lambda c: c == "browser" or c.startswith("tests/browser/")),
    ("grader (tests/test_grade.py)", lambda c: c == "tests/test_grade.py"),
    ("fuzz", lambda c: "fuzz" in c),
    ("blitting (tests/test_blit.py)", lambda c: c == "tests/test_blit.py"),
    ("checkers (tests/test_checks*.py)", lambda c: c.startswith("tests/test_checks")),
    ("widgets (tests/test_widgets*, geometry_widgets)", lambda c: "widgets" in c),
    ("other unit tests", lambda c: True),
]


#: 10^7 Python additions on this 2-core machine, quiet hour .. busy hour
LOOP_SECONDS_HERE = "0.62 s in a quiet hour, up to 1.2 s in a busy one"


def loop_seconds(n: int = 10_000_000) -> float:
    """Wall seconds of ``n`` Python additions, the best of three: the machine's speed now."""
    best = float("inf")
    for _ in range(3):
        t0, s = time.perf_counter(), 0
        for i in range(n):
            s += i
        best = min(best, time.perf_counter() - t0)
    return best


def latest_run() -> Path | None:
    runs = sorted(p for p in RUNS.glob("run-*") if (p / "by-file.json").exists())
    return runs[-1] if runs else None


def table(run: Path, wall: float | None = None, rc: int | None = None, cpu_all: float | None = None) -> str:
    by_file = json.loads((run / "by-file.json").read_text(encoding="utf-8"))
    rows = {name: {"tests": 0, "failed": 0, "seconds": 0.0, "files": 0} for name, _ in GROUPS}
    for cat, v in by_file.items():
        name = next(n for n, match in GROUPS if match(cat))
        r = rows[name]
        r["tests"] += v["tests"]
        r["failed"] += v["failed"]
        r["seconds"] += v["seconds"]
        r["files"] += 1
    lines = [f"`make test` by test group (run {run.name})", ""]
    hdr = f"{'group':<48} {'tests':>6} {'failed':>6} {'seconds':>8}"
    lines += [hdr, "-" * len(hdr)]
    for name, _ in GROUPS:
        r = rows[name]
        if r["tests"] or r["seconds"]:
            lines.append(f"{name:<48} {r['tests']:>6} {r['failed']:>6} {r['seconds']:>8.1f}")
    total = sum(r["seconds"] for r in rows.values())
    lines += ["-" * len(hdr), f"{'sum over all tests (all workers)':<48} {sum(r['tests'] for r in rows.values()):>6} "
              f"{sum(r['failed'] for r in rows.values()):>6} {total:>8.1f}"]
    if wall is not None:
        lines.append(f"{'wall time of make test (after set-up)':<48} {'':>6} {'':>6} {wall:>8.1f}  "
                     f"(exit code {rc})")
    try:   # how evenly the workers were loaded (tests/nbrun.py)
        workers = json.loads((run / "workers.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        workers = {}
    if workers:
        lines.append("workers (summed test seconds; when each reported its last test, s after the start): "
                     + ", ".join(f"{k} {v['seconds']:.0f} s, last at {v['last']:.0f} s" for k, v in workers.items()))
    cpu = {}
    for f in run.glob("*.json"):
        if f.name.endswith(".kernel.json") or f.name in ("by-file.json",
                                                          "workers.json"):
            continue
        try:
            rec = json.loads(f.read_text(encoding="utf-8"))
        except ValueError:
            continue
        if isinstance(rec, dict) and "cpu_seconds" in rec:
            top = rec["path"].split("/")[0]
            cpu[top] = cpu.get(top, 0.0) + rec["cpu_seconds"]
    if cpu:
        lines.append("CPU seconds in the notebooks' kernels (cells + figure checks): "
                     + ", ".join(f"{k} {v:.1f}" for k, v in sorted(cpu.items())))
    if cpu_all is not None:
        lines.append(f"CPU seconds of every process of make test: {cpu_all:.1f} "
                     f"({cpu_all / BASELINE_CPU_S:.0%} of the baseline {BASELINE_CPU_S:.0f}; budget 115 %)")
    timings = []
    for f in sorted((run / "browser-timings").glob("*.json")):
        try:
            timings.append(json.loads(f.read_text(encoding="utf-8")))
        except ValueError:
            continue
    if timings:   # tests/browser/conftest.py: seconds per phase of each notebook's browser test
        lines += ["", "browser tests by phase (s):"]
        for t in sorted(timings, key=lambda t: -float(t["phases"].get("total", sum(
                v for k, v in t["phases"].items() if k != "total")))):
            ph = t["phases"]
            total = ph.get("total", sum(v for k, v in ph.items() if k != "total"))
            lines.append(f"  {t['name']:<44} {total:7.1f}  "
                         + ", ".join(f"{k} {v}" for k, v in ph.items() if k != "total"))
    ex = run / "executions.jsonl"
    counts = Counter()
    hosts = Counter()
    if ex.exists():
        for line in ex.read_text(encoding="utf-8").splitlines():
            e = json.loads(line)
            if "/selfcheck" in e["path"]:
                continue   # the generated notebooks of the self-checks
            counts[e["path"]] += 1
            hosts[e["host"]] += 1
    if counts:
        most = max(counts.values())
        lines += ["", f"notebook executions: {sum(counts.values())} of {len(counts)} notebooks "
                  f"({', '.join(f'{h} {n}' for h, n in sorted(hosts.items()))}); "
                  f"most executions of one notebook: {most}"
                  + ("" if most == 1 else " (" + ", ".join(p for p, n in counts.items() if n == most) + ")"),
                  "(not counted: JupyterLab Run All in the browser tests, and the grader's fresh kernels)"]
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--last", action="store_true", help="print the table of the latest run, run nothing")
    ap.add_argument("--args", default="", help="PYTEST_ARGS for make test (e.g. \"-m 'not browser'\")")
    ap.add_argument("--direct", action="store_true",
                    help="run `python -m pytest -n 2 --dist loadgroup` with this interpreter instead of `make setup` + `make test` "
                         "(for a shared venv that make must not re-install)")
    ap.add_argument("--log", default=str(ROOT / "benchmarks" / "results" / "suite_time.log"),
                    help="where make's output goes (default benchmarks/results/, git-ignored)")
    args = ap.parse_args(argv)
    if args.last:
        run = latest_run()
        if run is None:
            ap.error("no run recorded in build/nbrun/ yet")
        print(table(run))
        return 0
    Path(args.log).parent.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
    with open(args.log, "w") as log:
        if args.direct:
            cmd = [sys.executable, "-m", "pytest", "-n", "2", "--dist", "loadgroup", *shlex.split(args.args)]
        else:
            subprocess.run(["make", "setup"], cwd=ROOT, stdout=log, stderr=subprocess.STDOUT, env=env)
            cmd = ["make", "test"] + ([f"PYTEST_ARGS={args.args}"] if args.args else [])
        before = latest_run()
        speed = [loop_seconds()]
        print(f"  running {shlex.join(cmd)} ...", file=sys.stderr, flush=True)
        t0, r0 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT, env=env)
        wall, r1 = time.monotonic() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu_all = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        speed.append(loop_seconds())
    # the run this command made: the fullest run folder begun after it started (other pytest runs
    # in the same tree may have left smaller ones meanwhile)
    begun = [r for r in RUNS.glob("run-*") if (r / "by-file.json").exists() and r != before
             and r.stat().st_mtime >= time.time() - wall - 5]
    run = max(begun, key=lambda r: sum(v["tests"] for v in json.loads((r / "by-file.json").read_text()).values()),
              default=None)
    if run is None:
        print(f"make test left no record in build/nbrun/ (exit code {p.returncode}); see {args.log}")
        return 1
    print(f"\n{table(run, wall, p.returncode, cpu_all)}\n"
          f"machine speed: 10^7 Python additions took {speed[0]:.2f} s before the run and {speed[1]:.2f} s after "
          f"({LOOP_SECONDS_HERE} here; compare runs made at similar speeds)"
          f"\n\n(pytest output in {args.log}; command: {shlex.join(cmd)})")
    return 0 if p.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
