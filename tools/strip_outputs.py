"""Keep the course's notebooks without outputs, so that running them never dirties the checkout.

    python tools/strip_outputs.py NB [NB ...]   strip these notebooks in place

Stripping removes outputs, execution counts, the per-cell view state JupyterLab records
(``collapsed``, ``scrolled``, ``execution``) and saved widget state, and writes the kernel and
language metadata the course commits, in nbformat's own layout: the form every notebook of
book/, exercises/ and solutions/ is committed in (tests/test_notebook_filter.py).

:func:`save_hook` is the JupyterLab server's pre-save hook (``jupyter/jupyter_server_config.py``,
which ``make lab`` passes to the server): a course notebook a student runs and saves (autosave
included) is written in that same form, byte for byte what git has, so ``git status`` stays clean
and a ``git pull`` of a course update meets no conflict. Notebooks elsewhere (the student's
``workspace/``) are saved as they are.
"""
from __future__ import annotations

import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]
KERNELSPEC = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}
VIEW_STATE = ("collapsed", "scrolled", "execution")


def stripped(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """The notebook as the repository keeps it (changed in place and returned)."""
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell["outputs"] = []
            cell["execution_count"] = None
        for key in VIEW_STATE:
            cell.get("metadata", {}).pop(key, None)
    nb.metadata.pop("widgets", None)
    nb.metadata["kernelspec"] = dict(KERNELSPEC)
    nb.metadata["language_info"] = {"name": "python"}
    return nb


def text_of(nb: nbformat.NotebookNode) -> str:
    return nbformat.writes(nb) + "\n"


def strip(path: str | Path) -> bool:
    """Strip one notebook file in place; True when it changed."""
    path = Path(path)
    before = path.read_text(encoding="utf-8")
    after = text_of(stripped(nbformat.reads(before, as_version=4)))
    if after != before:
        path.write_text(after, encoding="utf-8")
    return after != before


COURSE_FOLDERS = ("book", "exercises", "solutions")


def is_course_notebook(path: Path) -> bool:
    """Is ``path`` a notebook of this checkout's book/, exercises/ or solutions/?"""
    path = path.resolve()
    return path.suffix == ".ipynb" and any(path.parent == ROOT / d for d in COURSE_FOLDERS)


def save_hook(model: dict, path: str, contents_manager: object, **kwargs: object) -> None:
    """Jupyter's pre-save hook: a course notebook is saved in its committed form."""
    root = Path(getattr(contents_manager, "root_dir", ROOT))
    if model.get("type") != "notebook" or not is_course_notebook(root / path):
        return
    model["content"] = stripped(nbformat.from_dict(model["content"]))


if __name__ == "__main__":
    for p in sys.argv[1:]:
        if strip(p):
            print(f"stripped {p}")
