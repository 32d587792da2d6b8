"""Math renders everywhere: no TeX or sub/superscript markup in notebook prose outside math and code.

JupyterLab renders ``$...$`` and ``$$...$$`` with MathJax; anything else is shown as typed, so a
formula written as ``g_{a,b}``, ``ξ^θ`` or ``\\dot g`` in plain prose reaches the student raw.
Over every markdown cell of book/, exercises/ and solutions/, after removing fenced and inline
code, HTML comments and math, this test fails on ``_{``, ``^`` (markdown has no superscripts),
backslash commands (``\\alpha``) and one-letter names with a subscript (``ω_ξ``), naming
notebook, cell and the offending text.
"""
import re
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted(p for d in ("book", "exercises", "solutions") for p in (ROOT / d).glob("*.ipynb"))

_FENCED = re.compile(r"^(```|~~~).*?^\1[^\n]*$", re.S | re.M)
_INLINE_CODE = re.compile(r"(`+)(?!`).+?(?<!`)\1(?!`)", re.S)
_COMMENT = re.compile(r"<!--.*?-->", re.S)
_HTML_CODE = re.compile(r"<(code|pre|kbd)\b[^>]*>.*?</\1>", re.S | re.I)
# math: $$...$$, $...$ (not an escaped \$), \(...\), \[...\]
_MATH = re.compile(r"\$\$.+?\$\$|(?<![\\$])\$(?!\$).+?(?<![\\$])\$|\\\(.+?\\\)|\\\[.+?\\\]", re.S)
# ``_{``, any ``^``, a backslash command, or a one-letter name with a subscript (``ω_ξ``, ``T_e``)
_BAD = re.compile(r"_\{|\^|\\[A-Za-z]+|(?<![\w/.-])[A-Za-zα-ωΑ-Ω]_[A-Za-z0-9α-ωΑ-Ω]")


def prose(text):
    """The markdown ``text`` with code, comments and math removed (what MathJax leaves alone)."""
    for pattern in (_FENCED, _COMMENT, _HTML_CODE, _INLINE_CODE, _MATH):
        text = pattern.sub(" ", text)
    return text


def raw_markup(text):
    """[(snippet, markup)] for every piece of TeX markup outside math and code in ``text``."""
    out = []
    left = prose(text)
    for m in _BAD.finditer(left):
        a, b = max(0, m.start() - 25), min(len(left), m.end() + 25)
        out.append((left[a:b].replace("\n", " "), m.group()))
    return out


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_no_raw_formula_markup_in_markdown(path):
    nb = nbformat.read(path, as_version=4)
    found = [f"cell {i}: {markup!r} in ...{snippet}..."
             for i, cell in enumerate(nb.cells) if cell.cell_type == "markdown"
             for snippet, markup in raw_markup(cell.source)]
    assert not found, f"{path.relative_to(ROOT)}: formula markup outside $...$ (MathJax shows it raw):\n" + \
        "\n".join(found)


@pytest.mark.parametrize("text, bad", [
    ("the group $g_{a,b}$ composes", []),                       # inside math
    ("call `f_{x}` or\n```\nx^2 \\alpha\n```\n", []),           # inside code
    ("a price of \\$5 and \\$6", []),                           # escaped dollars are not commands
    ("$$\\dot g = g\\xi$$ and $\\xi^\\theta$", []),
    ("the map g_{a,b} sends", ["_{"]),                          # plain text: raw
    ("body velocity ξ^θ is", ["^"]),
    ("so \\dot g = g ξ", ["\\dot"]),
    ("$a$ then A_{i2} then $b$", ["_{"]),                       # between two formulas
    ("an unclosed $ sign and x^{2}", ["^"]),                    # a lone dollar opens nothing
    ("where det ω_ξ = 0", ["ω_ξ"]),                             # a one-letter name with a subscript
    ("the `drag_ratio` and ex4_1.ipynb, snake_case words", []),  # code, file names, words: not formulas
])
def test_the_scanner_itself(text, bad):
    assert [m for _, m in raw_markup(text)] == bad


CHAPTERS = sorted(p for p in (ROOT / "book").glob("[0-9][0-9]-*.ipynb") if p.name[:2] not in ("00", "90"))


@pytest.mark.parametrize("path", CHAPTERS, ids=lambda p: p.name)
def test_chapter_title_is_numbered_like_the_others(path):
    """Every chapter notebook opens with "# N · Title", N its file's number (issue 36: notebook
    11's title had none)."""
    first = nbformat.read(path, as_version=4).cells[0]
    heading = first.source.splitlines()[0] if first.cell_type == "markdown" and first.source else ""
    number = int(path.name[:2])
    assert re.fullmatch(rf"# {number} · \S.*", heading), f"{path.name} opens with {heading!r}"


def display_math_inside_paragraphs(text):
    """The ``$$...$$`` formulas of ``text`` (code removed) that share a paragraph with prose: the
    website's MyST parser reads a display formula only as a paragraph of its own (a blank line
    before and after), and then mis-pairs every ``$`` after it; JupyterLab renders either form."""
    text = _COMMENT.sub("", _INLINE_CODE.sub("", _FENCED.sub("", text)))
    bad = []
    for m in re.finditer(r"\$\$.+?\$\$", text, re.S):
        before, after = text[:m.start()], text[m.end():]
        alone_before = before == "" or before.endswith("\n\n") or before.rstrip(" ").endswith("\n\n")
        alone_after = after.strip(" ") == "" or after.lstrip(" ").startswith("\n\n") \
            or after.lstrip(" ") == "\n"
        if not (alone_before and alone_after):
            bad.append(m.group()[:60])
    return bad


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_display_math_stands_in_its_own_paragraph(path):
    nb = nbformat.read(path, as_version=4)
    found = [f"cell {i}: {f!r}" for i, cell in enumerate(nb.cells) if cell.cell_type == "markdown"
             for f in display_math_inside_paragraphs(cell.source)]
    assert not found, (f"{path.relative_to(ROOT)}: put a blank line before and after each $$...$$ "
                       "(the website shows the rest of the paragraph as raw TeX otherwise):\n"
                       + "\n".join(found))


@pytest.mark.parametrize("text, bad", [
    ("so\n\n$$a = b$$\n\nthen", []),
    ("$$a = b$$", []),
    ("so\n$$a = b$$\nthen", ["$$a = b$$"]),
    ("so\n\n$$a\n= b$$\nthen", ["$$a\n= b$$"]),
    ("code `$$x$$` inline", []),
])
def test_the_display_math_scanner_itself(text, bad):
    assert display_math_inside_paragraphs(text) == bad


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_page_titles_hold_no_math(path):
    """A notebook's title (its ``# `` heading) is also its entry in the website's side bar on every
    page and the browser tab's title, and pages without formulas load no MathJax: there
    ``$\\mathbb{R}$`` would show raw. Titles use plain Unicode (ℝ⁺, ×, ξ)."""
    nb = nbformat.read(path, as_version=4)
    found = [line for cell in nb.cells if cell.cell_type == "markdown"
             for line in _FENCED.sub("", cell.source).splitlines()
             if line.startswith("# ") and _MATH.search(line)]
    assert not found, f"{path.relative_to(ROOT)}: math in the title: {found}"
