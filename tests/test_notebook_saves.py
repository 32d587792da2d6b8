"""Running a course notebook never dirties the checkout: the Jupyter server `make lab` starts saves
a notebook of book/, exercises/ or solutions/ in its committed form (jupyter/jupyter_server_config.py,
tools/strip_outputs.py), so after a student runs and saves one, `git status` is clean and a
`git pull` of a course update meets no conflict; the student's workspace/ keeps its outputs."""
import json
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import strip_outputs  # noqa: E402

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")


def git(cwd, *args):
    env = {"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@x", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@x", "HOME": str(cwd), "PATH": "/usr/bin:/bin"}
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True, env=env).stdout


def _server_contents_manager(root):
    """The contents manager of a Jupyter server started with the course's config file."""
    from jupyter_server.services.contents.filemanager import FileContentsManager
    from traitlets.config.loader import PyFileConfigLoader

    config = PyFileConfigLoader("jupyter_server_config.py", path=str(ROOT / "jupyter")).load_config()
    return FileContentsManager(root_dir=str(root), config=config)


def _run(nb):
    """What a student's Run All leaves in the notebook: outputs, counts, kernel metadata."""
    from nbclient import NotebookClient

    NotebookClient(nb, timeout=60, kernel_name="python3").execute()
    nb.metadata["language_info"] = {"name": "python", "version": sys.version.split()[0], "mimetype": "text/x-python"}
    nb.cells[0].metadata["scrolled"] = True
    return nb


def test_every_committed_notebook_is_in_its_saved_form():
    bad = [str(p.relative_to(ROOT)) for d in strip_outputs.COURSE_FOLDERS for p in sorted((ROOT / d).glob("*.ipynb"))
           if strip_outputs.text_of(strip_outputs.stripped(nbformat.read(p, as_version=4))) != p.read_text(encoding="utf-8")]
    assert not bad, f"notebooks not in their saved form (run python tools/strip_outputs.py on them): {bad}"


# traitlets applies a class's config twice and jupyter_server warns on the second, identical hook
@pytest.mark.filterwarnings("ignore:Overriding existing pre_save_hook:UserWarning")
def test_a_run_and_saved_notebook_stays_clean_and_a_course_update_pulls(tmp_path, monkeypatch):
    upstream, student = tmp_path / "course", tmp_path / "student"
    (upstream / "book").mkdir(parents=True)
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell("# A chapter"),
                                         nbformat.v4.new_code_cell("print(6 * 7)")])
    (upstream / "book" / "01.ipynb").write_text(strip_outputs.text_of(strip_outputs.stripped(nb)))
    shutil.copy(ROOT / ".gitignore", upstream / ".gitignore")          # checkpoints, workspace/
    git(upstream, "init", "-q", "-b", "main")
    git(upstream, "add", "-A")
    git(upstream, "commit", "-q", "-m", "course")
    git(tmp_path, "clone", "-q", str(upstream), str(student))
    monkeypatch.setattr(strip_outputs, "ROOT", student)          # the hook guards this clone's folders

    cm = _server_contents_manager(student)
    ran = _run(nbformat.read(student / "book" / "01.ipynb", as_version=4))
    assert "".join(ran.cells[1].outputs[0]["text"]) == "42\n"
    cm.save({"type": "notebook", "format": "json", "content": json.loads(nbformat.writes(ran))}, "book/01.ipynb")
    assert git(student, "status", "--porcelain") == ""                 # saved, and git sees no change

    (student / "workspace").mkdir()
    cm.save({"type": "notebook", "format": "json", "content": json.loads(nbformat.writes(ran))}, "workspace/ex.ipynb")
    kept = nbformat.read(student / "workspace" / "ex.ipynb", as_version=4)
    assert "".join(kept.cells[1].outputs[0]["text"]) == "42\n"         # the student's own notebooks keep outputs

    course = nbformat.read(upstream / "book" / "01.ipynb", as_version=4)
    course.cells[0].source = "# A chapter, corrected"
    (upstream / "book" / "01.ipynb").write_text(strip_outputs.text_of(course))
    git(upstream, "commit", "-q", "-am", "update")
    git(student, "pull", "-q", "--no-rebase")                          # no conflict, no refusal
    assert "corrected" in (student / "book" / "01.ipynb").read_text()


def test_without_the_course_config_the_same_save_dirties_the_checkout(tmp_path):
    """The check above can fail: a plain server writes the outputs and git sees the change."""
    from jupyter_server.services.contents.filemanager import FileContentsManager

    (tmp_path / "book").mkdir()
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("print(1)")])
    (tmp_path / "book" / "01.ipynb").write_text(strip_outputs.text_of(strip_outputs.stripped(nb)))
    git(tmp_path, "init", "-q")
    git(tmp_path, "add", "-A")
    git(tmp_path, "commit", "-q", "-m", "c")
    ran = _run(nbformat.read(tmp_path / "book" / "01.ipynb", as_version=4))
    FileContentsManager(root_dir=str(tmp_path)).save(
        {"type": "notebook", "format": "json", "content": json.loads(nbformat.writes(ran))}, "book/01.ipynb")
    assert "01.ipynb" in git(tmp_path, "status", "--porcelain")
