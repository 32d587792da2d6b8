"""The pure part of benchmarks/browser_latency.py: which panels to move, statistics, the table.

Nothing here touches a browser, so tests/test_browser_latency_report.py runs it anywhere.

* :func:`resolve_notebooks`: the notebooks asked for (paths, globs, or a book notebook's number
  such as ``00``); none: every notebook of book/.
* :func:`parse_panels`: ``--panels 0,2-3`` -> {0, 2, 3} (None: every panel).
* :func:`live_panels`: of the panels the page found (an output with an ipympl canvas and an
  enabled slider, numbered in page order), the ones asked for; :func:`slider_order`: which of a
  panel's sliders to try, in order (enabled, with a range).
* :func:`pool`: the minimal panel measured several times in one run, as one row;
* :func:`summarise` and :func:`pct`: n, median, p95 (linear interpolation) and max of the
  latencies; :func:`verdict`: is a panel's median at or below the minimal panel's?
* :func:`format_table`: the table printed at the end, a row per panel (and one per notebook
  without a live panel or whose measurement failed), the minimal panel first.
"""
from __future__ import annotations

import json
import math
import statistics
from dataclasses import asdict, dataclass, field
from pathlib import Path

FLOOR_NAME = "(minimal panel)"
#: p95 a student should not notice (issue 36, item 8), on a quiet machine
P95_GOAL_MS = 100.0


def resolve_notebooks(args, root: Path) -> list[str]:
    """Paths relative to ``root`` (posix) of the notebooks named by ``args``: a path (absolute or
    relative to the working directory or to ``root``), a glob relative to ``root``, or the start of
    a book notebook's name (``00``, ``11-many``). No args: every ``book/*.ipynb``. Raises
    ValueError for a name that matches nothing or a file outside ``root``."""
    root = Path(root).resolve()
    if not args:
        return [p.relative_to(root).as_posix() for p in sorted((root / "book").glob("*.ipynb"))]
    out: list[str] = []
    for a in args:
        p = Path(a)
        candidates = [p] if p.is_absolute() else [Path.cwd() / p, root / p]
        hit = next((c.resolve() for c in candidates if c.is_file()), None)
        if hit is not None:
            found = [hit]
        else:
            found = sorted(root.glob(a)) if any(ch in a for ch in "*?[") else []
            found = found or sorted((root / "book").glob(f"{a}*.ipynb"))
        found = [f for f in found if f.suffix == ".ipynb"]
        if not found:
            raise ValueError(f"no notebook matches {a!r}")
        for f in found:
            try:
                rel = f.resolve().relative_to(root).as_posix()
            except ValueError:
                raise ValueError(f"{f} is not inside {root}") from None
            if rel not in out:
                out.append(rel)
    return out


def parse_panels(spec: str | None) -> set[int] | None:
    """``"0,2-4"`` -> {0, 2, 3, 4}; empty or None -> None (every panel)."""
    if spec is None or not spec.strip():
        return None
    out: set[int] = set()
    for part in spec.split(","):
        part = part.strip()
        if not part:
            continue
        lo, sep, hi = part.partition("-")
        try:
            a = int(lo)
            b = int(hi) if sep else a
        except ValueError:
            raise ValueError(f"not a panel number or range: {part!r} (use e.g. 0,2-4)") from None
        if a < 0 or b < a:
            raise ValueError(f"bad panel range: {part!r}")
        out.update(range(a, b + 1))
    return out or None


def live_panels(found: list[dict] | None, wanted: set[int] | None = None) -> list[dict]:
    """The panels to measure: ``found`` as the page lists them ({"index": k, "cell": c, ...},
    index = the panel's number in the notebook, counted from 0), restricted to ``wanted``."""
    out = [p for p in (found or []) if isinstance(p, dict) and isinstance(p.get("index"), int)]
    out.sort(key=lambda p: p["index"])
    return [p for p in out if wanted is None or p["index"] in wanted]


def slider_order(sliders: list[dict] | None, limit: int = 3) -> list[int]:
    """Indices (among the panel's sliders) of up to ``limit`` sliders worth moving, in page order:
    enabled, with a range. The first that changes the picture is measured."""
    out = []
    for i, s in enumerate(sliders or []):
        lo, hi = s.get("min"), s.get("max")
        if s.get("disabled") or lo is None or hi is None or not hi > lo:
            continue
        out.append(i)
    return out[:limit]


def pct(xs, q: float) -> float:
    """The ``q`` quantile (0..1) of ``xs``, linearly interpolated; nan for no data."""
    xs = sorted(xs)
    if not xs:
        return float("nan")
    k = (len(xs) - 1) * q
    i = int(k)
    j = min(i + 1, len(xs) - 1)
    return xs[i] + (xs[j] - xs[i]) * (k - i)


def summarise(lat) -> dict:
    lat = [float(x) for x in lat]
    if not lat:
        return {"n": 0, "median": float("nan"), "p95": float("nan"), "max": float("nan")}
    return {"n": len(lat), "median": statistics.median(lat), "p95": pct(lat, 0.95), "max": max(lat)}


@dataclass
class Row:
    """One line of the table: a panel measured, or a notebook with nothing measured (``note``)."""
    notebook: str
    panel: int | None = None
    cell: int | None = None
    slider: str = ""
    canvas: str = ""
    lat: list = field(default_factory=list)
    misses: int = 0
    pictures: list = field(default_factory=list)   # pictures the canvas showed, per move
    note: str = ""

    @property
    def stats(self) -> dict:
        return summarise(self.lat)


