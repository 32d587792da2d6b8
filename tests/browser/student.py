"""What a student does in an open notebook, after Run All (issue 19), on top of browserlab.py.

* :func:`control_problems`: every slider track narrower than :data:`MIN_TRACK` px, every label,
  checkbox, button or progress text cut by its box, and every panel (its controls and figure
  together) taller than :data:`MAX_PANEL_HEIGHT` px, as laid out at 1366 x 768 with the file
  browser open.
* :func:`play_animations`: press ▶ on every animation of the notebook and require the picture
  on screen to change (the frame shown, and the pixels of the image), then pause it again.
* :func:`drag_check`: for every interactive panel, drag the first enabled slider of each panel
  to the same place twice: once slowly (one mouse move, then wait until the kernel and the
  canvas are still) and once quickly (:data:`QUICK_STEPS` mouse moves :data:`QUICK_PAUSE_MS` ms
  apart, as a hurried hand does); the canvases must then be the same, pixel for pixel up to
  :data:`PIXEL_TOLERANCE` of them. Ghosts (a previous arm still drawn, a readout overprinted)
  are exactly such differences. Every panel is dragged first, then all are waited for
  together, so a notebook with many panels costs a few seconds, not a few per panel.
* :func:`widget_threads`: the kernel serves the widgets' messages on its main thread only (no
  kernel subshell), so no figure is drawn from two threads at once.
"""
from __future__ import annotations

import time

import labview

MIN_TRACK = 150            # px, a slider's track at 1366 x 768
MAX_PANEL_HEIGHT = 650     # px, a panel's controls and figure together (issue 19: "at most about 650")
QUICK_STEPS = 10
QUICK_PAUSE_MS = 40
DRAG_PX = 60
PIXEL_TOLERANCE = 2e-3     # fraction of a canvas' pixels allowed to differ (antialiasing slivers)

_CONTROLS_JS = r"""
(id) => {
  const root = document.getElementById(id);
  const out = [];
  if (!root) return ['notebook panel not in the DOM'];
  const cells = [...root.querySelectorAll('.jp-Cell')];
  let n = 0; const inNum = new Map();
  for (const c of cells) if (c.classList.contains('jp-CodeCell')) inNum.set(c, ++n);
  const where = (el) => { const c = el.closest('.jp-Cell'); return `In[${inNum.get(c) || '?'}]`; };
  const visible = (el) => { const r = el.getBoundingClientRect(); return r.width > 0 && r.height > 0; };
  const text = (el) => (el.innerText || el.textContent || '').trim().replace(/\s+/g, ' ');
  for (const area of root.querySelectorAll('.jp-OutputArea-output')) {
    for (const s of area.querySelectorAll('.widget-slider')) {
      if (!visible(s)) continue;
      const t = s.querySelector('.noUi-target, .slider-container');
      const w = t ? t.getBoundingClientRect().width : 0;
      const lab = s.closest('.widget-vbox');
      const name = text(s.querySelector('.widget-label')) ||
                   (lab && lab.querySelector('.gm-control-label') ? text(lab.querySelector('.gm-control-label')) : '?');
      if (w < %(MIN_TRACK)d) out.push(`${where(s)}: slider '${name}' has a ${Math.round(w)} px track (< %(MIN_TRACK)d px)`);
    }
    const cut = '.widget-label, .widget-checkbox label, .widget-checkbox .widget-label-basic, button.jupyter-button, ' +
                '.widget-readout, .widget-html-content, .widget-label-basic, .widget-dropdown select, .widget-progress .widget-label';
    for (const el of area.querySelectorAll(cut)) {
      if (!visible(el) || !text(el)) continue;
      if (el.scrollWidth > el.clientWidth + 1 && getComputedStyle(el).overflowX !== 'visible')
        out.push(`${where(el)}: '${text(el).slice(0, 60)}' is cut (${el.scrollWidth} px of text in ${el.clientWidth} px)`);
    }
    const canvas = area.querySelector('.jupyter-matplotlib canvas');
    const slider = area.querySelector('.widget-slider, .widget-dropdown, .widget-toggle-buttons, .widget-checkbox');
    if (canvas && slider) {
      // the panel from its title to the bottom of its lowest part (the first widget box found
      // may be the controls' column alone, which made a 530 px panel measure 189 px)
      const parts = [...area.querySelectorAll('.jupyter-widgets, canvas')].map(e => e.getBoundingClientRect())
                      .filter(r => r.width > 0 && r.height > 0);
      const h = Math.max(...parts.map(r => r.bottom)) - Math.min(...parts.map(r => r.top));
      if (h > %(MAX_PANEL_HEIGHT)d) out.push(`${where(area)}: the panel and its controls are ${Math.round(h)} px tall (> %(MAX_PANEL_HEIGHT)d px: not on one laptop screen)`);
    }
  }
  return [...new Set(out)];
}
""" % {"MIN_TRACK": MIN_TRACK, "MAX_PANEL_HEIGHT": MAX_PANEL_HEIGHT}


