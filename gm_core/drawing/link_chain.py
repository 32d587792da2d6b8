"""Drawing for notebook 11 (beyond the draft): chains of any number of links and continuous bodies.

* :class:`ChainSliceScene`: a chain you design (links, physics), one connection row on a 2-D
  slice of its shape space and the constraint curvature of that row on the same slice;
* :class:`WaveGaitScene`: a travelling-wave gait (amplitude, phase lag between joints) and the
  motion it makes over one cycle, with the net displacement and the efficiency;
* :class:`OptimalGaitScene`: a chain you design (links, taper, physics), a wave to start from
  and, once :meth:`OptimalGaitScene.optimize` has run, its most efficient gait and one cycle of
  the motion;
* :func:`animate_chain_gait`: a gait of any number of joints as an animation that plays without a
  kernel (joint angles against time, and the body moving in the plane);
* :func:`links_comparison_figure`, :func:`continuum_figure`: the notebook's two comparisons.

The scenes compute by calling the math (:mod:`gm_core.systems`, :mod:`gm_core.systems.motion`,
:mod:`gm_core.geometry`); artists are made once and moved in ``set``.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, ClassVar, cast

import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.text import Text
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.drawing.connection import ROW_LABELS, ConnectionFieldArtist, Limits, math_title, style_shape_axes
from gm_core.drawing.curvature import CurvatureMapArtist
from gm_core.drawing.motion import SystemArtist, style_world_axes
from gm_core.drawing.toolkit.primitives import SingularFlag, TrailArtist, animate
from gm_core.drawing.toolkit.recent import Recent
from gm_core.drawing.toolkit.style import MATH_PT, PALETTE, Scene, freeze_layout, new_figure, readout, signed, title
from gm_core.geometry import efficiency, optimize_chain_gait, travelling_wave, wave_start
from gm_core.geometry.optimal import OptimalGait
from gm_core.groups import SE2
from gm_core.systems import LinkChain, LocomotionSystem, shape_slice
from gm_core.systems.gaits import Gait
from gm_core.systems.motion import Trajectory, trajectory
from gm_core.systems.restricted import AffineRestriction
from gm_core.validation import FloatArray, check_int, check_option

__all__ = ["ChainSliceScene", "WaveGaitScene", "OptimalGaitScene", "animate_chain_gait", "links_comparison_figure",
           "continuum_figure", "design_chain", "PHYSICS_LABELS", "JOINT_MAP", "JOINT_MAP_TOP", "joint_colours"]

#: Dropdown labels of the physics of :class:`~gm_core.systems.LinkChain`.
PHYSICS_LABELS = {"low Re (drag)": "low_re", "high Re (added mass)": "high_re", "floating (momentum)": "floating"}
#: The joints' colour map: sequential and colour-vision safe (viridis, perceptually uniform, its
#: lightness rising monotonically for every common colour-vision deficiency), from the head's joint
#: (dark) to the tail's (light), stopped at JOINT_MAP_TOP short of its pale yellow end.
JOINT_MAP, JOINT_MAP_TOP = "viridis", 0.85


def joint_colours(n: int) -> list[str]:
    """The colours of ``n`` joints' curves and names, joint 1 first: ``n`` evenly spaced samples of
    :data:`JOINT_MAP`. A wave running along the body reads as a run of colour, and neighbouring
    joints, the pairs a student compares, differ in lightness as much as ``n`` allows (for six
    joints by more than 10 units of CIELAB lightness, in every colour vision; tests check it)."""
    from matplotlib import colormaps
    from matplotlib.colors import to_hex

    n = check_int(n, "n", minimum=1, maximum=100)
    cmap = colormaps[JOINT_MAP]
    return [to_hex(cmap(JOINT_MAP_TOP * k / max(n - 1, 1))) for k in range(n)]


def design_chain(links: int, physics: str = "low_re", total_length: float = 3.0, taper: float = 0.0,
                 frame: str = "com") -> LinkChain:
    """The chain a student designs (a :meth:`LinkChain.tapered`; ``physics`` may be a dropdown label)."""
    return LinkChain.tapered(links, PHYSICS_LABELS.get(physics, physics), total_length=total_length, taper=taper,
                             frame=frame)


class PartsArtist:
    """Every rigid part of a system as one PolyCollection: ``set(system, g, r)`` moves it in place,
    whatever the number of parts (the chain may gain or lose links between two calls)."""

    def __init__(self, ax: Axes, facecolor: ColorType = PALETTE["orange"], alpha: float = 0.6,
                 edgecolor: ColorType = "k", zorder: float = 3) -> None:
        from matplotlib.collections import PolyCollection

        self.coll = PolyCollection([], facecolors=facecolor, edgecolors=edgecolor, alpha=alpha, linewidths=0.8,
                                   zorder=zorder)
        ax.add_collection(self.coll)

    def set(self, system: LocomotionSystem, g: ArrayLike, r: ArrayLike) -> None:
        poses = SE2.compose(np.asarray(g, dtype=float), system.part_poses(np.asarray(r, dtype=float)))
        self.coll.set_verts([SE2.act_on_points(pose, p.outline) for p, pose in zip(system.parts(), poses)])


def _chain_axes_title(system: LinkChain) -> str:
    physics = {v: k for k, v in PHYSICS_LABELS.items()}.get(system.physics, system.physics.replace("_", " "))
    return f"{system.n_links} links, {physics}"


def _joint_math(k: int) -> str:
    """Joint ``k`` (0-based) as mathtext, as notebooks 08-10 label shape axes: ``$\\alpha_1$``."""
    return rf"$\alpha_{k + 1}$"


class ChainSliceScene(Scene):
    """A chain, one row of its connection on a 2-D slice of shape space, and that row's curvature there.

    Values: ``links`` (3-7), ``physics`` (a key of :data:`PHYSICS_LABELS` or a physics name),
    ``row`` (0, 1, 2 = x, y, theta), ``axis1``, ``axis2`` (the two joints spanning the slice,
    1-based; one beyond the chain's last joint is the last joint; the other joints stay
    straight). One joint named twice spans no slice (:func:`~gm_core.systems.shape_slice`
    refuses it): the field and the map are hidden and a flag on each says so (``same``).
    Options: ``total_length`` (3), ``taper`` (0), ``limits`` of the slice (+-2), ``n_map``
    (curvature pixels per side).
    """

    FIGSIZE = (9.0, 3.3)
    NCOLS = 3
    #: designs (chains and slices) kept for a slider moved back and forth
    DESIGNS_KEPT: ClassVar[int] = 16

    def __init__(self, total_length: float = 3.0, taper: float = 0.0, limits: Limits = ((-2.0, 2.0), (-2.0, 2.0)),
                 n_map: int = 21, **options: Any) -> None:
        self.total_length, self.taper, self.limits, self.n_map = total_length, taper, limits, n_map
        self._designs: Recent[tuple[int, str, int, int], tuple[LinkChain, AffineRestriction | None]] = \
            Recent(self.DESIGNS_KEPT)
        super().__init__(**options)

    def _build(self, links: int, physics: str, axis1: int, axis2: int) -> None:
        # a joint beyond the chain's end is its last joint (the panel's sliders reach it)
        n = links - 1
        i = min(check_int(axis1, "axis1", minimum=1, maximum=6, what=" (a joint, 1-based)"), n) - 1
        j = min(check_int(axis2, "axis2", minimum=1, maximum=6, what=" (a joint, 1-based)"), n) - 1
        self.pair = (i, j)
        #: True when both slice joints are one joint: no slice (shape_slice refuses it)
        self.same = i == j
        # a design seen before is the same system and slice objects again, so the math layer's
        # caches (curvature_grid) serve a slider moved back and forth
        def make() -> tuple[LinkChain, AffineRestriction | None]:
            system = design_chain(links, physics, self.total_length, self.taper)
            return system, None if self.same else shape_slice(system, None, (i, j), limits=self.limits)

        self.system, self.slice = self._designs.get((links, physics, i, j), make)

    @override
    def decorate(self) -> None:
        ax0, ax1, ax2 = self.axes
        style_world_axes(ax0, 0.62 * self.total_length)
        title(ax0, "the chain: slice joints bent (dots)", size=MATH_PT)

    @override
    def create(self) -> None:
        self._build(4, "low_re", 1, 2)
        ax0, ax1, ax2 = self.axes
        self.body = PartsArtist(ax0)
        (self.joint_dots,) = ax0.plot([], [], "o", ms=7, color=PALETTE["vermillion"], zorder=6)
        sliced = cast(AffineRestriction, self.slice)    # four links: a 2-D slice of the shape space
        style_shape_axes(ax1, sliced)
        style_shape_axes(ax2, sliced)
        self.field = ConnectionFieldArtist(ax1, sliced, 0, color="0.3")
        self.map = CurvatureMapArtist(ax2, sliced, 0, limits=self.limits, n=self.n_map)
        self.text = readout(ax0, 0.02, 0.02)
        self.flags = [SingularFlag(ax, loc=(0.5, 0.5)) for ax in (ax1, ax2)]
        for flag in self.flags:
            flag.text.set_verticalalignment("center")
        # PathText: cheap to redraw when the row changes; MATH_PT for the row's superscript
        self.titles = (title(ax1, size=MATH_PT), title(ax2, size=MATH_PT))
        self._key: tuple[int, str, int, int] | None = None
        self._labelled: tuple[int, int] | None = None     # the joints the axis labels name

    @override
    def set(self, links: int = 4, physics: str = "low_re", row: int = 2, axis1: int = 1, axis2: int = 2) -> None:
        links = check_int(links, "links", minimum=3, maximum=7, what=" (a slice needs two joints)")
        physics = check_option(PHYSICS_LABELS.get(physics, physics), "physics", tuple(PHYSICS_LABELS.values()))
        row = check_int(row, "row", minimum=0, maximum=2)
        axis1, axis2 = int(axis1), int(axis2)
        key = (links, physics, axis1, axis2)
        if key != self._key:
            self._key = key
            self._build(links, physics, axis1, axis2)
            self.body.set(self.system, np.zeros(3), self._drawn_shape())
            q = self._joint_positions()
            self.joint_dots.set_data(q[list(self.pair), 0], q[list(self.pair), 1])
            if self.pair != self._labelled:     # a new label is a full draw (blit.py)
                self._labelled = self.pair
                for ax in self.axes[1:]:
                    ax.set_xlabel(_joint_math(self.pair[0]), fontsize=MATH_PT, labelpad=0)
                    ax.set_ylabel(_joint_math(self.pair[1]), fontsize=MATH_PT, labelpad=0)
        for art in (self.field.quiver, self.map.image, self.field.zero_note, self.field.scale_note):
            if self.same or art in (self.field.quiver, self.map.image):
                art.set_visible(not self.same)        # the notes are the field's own (set below)
        for flag in self.flags:
            if self.same:
                flag.show(f"joint {self.pair[0] + 1} twice: no slice.\nChoose two different joints.")
            else:
                flag.hide()
        if not self.same:
            self.field.set(self.slice, row)
            self.map.set(self.slice, row)
        self.titles[0].set_text(math_title(f"−A, row {ROW_LABELS[row]}, on the slice"))
        self.titles[1].set_text(math_title(f"curvature D(−A), row {ROW_LABELS[row]}"))
        self.text.set_text(_chain_axes_title(self.system))    # the axis labels name the slice's joints
        self.row = row

    def _drawn_shape(self) -> FloatArray:
        """The chain is drawn with the slice's two joints bent by 0.6 rad, the others straight."""
        r = np.zeros(self.system.n_shape)
        r[list(self.pair)] = 0.6
        return r

    def _joint_positions(self) -> FloatArray:
        P = self.system.link_poses(self._drawn_shape())
        L = np.array(self.system.lengths)
        return P[:-1, :2] + 0.5 * L[:-1, None] * np.stack([np.cos(P[:-1, 2]), np.sin(P[:-1, 2])], -1)


