"""What a student sees in JupyterLab on a laptop (issue #12): a quiet start, and every figure whole.

* ``test_lab_starts_quiet``: a fresh JupyterLab page shows no "Get notified about official Jupyter
  news?" prompt, because the course's own settings (jupyter/overrides.json, installed by
  tools/lab_settings.py exactly as `make lab` and Binder's postBuild install it) say so;
  ``test_news_prompt_detector`` proves the check would see the prompt (user setting "Ask").
* ``test_layout_detector``: a generated notebook with a too-wide canvas, a blank animation image,
  an overflowing block and a scaled-down image, plus a good canvas: labview.layout_problems names
  exactly the four.
* ``test_figures_fit``: every notebook that draws and is not covered by
  test_notebooks_in_lab.py (exercises and solutions with ``%matplotlib inline``, static chapters),
  at 1366 x 768 with the file browser open: no output overflows its area, no image or canvas is
  wider than its area, every animation shows a picture. A notebook whose outputs hold no live
  part (no widget, no named panel) is shown as this run's one execution of it left it (
  tests/nbrun.py: the outputs Run All gives, opened in JupyterLab as the student's notebook);
  one with live parts is run with Run All, and its named panels must hold what a cell-by-cell
  run gives.
"""
from __future__ import annotations

import json
import time

import browserlab
import labview
import nbrun
import pytest

# each notebook's test runs in its notebook's xdist group (nbrun.params); the self-checks in "browser"
# (tests/nbrun.py: default_groups)
pytestmark = pytest.mark.browser

NOTEBOOKS = labview.figure_notebooks(exclude=set(browserlab.interactive_notebooks()))
NOTIFICATION = "/lab/api/settings/@jupyterlab/apputils-extension:notification"


def _fresh_lab_page(browser_context, lab_server):
    page = browser_context.new_page()
    page.goto(f"{lab_server.url}/lab?reset&token={lab_server.token}", wait_until="domcontentloaded",
              timeout=90_000)
    page.wait_for_function("() => window.jupyterapp && window.jupyterapp.shell && "
                           "document.querySelector('#filebrowser')", timeout=90_000)
    return page


def _wait_for_news(page, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        shown = labview.news_prompt_shown(page)
        if shown:
            return shown
        page.wait_for_timeout(250)
    return []


def test_lab_starts_quiet(lab_server, browser_context):
    setting = lab_server.api("GET", NOTIFICATION)
    defaults = {k: v.get("default") for k, v in setting["schema"]["properties"].items()}
    # the course's overrides change the defaults; the student has no setting of their own yet
    assert defaults["fetchNews"] == "false" and defaults["checkForUpdates"] is False, defaults
    assert json.loads(setting["raw"] or "{}") == {}, setting["raw"]
    page = _fresh_lab_page(browser_context, lab_server)
    try:
        shown = _wait_for_news(page, 6)
    finally:
        page.close()
    assert not shown, f"the news prompt is shown to the student: {shown}"


def test_news_prompt_detector(lab_server, browser_context):
    """With the user setting back at "Ask" the prompt appears, and the check sees it."""
    lab_server.api("PUT", NOTIFICATION, body={"raw": json.dumps({"fetchNews": "none"})})
    try:
        page = _fresh_lab_page(browser_context, lab_server)
        try:
            shown = _wait_for_news(page, 20)
        finally:
            page.close()
    finally:
        lab_server.api("PUT", NOTIFICATION, body={"raw": "{}"})
    assert shown, "with fetchNews 'none' the news prompt should appear (the detector sees nothing?)"


def test_layout_detector(lab, record_timing):
    with browserlab.NotebookPage(lab, labview.LAYOUT_SELFCHECK_PATH) as nbp:
        nbp.open()
        nbp.run_all()
        nbp.check_no_errors()
        problems, counts = labview.settled_layout(nbp)
    record_timing("(layout self-check notebook)", nbp.timings.phases)
    text = "\n".join(problems)
    assert counts["canvases"] >= 2 and counts["animations"] == 1, counts
    assert any(p.startswith("In[2]") and "canvas is 1200 px wide" in p for p in problems), text
    assert any(p.startswith("In[3]") and "the student sees no picture" in p for p in problems), text
    assert any(p.startswith("In[4]") and "output overflows its area" in p for p in problems), text
    assert not any(p.startswith("In[5]") for p in problems), text
    assert any(p.startswith("In[6]") and "image is 1200 px wide, shown scaled down" in p for p in problems), text
    assert 850 <= counts["minWidth"] <= 1000, f"output width at 1366 px with the file browser: {counts}"


def _executed_form(notebook) -> dict | None:
    """This run's executed form of ``notebook`` (tests/nbrun.py: its one execution), when Run All
    in JupyterLab shows exactly that: its outputs are pictures, text and HTML, with no widget,
    which would need its kernel, and no named panel (its state after the run is empty). None
    otherwise."""
    record = nbrun.record(notebook)
    if record.get("errors") or labview.parse_panel_state(record["epilogue"]["stdout"]):
        return None
    if any("application/vnd.jupyter.widget-view+json" in out.get("data", {})
           for outs in record["outputs"].values() for out in outs):
        return None
    return nbrun.executed_notebook(record)


@pytest.mark.parametrize("notebook", nbrun.params(NOTEBOOKS))
def test_figures_fit(notebook, lab, record_timing, prestart_next):
    """Run All's pictures at 1366 x 768 with the file browser open. A notebook whose outputs
    hold no live part is shown as this run executed it (the same kernel code that Run All runs,
    its one execution in this run, written where the student's notebook is and opened in JupyterLab);
    one with widgets or named panels is run in JupyterLab, and its panels' state must match the
    cell-by-cell run."""
    relpath = notebook.relative_to(browserlab.ROOT).as_posix()
    executed = _executed_form(notebook)
    with browserlab.NotebookPage(lab, relpath) as nbp:
        if executed is not None:
            (lab.server.course / relpath).write_text(json.dumps(executed), encoding="utf-8")
            nbp.open(kernel=False)
            nbp.check_no_errors()
            t0 = time.monotonic()
            problems, counts = labview.settled_layout(nbp)
            nbp.timings.mark("look", t0)
            st = nbp.read_status()
            if st["executed"] != st["ncode"]:
                problems.append(f"{st['ncode'] - st['executed']} code cells show no execution")
        else:
            nbp.open()
            prestart_next()
            nbp.run_all()
            nbp.check_no_errors()
            problems, counts = labview.settled_layout(nbp)
            state = labview.compare_panel_states(labview.kernel_panel_state(nbp),
                                                 labview.expected_panel_state(notebook))
            problems += [f"Run All differs from cell by cell: {d}" for d in state]
        shot = nbp.screenshot() if problems else None
    record_timing(relpath, nbp.timings.phases)
    assert not problems, (f"{relpath} as the student sees it ({counts}; screenshot {shot}):\n  "
                          + "\n  ".join(problems))