_BLANK_CANVASES_JS = r"""
(id) => {
  const root = document.getElementById(id);
  let blank = 0, n = 0;
  for (const fig of root.querySelectorAll('.jupyter-matplotlib')) {
    const c = fig.querySelector('canvas');   // the picture (the second canvas is the rubber band)
    if (!c) continue;
    n++;
    if (!c.width || !c.height) { blank++; continue; }
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let drawn = false;
    for (let i = 3; i < d.length; i += 4 * 97) if (d[i] !== 0) { drawn = true; break; }
    if (!drawn) blank++;
  }
  return {n, blank};
}
"""


def wait_for_pictures(nbp, timeout: float = 90.0) -> dict:
    """Wait until every ipympl canvas of the notebook shows a picture (fail after ``timeout`` s)."""
    deadline = time.monotonic() + timeout
    while True:
        res = nbp.page.evaluate(_BLANK_CANVASES_JS, nbp.read_status()["panelId"])
        if not res["blank"]:
            return res
        if time.monotonic() > deadline:
            nbp.fail(f"{res['blank']} of {res['n']} interactive figures still blank {timeout:.0f} s after Run All")
        nbp.page.wait_for_timeout(200)


def control_problems(nbp) -> list[str]:
    return nbp.page.evaluate(_CONTROLS_JS, nbp.read_status()["panelId"])


# -- animations -----------------------------------------------------------------------------

_ANIMS_JS = r"""
(id) => {
  const root = document.getElementById(id);
  const out = [];
  root.querySelectorAll('.gm-anim').forEach((a, k) => {
    a.setAttribute('data-gm-anim', String(k));
    const img = a.querySelector('img');
    out.push({index: k, ready: a.getAttribute('data-gm-ready') === '1', frame: img ? img.getAttribute('data-frame') : null,
              frames: Number(a.getAttribute('data-frames') || 0)});
  });
  // animations that are not the course's player (e.g. a bare to_jshtml) are counted too
  const other = root.querySelectorAll('.animation img[id^="_anim_img"]').length;
  return {anims: out, other};
}
"""


# One player's state as the page holds it: (ready, frame number shown, playing). One evaluate
# reads all three (a locator's get_attribute resolves its selector again on every call).
_PLAYER_JS = r"""
(k) => {
  const a = document.querySelector(`[data-gm-anim="${k}"]`);
  const img = a && a.querySelector('img');
  return [a && a.getAttribute('data-gm-ready'), img && img.getAttribute('data-frame'),
          a && a.getAttribute('data-playing')];
}
"""


def play_animations(nbp, wait_ms: int = 900) -> tuple[list[str], int]:
    """Press ▶ on every animation; (problems, number of animations)."""
    page = nbp.page
    res = page.evaluate(_ANIMS_JS, nbp.read_status()["panelId"])
    problems = [f"{res['other']} animation(s) not made with gm_core.drawing.toolkit.primitives.jshtml"] if res["other"] else []
    for a in res["anims"]:
        root = page.locator(f'[data-gm-anim="{a["index"]}"]')
        root.scroll_into_view_if_needed()
        img = root.locator("img").first
        deadline = time.monotonic() + 10
        while page.evaluate(_PLAYER_JS, a["index"])[0] != "1" and time.monotonic() < deadline:
            page.wait_for_timeout(100)
        ready, before_frame, _ = page.evaluate(_PLAYER_JS, a["index"])
        if ready != "1":
            problems.append(f"animation #{a['index']}: its player never started (no script ran)")
            continue
        before_px = img.screenshot()
        root.locator("button.gm-anim-play").click()
        # the picture on screen must change: poll (a busy page may show the next frame late).
        # The player's frame number is read first; the screen is looked at (an element
        # screenshot, costly for the browser) only once the player says it has moved on.
        deadline = time.monotonic() + max(wait_ms / 1000, 10.0)
        after_px = before_px
        while True:
            page.wait_for_timeout(100)
            _, after_frame, playing = page.evaluate(_PLAYER_JS, a["index"])
            if after_frame != before_frame:
                after_px = img.screenshot()
            if (after_frame != before_frame and after_px != before_px) or time.monotonic() > deadline:
                break
        root.locator("button.gm-anim-play").click()  # pause again
        if a["frames"] < 2:
            problems.append(f"animation #{a['index']} has {a['frames']} frame(s)")
        elif after_frame == before_frame or after_px == before_px or playing != "1":
            problems.append(f"animation #{a['index']}: ▶ pressed, but the picture did not change "
                            f"(frame {before_frame} -> {after_frame}, playing={playing})")
    return problems, len(res["anims"])