def _joint_names(ax: Axes, n_max: int) -> list[Text]:
    """The key of the joint curves: each joint's name, in its curve's colour, along the top of the
    gait axes (curves stay below 1.5 rad there); :func:`_show_joints` shows the chain's."""
    return [ax.text(0.04 + 0.16 * k, 0.97, _joint_math(k), color=c, fontsize=MATH_PT, ha="left", va="top",
                    transform=ax.transAxes) for k, c in enumerate(joint_colours(n_max))]


def _show_joints(names: Sequence[Text], curves: Sequence[Sequence[Line2D]], n: int) -> None:
    """Show the names of a chain's ``n`` joints and colour them and each list of joint curves
    with :func:`joint_colours` of ``n`` (curves beyond ``n`` hold no data and are not drawn)."""
    colours = joint_colours(n)
    for k, name in enumerate(names):
        name.set_visible(k < n)
        if k < n:
            name.set_color(colours[k])
    for lines in curves:
        for line, c in zip(lines, colours):
            line.set_color(c)


def _gait_and_motion_axes(axes: Sequence[Axes], total_length: float, gait_title: str, motion_title: str) -> None:
    """Style the two axes of a gait scene: joint angles over one period, and the world of one cycle."""
    ax0, ax1 = axes
    ax0.set_xlim(0, 2 * np.pi)
    ax0.set_ylim(-2.2, 2.2)
    ax0.set_xlabel("t", fontsize=9, labelpad=0)
    ax0.set_ylabel("joint angles (rad)", fontsize=9, labelpad=0)
    ax0.set_title(gait_title, fontsize=9)
    style_world_axes(ax1, 0.7 * total_length, (-0.15 * total_length, 0.0))
    ax1.set_title(motion_title, fontsize=9)


