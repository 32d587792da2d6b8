"""Every interactive chapter notebook, opened in a real JupyterLab in headless Chromium, used as a
student uses it (issue 19): 1366 x 768 window, file browser open.

For each ``book/*.ipynb`` containing ``%matplotlib widget`` (found when pytest collects, so new
chapters are covered automatically), opened and run once: Run All, every code cell ran, no output
shows a traceback or "Error displaying widget"; then on that one page (tests/browser/labview.py,
tests/browser/student.py): layout and panel state against a cell-by-cell run (this run's one
execution of the notebook, tests/nbrun.py), slider tracks >= 150 px, nothing cut, every panel
with its controls on one screen, ▶ plays every animation, the first slider of every panel
dragged quickly ends on the same picture as a slow drag to the same value, and no page error,
failed request or request off the machine.

``test_detector_*`` and ``test_student_checks_can_fail`` keep the proof that the checks can fail
inside the suite: generated notebooks with a working and a dead panel, and with a panel that
loses difference frames with and without key frames, a squeezed slider and a too-tall panel.
"""
from __future__ import annotations

import time

import browserlab
import labview
import nbrun
import pytest
import student

# each notebook's test runs in its notebook's xdist group (nbrun.params); the self-checks in "browser"
# (tests/nbrun.py: default_groups)
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


def test_student_checks_can_fail(lab, record_timing, prestart_next):
    """The student's checks on a generated notebook (student.student_selfcheck_notebook): a
    panel whose dropped difference frames are repaired by a key frame passes the drag check, the
    same panel without key frames fails it, a long label's short track and a too-tall panel are
    named, and ▶ plays an animation."""
    with browserlab.NotebookPage(lab, student.STUDENT_SELFCHECK_PATH) as nbp:
        nbp.open()
        prestart_next()
        nbp.run_all()
        nbp.check_no_errors()
        t0 = time.monotonic()
        student.wait_for_pictures(nbp)
        nbp.page.wait_for_timeout(1000)
        controls = student.control_problems(nbp)
        t0 = nbp.timings.mark("look", t0)
        anims, n_anims = student.play_animations(nbp)
        t0 = nbp.timings.mark("play", t0)
        drags, info = student.drag_check(nbp)   # times its own parts ("drag: ...")
        nbp.check_no_errors()
    record_timing("(student self-check notebook)", nbp.timings.phases)
    rows = {r["panel"]: r for r in info["panels"]}
    assert len(rows) == 3 and all(r["moved"] and r["changed"] for r in rows.values()), info
    assert rows[0]["differing"] <= student.PIXEL_TOLERANCE, f"key frames did not repair the picture: {info}"
    assert rows[2]["differing"] <= student.PIXEL_TOLERANCE, info
    assert rows[1]["differing"] > student.PIXEL_TOLERANCE, f"the dropped frames' ghost was not seen: {info}"
    assert [p for p in drags if p.startswith("panel #1 ")] and not [p for p in drags if not p.startswith("panel #1 ")], drags
    assert n_anims == 1 and anims == [], anims
    assert any("In[4]" in p and "track" in p and "a label long enough" in p for p in controls), controls
    assert any("In[4]" in p and "px tall" in p for p in controls), controls
    assert not [p for p in controls if "In[4]" not in p], controls


@pytest.mark.parametrize("notebook", nbrun.params(NOTEBOOKS, id_of=lambda p: p.name))
def test_interactive_notebook_as_a_student_uses_it(notebook, lab, record_timing, prestart_next):
    """Run All, then what a student sees and does (1366 x 768 window, file browser open):

    * nothing overflows its output area, every animation shows a picture, every named panel holds
      what a cell-by-cell run gives (labview);
    * every slider track is >= 150 px, no label, checkbox, button or readout is cut, and no panel
      with its controls is taller than one laptop screen (student.control_problems);
    * ▶ plays every animation (student.play_animations);
    * the first slider of every panel, dragged quickly, leaves the same picture as a slow drag to
      the same value, and the picture follows the slider (student.drag_check); the kernel serves
      the widgets' messages on its main thread only, so no figure is drawn from two threads at
      once (student.widget_threads);
    * no cell or widget error, no page error, no failed request and no request off the machine;
    * saved, closed and reopened without a kernel, its animations still play (student.replay_saved).
    """
    relpath = notebook.relative_to(browserlab.ROOT).as_posix()
    problems, info = [], {}
    expected = labview.expected_panel_state(notebook)   # the reference: this run's execution
    with browserlab.NotebookPage(lab, relpath) as nbp:
        nbp.open()
        prestart_next()
        nbp.run_all()
        nbp.check_no_errors()
        t0 = time.monotonic()
        student.wait_for_pictures(nbp)
        settled = student.settle_panels(nbp)   # the widgets' first messages from the browser have been answered
        layout, info["counts"] = labview.layout_problems(nbp)
        problems += layout
        problems += [f"Run All differs from cell by cell: {d}" for d in
                     labview.compare_panel_states(labview.kernel_panel_state(nbp), expected)]
        problems += student.control_problems(nbp)
        t0 = nbp.timings.mark("look", t0)
        anim_problems, info["animations"] = student.play_animations(nbp)
        problems += anim_problems
        t0 = nbp.timings.mark("play", t0)
        drag_problems, drags = student.drag_check(nbp, settled=settled)   # times its own parts ("drag: ...")
        t0 = time.monotonic()
        problems += drag_problems + student.widget_threads(nbp)
        info["panels dragged"] = len(drags["panels"])
        nbp.timings.mark("threads", t0)
        problems += nbp.page_problems
        nbp.check_no_errors(page_problems=False)
        if info["animations"]:  # saved, closed, reopened with no kernel: the animations still play
            t0 = time.monotonic()
            replay, _ = student.replay_saved(nbp)
            problems += replay + [p for p in nbp.page_problems if p not in problems]
            nbp.timings.mark("reopen", t0)
        if problems:
            info["screenshot"] = nbp.screenshot()
    record_timing(relpath, nbp.timings.phases)
    assert not problems, f"{relpath} as the student uses it ({info}):\n  " + "\n  ".join(problems)