# -- quick drag against slow drag ---------------------------------------------------------------

_PANELS_JS = r"""
(id) => {
  const root = document.getElementById(id);
  for (const el of root.querySelectorAll('[data-gm-drag]')) el.removeAttribute('data-gm-drag');
  const out = [];
  let k = 0;
  for (const area of root.querySelectorAll('.jp-Cell .jp-OutputArea-output')) {
    const c = area.querySelector('.jupyter-matplotlib canvas');
    const sliders = [...area.querySelectorAll('.widget-slider')].filter(s =>
      !s.querySelector('.noUi-target[disabled], .noUi-target.noUi-state-disabled') && s.querySelector('.noUi-handle') &&
      !s.querySelector('.noUi-handle').closest('[disabled]'));
    if (!c || !sliders.length) continue;
    area.setAttribute('data-gm-drag', String(k));
    sliders[0].setAttribute('data-gm-drag-slider', String(k));
    const cell = area.closest('.jp-Cell');
    const cells = [...root.querySelectorAll('.jp-Cell')];
    out.push({index: k, cell: cells.indexOf(cell)});
    k++;
  }
  return out;
}
"""

# Every ipympl canvas of the page, watched: how many pictures it has shown and whether the last
# one was whole (image mode 'full', which ipympl reads when the picture has loaded; a panel's
# key frame is whole, a blit is a difference). Its view's element gets data-gm-pictures="<model
# id>". The widget manager is reached through a widget renderer of the notebook's outputs.
_WATCH_PICTURES_JS = r"""
async () => {
  const nb = window.jupyterapp.shell.currentWidget;
  let manager = null;
  for (const cell of nb.content.widgets) {
    for (const child of (cell.outputArea ? cell.outputArea.widgets : [])) {
      for (const w of (child.widgets || [])) if (w._manager && w._manager.promise) manager = await w._manager.promise;
      if (manager) break;
    }
    if (manager) break;
  }
  if (!manager) return 'no widget manager found in the notebook outputs';
  const seen = window.__gmPictures = window.__gmPictures || {};
  for (const id of Object.keys(manager._models)) {
    const m = await manager._models[id];
    if (m.get('_model_name') !== 'MPLCanvasModel' || !m.image) continue;
    if (!seen[id]) {
      const rec = seen[id] = {shown: 0, whole: true};
      m.image.addEventListener('load', () => { rec.shown++; rec.whole = m.get('_image_mode') === 'full'; });
    }
    for (const v of Object.values(m.views || {})) (await v).el.setAttribute('data-gm-pictures', id);
  }
  return '';
}
"""