class WaveGaitScene(Scene):
    """A travelling-wave gait of a chain and the motion of one cycle: trail, body at start and end, numbers.

    Values: ``links`` (2-7), ``physics``, ``amplitude`` (rad), ``lag`` (phase lag between
    neighbouring joints, rad). The readout gives the net displacement per cycle (in the
    centre-of-mass frame) and the efficiency (translation per unit path length in the
    physics' cost metric).
    """

    FIGSIZE = (8.0, 3.6)
    NCOLS = 2
    #: waves (chain, gait, motion, efficiency) kept for a slider moved back and forth
    WAVES_KEPT: ClassVar[int] = 32

    def __init__(self, total_length: float = 3.0, taper: float = 0.0, **options: Any) -> None:
        self.total_length, self.taper = total_length, taper
        self._waves: Recent[tuple[int, str, float, float], tuple[LinkChain, Gait, Trajectory, float]] = \
            Recent(self.WAVES_KEPT)
        super().__init__(**options)

    @override
    def decorate(self) -> None:
        _gait_and_motion_axes(self.axes, self.total_length, "the gait: one wave along the body",
                              "one cycle: start (faint) and end")

    @override
    def create(self) -> None:
        ax0, ax1 = self.axes
        self.lines = [ax0.plot([], [], color=c, lw=1.8)[0] for c in joint_colours(6)]
        self.names = _joint_names(ax0, 6)
        self.start = PartsArtist(ax1, facecolor=PALETTE["orange"], alpha=0.2, edgecolor="0.5")
        self.end = PartsArtist(ax1)
        self.trail = TrailArtist(ax1, color=PALETTE["green"])
        self.text = readout(ax1, 0.02, 0.02)

    def compute(self, links: int, physics: str, amplitude: float, lag: float) -> None:
        def make() -> tuple[LinkChain, Gait, Trajectory, float]:
            system = design_chain(links, physics, self.total_length, self.taper)
            gait = travelling_wave(system.n_shape, amplitude, lag)
            traj = trajectory(system, gait, n_frames=61, substeps=8)
            # g(T) of the trajectory drawn (within ~1e-9 of net_displacement's); 1024 samples of
            # the wave's path length agree with 4096 to ~1e-7 (the readout shows 4 decimals).
            # Every physics of design_chain has a cost metric (drag or kinetic energy).
            eff = efficiency(system, gait, check=False, samples=1024, displacement=traj.g[-1])
            return system, gait, traj, eff

        self.system, self.gait, self.traj, self.efficiency = self._waves.get(
            (links, physics, amplitude, lag), make)
        self.g = self.traj.g[-1]

    @override
    def set(self, links: int = 4, physics: str = "low_re", amplitude: float = 0.8, lag: float = 1.2) -> None:
        links = check_int(links, "links", minimum=2, maximum=7)
        physics = check_option(PHYSICS_LABELS.get(physics, physics), "physics", tuple(PHYSICS_LABELS.values()))
        self.compute(links, physics, float(amplitude), float(lag))
        t = self.traj.t
        for k, line in enumerate(self.lines):
            if k < self.system.n_shape:
                line.set_data(t, self.traj.r[:, k])
            else:
                line.set_data([], [])
        _show_joints(self.names, [self.lines], self.system.n_shape)
        self.start.set(self.system, self.traj.g[0], self.traj.r[0])
        self.end.set(self.system, self.g, self.traj.r[-1])
        self.trail.set(self.traj.g[:, :2])
        self.text.set_text(f"g(T) = ({signed(self.g)})\nefficiency {self.efficiency:.4f}")


