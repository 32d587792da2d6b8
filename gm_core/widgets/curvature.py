"""Panels for the geometry notebook: a gait on the curvature map, frames compared, optimisation progress.

Numbers come from :mod:`gm_core.geometry` and :mod:`gm_core.locomotion`; artists from
:mod:`gm_core.drawing.curvature`. Each update moves existing artists and calls draw_idle.
"""
from __future__ import annotations

import html

import ipywidgets as W
import numpy as np

from .._validate import SingularShapeError
from ..drawing.base import SingularFlag, new_figure
from ..drawing.curvature import DPI, FONT, ROWS, CurvatureMapArtist, FieldArtist, GaitArtist, _style
from ..drawing.toolkit import PALETTE
from ..geometry import body_frames, body_velocity_integral, fourier_gait, optimize_gait, stokes_estimate
from ..locomotion import net_displacement
from ..systems import LowReSwimmer
from .base import Panel, register, slider

__all__ = ["shaped_gait", "numbers_table", "GaitStokesPanel", "FrameFieldsPanel", "optimize_with_progress"]

FRAMES = ("middle link", "centre of mass", "minimum perturbation")
#: ToggleButtons' default buttons are too narrow for "minimum perturbation" (cut to "minimum perturb…"):
#: wide enough for the longest frame name at the widgets' 13 px font
FRAME_BUTTONS = {"button_width": "15em"}


def shaped_gait(c1=0.0, c2=0.0, a=1.0, b=1.0, tilt=0.0, bend=0.0, period=1.0):
    """An ellipse gait (semi-axes a, b, turned by ``tilt``, centre (c1, c2)) bent into a bean by ``bend``.

    ``bend`` adds a second harmonic along the minor axis, which makes the loop non-convex for
    |bend| above about a/4. Counter-clockwise for positive a and b.
    """
    c, s = np.cos(tilt), np.sin(tilt)
    R = np.array([[c, -s], [s, c]])
    cos_c = np.array([[a, 0.0], [0.0, bend]])  # (u, v) cos coefficients, harmonics 1 and 2
    sin_c = np.array([[0.0, 0.0], [b, 0.0]])
    return fourier_gait(R @ cos_c, R @ sin_c, (c1, c2), period=period, name="shaped gait")


LIMITS = ((-2.5, 2.5), (-2.5, 2.5))


def _frames(system):
    frames = getattr(_frames, "_cache", {})
    key = id(system)
    if key not in frames:
        frames[key] = body_frames(system, LIMITS)
        _frames._cache = frames
    return frames[key]


def numbers_table(exact, stokes, bvi):
    """HTML table of the three estimates (rows x, y, θ of g(T)), 4 decimals."""
    head = "".join(f"<th style='padding:0 8px'>{r}</th>" for r in ROWS)
    rows = "".join(f"<tr><td>{name}</td>" + "".join(f"<td style='padding:0 8px'>{v:+.4f}</td>" for v in vals)
                   + "</tr>" for name, vals in (("exact g(T)", exact), ("Stokes ∬D(−A)", stokes),
                                                ("∫ξ dt", bvi)))
    return (f"<table style='font-family:monospace;font-size:13px'><tr><th></th>{head}</tr>{rows}</table>")


#: Interactive resolution of GaitStokesPanel (fixed, so every slider change costs the same).
#: Exact g(T): fourth-order Magnus steps of net_displacement; 128 of them agree with the adaptive
#: integration to about 1e-8 for the panel's gaits. Stokes estimate: the radial quadrature of
#: stokes_estimate at (64, 12) points, body-velocity integral: 256 trapezoid steps; both agree
#: with their refined values to 1e-7 or better (tests/test_geometry*.py check all three).
EXACT_STEPS = 128
STOKES_SAMPLES = (64, 12)
BVI_SAMPLES = 256