# a cheap fingerprint of every listed panel's canvas (FNV-1a over all pixels), its first
# slider's value and its pictures (shown, last one whole), all panels in one call. ipympl paints
# a view's canvas only when a picture has loaded (counted by _WATCH_PICTURES_JS) or the canvas
# is resized, so a watched canvas whose count and size are those of the last reading keeps its
# pixels: its fingerprint is reused rather than computed again (the _settle loop asks ten times a
# second, and hashing every canvas each time would take the page's time from the notebook).
_STATE_JS = r"""
(keys) => {
  const out = {};
  const known = window.__gmHashes = window.__gmHashes || {};
  for (const k of keys) {
    const area = document.querySelector(`[data-gm-drag="${k}"]`);
    if (!area) { out[k] = null; continue; }
    const c = area.querySelector('.jupyter-matplotlib canvas');
    const view = area.querySelector('[data-gm-pictures]');
    const pics = view && window.__gmPictures ? window.__gmPictures[view.getAttribute('data-gm-pictures')] : null;
    const w = c ? c.width : 0, ht = c ? c.height : 0;
    const sig = pics ? `${view.getAttribute('data-gm-pictures')}|${pics.shown}|${w}|${ht}` : null;
    let h = 2166136261 >>> 0;
    if (sig !== null && known[k] && known[k].sig === sig && known[k].canvas === c) {
      h = known[k].hash;
    } else if (c && w && ht) {
      const d = new Uint32Array(c.getContext('2d').getImageData(0, 0, w, ht).data.buffer);
      for (let i = 0; i < d.length; i++) { h ^= d[i]; h = Math.imul(h, 16777619) >>> 0; }
    }
    known[k] = {sig, hash: h, canvas: c};
    const s = area.querySelector(`[data-gm-drag-slider="${k}"] .noUi-target`);
    const v = s && s.noUiSlider ? Number(s.noUiSlider.get()) : null;
    out[k] = {hash: h, value: v, w, h: ht, shown: pics ? pics.shown : null, whole: pics ? pics.whole : null};
  }
  return out;
}
"""

_PIXELS_JS = r"""
(keys) => {
  const out = {};
  for (const k of keys) out[k] = document.querySelector(`[data-gm-drag="${k}"] .jupyter-matplotlib canvas`).toDataURL('image/png');
  return out;
}
"""


def _pixels(page, keys) -> dict:
    """PNG data URLs of the listed panels' canvases, in one call."""
    return {int(k): v for k, v in page.evaluate(_PIXELS_JS, keys).items()}


# The slider's track, its handle's centre line, range and value, once the handle is on screen
# and stands still: after a scroll JupyterLab lays out the cells that came into view, which can
# move things a few frames later, so then the handle must keep its place for 150 ms. When the
# handle is on screen where an earlier reading (``prev``) saw it, nothing has moved and one
# reading suffices: at once (nothing scrolled since), or after putting the notebook's scroll
# position back to where that reading was taken (``prev.scrollTop``). One round trip.
_GEOMETRY_JS = r"""
async ([k, prev]) => {
  const s = document.querySelector(`[data-gm-drag-slider="${k}"] .noUi-target`);
  const handle = s.querySelector('.noUi-handle');
  const frame = () => new Promise(ok => requestAnimationFrame(() => ok()));
  let scroller = s.parentElement;
  while (scroller && !(scroller.scrollHeight > scroller.clientHeight &&
                       /(auto|scroll)/.test(getComputedStyle(scroller).overflowY))) scroller = scroller.parentElement;
  const range = s.noUiSlider.options.range;
  const lo = Number(Array.isArray(range.min) ? range.min[0] : range.min);
  const hi = Number(Array.isArray(range.max) ? range.max[0] : range.max);
  const read = () => {
    const r = s.getBoundingClientRect(), h = handle.getBoundingClientRect();
    const cx = h.x + h.width / 2, cy = h.y + h.height / 2;
    const at = document.elementFromPoint(cx, cy);
    return {x: r.x, width: r.width, y: cy, lo, hi, value: Number(s.noUiSlider.get()),
            step: Number(s.noUiSlider.options.step) || 0, onHandle: !!(at && s.contains(at)),
            scrollTop: scroller ? scroller.scrollTop : null};
  };
  const same = (g) => g.onHandle && g.x === prev.x && g.y === prev.y && g.width === prev.width;
  let g = read();
  if (prev && same(g)) return g;
  if (prev && prev.scrollTop !== null && scroller) {
    scroller.scrollTop = prev.scrollTop;
    await frame(); await frame();
    g = read();
    if (same(g)) return g;
  }
  let last = null, since = performance.now();
  const until = since + 3000;
  while (performance.now() < until) {
    g = read();
    if (!(g.onHandle && last !== null && g.x === last.x && g.y === last.y)) since = performance.now();
    else if (performance.now() - since >= 150) return g;
    if (!g.onHandle) handle.scrollIntoView({block: 'center', inline: 'nearest'});
    last = g;
    await frame();
  }
  return g;
}
"""