class OptimalGaitScene(Scene):
    """A chain you design and its most efficient gait: joint angles against time and one cycle of motion.

    Values: ``links`` (3-6), ``physics``, ``taper`` (0 equal links; up to 0.6, the tail links
    shorter), ``order`` (Fourier harmonics per joint, 1 or 2). Each design starts from a
    travelling wave (:func:`gm_core.geometry.wave_start`, dashed); :meth:`optimize` runs
    :func:`gm_core.geometry.optimize_chain_gait` for the design shown (a second or so) and keeps
    the result, which is then drawn solid with the motion of one cycle (body at the start,
    faint, and at the end, with the path of the body frame). Option: ``total_length`` (3).
    """

    FIGSIZE = (8.4, 3.3)
    NCOLS = 2
    MAX_JOINTS: ClassVar[int] = 5

    def __init__(self, total_length: float = 3.0, **options: Any) -> None:
        self.total_length = total_length
        self._results: dict[tuple[int, str, float, int], OptimalGait] = {}
        super().__init__(**options)

    @override
    def decorate(self) -> None:
        _gait_and_motion_axes(self.axes, self.total_length, "the gait: start wave (dashed), best (solid)",
                              "one cycle of the start wave")

    @override
    def create(self) -> None:
        ax0, ax1 = self.axes
        colours = joint_colours(self.MAX_JOINTS)
        self.start_lines = [ax0.plot([], [], color=c, lw=1.0, ls="--", alpha=0.7)[0] for c in colours]
        self.best_lines = [ax0.plot([], [], color=c, lw=2.0)[0] for c in colours]
        self.names = _joint_names(ax0, self.MAX_JOINTS)
        self.first = PartsArtist(ax1, facecolor=PALETTE["orange"], alpha=0.2, edgecolor="0.5")
        self.last = PartsArtist(ax1)
        self.trail = TrailArtist(ax1, color=PALETTE["green"])
        self.text = readout(ax1, 0.02, 0.02)

    @staticmethod
    def _key(links: int, physics: str, taper: float, order: int) -> tuple[int, str, float, int]:
        return (int(links), physics, round(float(taper), 6), int(order))

    @override
    def set(self, links: int = 4, physics: str = "low_re", taper: float = 0.0, order: int = 1) -> None:
        links = check_int(links, "links", minimum=3, maximum=self.MAX_JOINTS + 1)
        physics = check_option(PHYSICS_LABELS.get(physics, physics), "physics", tuple(PHYSICS_LABELS.values()))
        order = check_int(order, "order", minimum=1, maximum=2)
        self.key = self._key(links, physics, taper, order)
        self.system = design_chain(links, physics, self.total_length, float(taper))
        self.start = wave_start(self.system.n_shape)
        self.result = self._results.get(self.key)
        gait = self.start if self.result is None else self.result.gait
        t = np.linspace(0, 2 * np.pi, 121)
        for lines, g in ((self.start_lines, self.start), (self.best_lines, None if self.result is None else gait)):
            r = None if g is None else g(t)
            for k, line in enumerate(lines):
                if r is not None and k < self.system.n_shape:
                    line.set_data(t, r[:, k])
                else:
                    line.set_data([], [])
        _show_joints(self.names, [self.start_lines, self.best_lines], self.system.n_shape)
        traj = trajectory(self.system, gait, n_frames=41, substeps=4)
        self.first.set(self.system, traj.g[0], traj.r[0])
        self.last.set(self.system, traj.g[-1], traj.r[-1])
        self.trail.set(traj.g[:, :2])
        gT = traj.g[-1]
        if self.result is None:
            self.start_efficiency = efficiency(self.system, self.start, check=False, samples=256, displacement=gT)
            self.axes[1].set_title("one cycle of the start wave", fontsize=9)
            self.text.set_text(f"start: efficiency {self.start_efficiency:.4f}\npress “optimise”")
        else:
            res = self.result
            best = cast(float, res.efficiency)    # optimize_chain_gait's objective: always set
            self.axes[1].set_title("one cycle of the best gait", fontsize=9)
            still = best < 1e-9
            self.text.set_text(f"best: efficiency {best:.4f} ({res.nit} steps)\n"
                               + ("no gait translates it: zero momentum\nkeeps its centre of mass still" if still else
                                  f"g(T) = ({signed(gT, 2)})"))

    def optimize(self, callback: Callable[[int, float], object] | None = None) -> OptimalGait:
        """Optimise the gait of the design shown (see :func:`gm_core.geometry.optimize_chain_gait`),
        keep the result for this design and draw it; ``callback(iteration, efficiency)`` reports
        progress. Returns the :class:`~gm_core.geometry.optimal.OptimalGait`."""
        links, physics, taper, order = self.key
        result = self._results[self.key] = optimize_chain_gait(self.system, order, start=self.start, callback=callback)
        self.set(links, physics, taper, order)
        return result                     # what set has just drawn (self.result)

    def animation(self, n_frames: int = 48, cycles: int = 2) -> tuple[FuncAnimation, Figure, Trajectory]:
        """The gait shown (the best one once found, else the start wave) as (anim, fig, traj):
        :func:`animate_chain_gait`."""
        gait = self.start if self.result is None else self.result.gait
        return animate_chain_gait(self.system, gait, n_frames=n_frames, cycles=cycles)


