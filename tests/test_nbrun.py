"""The plumbing that shares nbval's one execution of each notebook (tests/nbrun.py): reading a
record that another worker is still writing, and never waiting for one nobody is making."""
import json
import os
import threading
import time

import nbrun


def _record(rel, complete=True, epilogue=None):
    return {"path": rel, "complete": complete, "epilogue": epilogue, "breaches": [], "errors": []}


def test_a_notebook_nobody_executes_is_not_waited_for(tmp_path, monkeypatch):
    monkeypatch.setenv(nbrun.ENV, str(tmp_path))
    t = time.monotonic()
    assert nbrun.wait_for_record(tmp_path / "never.ipynb", timeout=30) is None
    assert time.monotonic() - t < 2


def test_a_record_being_written_elsewhere_is_waited_for(tmp_path, monkeypatch):
    monkeypatch.setenv(nbrun.ENV, str(tmp_path))
    path = tmp_path / "nb.ipynb"
    rel = nbrun.rel_of(path)
    (tmp_path / "executions.jsonl").write_text(json.dumps({"path": rel, "host": "kernel"}) + "\n")

    def finish_later():   # as nbrun._write does: the whole record appears at once (os.replace)
        time.sleep(1.0)
        tmp = tmp_path / "record.tmp"
        tmp.write_text(json.dumps(_record(rel, epilogue={"code": "E"})))
        os.replace(tmp, tmp_path / f"{nbrun.slug(rel)}.json")

    threading.Thread(target=finish_later).start()
    rec = nbrun.wait_for_record(path, epilogue="E", timeout=30)
    assert rec is not None and rec["complete"] and rec["epilogue"]["code"] == "E"
    # finished, but with another epilogue or incomplete: no waiting, no record
    assert nbrun.wait_for_record(path, epilogue="other", timeout=30) is None
    (tmp_path / f"{nbrun.slug(rel)}.json").write_text(json.dumps(_record(rel, complete=False)))
    assert nbrun.wait_for_record(path, timeout=30) is None


def test_waiting_is_bounded(tmp_path, monkeypatch):
    monkeypatch.setenv(nbrun.ENV, str(tmp_path))
    path = tmp_path / "slow.ipynb"
    (tmp_path / "executions.jsonl").write_text(json.dumps({"path": nbrun.rel_of(path), "host": "kernel"}) + "\n")
    t = time.monotonic()
    assert nbrun.wait_for_record(path, timeout=1.0) is None
    assert 0.9 < time.monotonic() - t < 5


def test_the_executed_form_holds_each_code_cells_outputs_and_run_all_counts(tmp_path):
    """What the figure-fit test shows in JupyterLab for a notebook without live parts."""
    src = {"cells": [{"cell_type": "markdown", "metadata": {}, "source": "# t"},
                     {"cell_type": "code", "execution_count": None, "metadata": {}, "outputs": [], "source": "1"},
                     {"cell_type": "markdown", "metadata": {}, "source": "x"},
                     {"cell_type": "code", "execution_count": None, "metadata": {}, "outputs": [], "source": "2"},
                     {"cell_type": "code", "execution_count": None, "metadata": {}, "outputs": [], "source": "pass"}],
           "metadata": {}, "nbformat": 4, "nbformat_minor": 5}
    path = tmp_path / "nb.ipynb"
    path.write_text(json.dumps(src))
    shown = {"output_type": "execute_result", "data": {"text/plain": "2"}, "metadata": {}, "execution_count": 2}
    record = dict(_record(nbrun.rel_of(path)), outputs={"2": [shown]})
    nb = nbrun.executed_notebook(record)
    code = [c for c in nb["cells"] if c["cell_type"] == "code"]
    assert [c["execution_count"] for c in code] == [1, 2, 3]
    assert [c["outputs"] for c in code] == [[], [shown], []]
    assert [c["source"] for c in nb["cells"]] == [c["source"] for c in src["cells"]]
    assert json.loads(path.read_text()) == src   # the notebook on disk is untouched


def test_the_unit_worker_takes_the_first_group_without_a_notebook_while_there_is_one():
    queue = ["browser", "nb:book/01.ipynb", "tests/test_grade.py", "nb:exercises/ex1_1.ipynb", "tests/test_blit.py"]
    assert nbrun.next_group(queue, unit_worker=False) == "browser"
    assert nbrun.next_group(queue, unit_worker=True) == "tests/test_grade.py"
    assert nbrun.next_group(queue[3:], unit_worker=True) == "tests/test_blit.py"
    # only notebook groups left: it takes them too, rather than stop early
    assert nbrun.next_group(["nb:book/01.ipynb", "browser"], unit_worker=True) == "nb:book/01.ipynb"
    assert nbrun.next_group(["nb:book/01.ipynb", "browser"], unit_worker=False) == "nb:book/01.ipynb"
