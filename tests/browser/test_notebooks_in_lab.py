"""Every interactive chapter notebook, opened in a real JupyterLab in headless Chromium.

For each ``book/*.ipynb`` containing ``%matplotlib widget`` (found when pytest collects, so new
chapters are covered automatically): wait for an idle kernel, Run All, check that every code cell
ran and that no output shows a traceback or "Error displaying widget", then move the first slider
of the first interactive panel with the keyboard and check that the ipympl canvas pixels changed.

``test_detector_*`` keeps the proof that the check can fail inside the suite: a generated notebook
has a working panel and one whose ``update`` does nothing; the same helper must say "changed" for
the first and "did not change" for the second.

The same test checks what the student sees after Run All (tests/browser/labview.py): the layout
at a 1366 x 768 window with the file browser open and the panels' state against a cell-by-cell
run; test_student_view.py covers the other notebooks with figures and the quiet start.
"""
from __future__ import annotations

import warnings

import browserlab
import labview
import pytest

pytestmark = pytest.mark.browser

NOTEBOOKS = browserlab.interactive_notebooks()


def test_detector_tells_a_live_panel_from_a_dead_one(lab, record_timing, prestart_next):
    with browserlab.NotebookPage(lab, browserlab.SELFCHECK_PATH) as page:
        page.open()
        prestart_next()
        page.run_all()
        page.check_no_errors()
        live = page.move_slider(page.find_panel(0), 0, change_timeout=20)
        dead = page.move_slider(page.find_panel(1), 0, change_timeout=2.5)
        page.check_no_errors()
    record_timing("(self-check notebook)", page.timings.phases)
    assert live.slider_moved and live.changed, f"working panel not detected as changing: {live}"
    assert dead.slider_moved, f"the broken panel's slider did not move, so the check proves nothing: {dead}"
    assert not dead.changed, f"a panel whose update does nothing was reported as changing: {dead}"


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_interactive_notebook_runs_and_responds(notebook, lab, record_timing, prestart_next):
    """... and, right after Run All (1366 x 768 window, file browser open): nothing overflows its
    output area, every animation shows a picture, and every named panel holds what a cell-by-cell
    run gives (labview)."""
    relpath = notebook.relative_to(browserlab.ROOT).as_posix()
    seen = {}

    def student_view(nbp):
        nbp.page.wait_for_timeout(1500)  # let the widgets' first messages from the browser arrive
        seen["layout"], seen["counts"] = labview.layout_problems(nbp)
        seen["state"] = labview.compare_panel_states(labview.kernel_panel_state(nbp),
                                                     labview.expected_panel_state(notebook))
        if seen["layout"] or seen["state"]:
            seen["screenshot"] = nbp.screenshot()

    result, phases = browserlab.check_interactive_notebook(lab, relpath, on_open=prestart_next,
                                                           after_run=student_view)
    record_timing(relpath, phases)
    assert result.changed and result.slider_moved, result
    problems = seen["layout"] + [f"Run All differs from cell by cell: {d}" for d in seen["state"]]
    assert not problems, (f"{relpath} as the student sees it ({seen['counts']}; screenshot "
                          f"{seen.get('screenshot')}):\n  " + "\n  ".join(problems))
    if not result.detail.startswith("panel #0, slider #0"):
        warnings.warn(f"{relpath}: the first slider of the first panel could not be judged; used {result.detail}", stacklevel=2)
