"""Multiple choice that must be read (issue #14, point 3), and the notebooks show the checker's options."""
import collections
from pathlib import Path

import nbformat
import pytest

from gm_core import checks
from gm_core.checks.exercise import REGISTRY, exercise_ids

ROOT = Path(__file__).resolve().parent.parent
CHOICES = [(ex_id, name, p) for ex_id in exercise_ids() for name, p in REGISTRY[ex_id].parts.items()
           if p.kind == "choice"]
pytestmark = pytest.mark.usefixtures("clean")


def test_correct_positions_are_balanced_across_the_course():
    positions = collections.Counter(list(p.options).index(sorted(p.key.correct)[0]) for _, _, p in CHOICES)
    assert len(CHOICES) >= 10
    n_letters = min(len(p.options) for _, _, p in CHOICES)
    fair = len(CHOICES) / n_letters
    assert all(positions[i] >= 1 for i in range(n_letters)), positions      # every position used
    assert max(positions.values()) <= fair + 1.5, positions                  # none dominates


def test_the_longest_option_is_not_a_tell():
    longest = sum(max(p.options.values(), key=len) == p.options[sorted(p.key.correct)[0]]
                  for _, _, p in CHOICES)
    assert longest <= len(CHOICES) // 4, f"the correct option is the longest in {longest} questions"


def test_option_order_is_stable():
    # the same letters and texts for every student and every run: the notebooks print the table
    again = {(e, n): dict(p.options) for e, n, p in CHOICES}
    import importlib
    for mod in ("gm_core.checks.ex1", "gm_core.checks.ex3"):
        importlib.reload(importlib.import_module(mod))
    try:
        assert {(e, n): dict(REGISTRY[e].parts[n].options) for e, n, _ in CHOICES} == again
    finally:
        for e, n, p in CHOICES:       # put the originals back (reload made new objects)
            REGISTRY[e].parts[n] = p
            setattr(REGISTRY[e], n, p)


#: The notebooks render an option's maths in $...$; the checker says it in plain text (its words
#: are what a typed answer is matched against, and what the widget's radio buttons show).
_PLAIN = [("$", ""), ("\\mathbb{R}", "R"), ("R^+", "R+"), ("\\times", "x"), ("\\dot r", "r_dot"),
          ("\\omega_\\xi", "omega_xi"), ("\\alpha_1", "alpha1"), ("\\alpha_2", "alpha2"),
          ("\\theta", "theta"), ("\\xi", "xi"), ("\\exp", "exp"), ("\\log", "log"), ("\\neq", "!="),
          ("\\sim", "~")]


def _plain(text):
    for tex, plain in _PLAIN:
        text = text.replace(tex, plain)
    return text


@pytest.mark.parametrize("ex_id,name,part", CHOICES, ids=lambda x: str(x) if isinstance(x, str) else "")
def test_notebooks_show_the_checker_options(ex_id, name, part):
    rows = [f"| {k} | {text} |" for k, text in part.options.items()]
    assert _plain("| a | $\\mathbb{R}^2 \\times S^1$, $\\dot r$ |") == "| a | R^2 x S^1, r_dot |"
    assert _plain("| b | $\\log$ on $(\\mathbb{R}^+, \\times)$: $\\exp(a) \\neq \\omega_\\xi$ |") == \
        "| b | log on (R+, x): exp(a) != omega_xi |"
    for folder in ("solutions", "exercises"):
        nb = nbformat.read(ROOT / folder / f"ex{ex_id.replace('.', '_')}.ipynb", as_version=4)
        text = "\n".join(_plain(c.source) for c in nb.cells if c.cell_type == "markdown")
        assert all(r in text for r in rows), (folder, ex_id, name, [r for r in rows if r not in text])


def test_solution_views_are_recorded(capsys):
    checks.ex3_2.b.solution()
    assert checks.solutions_viewed() == {"3.2": ["b"]}


def test_widget_records_and_reads_letters():
    w = checks.ex3_4.c.widget()
    w.radio.value = sorted(checks.ex3_4.c.key.correct)[0]
    w.button.click()
    assert "passed" in w.feedback.value
