"""A small self-contained HTML player for animations that play without a kernel and offline.

:func:`player_html` turns a list of PNG frames into one HTML block: the first frame is the
``<img>``'s own ``src`` (a picture even where scripts never run, e.g. an untrusted notebook), the
controls are plain ``<button>`` elements whose icons are inline SVG (no icon font, no CDN, no
network request of any kind), and a short script, written for this player, steps through the
frames. The script finds its own elements from ``document.currentScript`` (falling back to the
element id, polled until JupyterLab has attached the output), so it works in JupyterLab, in a
saved notebook reopened without a kernel and in static HTML pages.

Frames are rendered by :func:`gm_core.drawing.toolkit.primitives.jshtml` through matplotlib's public movie
writer interface (``Animation.save`` with an ``AbstractMovieWriter``); this module only writes
the page.
"""
from __future__ import annotations

import html as _html
import json
import uuid

__all__ = ["player_html", "MODES"]

#: Playback modes: start again, stop at the last frame, or run back and forth.
MODES = ("loop", "once", "reflect")

_ICONS = {  # 16 x 16 inline SVG paths, drawn in the button's text colour
    "first": "M1 2h2v12H1zM9 2v12L3 8zM15 2v12L9 8z",
    "prev": "M3 2h2v12H3zM13 3v10L6 8z",
    "play": "M4 2v12l10-6z",
    "pause": "M3 2h4v12H3zM9 2h4v12H9z",
    "next": "M11 2h2v12h-2zM3 3v10l7-5z",
    "last": "M13 2h2v12h-2zM7 2v12l6-6zM1 2v12l6-6z",
}

_LABELS = {"first": "first frame", "prev": "previous frame", "play": "play", "next": "next frame",
           "last": "last frame"}


def _icon(name: str) -> str:
    return (f'<svg viewBox="0 0 16 16" width="14" height="14" aria-hidden="true" focusable="false" '
            f'style="display:block"><path d="{_ICONS[name]}" fill="currentColor"/></svg>')


_STYLE = """
.gm-anim { display: inline-block; max-width: 100%; }
.gm-anim img.gm-anim-frame { display: block; max-width: 100%; height: auto; }
.gm-anim .gm-anim-controls { display: flex; flex-wrap: wrap; align-items: center; gap: 4px;
  margin-top: 4px; font: 13px sans-serif; }
.gm-anim button { display: inline-flex; align-items: center; justify-content: center;
  min-width: 30px; height: 26px; padding: 0 6px; border: 1px solid #999; border-radius: 3px;
  background: #f4f4f4; color: #222; cursor: pointer; }
.gm-anim button:hover { background: #e4e4e4; }
.gm-anim input[type=range] { flex: 1 1 160px; min-width: 120px; }
.gm-anim select { height: 26px; }
.gm-anim .gm-anim-counter { min-width: 5.5em; text-align: right; color: #333; }
"""

