"""The pure part of benchmarks/browser_latency.py (benchmarks/latency_report.py): which notebooks
and panels it measures, its statistics and its table, with no browser. A notebook without a live
panel, a panel never drawn and a minimal panel that gave nothing must print, not crash."""
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
import latency_report as lr  # noqa: E402


def test_parse_panels():
    assert lr.parse_panels(None) is None and lr.parse_panels("  ") is None
    assert lr.parse_panels("0,2-4") == {0, 2, 3, 4}
    assert lr.parse_panels("3, 1") == {1, 3}
    for bad in ("a", "2-1", "-1", "1-x"):
        with pytest.raises(ValueError):
            lr.parse_panels(bad)


def test_live_panels_selects_in_page_order_and_survives_no_panels():
    found = [{"index": 2, "cell": 9}, {"index": 0, "cell": 3}, {"index": 1, "cell": 5}]
    assert [p["index"] for p in lr.live_panels(found)] == [0, 1, 2]
    assert [p["cell"] for p in lr.live_panels(found, {0, 2, 7})] == [3, 9]
    assert lr.live_panels([]) == [] and lr.live_panels(None, {0}) == []


def test_slider_order_skips_disabled_and_rangeless_sliders():
    sliders = [{"disabled": True, "min": 0, "max": 1}, {"disabled": False, "min": 0, "max": 0},
               {"disabled": False, "min": None, "max": 1}, {"disabled": False, "min": -1, "max": 1},
               {"min": 0, "max": 5}, {"min": 0, "max": 2}, {"min": 0, "max": 3}]
    assert lr.slider_order(sliders) == [3, 4, 5]
    assert lr.slider_order(sliders, limit=1) == [3]
    assert lr.slider_order([]) == [] and lr.slider_order(None) == []


def test_statistics():
    assert lr.pct([], 0.95) != lr.pct([], 0.95)                 # nan
    assert lr.pct([5.0], 0.95) == 5.0
    xs = list(range(1, 21))                                       # 1..20
    assert lr.pct(xs, 0.5) == pytest.approx(10.5)
    assert lr.pct(xs, 0.95) == pytest.approx(19.05)               # between the 19th and 20th value
    assert lr.pct(list(reversed(xs)), 0.95) == pytest.approx(19.05)
    s = lr.summarise([30, 10, 20])
    assert (s["n"], s["median"], s["max"]) == (3, 20, 30)
    empty = lr.summarise([])
    assert empty["n"] == 0 and math.isnan(empty["median"]) and math.isnan(empty["p95"])


def test_verdict():
    floor = lr.Row(lr.FLOOR_NAME, panel=0, lat=[80, 90, 100])
    assert lr.verdict(lr.Row("a", lat=[50, 90, 200]), floor) == "yes"    # equal median counts
    assert lr.verdict(lr.Row("a", lat=[91]), floor) == "NO"
    assert lr.verdict(lr.Row("a"), floor) == "-"
    assert lr.verdict(floor, floor) == "-"
    assert lr.verdict(lr.Row("a", lat=[1]), None) == "-"
    assert lr.verdict(lr.Row("a", lat=[1]), lr.Row(lr.FLOOR_NAME)) == "-"


def test_the_minimal_panel_measured_again_pools_its_moves():
    first = lr.Row(lr.FLOOR_NAME, panel=0, lat=[80, 90], pictures=[1, 1])
    again = lr.Row(lr.FLOOR_NAME, panel=0, lat=[200, 210, 220], misses=1, pictures=[1], note="1 move(s) not drawn")
    pooled = lr.pool(first, again)
    assert pooled is first and pooled.lat == [80, 90, 200, 210, 220] and pooled.stats["median"] == 200
    assert pooled.misses == 1 and pooled.pictures == [1, 1, 1] and pooled.note == "1 move(s) not drawn"
    assert lr.pool(None, again) is again and lr.pool(first, None) is first and lr.pool(None, None) is None
    # a panel measured under the same later load is judged against the pooled floor
    assert lr.verdict(lr.Row("a", lat=[150]), first) == "yes"


def _rows():
    floor = lr.Row(lr.FLOOR_NAME, panel=0, cell=1, slider="theta", canvas="400x300",
                   lat=[85, 90, 87], pictures=[1, 1, 1])
    fast = lr.Row("book/00-start-here.ipynb", panel=0, cell=2, slider="x", canvas="600x400",
                  lat=[47, 52, 50], pictures=[2, 2, 2])
    slow = lr.Row("book/01-configuration-spaces.ipynb", panel=3, cell=12, slider="a very long slider label",
                  canvas="900x500,300x300", lat=[150, 173, 615], misses=1, pictures=[1, 2], note="1 move(s) not drawn")
    none = lr.Row("book/90-errata.ipynb", note="no live panel (no %matplotlib widget)")
    return floor, [floor, fast, slow, none]