def pool(floor: Row | None, new: Row | None) -> Row | None:
    """The minimal panel's row with the moves of a new measurement of it added (either may be None)."""
    if floor is None or new is None:
        return floor if new is None else new
    floor.lat.extend(new.lat)
    floor.pictures.extend(new.pictures)
    floor.misses += new.misses
    if new.note and new.note not in floor.note:
        floor.note = (floor.note + "; " if floor.note else "") + new.note
    return floor


def verdict(row: Row, floor: Row | None) -> str:
    """"yes" if the row's median is at or below the minimal panel's, "NO" if above, "-" if either
    has no data (or the row is the minimal panel itself)."""
    if floor is None or row is floor:
        return "-"
    a, b = row.stats["median"], floor.stats["median"]
    if math.isnan(a) or math.isnan(b):
        return "-"
    return "yes" if a <= b else "NO"


def _ms(x: float) -> str:
    return "-" if math.isnan(x) else f"{x:.0f}"


def short_name(notebook: str) -> str:
    return Path(notebook).stem if notebook != FLOOR_NAME else notebook


COLUMNS = (("notebook", "<", 26), ("panel", ">", 5), ("cell", ">", 4), ("slider", "<", 16),
           ("canvas", "<", 15), ("n", ">", 3), ("median", ">", 6), ("p95", ">", 5), ("max", ">", 5),
           ("miss", ">", 4), ("pics", ">", 4), ("<=min", ">", 5), ("note", "<", 0))


def format_table(rows: list[Row], floor: Row | None = None, moves: int | None = None,
                 header: str = "") -> str:
    """The report: a heading, the column names, the minimal panel's row first, then every row;
    times in ms. "<=min": median at or below the minimal panel's median of this run. "pics":
    median number of pictures the canvas showed per move (a panel that blits shows a difference
    image and later a whole key frame). A summary follows."""
    lines = []
    what = "slider key press -> first animation frame with changed canvas pixels (ms)"
    if moves is not None:
        what += f", {moves} moves per panel"
    lines.append(what)
    if header:
        lines.append(header)
    lines.append("panel: its number in the notebook, from 0 in page order (--panels); cell: the notebook cell "
                 "showing it, from 0;")
    lines.append("pics: pictures the canvas showed per move (median); <=min: median at or below the minimal panel's")
    lines.append("")

    def fmt(values):
        cells = []
        for (_name, align, width), v in zip(COLUMNS, values):
            v = str(v)
            if width and len(v) > width:
                v = v[:width - 1] + "~"
            cells.append(f"{v:{align}{width}}" if width else v)
        return " ".join(cells).rstrip()

    head = fmt([c[0] for c in COLUMNS])
    lines.append(head)
    lines.append("-" * len(head))
    ordered = ([floor] if floor is not None else []) + [r for r in rows if r is not floor]
    for r in ordered:
        s = r.stats
        pics = statistics.median(r.pictures) if r.pictures else float("nan")
        lines.append(fmt([
            short_name(r.notebook),
            "-" if r.panel is None else f"#{r.panel}",
            "-" if r.cell is None else r.cell,
            r.slider or "-",
            r.canvas or "-",
            s["n"], _ms(s["median"]), _ms(s["p95"]), _ms(s["max"]),
            r.misses, "-" if math.isnan(pics) else f"{pics:.0f}" if pics == int(pics) else f"{pics:.1f}",
            verdict(r, floor), r.note,
        ]))
    lines.append("")
    lines.extend(summary(rows, floor))
    return "\n".join(lines)


def summary(rows: list[Row], floor: Row | None) -> list[str]:
    measured = [r for r in rows if r is not floor and r.stats["n"]]
    out = []
    if floor is not None and floor.stats["n"]:
        above = [r for r in measured if verdict(r, floor) == "NO"]
        out.append(f"{len(measured) - len(above)} of {len(measured)} panels measured have a median at or "
                   f"below the minimal panel's ({floor.stats['median']:.0f} ms)"
                   + (": above it " + ", ".join(f"{short_name(r.notebook)} #{r.panel}" for r in above) if above else ""))
    elif floor is not None:
        out.append("the minimal panel gave no measurement: no comparison")
    slow = [r for r in measured if r.stats["p95"] > P95_GOAL_MS]
    out.append(f"{len(measured) - len(slow)} of {len(measured)} panels have p95 <= {P95_GOAL_MS:.0f} ms")
    unmeasured = [r for r in rows if r is not floor and not r.stats["n"]]
    if unmeasured:
        out.append(f"{len(unmeasured)} row(s) without a measurement: "
                   + "; ".join(f"{short_name(r.notebook)}" + (f" #{r.panel}" if r.panel is not None else "")
                               + f" ({r.note or 'no moves'})" for r in unmeasured))
    return out


def to_json(rows: list[Row], floor: Row | None, meta: dict | None = None) -> str:
    def one(r):
        d = asdict(r)
        d["stats"] = {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in r.stats.items()}
        d["at_or_below_minimal"] = verdict(r, floor)
        return d
    return json.dumps({"meta": meta or {}, "minimal": one(floor) if floor else None,
                       "rows": [one(r) for r in rows if r is not floor]}, indent=1, default=str)