def animate_chain_gait(system: LocomotionSystem, gait: Gait, n_frames: int = 60, cycles: int = 2, interval: float = 60,
                       world_lim: float | None = None) -> tuple[FuncAnimation, Figure, Trajectory]:
    """The gait as a kernel-free animation: joint angles against time (with a cursor) and the body moving.

    Works for any number of joints. Returns (anim, fig, traj); play it with
    :func:`gm_core.drawing.toolkit.primitives.jshtml`.
    """
    traj = trajectory(system, gait, n_frames, cycles=cycles)
    fig, (ax0, ax1) = new_figure(1, 2, figsize=(8.4, 3.6))
    T = gait.period * cycles
    t = np.linspace(0, T, 400)
    r = gait(t)
    for k, colour in enumerate(joint_colours(system.n_shape)):
        ax0.plot(t, r[:, k], color=colour, lw=1.8, label=_joint_math(k))
    ax0.set_xlim(0, T)
    ax0.set_xlabel("t", fontsize=9, labelpad=0)
    ax0.set_ylabel("joint angles (rad)", fontsize=9, labelpad=0)
    ax0.legend(fontsize=MATH_PT, ncol=min(system.n_shape, 4), loc="upper right", frameon=False,
               handlelength=1.5, columnspacing=1.2)
    lo, hi = float(r.min()), float(r.max())
    ax0.set_ylim(lo - 0.15 * (hi - lo) - 0.1, hi + 0.45 * (hi - lo) + 0.1)
    cursor = ax0.axvline(0.0, color="0.3", lw=1)
    body = SystemArtist(ax1, system, traj.g[0], traj.r[0])
    trail = TrailArtist(ax1, color=PALETTE["green"])
    size = 0.55 * sum(getattr(system, "lengths", (getattr(system, "length", 1.0),)))
    lo2, hi2 = traj.g[:, :2].min(0) - 1.1 * size, traj.g[:, :2].max(0) + 1.1 * size
    c, half = (lo2 + hi2) / 2, max(hi2 - lo2) / 2 if world_lim is None else world_lim
    style_world_axes(ax1, half, c)
    ax1.set_title(system.name, fontsize=9)

    def update(k: int) -> list[Artist]:
        k = int(k)
        body.set(traj.g[k], traj.r[k])
        trail.set(traj.g[: k + 1, :2])
        cursor.set_xdata([traj.t[k], traj.t[k]])
        return []

    update(0)
    freeze_layout(fig)   # lay out once: every frame is drawn with the same axes (faster frames)
    # line art: frames in 256 colours (a third of the bytes, no visible change)
    return animate(fig, update, range(n_frames), interval=interval, palette=True), fig, traj