def _geometry(page, k, prev=None, scrolled=False):
    """The slider's track (x, width), the handle's centre line y, its range and value; the
    handle's centre is at x + width * (value - lo) / (hi - lo) (noUiSlider's own mapping).
    ``prev``: an earlier reading of this slider; ``scrolled``: the page has been scrolled since
    (its scroll position is then put back to that reading's before looking)."""
    seen = None if prev is None else {"x": prev["x"], "y": prev["y"], "width": prev["width"],
                                      "scrollTop": prev["scrollTop"] if scrolled else None}
    g = page.evaluate(_GEOMETRY_JS, [k, seen])
    g["px"] = lambda v, g=g: g["x"] + g["width"] * (v - g["lo"]) / (g["hi"] - g["lo"])
    return g


def _drag(page, x0, y, x1, steps, pause_ms):
    """Press at x0, move to x1 in ``steps`` moves that start ``pause_ms`` ms apart, release."""
    page.mouse.move(x0, y)
    page.mouse.down()
    t0 = time.monotonic()
    for i in range(1, steps + 1):
        if pause_ms and i > 1:
            wait = t0 + (i - 1) * pause_ms / 1000 - time.monotonic()
            if wait > 0:
                page.wait_for_timeout(wait * 1000)
        page.mouse.move(x0 + (x1 - x0) * i / steps, y)
    page.mouse.up()


#: Seconds a canvas must stay unchanged (with the kernel idle and its last picture whole) to
#: count as final. A panel ends every burst of updates with a whole key frame (its timer fires
#: 0.25 s after the last update: gm_core.drawing.toolkit.blit.KeyFrames), and the browser sends a slider's
#: last value as soon as the kernel reports the previous one done, so once the key frame is on
#: the canvas and the kernel is idle nothing more is on its way; the stillness only bridges the
#: kernel's idle moments between queued messages.
SETTLED = 0.75
#: ... and with its last picture a difference: only a panel without key frames (the self-check's
#: broken one) ends on one for good; a course panel's key frame is on its way (at 0.25 s; this
#: leaves a loaded machine sixteen times that).
SETTLED_ON_A_DIFFERENCE = 4.0


def _settle(nbp, keys, still: float = SETTLED, timeout: float = 30.0, moved=None):
    """Wait until every listed canvas has been unchanged for ``still`` s, the kernel is idle and
    each canvas's last picture was whole: a panel ends every burst of changes with a whole key
    frame, which on a loaded machine can come later than ``still`` after the last difference
    (and a difference lost in the browser leaves a ghost until then). ``moved``: {key: pictures
    shown before the drags} of the panels whose slider the drags moved; each must show a new one."""
    page = nbp.page
    last = page.evaluate(_STATE_JS, keys)
    since = time.monotonic()
    deadline = since + timeout

    def enough(state, for_s):
        whole = all(v is None or v["whole"] is not False for v in state.values())
        shown = all(state[str(k)]["shown"] > n for k, n in (moved or {}).items())
        return shown and for_s >= (still if whole else max(still, SETTLED_ON_A_DIFFERENCE))

    while time.monotonic() < deadline:
        page.wait_for_timeout(100)
        now = page.evaluate(_STATE_JS, keys)
        if now != last:
            last, since = now, time.monotonic()
        elif enough(now, time.monotonic() - since) and nbp.read_status().get("kernel") == "idle":
            return {int(k): v for k, v in last.items()}
    nbp.fail(f"the panels' canvases did not settle within {timeout:.0f} s after the drags "
             "(still, kernel idle, last picture whole)")


def _differing(a_url: str, b_url: str, page) -> float:
    """Fraction of differing pixels of two PNG data URLs (decoded in the page)."""
    return page.evaluate(r"""
    async ([a, b]) => {
      const load = (u) => new Promise((ok, no) => { const i = new Image(); i.onload = () => ok(i); i.onerror = no; i.src = u; });
      const [ia, ib] = await Promise.all([load(a), load(b)]);
      if (ia.width !== ib.width || ia.height !== ib.height) return 1;
      const px = (img) => { const c = document.createElement('canvas'); c.width = img.width; c.height = img.height;
        const x = c.getContext('2d'); x.drawImage(img, 0, 0); return new Uint32Array(x.getImageData(0, 0, c.width, c.height).data.buffer); };
      const pa = px(ia), pb = px(ib);
      let n = 0; for (let i = 0; i < pa.length; i++) if (pa[i] !== pb[i]) n++;
      return n / pa.length;
    }""", [a_url, b_url])


