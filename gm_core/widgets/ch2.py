"""Chapter 2 panels: arms, mobile chains, generalized body frames and Jacobians, moved by sliders.

Every panel draws with the in-place artists of ``gm_core.drawing.ch2`` and takes its numbers from
``gm_core.chains``; ``naive_update`` is the clear-and-replot baseline used by the benchmark.
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from .. import chains as C
from ..groups import SE2
from ..drawing.base import FrameArtist
from ..drawing.chains import ArrowsArtist, ChainArtist, draw_chain_naive
from ..drawing.toolkit import PALETTE, new_figure, readout
from .base import Panel, register, slider

__all__ = ["SingleLinkPanel", "RRArmPanel", "RPArmPanel", "OffsetRPArmPanel", "MobileChainPanel",
           "TwoLinkMobilePanel", "ThreeLinkMobilePanel", "BetaFramePanel", "JacobianMethodsPanel",
           "ThreeLinkVelocityPanel"]

PI = float(np.pi)


def _square(ax, lim, center=(0.0, 0.0)):
    ax.set_xlim(center[0] - lim, center[0] + lim)
    ax.set_ylim(center[1] - lim, center[1] + lim)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)

def _three_link_scene(panel):
    """Shared set-up of the three-link panels: chain, square axes and a chain artist with the
    middle link as base (the chapter-2 convention of (2.57)-(2.59))."""
    panel.lengths = tuple(panel.options.get("lengths", (1.0, 1.0, 1.0)))
    panel.chain = C.three_link_chain(panel.lengths)
    panel.fig, panel.ax = new_figure(figsize=(5.5, 4.5))
    panel.lim = 0.75 * sum(panel.lengths)
    _square(panel.ax, panel.lim)
    panel.art = ChainArtist(panel.ax, 3, frames_shown=("g",), frame_length=0.25, base_link=1)



# ======================================================================= fixed-base arms
class _ArmPanel(Panel):
    """A fixed-base arm with one slider per joint and per joint speed; the end effector's velocity arrow."""

    joints = "R"
    lengths = (1.0,)
    offsets = None
    names = ("alpha",)
    ranges = ((-PI, PI),)
    start = (0.6,)
    frames_shown = ("f", "h")
    lim = 1.4

    def build(self):
        o = self.options
        self.chain = C.Chain(o.get("joints", self.joints), o.get("lengths", self.lengths),
                             offsets=o.get("offsets", self.offsets))
        self.fig, self.ax = new_figure(figsize=(5.5, 4.5))
        _square(self.ax, o.get("lim", self.lim))
        self.art = ChainArtist(self.ax, self.chain.n_links, frames_shown=self.frames_shown, pivot=True,
                               lengths=self.chain.lengths, offsets=self.chain.offsets)
        (self.sleeves,) = self.ax.plot([], [], "--", color="0.3", lw=2, zorder=1)
        self.vel = ArrowsArtist(self.ax, 1, label="end-effector velocity")
        self.controls = {}
        for name, (lo, hi), v in zip(self.names, self.ranges, self.start):
            self.controls[name] = slider(v, lo, hi, description=name)
        for name in self.names:
            self.controls[name + "_dot"] = slider(0.5, -2.0, 2.0, description=name + " rate")
        self.text = readout(self.ax, 0.02, 0.02)

    def _config(self, values):
        q = np.array([values[n] for n in self.names])
        qd = np.array([values[n + "_dot"] for n in self.names])
        return q, qd

    def compute(self, **values):
        """Frames, end-effector world velocity and Jacobian for the control values (tests use this)."""
        q, qd = self._config(values)
        fr = self.chain.frames(q)
        J = self.chain.jacobians(q, method="body")["h"][-1]
        return fr, J @ qd, J

    def update(self, **values):
        fr, v, J = self.compute(**values)
        self.art.set(fr)
        self.vel.set(fr["h"][-1, :2], v[:2])
        pts = []
        for i, jt in enumerate(self.chain.joints):
            if jt.kind == "prismatic" and i > 0:
                pts += [fr["h"][i - 1, :2], fr["f"][i, :2], [np.nan, np.nan]]
        pts = np.array(pts).reshape(-1, 2)
        self.sleeves.set_data(pts[:, 0], pts[:, 1])
        self.text.set_text("end effector h: x_dot=%+.2f y_dot=%+.2f theta_dot=%+.2f" % tuple(v))
        self.fig.canvas.draw_idle()

    def naive_update(self, **values):
        fr, v, _ = self.compute(**values)
        self.ax.clear()
        _square(self.ax, self.options.get("lim", self.lim))
        draw_chain_naive(self.ax, fr, frames_shown=self.frames_shown)
        self.ax.quiver([fr["h"][-1, 0]], [fr["h"][-1, 1]], [v[0]], [v[1]], angles="xy", scale_units="xy", scale=1)
        self.fig.canvas.draw_idle()