def links_comparison_figure(rows: Sequence[tuple[str, float, float]]) -> Figure:
    """Bars of efficiency and displacement per cycle for chains of different lengths.

    ``rows``: list of (label, efficiency, displacement). Returns the figure.
    """
    fig, (ax0, ax1) = new_figure(1, 2, figsize=(7.5, 2.9))
    labels = [r[0] for r in rows]
    x = np.arange(len(rows))
    for ax, vals, heading in ((ax0, [r[1] for r in rows], "efficiency (translation / path length)"),
                              (ax1, [r[2] for r in rows], "translation per cycle")):
        ax.bar(x, vals, color=PALETTE["blue"], width=0.6)
        for xi, v in zip(x, vals):
            ax.text(xi, v, f"{v:.3f}", ha="center", va="bottom", fontsize=9)
        ax.set_xticks(x, labels, fontsize=9)
        ax.set_ylim(0, 1.2 * max(vals))
        ax.set_title(heading, fontsize=9)
        ax.tick_params(labelsize=8)
    return fig


def continuum_figure(n_links: ArrayLike, errors: ArrayLike,
                     label: str = "largest difference of A, chain − body") -> Figure:
    """Log-log plot of the chain's error against the number of links, with the 1/N² slope for reference.

    Tick labels are plain numbers at the data (no mathtext powers, whose superscripts would be
    smaller than the figure standard's 10 px)."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator

    fig, ax = new_figure(1, 1, figsize=(4.6, 3.2))
    n_links, errors = np.asarray(n_links, float), np.asarray(errors, float)
    ax.loglog(n_links, errors, "o-", color=PALETTE["blue"], lw=1.8, label=label)
    ref = errors[0] * (n_links[0] / n_links) ** 2
    ax.loglog(n_links, ref, "--", color="0.4", lw=1.2, label="slope −2 (error ∝ 1/N²)")
    decades = 10.0 ** np.arange(np.floor(np.log10(min(errors.min(), ref.min()))),
                                np.ceil(np.log10(max(errors.max(), ref.max()))) + 1)
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    for axis, ticks in ((ax.xaxis, n_links), (ax.yaxis, decades)):
        axis.set_major_locator(FixedLocator(ticks))  # type: ignore[arg-type]  # an array, not the stub's Sequence
        axis.set_major_formatter(plain)
        axis.set_minor_locator(NullLocator())
    ax.set_xlabel("links N", fontsize=9, labelpad=0)
    ax.set_ylabel("error", fontsize=9, labelpad=0)
    ax.legend(fontsize=8, frameon=False)
    ax.tick_params(labelsize=8)
    ax.set_title("a chain sampling the curvature → the continuous body", fontsize=9)
    return fig