def settle_panels(nbp) -> dict:
    """Wait until every interactive panel's canvas has settled after Run All (the pictures of
    the last cells and of the widgets' first messages from the browser have arrived: each
    canvas still, its last picture whole, the kernel idle). Returns the panels and their state,
    which :func:`drag_check` takes as its starting point while nothing has changed since."""
    page = nbp.page
    panels = page.evaluate(_PANELS_JS, nbp.read_status()["panelId"])
    keys = [p["index"] for p in panels]
    if not keys:
        return {"panels": panels, "state": {}}
    missing = page.evaluate(_WATCH_PICTURES_JS)
    if missing:
        nbp.fail(f"cannot watch the canvases' pictures: {missing}")
    return {"panels": panels, "state": _settle(nbp, keys)}


def drag_check(nbp, shots_dir=None, settled=None) -> tuple[list[str], dict]:
    """Slow drag, back, quick drag to the same place, on the first slider of every panel.

    ``settled``: :func:`settle_panels`'s result, when it was called before (and the canvases are
    still as it left them, checked here). Returns (problems, info); ``info['panels']`` lists per
    panel the value reached, whether the picture changed with the drag, and the fraction of
    pixels that differ between the quick and the slow drag's final pictures. ``shots_dir``: PNGs of the canvas after each drag are saved
    there (tools/screenshots.py)."""
    page = nbp.page
    phases = nbp.timings.phases

    def clock(phase, t0):  # time spent per part of the check, summed (benchmarks/suite_time.py)
        now = time.monotonic()
        phases[phase] = round(phases.get(phase, 0.0) + now - t0, 2)
        return now

    t0 = time.monotonic()
    if settled is None:
        settled = settle_panels(nbp)
    panels = settled["panels"]
    keys = [p["index"] for p in panels]
    problems, rows = [], []
    if not keys:
        return problems, {"panels": rows}
    start = settled["state"]
    now = page.evaluate(_STATE_JS, keys)
    if any(now[str(k)] != start[k] for k in keys) or nbp.read_status().get("kernel") != "idle":
        start = _settle(nbp, keys)   # something changed since: settle again
    t0 = clock("drag: settle", t0)
    unwatched = [k for k in keys if start[k]["shown"] is None]
    if unwatched:
        nbp.fail(f"the pictures of panel(s) {unwatched} are not watched (no ipympl canvas model found)")
    start_px = _pixels(page, keys)
    direction, distance = {}, {}

    def whole_steps(g):
        """A displacement near DRAG_PX px that is (nearly) a whole number of slider steps, so a
        drag there and back returns to the same value."""
        if not g["step"] or not g["width"]:
            return DRAG_PX
        per_px = (g["hi"] - g["lo"]) / g["width"] / g["step"]
        return min(range(DRAG_PX - 15, DRAG_PX + 16), key=lambda d: abs(d * per_px - round(d * per_px)))

    def drag(k, sign, steps, pause_ms, g=None):
        # Whole pixels (the browser rounds mouse positions) from the handle's centre: noUiSlider
        # moves a handle by the mouse's displacement, so equal values and equal displacements
        # give equal results.
        g = g or _geometry(page, k)
        x = round(g["px"](g["value"]))
        _drag(page, x, round(g["y"]), x + sign * direction[k] * distance[k], steps, pause_ms)

    seen = {}
    for k in keys:
        g = seen[k] = _geometry(page, k)
        direction[k] = 1 if g["value"] <= (g["lo"] + g["hi"]) / 2 else -1
        distance[k] = whole_steps(g)
        # the slow drag: one mouse move. The slider shows its value on its grid (min + k *
        # step), so the handle ends on a grid value, a whole number of steps from where the
        # move back below leaves it, and the quick drag over the same displacement ends there too.
        # (A drag the page did not take, the handle not moved at all, is made again, twice at most.)
        for _attempt in range(3):
            drag(k, +1, 1, 0, g)
            g = _geometry(page, k, prev=g)
            if g["value"] != start[k]["value"]:
                break
    t0 = clock("drag: moves", t0)
    after = page.evaluate(_STATE_JS, keys)
    moved = {k: start[k]["shown"] for k in keys if after[str(k)]["value"] != start[k]["value"]}
    slow = _settle(nbp, keys, moved=moved)
    slow_px = _pixels(page, keys)
    t0 = clock("drag: settle", t0)
    for k in keys:  # back (one move), then the hurried drag over the same displacement
        g = _geometry(page, k, prev=seen[k], scrolled=True)
        drag(k, -1, 1, 0, g)
        drag(k, +1, QUICK_STEPS, QUICK_PAUSE_MS, _geometry(page, k, prev=g))
    t0 = clock("drag: moves", t0)
    quick = _settle(nbp, keys, moved={k: slow[k]["shown"] for k in moved})
    quick_px = _pixels(page, keys)
    t0 = clock("drag: settle", t0)
    for p in panels:
        k = p["index"]
        moved = slow[k]["value"] != start[k]["value"]
        changed = slow_px[k] != start_px[k]
        same_value = quick[k]["value"] == slow[k]["value"]
        diff = 0.0 if quick_px[k] == slow_px[k] else _differing(quick_px[k], slow_px[k], page)
        rows.append({"panel": k, "cell": p["cell"], "start": start[k]["value"], "value": slow[k]["value"],
                     "quick_value": quick[k]["value"], "moved": moved, "changed": changed, "differing": diff})
        where = f"panel #{k} (cell {p['cell']})"
        if not moved:
            problems.append(f"{where}: dragging its first slider {DRAG_PX} px did not move it")
        elif not same_value:
            problems.append(f"{where}: the quick drag ended on {quick[k]['value']}, the slow one on {slow[k]['value']}")
        elif diff > PIXEL_TOLERANCE:
            problems.append(f"{where}: after a quick drag {diff:.2%} of the canvas differs from the slow drag "
                            "to the same value (a ghost of an earlier frame?)")
        if shots_dir is not None:
            import base64
            for tag, url in (("slow", slow_px[k]), ("quick", quick_px[k])):
                (shots_dir / f"panel{k:02d}-{tag}.png").write_bytes(base64.b64decode(url.split(",", 1)[1]))
    if rows and not any(r["changed"] for r in rows):
        problems.append("no panel's picture changed when its first slider was dragged")
    clock("drag: compare", t0)
    return problems, {"panels": rows}