@register
class SingleLinkPanel(_ArmPanel):
    """One link on a pivot: the proximal frame rotates with alpha, the distal frame follows (2.4); arrow (2.17)."""

    title = "A pivoted link (fig. 2.2): frames g and h, velocity of h from (2.17)"


@register
class RRArmPanel(_ArmPanel):
    """The two-link rotary arm of fig. 2.3 with its end-effector velocity (2.19)."""

    title = "Two-link arm (fig. 2.3): forward kinematics (2.5)-(2.7), end-effector velocity (2.19)"
    joints = "RR"
    lengths = (1.0, 0.8)
    names = ("alpha1", "alpha2")
    ranges = ((-PI, PI), (-PI, PI))
    start = (0.5, 0.8)
    lim = 2.0


@register
class RPArmPanel(_ArmPanel):
    """The rotary-prismatic arm of fig. 2.4: link 2 slides out by delta along link 1, (2.10)-(2.11), (2.45)."""

    title = "Rotary-prismatic arm (fig. 2.4): the dashed gap is the slide delta"
    joints = "RP"
    lengths = (1.0, 0.6)
    names = ("alpha", "delta")
    ranges = ((-PI, PI), (0.0, 1.0))
    start = (0.5, 0.3)
    frames_shown = ("f", "h")
    lim = 2.5


@register
class OffsetRPArmPanel(RPArmPanel):
    """The rotary-prismatic arm with link 2 offset sideways by a (fig. 2.10, exercise 2.2)."""

    title = "Offset rotary-prismatic arm (fig. 2.10): velocity of the end effector"
    offsets = (0.3, 0.0)

    def compute(self, **values):
        fr, v, J = super().compute(**values)
        q, qd = self._config(values)
        a = self.chain.offsets[0]
        # the same body velocity from the closed form of exercise 2.2
        Jb = C.rp_arm_body_jacobians(q[0], q[1], *self.chain.lengths, offset=a)["h2"]
        self.closed_form = SE2.body_to_world(fr["h"][-1], Jb @ qd)
        return fr, v, J


