"""Quiet outputs (issue 19, point 7): no output of any executed notebook shows a warning.

Read from the record of the one execution of every notebook of book/, exercises/ and
solutions/ in this run (tests/nbrun.py): every output the kernel sent, cell by cell.
A warning is a stderr stream naming a ``...Warning`` (what Python's ``warnings`` module prints),
or the ``file:line: SomeWarning:`` line of ``warnings.showwarning`` in any text output. The cause
is fixed where it arises (gm_core), never filtered.

``test_warning_detector_*`` keeps the proof that the check can fail: a generated notebook that
warns, executed like the course's, is caught; a quiet one is not.
"""
from __future__ import annotations

import re
from pathlib import Path

import nbfigures
import nbrun
import pytest

NOTEBOOKS = nbfigures.course_notebooks()
_SHOWWARNING = re.compile(r":\d+: \w*Warning\b")
_NAMED = re.compile(r"\b\w*Warning\b")


def _texts(output: dict):
    if output.get("output_type") == "stream":
        yield output.get("name", ""), output.get("text", "")
    for mime, value in (output.get("data") or {}).items():
        if mime.startswith("text/"):
            yield mime, "".join(value) if isinstance(value, list) else str(value)


def warnings_in(record: dict) -> list[str]:
    """One line per output that shows a warning: ``<notebook> In[k] <stream or mime>: <first line>``."""
    out = []
    for k, outputs in sorted(record.get("outputs", {}).items(), key=lambda kv: int(kv[0])):
        for o in outputs:
            for where, text in _texts(o):
                hit = (_NAMED.search(text) if where == "stderr" else None) or _SHOWWARNING.search(text)
                if hit:
                    line = next((ln for ln in text.splitlines() if hit.group(0) in ln), text.strip()[:200])
                    out.append(f"{record['path']} In[{k}] {where}: {line.strip()[:300]}")
    return out


@pytest.mark.parametrize("path", nbrun.params(NOTEBOOKS))
def test_no_output_shows_a_warning(path, notebook_record):
    rec = notebook_record(path)
    assert rec["complete"] and rec.get("outputs"), f"{rec['path']}: no complete record of its outputs"
    found = warnings_in(rec)
    assert not found, f"{len(found)} outputs show a warning:\n  " + "\n  ".join(found)


@nbrun.SELFCHECK
def test_warning_detector_reads_the_outputs_the_kernel_sent(selfcheck_records):
    noisy, quiet = selfcheck_records["warns.ipynb"], selfcheck_records["quiet.ipynb"]
    found = warnings_in(noisy)
    assert len(found) == 2, found
    assert "In[1] stderr:" in found[0] and "UserWarning: the layout has changed" in found[0]
    assert "In[2] text/plain:" in found[1] and "RuntimeWarning" in found[1]
    assert warnings_in(quiet) == [] and quiet["outputs"]["1"], quiet["outputs"]


def test_warning_detector_on_outputs():
    rec = {"path": "x.ipynb", "outputs": {
        "1": [{"output_type": "stream", "name": "stderr", "text": "/a/b.py:3: DeprecationWarning: old\n  x()\n"}],
        "2": [{"output_type": "stream", "name": "stdout", "text": "no Warnings here, just a word\n"}],
        "3": [{"output_type": "stream", "name": "stderr", "text": "progress 3/10\n"}],
        "4": [{"output_type": "display_data", "data": {"text/plain": "f.py:12: UserWarning: hm"}}],
    }}
    found = warnings_in(rec)
    assert [f.split(" ", 2)[1] for f in found] == ["In[1]", "In[4]"], found
    assert Path(rec["path"]).suffix == ".ipynb"
