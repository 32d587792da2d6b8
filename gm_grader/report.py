"""Grading results: Gradescope's ``results.json`` and ``grades.csv``, written atomically.

Both files are written by the grading process only, after every sandbox has ended, each to a
temporary file in the output folder and then moved into place (``os.replace``), so a reader never
sees half a file and nothing a notebook started can be writing them.
"""
from __future__ import annotations

import csv
import io
import json
from pathlib import Path

from gm_core.checks.files import atomic_write

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")
FIELDS = ["notebook", "exercise", "part", "status", "score", "max_score", "message"]


def check_visibility(v, what="visibility"):
    if v not in VISIBILITIES:
        raise ValueError(f"{what} must be one of {', '.join(VISIBILITIES)}; got {v!r}")
    return v


def results(rows, *, message="", elapsed=0.0, visibility="visible", max_score=None):
    """Gradescope's results dict. ``rows`` carry ``visibility`` per test (default ``visibility``)."""
    check_visibility(visibility)
    tests = []
    for r in rows:
        name = f"{r['notebook']}: exercise {r['exercise']} part {r['part']}" if r["part"] else r["notebook"]
        tests.append({"name": name, "number": f"{r['exercise']}{r['part']}",
                      "score": float(r["score"]), "max_score": float(r["max_score"]),
                      "status": "passed" if r["status"] == "passed" else "failed",
                      "output": r["message"], "visibility": r.get("visibility", visibility)})
    total = sum(t["score"] for t in tests)
    top = sum(t["max_score"] for t in tests)
    out = {"score": total, "execution_time": round(float(elapsed), 1), "output": message,
           "visibility": visibility, "stdout_visibility": "hidden", "tests": tests}
    if max_score is not None and top > 0 and abs(top - float(max_score)) > 1e-9:
        out["score"] = round(total * float(max_score) / top, 6)
        out["output"] = (message + "\n" if message else "") + (
            f"Points: {total:g} of {top:g}, scaled to the assignment's maximum of {float(max_score):g}.")
    return out


def write(rows, out_dir, **kw):
    """Write results.json and grades.csv into ``out_dir`` (atomically); return the results."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    res = results(rows, **kw)
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=FIELDS, extrasaction="ignore")
    w.writeheader()
    w.writerows(rows)
    atomic_write(out_dir / "grades.csv", buf.getvalue())
    atomic_write(out_dir / "results.json", json.dumps(res, indent=1) + "\n")
    return res
