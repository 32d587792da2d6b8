"""Write a Gradescope autograder zip for the course: ``python tools/gradescope_kit.py`` (``make gradescope``).

    python tools/gradescope_kit.py [--out build/gradescope/gm-course-autograder.zip]
                                   [--exercises 1.4 2.1 ...] [--weights weights.json]
                                   [--cell-timeout 120] [--time-limit 5]

The zip holds, at its top (where Gradescope expects them):

* ``setup.sh``: makes a virtual environment ``/autograder/gm-venv`` and installs the course into
  it **from the zip itself** (``course/``, with its ``[grader]`` extra; bubblewrap too when apt is
  there and it is missing);
* ``run_autograder``: grades the notebooks of ``/autograder/submission`` with
  ``python -m gm_grader`` into ``/autograder/results/results.json`` (``kit_run.py`` does the
  work);
* ``course/``: ``pyproject.toml``, ``README.md``, ``LICENSE``, ``gm_core/`` and ``gm_grader/``;
* ``assignment.json``: the exercises the assignment expects (and any weights), handed to the
  grader's ``--assignment``, so a missing notebook still gets its rows with 0 points;
* ``kit.json``: the grading options. The grader runs with ``--no-sandbox``, as its README says for
  Gradescope, where every submission has its own container (``--sandbox`` keeps bubblewrap).

Both scripts take their
paths from ``GM_AUTOGRADER_ROOT`` (default ``/autograder``) and the Python that makes the venv
from ``GM_AUTOGRADER_PYTHON`` (default ``python3``), so a test can run the kit in any folder.
"""
from __future__ import annotations

import argparse
import json
import re
import stat
import sys
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OUT = ROOT / "build" / "gradescope" / "gm-course-autograder.zip"
COURSE_FILES = ["pyproject.toml", "README.md", "LICENSE"]
EXERCISE_ID = re.compile(r"^\d+\.\d+$")

SETUP_SH = r"""#!/usr/bin/env bash
# Gradescope runs this once when it builds the autograder image. It installs the course from this
# zip (course/) into a virtual environment; nothing is downloaded but the course's dependencies.
set -euo pipefail
ROOT="${GM_AUTOGRADER_ROOT:-/autograder}"
PYTHON="${GM_AUTOGRADER_PYTHON:-python3}"
SRC="$ROOT/source"
if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
  need=""
  command -v "$PYTHON" >/dev/null 2>&1 || need="python3"
  "$PYTHON" -m venv --help >/dev/null 2>&1 || need="$need python3-venv"
  command -v bwrap >/dev/null 2>&1 || need="$need bubblewrap"
  if [ -n "$need" ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $need python3-pip || true
  fi
fi
"$PYTHON" -m venv "$ROOT/gm-venv"
"$ROOT/gm-venv/bin/python" -m pip install --quiet --disable-pip-version-check "$SRC/course[grader]"
"$ROOT/gm-venv/bin/python" -c "import gm_core, gm_grader, nbclient; print('gm-course installed:', gm_core.__file__)"
# Gradescope's container has no sandbox, so the grader runs every notebook as a user of its own:
# only root may read the answer keys and the course's source (solutions included); that user
# may only enter $ROOT and run the venv's Python.
KEYS="$("$ROOT/gm-venv/bin/python" -c "import gm_core.checks.keys as k, os; print(os.path.dirname(k.__file__))")"
chmod -R go-rwx "$KEYS" "$SRC"
chmod go+x "$ROOT"
"""

RUN_AUTOGRADER = r"""#!/usr/bin/env bash
# Gradescope runs this for every submission: /autograder/submission -> /autograder/results.
set -uo pipefail
ROOT="${GM_AUTOGRADER_ROOT:-/autograder}"
mkdir -p "$ROOT/results"
cd "$ROOT"
exec "$ROOT/gm-venv/bin/python" "$ROOT/source/kit_run.py"
"""

