"""The student-side half of grading: run inside the graded notebook's own kernel.

``collect_all`` runs every part's probes on the notebook's answers (in the sandbox, under the
time limit) and returns JSON text of plain outcomes. The grader (:mod:`gm_core.grade`) decodes it
and judges in its own process, so nothing the notebook did to gm_core, the checkers or their
state in its kernel can change the verdicts.
"""
from __future__ import annotations

import json

from ._core import REGISTRY
from ._sandbox import collect, safe_name, safe_text

MARKER = "<<gm-course-grading>>"


def collect_all(ex_id, getters, time_limit=None):
    """{part name: {"outcomes": [...], "output": text} or {"missing": reason}} as JSON text.

    ``getters`` maps part names to zero-argument functions returning the answer (so a missing
    variable is a per-part NameError, not a failed cell).
    """
    ex = REGISTRY[str(ex_id)]
    out = {}
    for name, part in ex.parts.items():
        get = getters.get(name)
        if get is None:
            out[name] = {"missing": "no check cell for this part was found in the notebook"}
            continue
        try:
            answer = get()
        except BaseException as exc:  # noqa: BLE001 - NameError for a deleted variable, anything
            out[name] = {"missing": f"the answer could not be read ({safe_name(exc)}: {safe_text(exc, 120)})"}
            continue
        outcomes, output = collect(answer, part.probes(), time_limit, raw=True)
        out[name] = {"outcomes": outcomes, "output": output}
    return json.dumps(out)