# ======================================================================= mobile chains
class MobileChainPanel(Panel):
    """A free-floating chain: pose sliders place the base link's centre, joint sliders set the shape.

    The shared base of the two- and three-link panels (not registered itself; pass ``lengths=...``
    for other chains).

    Options: ``lengths`` (2 or more links). Controls: x, y, theta of the base link's medial frame,
    one joint angle per joint, the base link index, and for three links the shape symmetry
    ("free", "even" alpha2 = alpha1, "odd" alpha2 = -alpha1, fig. 2.6).
    """

    title = "Mobile articulated system (figs. 2.5, 2.6, 2.8): base link, shape and symmetry"
    default_lengths = (1.0, 1.0, 1.0)

    def build(self):
        self.lengths = tuple(self.options.get("lengths", self.default_lengths))
        n = len(self.lengths)
        self.n = n
        self.chains = [C.MobileChain(self.lengths, base_link=b) for b in range(n)]
        self.fig, self.ax = new_figure(figsize=(5.5, 4.5))
        self.lim = 0.75 * sum(self.lengths) + 0.5
        _square(self.ax, self.lim)
        self.art = ChainArtist(self.ax, n, frames_shown=("f", "g", "h"), frame_length=0.25)
        self.body = FrameArtist(self.ax, length=0.5, colors=("darkred", "darkgreen"), zorder=7)
        c = {"x": slider(0.0, -1.0, 1.0, description="x"), "y": slider(0.0, -1.0, 1.0, description="y"),
             "theta": slider(0.0, -PI, PI, description="theta")}
        for j in range(n - 1):
            c[f"alpha{j + 1}"] = slider([0.6, -0.6, 0.4][j % 3], -2.5, 2.5, description=f"alpha{j + 1}")
        c["base_link"] = W.IntSlider(value=(n - 1) // 2, min=0, max=n - 1, description="base link")
        if n == 3:
            c["shape"] = W.Dropdown(options=["free", "even", "odd"], value="free", description="shape")
        c["all_frames"] = W.Checkbox(value=False, description="show f and h frames")
        self.controls = c

    def shape(self, values):
        """The joint angles after applying the symmetry choice: ``(n - 1,)``."""
        a = np.array([values[f"alpha{j + 1}"] for j in range(self.n - 1)], dtype=float)
        mode = values.get("shape", "free")
        if mode == "even":
            a[1] = a[0]
        elif mode == "odd":
            a[1] = -a[0]
        return a

    def compute(self, **values):
        a = self.shape(values)
        g = np.array([values["x"], values["y"], values["theta"]])
        b = int(values["base_link"])
        return self.chains[b].frames(a, g), g, b

    def update(self, **values):
        fr, g, b = self.compute(**values)
        self.art.set(fr)
        self.art.set_base_link(b)
        self.body.set(g)
        show = bool(values.get("all_frames", False))
        for k in ("f", "h"):
            for fa in self.art.frames[k]:
                fa.quiver.set_visible(show)
        if "alpha2" in self.controls:
            self.controls["alpha2"].disabled = values.get("shape", "free") != "free"
        self.fig.canvas.draw_idle()

    def naive_update(self, **values):
        fr, g, b = self.compute(**values)
        self.ax.clear()
        _square(self.ax, self.lim)
        draw_chain_naive(self.ax, fr, frames_shown=("g",))
        self.fig.canvas.draw_idle()


@register
class TwoLinkMobilePanel(MobileChainPanel):
    """The two-link mobile system of fig. 2.5, configuration space SE(2) x S^1."""

    title = "Two-link mobile system (fig. 2.5): g2 from (2.12)-(2.13)"
    default_lengths = (1.0, 1.0)


@register
class ThreeLinkMobilePanel(MobileChainPanel):
    """The three-link mobile system of fig. 2.8 with even/odd shapes (fig. 2.6)."""

    title = "Three-link mobile system (figs. 2.6, 2.8): sign convention and symmetric shapes"


# ======================================================================= generalized body frames
@register
class BetaFramePanel(Panel):
    """A body frame g = g_2 beta placed by sliders (fig. 2.7) or at the centre of mass (fig. 2.9, ex. 2.3)."""

    title = "Generalized body frame beta (figs. 2.7, 2.9)"

    def build(self):
        _three_link_scene(self)
        self.beta_art = FrameArtist(self.ax, length=0.5, colors=("k", PALETTE["sky"]), zorder=8)
        (self.link_line,) = self.ax.plot([], [], ":", color="k", lw=1.5)
        (self.centres,) = self.ax.plot([], [], "s", color="k", ms=4)
        self.controls = {
            "alpha1": slider(0.8, -2.5, 2.5, description="alpha1"),
            "alpha2": slider(0.8, -2.5, 2.5, description="alpha2"),
            "frame": W.Dropdown(options=["sliders", "centre of mass"], value="centre of mass",
                                description="beta"),
            "beta_x": slider(0.3, -1.0, 1.0, description="beta x"),
            "beta_y": slider(0.2, -1.0, 1.0, description="beta y"),
            "beta_theta": slider(0.0, -PI, PI, description="beta theta"),
        }

    def compute(self, **values):
        a = np.array([values["alpha1"], values["alpha2"]])
        fr = self.chain.frames(a)
        if values["frame"] == "centre of mass":
            beta, _ = C.com_frame(a, self.lengths)
        else:
            beta = np.array([values["beta_x"], values["beta_y"], values["beta_theta"]])
        return fr, beta

    def update(self, **values):
        fr, beta = self.compute(**values)
        self.art.set(fr)
        g = SE2.compose(fr["g"][1], beta)  # middle link at e here, so g = beta (2.14)
        self.beta_art.set(g)
        self.link_line.set_data([fr["g"][1, 0], g[0]], [fr["g"][1, 1], g[1]])
        self.centres.set_data(fr["g"][:, 0], fr["g"][:, 1])
        for k in ("beta_x", "beta_y", "beta_theta"):
            self.controls[k].disabled = values["frame"] != "sliders"
        self.fig.canvas.draw_idle()

    def naive_update(self, **values):
        fr, beta = self.compute(**values)
        self.ax.clear()
        _square(self.ax, self.lim)
        draw_chain_naive(self.ax, fr)
        draw_chain_naive(self.ax, {"f": beta[None], "g": beta[None], "h": beta[None]}, width=0.0)
        self.fig.canvas.draw_idle()


# ======================================================================= Jacobians
@register
class JacobianMethodsPanel(Panel):
    """The end-effector velocity of a chain by the three Jacobian methods of section 2.5, live side by side."""

    title = "Three ways to a Jacobian: direct (2.16), world iterative (2.31), body iterative (2.37)"
    COLORS = {"direct": PALETTE["blue"], "world": PALETTE["orange"], "body": PALETTE["purple"]}

    def build(self):
        o = self.options
        self.chain = C.Chain(o.get("joints", "RPR"), o.get("lengths", (1.0, 0.5, 0.7)))
        n = self.chain.n_joints
        self.fig, self.ax = new_figure(figsize=(6, 4.5))
        self.lim = float(self.chain.lengths.sum() + 1.2)
        _square(self.ax, self.lim)
        self.art = ChainArtist(self.ax, n, frames_shown=("h",), pivot=True, frame_length=0.25)
        widths = {"direct": 0.016, "world": 0.010, "body": 0.005}
        self.arrows = {m: ArrowsArtist(self.ax, 1, color=self.COLORS[m], width=widths[m], label=m)
                       for m in C.METHODS}
        self.ax.legend(loc="upper right", fontsize=8)
        self.text = readout(self.ax, 0.02, 0.02)
        self.controls = {}
        for i, jt in enumerate(self.chain.joints):
            lo, hi = (-PI, PI) if jt.kind == "revolute" else (0.0, 1.0)
            self.controls[f"q{i + 1}"] = slider(0.4 * (i + 1) if jt.kind == "revolute" else 0.3, lo, hi,
                                                description=f"q{i + 1} ({jt.letter})")
        for i in range(n):
            self.controls[f"q{i + 1}_dot"] = slider(0.5, -2.0, 2.0, description=f"q{i + 1} rate")

    def compute(self, **values):
        n = self.chain.n_joints
        q = np.array([values[f"q{i + 1}"] for i in range(n)])
        qd = np.array([values[f"q{i + 1}_dot"] for i in range(n)])
        key = tuple(q)
        if getattr(self, "_at", None) != key:  # frames and Jacobians depend on q only: a rate slider reuses them
            self._fr = self.chain.frames(q)
            self._J = {m: self.chain.jacobians(q, method=m)["h"][-1] for m in C.METHODS}
            self._at = key
        return self._fr, {m: J @ qd for m, J in self._J.items()}

    def update(self, **values):
        fr, v = self.compute(**values)
        self.art.set(fr)
        p = fr["h"][-1, :2]
        for m, a in self.arrows.items():
            a.set(p, v[m][:2])
        spread = max(np.abs(v[m] - v["direct"]).max() for m in C.METHODS)
        lines = ["method   x_dot    y_dot    th_dot"]
        lines += [f"{m:7s} {v[m][0]:+8.4f} {v[m][1]:+8.4f} {v[m][2]:+8.4f}" for m in C.METHODS]
        lines.append(f"largest disagreement {spread:.1e}")
        self.spread = spread
        self.text.set_text("\n".join(lines))
        self.fig.canvas.draw_idle()

    def naive_update(self, **values):
        fr, v = self.compute(**values)
        self.ax.clear()
        _square(self.ax, self.lim)
        draw_chain_naive(self.ax, fr, frames_shown=("h",))
        p = fr["h"][-1]
        for m in C.METHODS:
            self.ax.quiver([p[0]], [p[1]], [v[m][0]], [v[m][1]], color=self.COLORS[m], angles="xy",
                           scale_units="xy", scale=1)
        self.fig.canvas.draw_idle()


@register
class ThreeLinkVelocityPanel(Panel):
    """Body velocities of the three links from (xi, alpha_dot) through the corrected (2.57)-(2.59)."""

    title = "Three-link system: link body velocities from xi and the joint speeds (2.57)-(2.59)"

    def build(self):
        _three_link_scene(self)
        self.arrows = ArrowsArtist(self.ax, 3, color=PALETTE["purple"], scale=0.5, label="link velocity (x 0.5)")
        self.text = readout(self.ax, 0.02, 0.02)
        self.controls = {
            "alpha1": slider(0.6, -2.5, 2.5, description="alpha1"),
            "alpha2": slider(-0.4, -2.5, 2.5, description="alpha2"),
            "xi_x": slider(0.5, -1.0, 1.0, description="xi x"),
            "xi_y": slider(0.0, -1.0, 1.0, description="xi y"),
            "xi_theta": slider(0.0, -1.0, 1.0, description="xi theta"),
            "alpha1_dot": slider(0.0, -1.0, 1.0, description="alpha1 rate"),
            "alpha2_dot": slider(1.0, -1.0, 1.0, description="alpha2 rate"),
        }

    def compute(self, **values):
        """Frames (middle link at e), link body velocities ``(3, 3)`` and their world velocities ``(3, 3)``."""
        a = np.array([values["alpha1"], values["alpha2"]])
        u = np.array([values[k] for k in ("xi_x", "xi_y", "xi_theta", "alpha1_dot", "alpha2_dot")])
        fr = self.chain.frames(a)
        xis = np.stack([J @ u for J in C.three_link_jacobians(a, self.lengths)])
        world = SE2.body_to_world(fr["g"], xis)
        return fr, xis, world

    def update(self, **values):
        fr, xis, world = self.compute(**values)
        self.art.set(fr)
        self.arrows.set(fr["g"][:, :2], world[:, :2])
        self.text.set_text("\n".join(f"xi_{i + 1} = ({x[0]:+.2f}, {x[1]:+.2f}, {x[2]:+.2f})"
                                     for i, x in enumerate(xis)))
        self.fig.canvas.draw_idle()

    def naive_update(self, **values):
        fr, xis, world = self.compute(**values)
        self.ax.clear()
        _square(self.ax, self.lim)
        draw_chain_naive(self.ax, fr)
        self.ax.quiver(fr["g"][:, 0], fr["g"][:, 1], world[:, 0], world[:, 1], angles="xy",
                       scale_units="xy", scale=2.0)
        self.fig.canvas.draw_idle()