# -- one thread draws the figures -------------------------------------------------------------

# ipykernel >= 7 serves each kernel subshell on a thread of its own, named "subshell-<id>".
_THREADS_CODE = "import threading; print('GM-THREADS', *sorted(t.name for t in threading.enumerate()))"


def widget_threads(nbp) -> list[str]:
    """Problems if the notebook's kernel serves widget messages on a subshell thread.

    JupyterLab >= 4.4 sends widget (comm) messages to a kernel subshell by default (its setting
    ``commsOverSubshells``), and ipykernel >= 7 serves every subshell on its own thread. Then
    ipympl draws a canvas for the browser (its "draw" and "refresh" requests) and a panel's key
    frame fires there, while the main thread updates and blits the same figure for a slider:
    matplotlib is not thread-safe, and the two threads share one Agg buffer and one "last picture
    sent". Under load this sent half-drawn pictures and lost others (a quick drag of notebook 11's
    chain left 68 % of the canvas wrong; a slow drag of 01's torus panel, 11 %). The course's
    JupyterLab settings (jupyter/overrides.json) turn comms over subshells off."""
    out = labview.kernel_exec(nbp, _THREADS_CODE)
    line = next((ln for ln in out.splitlines() if ln.startswith("GM-THREADS")), None)
    if line is None:
        return [f"could not list the kernel's threads: {out[-300:]!r}"]
    sub = [t for t in line.split()[1:] if t.startswith("subshell")]
    return [f"the kernel serves widget messages on {len(sub)} subshell thread(s) besides the main one "
            "(JupyterLab's commsOverSubshells is on): figures are drawn from two threads at once"] if sub else []


# -- the self-check: the checks above can fail ------------------------------------------------

STUDENT_SELFCHECK_PATH = "_browser_selfcheck/student.ipynb"

