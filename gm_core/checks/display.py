"""How checkers show things: a coloured box in a notebook, plain text elsewhere; the progress
table in HTML. No gm_core imports but the status names."""
from __future__ import annotations

import html
import re
from collections.abc import Sequence

from gm_core.checks.store import FAILED, IN_PROGRESS, PASSED, UNATTEMPTED

COLORS = {PASSED: "#1a7f37", FAILED: "#b42318", UNATTEMPTED: "#6e7781", IN_PROGRESS: "#9a6700",
          "hint": "#7a5c00", "solution": "#0550ae", "notice": "#8250df"}
LABELS = {PASSED: "Correct", FAILED: "Not yet", UNATTEMPTED: "Unattempted", IN_PROGRESS: "In progress",
          "hint": "Hint", "solution": "Solution", "notice": "Course update"}


def in_notebook() -> bool:
    """True inside a Jupyter kernel (IPython with a kernel), where checkers show HTML boxes."""
    try:
        from IPython import get_ipython
    except Exception:  # noqa: BLE001 - IPython is always there with Jupyter
        return False
    ip = get_ipython()
    return ip is not None and hasattr(ip, "kernel")


#: A notebook named by a path relative to the notebook's folder (``../solutions/ex1_4.ipynb``).
_NOTEBOOK_PATH = re.compile(r"(?<![\w/.])(\.\./[\w.-]+(?:/[\w.-]+)*\.ipynb)")


def box_html(kind: str, title: str, message: str, extra: str = "") -> str:
    """The HTML of a message box: ``kind`` (a status, "hint", "solution", "notice") sets its colour
    and label; ``extra``, what the student's code printed, is folded away under the message. A
    relative path to a notebook in the message (``../solutions/ex1_4.ipynb``) becomes a link,
    which JupyterLab opens in a tab of its own."""
    color = COLORS.get(kind, "#333")
    label = LABELS.get(kind, kind)
    body = _NOTEBOOK_PATH.sub(r'<a href="\1">\1</a>',
                              html.escape(message)).replace("\n", "<br>")
    more = ""
    if extra:
        more = ('<details><summary style="color:#555">What your code printed</summary><pre '
                f'style="font-size:85%;max-height:12em;overflow:auto">{html.escape(extra)}</pre></details>')
    return (f'<div style="border-left:4px solid {color};padding:4px 10px;margin:4px 0">'
            f'<b style="color:{color}">{label}</b> <span style="color:#555">({html.escape(title)})'
            f'</span><br>{body}{more}</div>')


def show(kind: str, title: str, message: str, extra: str = "") -> None:
    """Display a coloured message box in a notebook, or print it as plain text elsewhere. Once."""
    if in_notebook():
        try:
            from IPython.display import HTML, display
            display(HTML(box_html(kind, title, message, extra)))
            return
        except Exception:  # noqa: BLE001
            pass
    label = LABELS.get(kind, kind)
    print(f"[{label}] ({title}) {message}")
    if extra:
        print("  Your code printed:\n    " + extra.replace("\n", "\n    "))


#: A mark beside each status in the progress table.
_ICON = {PASSED: "&#10004;", FAILED: "&#10008;", UNATTEMPTED: "&middot;", IN_PROGRESS: "&#9680;"}


def progress_table_html(rows: Sequence[tuple[str, str, str, str]], where: str = "") -> str:
    """The progress table in HTML, from its rows (exercise, status, parts passed, note), as
    ``ProgressTable.rows()`` gives them, and where the record is kept."""
    cells = []
    for ex_id, status, done, note in rows:
        color = COLORS.get(status, "#333")
        cells.append(f'<tr><td>{html.escape(ex_id)}</td><td style="color:{color}">'
                     f'{_ICON.get(status, "")} {html.escape(status)}</td>'
                     f'<td style="color:#555">{html.escape(done)}</td>'
                     f'<td style="color:#555">{html.escape(note)}</td></tr>')
    note = (f'<span style="color:#555;font-size:85%">Record: {html.escape(where)}.</span>'
            if where else "")
    return ('<table style="font-size:90%"><tr><th>exercise</th><th>status</th><th>parts passed</th>'
            "<th></th></tr>" + "".join(cells) + "</table>" + note)