def test_table_has_the_minimal_row_first_and_a_verdict_per_panel():
    floor, rows = _rows()
    text = lr.format_table(rows[::-1], floor, moves=20, header="load average 3.00 on 2 CPU(s)")
    lines = text.splitlines()
    assert "20 moves per panel" in lines[0] and "load average" in lines[1]
    head = next(i for i, ln in enumerate(lines) if ln.startswith("notebook"))
    body = lines[head + 2:]
    assert body[0].startswith(lr.FLOOR_NAME) and "87" in body[0].split()
    assert sum(ln.startswith(lr.FLOOR_NAME) for ln in lines) == 1
    start = next(ln for ln in body if ln.startswith("00-start-here"))
    assert start.split()[-1] == "yes" and " 50 " in start
    slow = next(ln for ln in body if ln.startswith("01-configuration"))
    assert " NO " in slow and "not drawn" in slow and "a very long sli~" in slow
    errata = next(ln for ln in body if ln.startswith("90-errata"))
    assert "no live panel" in errata
    assert "1 of 2 panels measured have a median at or below the minimal panel's (87 ms)" in text
    assert "above it 01-configuration-spaces #3" in text
    assert "1 of 2 panels have p95 <= 100 ms" in text
    assert "90-errata (no live panel" in text
    assert all(len(ln) < 200 for ln in lines)


def test_table_survives_nothing_measured():
    only = lr.Row("book/90-errata.ipynb", note="no live panel")
    text = lr.format_table([only], None)
    assert "no live panel" in text and "0 of 0 panels have p95" in text
    broken_floor = lr.Row(lr.FLOOR_NAME, note="failed: timeout")
    text = lr.format_table([broken_floor, only], broken_floor)
    assert "failed: timeout" in text and "no comparison" in text
    assert lr.format_table([], None).count("\n") >= 3


def test_json_is_plain_json():
    floor, rows = _rows()
    data = json.loads(lr.to_json(rows, floor, {"moves": 20}))   # no NaN: strict parsers read it
    assert data["minimal"]["stats"]["median"] == 87
    byname = {r["notebook"]: r for r in data["rows"]}
    assert byname["book/90-errata.ipynb"]["stats"]["median"] is None
    assert byname["book/00-start-here.ipynb"]["at_or_below_minimal"] == "yes"
    json.loads(lr.to_json([], None))


def test_resolve_notebooks(tmp_path, monkeypatch):
    book = tmp_path / "book"
    book.mkdir()
    for name in ("00-start-here.ipynb", "01-config.ipynb", "11-many-links.ipynb", "notes.md"):
        (book / name).write_text("{}")
    monkeypatch.chdir(tmp_path)
    assert lr.resolve_notebooks([], tmp_path) == ["book/00-start-here.ipynb", "book/01-config.ipynb",
                                                  "book/11-many-links.ipynb"]
    assert lr.resolve_notebooks(["00", "book/11-many-links.ipynb", "00"], tmp_path) == [
        "book/00-start-here.ipynb", "book/11-many-links.ipynb"]
    assert lr.resolve_notebooks([str(book / "01-config.ipynb")], tmp_path) == ["book/01-config.ipynb"]
    assert lr.resolve_notebooks(["book/0*.ipynb"], tmp_path) == ["book/00-start-here.ipynb", "book/01-config.ipynb"]
    for bad in ("42", "book/nothing.ipynb", "notes"):
        with pytest.raises(ValueError):
            lr.resolve_notebooks([bad], tmp_path)
    outside = tmp_path.parent / "elsewhere.ipynb"
    outside.write_text("{}")
    with pytest.raises(ValueError):
        lr.resolve_notebooks([str(outside)], tmp_path)


def test_the_benchmark_rejects_bad_options_before_starting_anything():
    """Argument errors come from argparse at once (no server, no browser): exit status 2."""
    for args in (["--panels", "x"], ["no-such-notebook"], ["--moves", "0"]):
        res = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "browser_latency.py"), *args],
                             capture_output=True, text=True, timeout=60, cwd=ROOT)
        assert res.returncode == 2, (args, res.stdout, res.stderr)
        assert "error" in res.stderr