_SELFCHECK_SETUP = r'''%matplotlib widget
import numpy as np
import ipywidgets as W
import matplotlib.pyplot as plt
from gm_core.drawing.toolkit.primitives import animate, jshtml
from gm_core.drawing.toolkit.blit import KeyFrames

def ghost_panel(key_frames, description="t", figsize=(4, 3)):
    """A blitted line whose update sends two difference images back to back, as a kernel that
    has fallen behind a fast drag does: the browser drops the first (matplotlib #19116)."""
    with plt.ioff():
        fig, ax = plt.subplots(figsize=figsize, dpi=100)
    fig.canvas.header_visible = fig.canvas.footer_visible = fig.canvas.toolbar_visible = False
    ax.set(xlim=(-1.2, 1.2), ylim=(-1.2, 1.2))
    (line,) = ax.plot([0, np.cos(0.3)], [0, np.sin(0.3)], lw=6, animated=True)
    state = {"bg": None}
    def on_draw(event):
        state["bg"] = fig.canvas.copy_from_bbox(fig.bbox)
        ax.draw_artist(line)
    fig.canvas.mpl_connect("draw_event", on_draw)
    keys = KeyFrames(fig) if key_frames else None
    def show(t):
        if state["bg"] is None:
            return
        fig.canvas.restore_region(state["bg"])
        line.set_data([0, np.cos(t)], [0, np.sin(t)])
        ax.draw_artist(line)
        fig.canvas.blit(fig.bbox)
    slider = W.FloatSlider(value=0.3, min=-3.0, max=3.0, step=0.01, description=description,
                           continuous_update=True, layout=W.Layout(width="420px"),
                           style={"description_width": "initial"})
    def update(change):
        show(change["new"] + 1.5)   # sent ...
        show(change["new"])         # ... and replaced at once
        if keys is not None:
            keys.touch()
    slider.observe(update, names="value")
    return W.HBox([W.VBox([slider]), fig.canvas])
'''


def student_selfcheck_notebook() -> dict:
    """In[2] a blitting panel with key frames (must pass the drag check), In[3] the same without
    (must fail it), In[4] a slider whose long label leaves a short track and whose figure is too
    tall, In[5] an animation made by gm_core (▶ must change its picture)."""
    def code(i, src):
        return {"cell_type": "code", "execution_count": None, "id": f"student-{i}", "metadata": {},
                "outputs": [], "source": src}
    cells = [
        code(1, _SELFCHECK_SETUP),
        code(2, "ghost_panel(key_frames=True)"),
        code(3, "ghost_panel(key_frames=False)"),
        code(4, "ghost_panel(True, description='a label long enough to squeeze the slider track away',\n"
                "            figsize=(4, 7))"),
        code(5, "with plt.ioff():\n"
                "    fig, ax = plt.subplots(figsize=(3, 2), dpi=100)\n"
                "ax.set(xlim=(0, 5), ylim=(0, 1))\n"
                "(dot,) = ax.plot([0], [0.5], 'o', ms=20)\n"
                "jshtml(animate(fig, lambda k: dot.set_data([k], [0.5]), frames=range(6), interval=60))"),
    ]
    return {"cells": cells, "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python",
                                                        "name": "python3"}},
            "nbformat": 4, "nbformat_minor": 5}


# -- the saved notebook, reopened without a kernel ----------------------------------------------

_SAVE_AND_CLOSE_JS = r"""
async (path) => {
  const app = window.jupyterapp;
  for (const w of [...app.shell.widgets('main')]) {
    if (w.context && w.context.path === path) { await w.context.save(); w.dispose(); }
  }
  return true;
}
"""


def replay_saved(nbp, timeout: float = 60.0) -> tuple[list[str], int]:
    """Save the executed notebook, close it, shut its kernel down and open it again with no
    kernel: every animation must still play (the player is plain HTML and JavaScript).
    Returns (problems, number of animations found)."""
    page = nbp.page
    page.evaluate(_SAVE_AND_CLOSE_JS, nbp.relpath)
    nbp.server.delete_sessions(nbp.relpath)
    nbp.lab.open(nbp.relpath, timeout, kernel=False)
    deadline = time.monotonic() + timeout
    while True:
        st = nbp.read_status()
        n = page.evaluate("(id) => document.getElementById(id) ? document.getElementById(id)"
                          ".querySelectorAll('.gm-anim').length : 0", st.get("panelId")) if st.get("panelId") else 0
        if n or time.monotonic() > deadline:
            break
        page.wait_for_timeout(200)
    if not n:
        return ["the saved notebook, reopened, shows no animation"], 0
    problems, count = play_animations(nbp)
    return [f"reopened without a kernel: {p}" for p in problems], count
