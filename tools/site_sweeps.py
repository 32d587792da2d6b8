"""Pre-rendered slider sweeps for the website (used by tools/build_site.py).

The panels listed in ``site/sweeps.toml`` are the ones where one slider tells the story. When the
site executes a page, :func:`kernel_code` runs first in its kernel and registers an IPython
display formatter for ``gm_core.widgets.base.Panel`` (IPython's public ``for_type``): a listed
panel is displayed as usual (live view, PNG of its first state) plus a ``text/html`` sweep, the
course's own player (:func:`gm_core.drawing.toolkit.player.player_html`) with one picture per value of
that control, made with the panel's public ``refresh(**values)`` (the control widgets themselves
are not touched, and the panel is put back to its first state afterwards). The output's metadata
``gm_sweep`` marks it; :func:`prefer_sweep` makes the site show the sweep instead of the single
picture.
"""
from __future__ import annotations

import json
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:    # Python 3.10: the same parser from PyPI (tomli, declared for < 3.11)
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / "site" / "sweeps.toml"
KEYS = {"control", "frames", "values", "interval"}


def load(path: Path = CONFIG) -> dict:
    """{panel class name: {control, frames?, values?, interval?}}, validated."""
    config = tomllib.loads(Path(path).read_text())
    for name, spec in config.items():
        if not isinstance(spec, dict) or not isinstance(spec.get("control"), str):
            raise ValueError(f"{path}: [{name}] needs control = \"<name of the panel's control>\"")
        if set(spec) - KEYS:
            raise ValueError(f"{path}: [{name}] has unknown keys {sorted(set(spec) - KEYS)} (known: {sorted(KEYS)})")
        frames = spec.get("frames", 24)
        if isinstance(frames, bool) or not isinstance(frames, int) or not 2 <= frames <= 60:
            raise ValueError(f"{path}: [{name}] frames must be a whole number from 2 to 60")
        values = spec.get("values")
        if values is not None and (not isinstance(values, list) or not 2 <= len(values) <= 60
                                   or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)):
            raise ValueError(f"{path}: [{name}] values must be a list of 2 to 60 numbers")
    return config


KERNEL = r'''
def __gm_site_sweeps(config):
    import base64, html, io, json
    import numpy as np
    from IPython import get_ipython
    from gm_core.drawing.toolkit.player import player_html
    from gm_core.widgets.base import Panel

    def fmt(v):
        return f"{v:.3g}" if isinstance(v, float) else str(v)

    def grid(control, spec):
        is_int = isinstance(control.value, int) and not isinstance(control.value, bool)
        vals = list(spec["values"]) if "values" in spec else list(np.linspace(control.min, control.max, spec.get("frames", 24)))
        vals = [v for v in vals if control.min <= v <= control.max]
        if is_int:
            return sorted({int(round(v)) for v in vals} | {int(control.value)})
        vals = [float(v) for v in vals]
        k = int(np.argmin([abs(v - control.value) for v in vals]))
        vals[k] = float(control.value)            # the first state is one of the pictures
        return vals

    def bundle(panel, include=None, exclude=None):
        out = panel._repr_mimebundle_(include=include, exclude=exclude)
        spec = config.get(type(panel).__name__)
        if not spec or panel.fig is None or spec["control"] not in panel.controls:
            return out
        data, meta = out if isinstance(out, tuple) else (out, {})
        name = spec["control"]
        control = panel.controls[name]
        vals = grid(control, spec)
        frames = []
        try:
            for v in vals:
                panel.refresh(**{name: v})
                buf = io.BytesIO()
                panel.fig.savefig(buf, format="png", dpi="figure")
                frames.append("data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii"))
        finally:
            panel.refresh()                       # back to the first state (the controls' values)
        label = getattr(control, "description", "") or getattr(control, "tooltip", "") or name
        start = vals.index(control.value)
        what = meta.get("image/png", {}).get("alt", "")
        title = (f"Pre-rendered sweep of {label} from {fmt(vals[0])} to {fmt(vals[-1])} in {len(vals)} pictures; "
                 f"the slider below moves through them. {what}")[:500]
        player = player_html(frames, interval=spec.get("interval", 150),
                             width=panel.fig.get_figwidth() * panel.fig.dpi, mode="reflect",
                             title=title, start=start, slider_label=f"{label} (pre-rendered)")
        esc = html.escape(label)
        caption = (f'<p class="gm-sweep-caption">No kernel needed: move the slider to change <b>{esc}</b> '
                   f'from {fmt(vals[0])} to {fmt(vals[-1])} (<span class="gm-sweep-value" aria-live="polite">{esc} = '
                   f'{fmt(vals[start])}</span>); the other controls keep their first values. Open the '
                   f'notebook in JupyterLab to use them all.</p>')
        data["text/html"] = (f'<div class="gm-sweep" data-label="{esc}" '
                             f'data-values="{html.escape(json.dumps([fmt(v) for v in vals]))}">{caption}{player}</div>')
        meta["gm_sweep"] = {"control": name, "values": vals}
        return data, meta

    get_ipython().display_formatter.mimebundle_formatter.for_type(Panel, bundle)

__gm_site_sweeps(json.loads(%(config)r))
del __gm_site_sweeps
'''


def kernel_code(config: dict | None = None) -> str:
    """Code run first in a page's kernel: listed panels are displayed with their sweep."""
    config = load() if config is None else config
    return "import json\n" + KERNEL % {"config": json.dumps(config, sort_keys=True)}


def prefer_sweep(out: dict) -> bool:
    """On a swept panel's output keep only the sweep (text/html): the site then shows it in place
    of the single picture. Returns whether ``out`` is a sweep."""
    if "gm_sweep" not in out.get("metadata", {}) or "text/html" not in out.get("data", {}):
        return False
    for key in list(out["data"]):
        if key != "text/html":
            del out["data"][key]
    out["metadata"] = {}
    return True
