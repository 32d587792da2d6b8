"""Grading results: Gradescope's ``results.json`` and ``grades.csv``, written atomically.

Both files are written by the grading process only, after every sandbox has ended, each to a
temporary file in the output folder and then moved into place (``os.replace``), so a reader never
sees half a file and nothing a notebook started can be writing them. Each is written even when
the other cannot be (:class:`ReportError` then says which and why), and no text can stop either:
a name that is not UTF-8 (a lone surrogate, as Python reads such a name) is written with ``?``
in its place.
"""
from __future__ import annotations

import csv
import io
import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from gm_core.checks.files import atomic_write

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")
FIELDS = ["notebook", "exercise", "part", "status", "score", "max_score", "message"]


class ReportError(OSError):
    """One or both report files could not be written: ``causes`` says which and why;
    ``results`` is what was to be written."""

    def __init__(self, causes: Sequence[str], results: dict[str, Any]) -> None:
        super().__init__("; ".join(causes))
        self.causes = tuple(causes)
        self.results = results


def _text(v: Any) -> Any:
    """``v`` with every lone surrogate of a string replaced by ``?`` (always writable as UTF-8)."""
    if isinstance(v, str):
        return v.encode("utf-8", "replace").decode("utf-8")
    return v


def _clean(rows: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    return [{k: _text(v) for k, v in r.items()} for r in rows]


def check_visibility(v: str, what: str = "visibility") -> str:
    if v not in VISIBILITIES:
        raise ValueError(f"{what} must be one of {', '.join(VISIBILITIES)}; got {v!r}")
    return v


def results(rows: Sequence[Mapping[str, Any]], *, message: str = "", elapsed: float = 0.0,
            visibility: str = "visible", max_score: float | None = None) -> dict[str, Any]:
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
    out: dict[str, Any] = {"score": total, "execution_time": round(float(elapsed), 1), "output": message,
           "visibility": visibility, "stdout_visibility": "hidden", "tests": tests}
    if max_score is not None and top > 0 and abs(top - float(max_score)) > 1e-9:
        out["score"] = round(total * float(max_score) / top, 6)
        out["output"] = (message + "\n" if message else "") + (
            f"Points: {total:g} of {top:g}, scaled to the assignment's maximum of {float(max_score):g}.")
    return out


def write(rows: Sequence[Mapping[str, Any]], out_dir: str | Path, *, message: str = "",
          elapsed: float = 0.0, visibility: str = "visible",
          max_score: float | None = None) -> dict[str, Any]:
    """Write results.json and grades.csv into ``out_dir`` (atomically); return the results.
    Raises :class:`ReportError` (after writing what it could) when a file cannot be written."""
    rows = _clean(rows)
    res = results(rows, message=_text(message), elapsed=elapsed, visibility=visibility,
                  max_score=max_score)
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=FIELDS, extrasaction="ignore")
    w.writeheader()
    w.writerows(rows)
    out = Path(out_dir)
    causes = []
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ReportError([f"the output folder {out} could not be made ({exc})"], res) from None
    for name, text in (("grades.csv", buf.getvalue()),
                       ("results.json", json.dumps(res, indent=1) + "\n")):
        try:
            atomic_write(out / name, text)
        except (OSError, ValueError) as exc:
            causes.append(f"{out / name} could not be written ({type(exc).__name__}: {exc})")
    if causes:
        raise ReportError(causes, res)
    return res