KIT_RUN = r'''"""Grade /autograder/submission into /autograder/results with the installed course."""
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(os.environ.get("GM_AUTOGRADER_ROOT", "/autograder"))
SRC = ROOT / "source"
RES = ROOT / "results"
KIT = json.loads((SRC / "kit.json").read_text())


def main():
    RES.mkdir(parents=True, exist_ok=True)
    sub = ROOT / "submission"
    sub.mkdir(parents=True, exist_ok=True)
    cmd = [sys.executable, "-m", "gm_grader", str(sub), "--out", str(RES),
           "--assignment", str(SRC / "assignment.json"),
           "--cell-timeout", str(KIT["cell_timeout"]), "--time-limit", str(KIT["time_limit"])]
    if not KIT["sandbox"]:
        cmd.append("--no-sandbox")   # Gradescope gives every submission its own container
    report = RES / "results.json"
    report.unlink(missing_ok=True)   # so a report found below is this run's
    res = subprocess.run(cmd, cwd=str(ROOT), capture_output=True, text=True)
    print(res.stdout[-4000:], res.stderr[-4000:], sep="\n")
    # Exit 4 (the grader failed on some notebook) still writes every other grade, and rows for
    # that notebook saying the fault is the grader's: that report stands.
    if res.returncode not in (0, 4) or not report.exists():
        failed = {"score": 0.0, "tests": [],
                  "output": "The autograder could not grade this submission; please tell your instructor."}
        report.write_text(json.dumps(failed, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
'''


def _exercise_ids():
    return sorted(p.stem[2:].replace("_", ".") for p in (ROOT / "exercises").glob("ex*_*.ipynb"))


def _add(zf: zipfile.ZipFile, arcname: str, data, executable=False):
    info = zipfile.ZipInfo(arcname, date_time=(2020, 1, 1, 0, 0, 0))
    info.external_attr = ((0o755 if executable else 0o644) | stat.S_IFREG) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    zf.writestr(info, data)


def build_kit(out: Path = DEFAULT_OUT, exercises=None, weights=None, cell_timeout=120.0, time_limit=5.0,
              sandbox=False) -> Path:
    """Write the zip; return its path. ``exercises``: ids such as "1.4" (default: all)."""
    known = _exercise_ids()
    exercises = list(exercises) if exercises else known
    bad = [e for e in exercises if not EXERCISE_ID.match(str(e)) or e not in known]
    if bad:
        raise ValueError(f"exercises: unknown exercise id(s) {bad}; known: {', '.join(known)}")
    if weights is not None and not isinstance(weights, dict):
        raise TypeError("weights: a JSON object {part id: points}")
    if not (cell_timeout > 0 and time_limit > 0):
        raise ValueError("cell_timeout and time_limit must be positive seconds")
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    kit = {"cell_timeout": float(cell_timeout), "time_limit": float(time_limit), "sandbox": bool(sandbox)}
    assignment = {"exercises": exercises, **({"weights": weights} if weights else {})}
    with zipfile.ZipFile(out, "w") as zf:
        _add(zf, "setup.sh", SETUP_SH, executable=True)
        _add(zf, "run_autograder", RUN_AUTOGRADER, executable=True)
        _add(zf, "kit_run.py", KIT_RUN)
        _add(zf, "kit.json", json.dumps(kit, indent=1) + "\n")
        _add(zf, "assignment.json", json.dumps(assignment, indent=1) + "\n")
        for name in COURSE_FILES:
            _add(zf, f"course/{name}", (ROOT / name).read_bytes())
        for path in sorted(p for pkg in ("gm_core", "gm_grader") for p in (ROOT / pkg).rglob("*")
                           if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"):
            _add(zf, f"course/{path.relative_to(ROOT).as_posix()}", path.read_bytes())
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python tools/gradescope_kit.py", description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT, help="the zip to write")
    ap.add_argument("--exercises", nargs="+", help="exercise ids the assignment expects, e.g. 1.4 2.1 (default all)")
    ap.add_argument("--weights", type=Path, help="JSON {part id: points}, as for python -m gm_grader")
    ap.add_argument("--cell-timeout", type=float, default=120.0)
    ap.add_argument("--time-limit", type=float, default=5.0)
    ap.add_argument("--sandbox", action="store_true", help="grade inside bubblewrap on the autograder too")
    args = ap.parse_args(argv)
    weights = json.loads(args.weights.read_text()) if args.weights else None
    try:
        out = build_kit(args.out, args.exercises, weights, args.cell_timeout, args.time_limit, args.sandbox)
    except (ValueError, TypeError) as exc:
        print(f"gradescope_kit: {exc}", file=sys.stderr)
        return 2
    print(f"wrote {out} ({out.stat().st_size / 1e3:.0f} kB): upload it as the assignment's autograder "
          f"(Gradescope: Configure Autograder -> Zip file upload)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