# The player. `root` is the .gm-anim element; every lookup is inside it (no global ids needed).
_SCRIPT = r"""
(function () {
  var id = %(id)s, frames = %(frames)s, interval = %(interval)d, mode0 = %(mode)s, first = %(start)d;
  var me = document.currentScript;
  function setup(root) {
    if (root.getAttribute('data-gm-ready')) return;
    root.setAttribute('data-gm-ready', '1');
    var img = root.querySelector('img.gm-anim-frame');
    var slider = root.querySelector('input.gm-anim-slider');
    var counter = root.querySelector('.gm-anim-counter');
    var play = root.querySelector('button.gm-anim-play');
    var mode = root.querySelector('select.gm-anim-mode');
    var k = 0, dir = 1, timer = null;
    mode.value = mode0;
    function show(i) {
      k = Math.max(0, Math.min(frames.length - 1, i));
      img.src = frames[k];
      img.setAttribute('data-frame', String(k));
      slider.value = String(k);
      counter.textContent = (k + 1) + ' / ' + frames.length;
    }
    function icon(name) { play.innerHTML = %(icons)s[name]; play.setAttribute('aria-label', name);
                          play.title = name; }
    function stop() { if (timer !== null) { clearTimeout(timer); timer = null; } icon('play');
                      root.setAttribute('data-playing', '0'); }
    function tick() {
      var m = mode.value, n = frames.length, j = k + dir;
      if (j >= n || j < 0) {
        if (m === 'loop') j = dir > 0 ? 0 : n - 1;
        else if (m === 'reflect') { dir = -dir; j = k + dir; }
        else { stop(); return; }
      }
      show(j);
      timer = setTimeout(tick, interval);
    }
    function start() {
      if (timer !== null) return;
      if (mode.value === 'once' && k >= frames.length - 1) show(0);
      icon('pause'); root.setAttribute('data-playing', '1');
      timer = setTimeout(tick, interval);
    }
    root.addEventListener('click', function (e) {
      var b = e.target.closest ? e.target.closest('button[data-act]') : null;
      if (!b || !root.contains(b)) return;
      var act = b.getAttribute('data-act');
      if (act === 'play') { if (timer === null) { dir = 1; start(); } else stop(); }
      else if (act === 'first') { stop(); show(0); }
      else if (act === 'last') { stop(); show(frames.length - 1); }
      else if (act === 'prev') { stop(); show(k - 1); }
      else if (act === 'next') { stop(); show(k + 1); }
    });
    slider.addEventListener('input', function () { stop(); show(parseInt(slider.value, 10)); });
    show(first);
  }
  function find(tries) {
    var root = (me && me.parentNode && me.parentNode.classList &&
                me.parentNode.classList.contains('gm-anim')) ? me.parentNode : document.getElementById(id);
    if (root && root.isConnected !== false) { setup(root); return; }
    if (tries < 600) setTimeout(function () { find(tries + 1); }, 100);
  }
  find(0);
})();
"""


def player_html(frames: list[str], interval: float = 50, width: float | None = None,
                mode: str = "loop", title: str = "animation", start: int = 0, slider_label: str = "frame") -> str:
    """HTML (with its script) playing ``frames`` (PNG data URLs) ``interval`` ms apart.

    ``width`` is the frames' width in CSS px (the ``<img>`` gets it, so the page lays the picture
    out at its true size before any script runs); ``mode`` is one of :data:`MODES`; ``start`` is
    the frame shown first (a pre-rendered slider sweep starts at the slider's own value) and
    ``slider_label`` the accessible name of the frame slider.
    """
    if mode not in MODES:
        raise ValueError(f"mode must be one of {MODES}, got {mode!r}")
    if not frames:
        raise ValueError("frames must hold at least one frame")
    if isinstance(start, bool) or not isinstance(start, int) or not 0 <= start < len(frames):
        raise ValueError(f"start must be a frame index in [0, {len(frames) - 1}], got {start!r}")
    uid = uuid.uuid4().hex[:12]
    size = f' width="{int(round(width))}"' if width else ""
    buttons = "".join(
        f'<button type="button" data-act="{a}" title="{_LABELS[a]}" aria-label="{_LABELS[a]}"'
        f'{" class=" + chr(34) + "gm-anim-play" + chr(34) if a == "play" else ""}>{_icon(a)}</button>'
        for a in ("first", "prev", "play", "next", "last"))
    options = "".join(f'<option value="{m}">{m}</option>' for m in MODES)
    script = _SCRIPT % {
        "id": json.dumps(f"gm-anim-{uid}"),
        "frames": json.dumps(frames),
        "interval": max(1, int(round(interval))),
        "mode": json.dumps(mode),
        "start": start,
        "icons": json.dumps({"play": _icon("play"), "pause": _icon("pause")}),
    }
    return (f'<div class="gm-anim" id="gm-anim-{uid}" data-frames="{len(frames)}" '
            f'aria-label="{_html.escape(title, quote=True)}">'
            f"<style>{_STYLE}</style>"
            f'<img id="_anim_img{uid}" src="{frames[start]}"{size} class="gm-anim-frame" alt="{_html.escape(title, quote=True)}">'
            f'<div class="gm-anim-controls">{buttons}'
            f'<input type="range" class="gm-anim-slider" min="0" max="{len(frames) - 1}" value="{start}" step="1" '
            f'aria-label="{_html.escape(slider_label, quote=True)}">'
            f'<select class="gm-anim-mode" aria-label="when the last frame is reached">{options}</select>'
            f'<span class="gm-anim-counter">{start + 1} / {len(frames)}</span></div>'
            f"<script>{script}</script></div>")
