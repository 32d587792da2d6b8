"""ipywidgets front ends for the checkers: multiple choice, the slide rule (1.5), progress.

Imported only when a widget is asked for, so ``import gm_core.checks`` stays ipywidgets-free. The
slide rule is drawn as SVG inside an HTML widget (no matplotlib), built by the pure function
:func:`slide_rule_svg` that the tests can call headless.
"""
from __future__ import annotations

import contextlib
import html
import io

import numpy as np

from ._core import exercise_ids, part_progress, progress, solutions_viewed
from ._display import COLORS
from ._progress import (
    FAILED,
    IN_PROGRESS,
    PASSED,
    UNATTEMPTED,
    find_workspace,
    not_saved,
    pending_updates,
)


def choice_widget(part):
    """RadioButtons with the options, a Check button and a feedback line; records progress."""
    import ipywidgets as W

    options = [(f"({k}) {text}", k) for k, text in part.options.items()]
    radio = W.RadioButtons(options=options, value=None, layout=W.Layout(width="auto"))
    button = W.Button(description="Check", button_style="primary")
    out = W.HTML()

    def on_click(_):
        v = part.check(radio.value, quiet=True)
        color = COLORS.get(v.status, "#6e7781")
        out.value = f'<span style="color:{color}"><b>{v.status}</b>: {html.escape(v.message)}</span>'

    button.on_click(on_click)
    box = W.VBox([W.HTML(f"<b>{html.escape(part.prompt)}</b>"), radio, button, out])
    box.radio, box.button, box.feedback = radio, button, out  # handles for tests
    return box


# ------------------------------------------------------------------------------ slide rule
_W, _PAD = 760, 20          # SVG width and left padding (pixels)
_DECADE = 340.0              # pixels per decade: D spans two decades (1..100), C one (1..10)


def _ticks(x0, y, up, decades):
    parts = []
    for d in range(decades):
        for m in range(10, 100):
            v = m / 10 * 10 ** d
            x = x0 + _DECADE * np.log10(v)
            major = m % 10 == 0
            half = m % 5 == 0
            h = 14 if major else (9 if half else 5)
            y2 = y - h if up else y + h
            parts.append(f'<line x1="{x:.1f}" y1="{y}" x2="{x:.1f}" y2="{y2}" stroke="#333" '
                         f'stroke-width="{1.2 if major else 0.6}"/>')
            if major:
                ty = y - 18 if up else y + 28
                parts.append(f'<text x="{x:.1f}" y="{ty}" font-size="12" text-anchor="middle">'
                             f'{int(round(v))}</text>')
    xe = x0 + _DECADE * decades
    parts.append(f'<line x1="{xe:.1f}" y1="{y}" x2="{xe:.1f}" y2="{y - 14 if up else y + 14}" '
                 'stroke="#333" stroke-width="1.2"/>')
    parts.append(f'<text x="{xe:.1f}" y="{y - 18 if up else y + 28}" font-size="12" '
                 f'text-anchor="middle">{10 ** decades}</text>')
    return parts


def slide_rule_svg(a, b):
    """SVG of a slide rule set to multiply a by b (1 <= a, b <= 10) and the product it shows.

    The fixed D scale (two decades, 1..100) has the number v at distance log10(v); the sliding C
    scale (one decade) is shifted so that its 1 sits over a on D; the cursor is over b on C, so it
    reads log10(a) + log10(b) = log10(ab) on D. Returns ``(svg_text, product, cursor_x_pixels)``.
    """
    a = float(np.clip(a, 1.0, 10.0))
    b = float(np.clip(b, 1.0, 10.0))
    shift = _DECADE * np.log10(a)
    cursor = _PAD + shift + _DECADE * np.log10(b)
    product = 10 ** ((cursor - _PAD) / _DECADE)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_W}" height="150">',
             # the fixed body (D scale)
             f'<rect x="{_PAD - 8}" y="76" width="{2 * _DECADE + 16}" height="60" fill="#f6efe0" '
             'stroke="#999"/>',
             # the slide (C scale)
             f'<rect x="{_PAD + shift - 8:.1f}" y="20" width="{_DECADE + 16}" height="56" '
             'fill="#fffbe8" stroke="#999"/>',
             '<text x="4" y="64" font-size="13" font-weight="bold">C</text>',
             '<text x="4" y="100" font-size="13" font-weight="bold">D</text>']
    parts += _ticks(_PAD + shift, 76, True, 1)
    parts += _ticks(_PAD, 76, False, 2)
    parts.append(f'<line x1="{cursor:.1f}" y1="8" x2="{cursor:.1f}" y2="142" stroke="#b42318" '
                 'stroke-width="2"/>')
    parts.append(f'<line x1="{_PAD + shift:.1f}" y1="8" x2="{_PAD + shift:.1f}" y2="142" '
                 'stroke="#0550ae" stroke-dasharray="4,3"/>')
    parts.append("</svg>")
    return "\n".join(parts), product, cursor