@register
class GaitStokesPanel(Panel):
    """Move, resize and reshape a gait on a curvature map; compare exact g(T), Stokes and ∮ξ dt.

    Each slider change recomputes the three at fixed interactive resolutions (``EXACT_STEPS``,
    ``STOKES_SAMPLES``, ``BVI_SAMPLES``: all within about 1e-7 of the library's refined values)
    and redraws by blitting. The bars of each row (x, y, θ) are scaled by the largest of that
    row's three values (rows under 5 % of the largest row stay small), so the axis never rescales; the numbers are in an HTML table under the
    figure (``self.numbers``: text rendered by the browser, not redrawn by matplotlib).
    """

    title = "A gait on the curvature map: exact displacement, Stokes estimate, body-velocity integral"

    def build(self):
        self.system = self.options.get("system") or LowReSwimmer()
        self.frames = _frames(self.system)
        self.fig, (self.ax, self.axb) = new_figure(1, 2, figsize=(9, 4.2), dpi=DPI, layout="compressed",
                                                   gridspec_kw=dict(width_ratios=[1.1, 1]))
        self.map = CurvatureMapArtist(self.ax, self.frames["middle link"], 0, limits=LIMITS)
        self._map_key = ("middle link", 0)
        _style(self.ax, self.map.limits)
        self.gait_artist = GaitArtist(self.ax)
        self.flag = SingularFlag(self.ax)
        x = np.arange(3)
        self.bars = {}
        for k, (label, color) in enumerate([("exact g(T)", "k"), ("Stokes ∬D(−A)", PALETTE["vermillion"]),
                                            ("∫ξ dt", PALETTE["grey"])]):
            self.bars[label] = self.axb.bar(x + (k - 1) * 0.27, np.zeros(3), 0.25, color=color, label=label)
        self.axb.set_xticks(x, [f"{r}" for r in ROWS], fontsize=FONT)
        # fixed limits, legend above the bars' reach, grid below them: nothing static is ever
        # covered by a moving bar, so blitted frames equal full redraws
        self.axb.set_ylim(-1.1, 1.45)
        self.axb.set_ylabel("each row ÷ its largest |value|", fontsize=FONT)
        self.axb.set_axisbelow(True)
        self.axb.yaxis.grid(True, lw=0.6, color="0.8")
        self.axb.tick_params(labelsize=FONT)
        self.axb.legend(fontsize=FONT, loc="upper center", ncols=3, handlelength=1.2, columnspacing=1.0)
        self.axb.set_title("numbers: in the table below", fontsize=FONT, loc="left")
        self.numbers = W.HTML()
        self.values_shown = None
        self.controls = {
            "c1": slider(0.0, -1.5, 1.5, description="centre α₁"),
            "c2": slider(0.0, -1.5, 1.5, description="centre α₂"),
            "a": slider(1.0, 0.1, 1.5, description="size a"),
            "b": slider(0.6, 0.1, 1.5, description="size b"),
            "tilt": slider(0.78, -1.6, 1.6, description="tilt"),
            "bend": slider(0.0, -0.6, 0.6, description="bend"),
            "row": W.ToggleButtons(options=[(r, i) for i, r in enumerate(ROWS)], value=0,
                                   description="map row"),
            "frame": W.ToggleButtons(options=list(FRAMES), value="middle link", description="frame",
                                     style=FRAME_BUTTONS),
        }

    def compute(self, c1, c2, a, b, tilt, bend, frame, **_):
        """(system, gait, exact g(T), Stokes estimate, body-velocity integral) at interactive resolution."""
        system = self.frames[frame]
        gait = shaped_gait(c1, c2, a, b, tilt, bend)
        stokes = stokes_estimate(system, gait, samples=STOKES_SAMPLES)  # checks the gait first
        exact = net_displacement(system, gait, steps=EXACT_STEPS, check=False)
        bvi = body_velocity_integral(system, gait, samples=BVI_SAMPLES, check=False)
        if not np.all(np.isfinite(exact)):
            raise SingularShapeError(f"the gait reaches a singular shape of {system.name}")
        return system, gait, exact, stokes, bvi

    @staticmethod
    def bar_heights(exact, stokes, bvi):
        """The bars (3 methods, 3 rows): each row divided by its largest |value|.

        A row whose values are all below 5 % of the largest value of any row is divided by that 5 %
        instead, so a row that is practically zero (2e-4 beside 0.27) draws as practically zero,
        not as a full-height bar.
        """
        vals = np.array([exact, stokes, bvi], dtype=float)
        top = np.abs(vals).max(axis=0)
        scale = np.maximum(top, 0.05 * top.max() + 1e-12)
        return vals / scale

    def update(self, **v):
        key = (v["frame"], v["row"])
        if key != self._map_key:  # the image is redrawn only when the map changes
            self.map.set(self.frames[v["frame"]], v["row"])
            self._map_key = key
        self.gait_artist.set(shaped_gait(v["c1"], v["c2"], v["a"], v["b"], v["tilt"], v["bend"]))
        try:
            _, _, exact, stokes, bvi = self.compute(**v)
        except SingularShapeError as e:
            self.flag.show("gait leaves the map or is singular")
            for bars in self.bars.values():
                for rect in bars:
                    rect.set_height(0.0)
            self.numbers.value = f"<p style='color:darkred'>{html.escape(str(e))}</p>"
            self.values_shown = None
        else:
            self.flag.hide()
            for bars, heights in zip(self.bars.values(), self.bar_heights(exact, stokes, bvi)):
                for rect, h in zip(bars, heights):
                    rect.set_height(h)
            self.numbers.value = numbers_table(exact, stokes, bvi)
            self.values_shown = (exact, stokes, bvi)
        self.fig.canvas.draw_idle()

    @property
    def widget(self):
        """The panel's box with the table of numbers under it."""
        if getattr(self, "_with_numbers", None) is None:
            self._with_numbers = W.VBox([Panel.widget.fget(self), self.numbers])
        return self._with_numbers

    def naive_update(self, **v):
        self.ax.clear()
        self.axb.clear()
        self.map = CurvatureMapArtist(self.ax, self.frames[v["frame"]], v["row"], limits=LIMITS)
        self._map_key = (v["frame"], v["row"])
        GaitArtist(self.ax).set(shaped_gait(v["c1"], v["c2"], v["a"], v["b"], v["tilt"], v["bend"]))
        try:
            _, _, exact, stokes, bvi = self.compute(**v)
            self.axb.bar(np.arange(9), np.concatenate([exact, stokes, bvi]))
        except SingularShapeError:
            pass
        self.fig.canvas.draw_idle()


