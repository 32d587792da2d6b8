"""The plumbing that executes each notebook once per run and shares its record (tests/nbrun.py)."""
import json
import os
import subprocess
import sys
import textwrap

import nbformat
import nbrun


def _record(rel, complete=True, epilogue=None):
    return {"path": rel, "complete": complete, "epilogue": epilogue, "breaches": [], "errors": []}


def test_a_record_names_the_cell_that_raised_and_is_made_once(tmp_path):
    """A generated notebook: a cell tagged raises-exception may raise, another may not; the
    record says which (Run All numbering), holds every cell's outputs, reaches the end, and a
    second reader gets the same record without a second execution."""
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell("x = 6 * 7\nprint(x)"),
                nbformat.v4.new_markdown_cell("text"),
                nbformat.v4.new_code_cell("1 / 0", metadata={"tags": ["raises-exception"]}),
                nbformat.v4.new_code_cell("undefined_name")]
    d = nbrun.run_dir() / "selfcheck-raises" / tmp_path.name
    d.mkdir(parents=True)
    path = d / "raises.ipynb"
    nbformat.write(nb, path)
    rec = nbrun.record(path)
    assert rec["complete"], rec["errors"]
    assert len(rec["errors"]) == 1 and "In[3]" in rec["errors"][0] and "NameError" in rec["errors"][0], rec["errors"]
    assert rec["outputs"]["1"][0]["text"] == "42\n"
    assert [o["output_type"] for o in rec["outputs"]["2"]] == ["error"]
    assert nbrun.record(path) is rec
    lines = (nbrun.run_dir() / "executions.jsonl").read_text(encoding="utf-8").splitlines()
    assert sum(json.loads(line)["path"] == nbrun.rel_of(path) for line in lines) == 1


def test_loadgroup_keeps_a_group_on_one_worker(tmp_path):
    """What `make test` relies on to execute each notebook once: under `--dist loadgroup`, every
    test of an xdist_group runs on one worker (pytest 9.2 with pytest-xdist 3.8 broke this:
    pyproject.toml pins pytest below 9.2)."""
    (tmp_path / "pytest.ini").write_text("[pytest]\naddopts = -p no:cacheprovider\n")
    (tmp_path / "test_groups.py").write_text(textwrap.dedent("""
        import os, pathlib, pytest

        @pytest.mark.xdist_group("one")
        @pytest.mark.parametrize("i", range(8))
        def test_grouped(i):
            pathlib.Path(f"grouped-{i}").write_text(os.environ["PYTEST_XDIST_WORKER"])

        @pytest.mark.parametrize("i", range(8))
        def test_free(i):
            assert i >= 0
    """))
    env = {k: v for k, v in os.environ.items() if k != nbrun.ENV}
    out = subprocess.run([sys.executable, "-m", "pytest", "-q", "-n", "2", "--dist", "loadgroup", "-c",
                          str(tmp_path / "pytest.ini"), "--rootdir", str(tmp_path), str(tmp_path / "test_groups.py")],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    workers = {(tmp_path / f"grouped-{i}").read_text() for i in range(8)}
    assert len(workers) == 1, f"the group ran on {sorted(workers)}"


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


def test_every_test_has_exactly_one_group(request):
    """pytest-xdist joins the names of every xdist_group mark a test carries, so a second mark
    (a module's pytestmark besides a notebook's) would take a reader out of its notebook's group."""
    items = request.session.items
    bad = [it.nodeid for it in items if len(list(it.iter_markers("xdist_group"))) != 1]
    assert not bad, f"tests with no group or several: {bad[:10]}"
    readers = [it for it in items if it.get_closest_marker(nbrun.MARK) is not None]
    wrong = [it.nodeid for it in readers
             if it.get_closest_marker("xdist_group").args[0] != nbrun.NOTEBOOK_GROUP + it.get_closest_marker(nbrun.MARK).args[0]]
    assert not wrong, f"readers outside their notebook's group: {wrong[:10]}"
