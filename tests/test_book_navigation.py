"""Every notebook of book/ is reachable from the start page by following "Next" links, and every
"Previous" link points back to the notebook whose "Next" led here."""
import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"
LINK = r"\[[^\]]*\]\(([\w.-]+\.ipynb)\)"


def _links(path, word):
    text = "".join("".join(c["source"]) for c in json.loads(path.read_text(encoding="utf-8"))["cells"]
                   if c["cell_type"] == "markdown")
    return [m.group(1) for m in re.finditer(rf"{word}:\s*(?:the\s+)?{LINK}", text)]


def _chain(start="00-start-here.ipynb"):
    order, page = [start], start
    while nxt := _links(BOOK / page, "Next"):
        assert len(nxt) == 1, f"{page} has {len(nxt)} Next links"
        assert nxt[0] not in order, f"{page}'s Next goes back to {nxt[0]}"
        order.append(nxt[0])
        page = nxt[0]
    return order


def test_next_links_reach_every_notebook_in_order():
    order = _chain()
    assert set(order) == {p.name for p in BOOK.glob("*.ipynb")}, (
        f"not reachable by Next from the start page: {sorted({p.name for p in BOOK.glob('*.ipynb')} - set(order))}")
    assert order == sorted(order), f"Next links jump around: {order}"


def test_previous_links_point_back():
    order = _chain()
    for before, page in zip(order[1:], order[2:]):
        assert _links(BOOK / page, "Previous") == [before], f"{page}'s Previous should be {before}"


def test_the_start_page_lists_every_chapter():
    listed = set(re.findall(LINK, "".join(json.loads((BOOK / "00-start-here.ipynb").read_text())["cells"][1]["source"])))
    assert listed == {p.name for p in BOOK.glob("*.ipynb")} - {"00-start-here.ipynb"}


def test_the_link_reader_can_fail(tmp_path):
    nb = {"cells": [{"cell_type": "markdown", "source": ["Next: the [errata](90-errata.ipynb) and [x](a.ipynb)"]}]}
    (tmp_path / "p.ipynb").write_text(json.dumps(nb))
    assert _links(tmp_path / "p.ipynb", "Next") == ["90-errata.ipynb"]