def slide_rule(a=2.0, b=3.0):
    """Two log scales sliding past each other: set a (slide) and b (cursor), read a*b on D."""
    import ipywidgets as W

    # Linear sliders on 1..10 in steps of 0.01: the values a student types or drags to (2, 3, 2.5)
    # are exact, so the rule reads 2 x 3 = 6 (a log-spaced slider rounds 2 to 10**0.301 = 1.9999).
    sa = W.FloatSlider(value=a, min=1.0, max=10.0, step=0.01, description="a (slide)",
                       readout_format=".2f", continuous_update=True)
    sb = W.FloatSlider(value=b, min=1.0, max=10.0, step=0.01, description="b (cursor)",
                       readout_format=".2f", continuous_update=True)
    view = W.HTML()
    text = W.HTML()

    def update(*_):
        svg, product, _x = slide_rule_svg(sa.value, sb.value)
        view.value = svg
        text.value = (f"Slide shifted by log10(a) = {np.log10(sa.value):.4f} of a decade; cursor "
                      f"at a further log10(b) = {np.log10(sb.value):.4f}. D reads "
                      f"<b>{product:.4g}</b> (a &times; b = {sa.value * sb.value:.4g}).")

    sa.observe(update, "value")
    sb.observe(update, "value")
    update()
    box = W.VBox([W.HTML("<b>Slide rule</b>: the blue line is the C scale's index (its 1), the "
                         "red line the cursor."), view, sa, sb, text])
    box.sliders = (sa, sb)
    box.view, box.readout = view, text
    return box


# ------------------------------------------------------------------------------ progress
_ICON = {PASSED: "&#10004;", FAILED: "&#10008;", UNATTEMPTED: "&middot;", IN_PROGRESS: "&#9680;"}


def updates_html(pending):
    """An HTML list of pending course updates (the student's kept file and the new version)."""
    items = "".join(
        f"<li>your <code>{html.escape(n['file'])}</code> is kept as you left it; the course's new "
        f"version is beside it: <code>{html.escape(n['new_version'])}</code></li>" for n in pending)
    return (f'<div style="border-left:4px solid {COLORS["notice"]};padding:4px 10px">'
            f'<b style="color:{COLORS["notice"]}">Course updates</b><ul>{items}</ul>'
            "Open the new version to see what changed; copy over what you want to keep.</div>")


def progress_html(mark_seen=False):
    """An HTML table of every exercise's status (the saved record), with parts passed."""
    with contextlib.redirect_stdout(io.StringIO()):   # the table says it itself when not saved
        status = progress()
    parts = part_progress()
    viewed = solutions_viewed()
    rows = []
    for ex_id in exercise_ids():
        s = status[ex_id]
        p = parts.get(ex_id, {})
        done = sum(v == PASSED for v in p.values())
        seen = viewed.get(ex_id, [])
        note = f"solution viewed: {', '.join(seen)}" if seen else ""
        rows.append(f'<tr><td>{ex_id}</td><td style="color:{COLORS[s]}">{_ICON[s]} {s}</td>'
                    f'<td style="color:#555">{done}/{len(p)} parts</td>'
                    f'<td style="color:#555">{html.escape(note)}</td></tr>')
    why = not_saved()
    where = (f"NOT SAVED, kept in this kernel only: the workspace cannot be written ({why})" if why
             else "saved in your workspace" if find_workspace() is not None
             else "this kernel only (not in a workspace)")
    where = html.escape(where)
    table = ('<table style="font-size:90%"><tr><th>exercise</th><th>status</th><th></th><th></th>'
             "</tr>" + "".join(rows) + f'</table><span style="color:#555;font-size:85%">Record: {where}.</span>')
    pending = pending_updates(mark_seen=mark_seen)
    return (updates_html(pending) if pending else "") + table


def progress_widget():
    """A small widget showing progress() and pending course updates; Refresh re-reads the record."""
    import ipywidgets as W

    view = W.HTML(progress_html(mark_seen=True))
    button = W.Button(description="Refresh", layout=W.Layout(width="90px"))

    def refresh(_=None):
        view.value = progress_html()

    button.on_click(refresh)
    box = W.VBox([view, button])
    box.view, box.refresh = view, refresh
    return box