@register
class FrameFieldsPanel(Panel):
    """The three rows of −A(r) as fields, in the frame chosen by a toggle (they straighten and shrink)."""

    title = "The connection seen from three body frames"

    def build(self):
        self.system = self.options.get("system") or LowReSwimmer()
        self.frames = _frames(self.system)
        self.fig, axes = new_figure(1, 3, figsize=(9, 3.3), dpi=DPI, layout="constrained")
        lim = LIMITS
        self.axes = axes
        self.fields = [FieldArtist(ax, self.system, i, limits=lim) for i, ax in enumerate(axes)]
        for i, ax in enumerate(axes):
            _style(ax, lim, f"row {ROWS[i]} of −A")
        self.norms = {}
        # the size of each row goes in its title, off the arrows
        self.labels = [ax.title for ax in axes]
        self.controls = {"frame": W.ToggleButtons(options=list(FRAMES), value="middle link", description="frame",
                                          style=FRAME_BUTTONS)}

    def field_norms(self, frame):
        """Mean |row of A| over the grid, per row (3,) (what the minimum-perturbation frame makes small)."""
        A = self.frames[frame].connection(self.fields[0].grid)
        return np.sqrt(np.nanmean(np.sum(A ** 2, axis=-1), axis=(0, 1)))

    def update(self, frame):
        ref = [f.set(self.frames["middle link"]) for f in self.fields] if not self.norms else self.norms["ref"]
        self.norms["ref"] = ref
        size = self.field_norms(frame)
        for i, (f, lab, sc, sz) in enumerate(zip(self.fields, self.labels, ref, size)):
            f.set(self.frames[frame], scale=sc)  # same arrow scale in every frame
            lab.set_text(f"row {ROWS[i]} of −A\nrms |row| = {sz:.3f}")
        self.fig.canvas.draw_idle()

    def naive_update(self, frame):
        for i, ax in enumerate(self.axes):
            ax.clear()
            FieldArtist(ax, self.frames[frame], i, limits=LIMITS)
        self.fig.canvas.draw_idle()


def optimize_with_progress(system, objective="displacement", order=3, **kw):
    """Run :func:`gm_core.geometry.optimize_gait` showing a progress bar and the current value; returns the result."""
    from IPython.display import display

    maxiter = kw.pop("maxiter", 200)
    bar = W.IntProgress(value=0, min=0, max=maxiter, description=f"max {objective}",
                        style={"description_width": "initial"})
    label = W.HTML("starting from a circle ...")
    display(W.HBox([bar, label]))

    def cb(it, val):
        bar.value = min(it, maxiter)
        label.value = f"iteration {it}: {objective} = {val:.5f}"

    res = optimize_gait(system, objective, order=order, maxiter=maxiter, callback=cb, **kw)
    bar.value = bar.max
    label.value = f"done after {res.nit} iterations: {objective} = {res.history[-1]:.5f}"
    return res
