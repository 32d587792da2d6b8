"""sysplotter's system library by its own names: ``load("three_link_lowRe")`` (numpy only).

sysplotter (OSU-LRAM/GeometricSystemPlotter, the MATLAB tool of the book's author's lab) ships
its systems as files ``sysf_<name>.m``. Each defines a locomotor by its geometry (link lengths,
rescaled to a body of total length 1; link shapes; shape modes; a base frame) and physics, and
returns its local connection ``s.A`` (the course's sign, xi = -A r_dot, (3.10)) and a cost
metric ``s.metric``. This module builds the same system from the course's own physics:

* :func:`names`: the files the catalog can load, in sysplotter's spelling;
* :func:`load`: the course's :class:`~gm_core.systems.LocomotionSystem` for a file, in the file's
  body frame and shape coordinates (its modes included);
* :func:`sysplotter_view`: ``(A, M)`` at a shape, as the file returns them: ``M`` with the file's
  own scaling, the identity where the file sets ``eye(n)``, ``None`` where it has no metric;
* :func:`sysplotter_files`: every one of sysplotter's files with how the catalog stands to it
  (the parity table: agrees, differs and why, or not in the catalog yet and why);
* :func:`passive_model`: for a file with spring/damper joints (``three_link_passive``), its
  :class:`~gm_core.systems.passive.PassiveJoints` with the file's joints, k and b;
* :func:`window_slice`: a file's system with two shape variables over the file's window (a slice
  through its straight shape if it has more), and :func:`tabulated`: the same connection as a stored
  table, interpolated (:data:`TABLE_RTOL`), for the systems too slow to compute live under a slider
  (:func:`tabulated_names`; the tables are made by ``tools/lab_tables.py``), as sysplotter itself
  tabulates A once on a grid and interpolates.

Where sysplotter is wrong the catalog gives the right value, never the defect. Two defects touch
the files loaded here. sysplotter's added mass of an ellipse (``Inertia_link.m``) lacks the factor
pi/8 of the rotational entry (the course's :func:`~gm_core.systems.fluids.ellipse_added_mass` has
it, and its panel method agrees), which changes every high-Reynolds file. Its change of body frame
for continuous backbones (``backbone_conversion.m``) is wrong for every frame but 'center', which
changes the continuous files in the 'tail' and 'com-mean' frames. ``tests/test_catalog.py`` shows
the catalog agrees with sysplotter run in Octave (``tools/sysplotter_reference.py``) to 1e-8 where
sysplotter computes in closed form and to the accuracy of its ode45 (:data:`CONTINUOUS_RTOL`,
:data:`CONTINUOUS_JUMP_RTOL`) where it integrates along a continuous body, and that with either
defect put back it reproduces sysplotter's numbers to the same tolerance. A third touches one file:
sysplotter's panel method for links whose flows interact (three_link_HighRe_panelMethod) is too coarse
and takes a wrong branch of an angle (:data:`PANEL_METHOD`); the catalog solves the coupled flow
(:class:`~gm_core.systems.panel_method.InteractingChain`) and, with sysplotter's method put back, agrees to 1e-8.

Continuous low-Re bodies (:class:`~gm_core.systems.SlenderBody`, length 1, drag coefficient 1,
drag ratio 2): sysplotter's arc length s in [-1/2, 1/2] is the course's s + 1/2 in [0, 1];
curvature modes (constant pieces, with panel edges at their jumps; centred waves) or a general
curvature (the triangle wave, amplitude and phase) as the file defines them.

The tape-measure swimmer (:class:`~gm_core.systems.TapeMeasure`, a floating looped chain): the model of
the file's own ``tapeMeasure_connectionAndMetric.m``, head frame, shape (alpha, L), with every derivative
in closed form where sysplotter takes central differences (step 1e-5) of the tip angle; the two agree to
1e-11 (within :data:`CLOSED_FORM_RTOL`).

Conventions read from sysplotter's ``N_link_chain.m`` and the files: joint angles ``alpha =
modes @ r``; base frames 'center' (the middle link, or for an even number of links the middle
joint halfway between its links: the course's ``"middle"``), 'com-mean' (the course's
``"com"``: equal links, so equal weights) and 'tail' (the centre of link 1); low-Re links of
drag diag(l, 2 l, 2 l^3 / 12); high-Re links as ellipses of semi-axes l / 2 and
``aspect_ratio`` l / 2 of density 1 in a fluid of density 1.
"""
from __future__ import annotations

import difflib
import json
import weakref
from collections.abc import Callable
from dataclasses import dataclass, replace
from importlib import resources
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups import SE2
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.diff_drive import DifferentialDrive
from gm_core.systems.kinematic_snake import KinematicSnake
from gm_core.systems.link_chain import LinkChain
from gm_core.systems.panel_method import InteractingChain
from gm_core.systems.passive import PassiveJoints
from gm_core.systems.reframed import body_jacobian
from gm_core.systems.restricted import AffineRestriction, shape_slice
from gm_core.systems.rotors import Rotors
from gm_core.systems.slender_body import GeneralCurvature, SlenderBody, segment_modes, wave_modes
from gm_core.systems.tabulated import TabulatedConnection
from gm_core.systems.tape_measure import TapeMeasure
from gm_core.validation import FloatArray, check_int

__all__ = ["SysplotterFile", "ParityRow", "names", "load", "sysplotter_view", "sysplotter_files", "reference", "parity", "passive_model",
           "with_sysplotter_added_mass", "with_sysplotter_frame_change", "with_sysplotter_panel_method", "CLOSED_FORM_RTOL", "CONTINUOUS_RTOL",
           "CONTINUOUS_JUMP_RTOL", "triangle_curvature", "amplitude_phase_curvature", "window_slice", "tabulated",
           "tabulated_names", "TABLE_RTOL", "TABLE_EXCLUDED", "TABLES"]

#: Relative agreement asked of the catalog where sysplotter computes in closed form (max |difference|
#: over max |sysplotter's value|, per file over its stored shapes).
CLOSED_FORM_RTOL = 1e-8

#: Relative agreement asked of the catalog's continuous bodies where sysplotter integrates along the body
#: with ode45 at its default tolerances (RelTol 1e-3, AbsTol 1e-6). Its integrals are nested (theta, then
#: the positions, then their Jacobian, then the drag, each an ode45 read back by interpolation), so its
#: values are that much less accurate: 2e-5 to 1.1e-2 over the stored shapes (the catalog's own values
#: converge to 1e-8 and better, tests/test_catalog.py).
CONTINUOUS_RTOL = 2e-2

#: The same where the curvature jumps inside one of sysplotter's integration intervals (constant-curvature
#: thirds and quarters: it breaks its integrals only at the middle): ode45 steps across the jump and the
#: positions are read back across the kink, which costs it 2 to 7 % here.
CONTINUOUS_JUMP_RTOL = 1e-1

#: The added-mass defect of sysplotter's ``Inertia_link.m``, in the words of the parity table.
PI_OVER_8 = ("sysplotter's rotational added mass of an ellipse (Inertia_link.m) lacks the factor pi/8; "
             "the catalog has it (with sysplotter's value put back, the two agree to 1e-8)")


@dataclass(frozen=True)
class SysplotterFile:
    """One of sysplotter's system files and how the catalog stands to it.

    ``metric`` is ``"physical"`` (the file's ``s.metric`` is the system's own cost metric, times
    ``metric_scale``), ``"identity"`` (the file sets ``eye(n)``) or ``"none"`` (no ``s.metric``).
    ``differs`` says why the catalog's value is not sysplotter's ("" where they agree);
    ``missing`` why the catalog cannot load the file yet ("" where it can); ``rtol`` how closely
    sysplotter's own values are computed (:data:`CLOSED_FORM_RTOL`, :data:`CONTINUOUS_RTOL` or
    :data:`CONTINUOUS_JUMP_RTOL`). ``passive`` (joint indices from 0), ``stiffness`` and ``damping``: the
    file's spring/damper joints (``s.physics.k``, ``s.physics.b``), whose model is
    :mod:`gm_core.systems.passive` (:func:`passive_model`); ``()`` where it has none.
    """

    name: str
    model: str
    grid_range: tuple[tuple[float, float], ...]
    build: Callable[[], LocomotionSystem] | None = None
    metric: str = "physical"
    metric_scale: float = 1.0
    differs: str = ""
    missing: str = ""
    rtol: float = CLOSED_FORM_RTOL
    passive: tuple[int, ...] = ()
    stiffness: float = 0.0
    damping: float = 0.0

    @property
    def loadable(self) -> bool:
        return self.build is not None


# -- the physics of sysplotter's chains, from the course's own -----------------------------------
def _lengths(n_links: int) -> tuple[float, ...]:
    return (1.0 / n_links,) * n_links


def _low_re(n_links: int, frame: str = "middle") -> LinkChain:
    return LinkChain(_lengths(n_links), "low_re", drag_ratio=2.0, frame=frame)


def _high_re(n_links: int, aspect_ratio: float = 0.1, frame: str = "middle") -> LinkChain:
    return LinkChain(_lengths(n_links), "high_re", aspect_ratio=1.0 / aspect_ratio, fluid_density=1.0,
                     body_density=1.0, frame=frame)


def _floating_ellipses(n_links: int, aspect_ratio: float) -> LinkChain:
    a = np.array(_lengths(n_links)) / 2
    b = aspect_ratio * a
    m = np.pi * a * b
    return LinkChain(_lengths(n_links), "floating", masses=m, inertias=m * (a ** 2 + b ** 2) / 4)


def _flapper(active: tuple[int, ...]) -> LinkChain:
    """Five ellipse links (ar 0.1), links marked 0 in ``active`` carrying nothing (sysplotter's activelinks)."""
    chain = _high_re(len(active))
    diag = np.array([np.diag(M) for M in chain.link_matrices()]) * np.array(active, dtype=float)[:, None]
    return LinkChain(chain.lengths, "high_re", aspect_ratio=10.0, body_density=1.0, link_diagonals=diag)


def _modal(chain: LinkChain, modes: ArrayLike, limits: tuple[tuple[float, float], ...], name: str) -> AffineRestriction:
    S = np.asarray(modes, dtype=float)
    return AffineRestriction(chain, S, shape_names=tuple(f"r{k + 1}" for k in range(S.shape[1])),
                             shape_limits=limits, name=name)


def block_modes(n_joints: int, n_modes: int, per_unit: float = 1 / 40) -> FloatArray:
    """sysplotter's constant-curvature blocks: mode k bends the k-th of ``n_modes`` equal runs of joints."""
    S = np.zeros((n_joints, n_modes))
    for i in range(n_joints):
        S[i, i * n_modes // n_joints] = per_unit
    return S


def serpenoid_joint_modes(n_links: int, waves: tuple[int, ...] = (1,)) -> FloatArray:
    """Joint i (1-based) = sum over waves w of r cos(2 pi w i / N) + r' sin(2 pi w i / N) (two_/four_mode_serpenoid)."""
    i = np.arange(1, n_links)[:, None] / n_links
    return np.hstack([np.hstack([np.cos(2 * np.pi * w * i), np.sin(2 * np.pi * w * i)]) for w in waves])


def _single_joint_modes(n_joints: int, joints: tuple[int, ...]) -> FloatArray:
    S = np.zeros((n_joints, len(joints)))
    for k, j in enumerate(joints):
        S[j, k] = 1.0
    return S


def _fish_tail_modes() -> FloatArray:
    """fishTail_HighRe_tapered: r1 the head joint (joint 20), r2 the amplitude of the tail's shape C (x - x^2/3)."""
    n_tail, n_head = 20, 10
    j = n_tail - 1
    C = (18 * j + 18) / (7 * j ** 2 + 8 * j)
    x = np.arange(1, n_tail) / n_tail
    S = np.zeros((n_tail + n_head - 1, 2))
    S[:j, 1] = C * (x - x ** 2 / 3)
    S[j, 0] = 1.0
    return S


def _box(half: float, n: int) -> tuple[tuple[float, float], ...]:
    return ((-half, half),) * n


def _chain_file(name: str, model: str, half: float, n: int, build: Callable[[], LocomotionSystem], **kw: Any) -> SysplotterFile:
    return SysplotterFile(name, model, _box(half, n), build, **kw)


# -- sysplotter's continuous bodies (s in [-1/2, 1/2] there, s' = s + 1/2 in [0, 1] here) -------------
_CONTINUOUS = "a continuous low-Re body (resistive force theory along a curvature-mode backbone)"

#: The frame-change defect of sysplotter's continuous backbones, in the words of the parity table.
FRAME_CHANGE = ("sysplotter's change of body frame for continuous backbones (backbone_conversion.m) is wrong for every "
                "frame but 'center' (it turns the points' velocities by the wrong angle); the catalog "
                "changes frame correctly: its metric is the centre frame's and A = Ad_{beta^-1} A_center - B_beta")

#: P(20) of sysplotter's triangle waves: the factor its polyfit gives the pinched sinusoid (shipped curv_triangle_*.m).
TRIANGLE_P20 = 3.581781447252943


def triangle_curvature(waves: int = 1) -> GeneralCurvature:
    """sysplotter's "triangle wave" of curvature: ``P amp sign(w) |w / amp|^20``, w = a1 cos(2 pi n u) + a2 sin(2 pi n u).

    u = s - 1/2 (sysplotter's arc length), n = ``waves``, amp = |(a1, a2)|, P = :data:`TRIANGLE_P20`
    (curv_triangle_wave_one_period.m / _two_periods.m). With q = w / amp: kappa = P amp q |q|^19 and
    d kappa / d a = P (20 |q|^19 (cos, sin) - 19 q |q|^19 a / amp). kappa is homogeneous of degree one
    in a, not differentiable at a = 0 (NaN there: a coordinate singularity, as in sysplotter).
    """
    k = 2 * np.pi * check_int(waves, "waves", minimum=1, maximum=100)

    def parts(s: FloatArray, a: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        c = np.stack([np.cos(k * (s - 0.5)), np.sin(k * (s - 0.5))], -1)           # (k, 2)
        amp = np.linalg.norm(a, axis=-1)[..., None]
        with np.errstate(invalid="ignore", divide="ignore"):
            q = (a @ c.T) / amp
        return c, amp, q, np.abs(q) ** 19

    def kappa(s: FloatArray, a: FloatArray) -> FloatArray:
        _, amp, q, q19 = parts(s, a)
        return TRIANGLE_P20 * amp * q * q19

    def dkappa(s: FloatArray, a: FloatArray) -> FloatArray:
        c, amp, q, q19 = parts(s, a)
        with np.errstate(invalid="ignore", divide="ignore"):
            return TRIANGLE_P20 * (20 * q19[..., None] * c - 19 * (q * q19)[..., None] * (a / amp)[..., None, :])

    return GeneralCurvature(kappa, dkappa, ("a1", "a2"), f"triangle wave of curvature, {waves} wave(s)")


def amplitude_phase_curvature(waves: int = 2) -> GeneralCurvature:
    """sysplotter's amplitude-phase serpenoid: ``kappa = A cos(phi - 2 pi n u)``, u = s - 1/2, n = ``waves``.

    d kappa / d(A, phi) = (cos(phi - 2 pi n u), -A sin(phi - 2 pi n u)) (curv_AmpPhase_wave_two_period.m).
    """
    k = 2 * np.pi * check_int(waves, "waves", minimum=1, maximum=100)

    def kappa(s: FloatArray, r: FloatArray) -> FloatArray:
        return r[..., :1] * np.cos(r[..., 1:] - k * (s - 0.5))

    def dkappa(s: FloatArray, r: FloatArray) -> FloatArray:
        arg = r[..., 1:] - k * (s - 0.5)
        return np.stack([np.cos(arg), -r[..., :1] * np.sin(arg)], -1)

    return GeneralCurvature(kappa, dkappa, ("A", "phi"), f"amplitude and phase of a serpenoid of {waves} waves")


def _continuous(curvature: Any, frame: str, half: float, breaks: tuple[float, ...] = (),
                integrals: Any = None) -> SlenderBody:
    """sysplotter's continuous low-Re body: length 1, drag coefficient 1, drag ratio 2, Gauss panels at its jumps."""
    n = curvature.n_shape if isinstance(curvature, GeneralCurvature) else len(curvature)
    return SlenderBody(1.0, curvature, integrals=integrals, breaks=breaks, drag_ratio=2.0, frame=frame, panels=16,
                       order=12, shape_limits=_box(half, n))


def _segments(pieces: int, frame: str, half: float) -> SlenderBody:
    modes, integrals, breaks = segment_modes(np.linspace(0.0, 1.0, pieces + 1))
    return _continuous(modes, frame, half, breaks, integrals)


def _waves(waves: tuple[int, ...], scaled: bool, frame: str, half: float) -> SlenderBody:
    modes, integrals = wave_modes(waves, 1.0, scaled=scaled)
    return _continuous(modes, frame, half, integrals=integrals)


class _SysplotterFrameChange(SlenderBody):
    """A continuous body of the catalog with sysplotter's frame change put back (its backbone_conversion.m).

    sysplotter gives the body velocity of the point s, relative to the new frame beta (h = beta^-1 h_orig),
    as ``Ad_{h^-1} xi + T_h L_{h^-1} T_e L_beta (J_orig - Ad_{h^-1} B_beta) r_dot`` = ``Ad_{h^-1} xi +
    R(2 theta_beta - theta_orig) (J_orig - Ad_{h^-1} B_beta) r_dot`` (J_orig = d h_orig / dr, a coordinate
    derivative; B_beta the body Jacobian of beta, its J_zero) where the right one is ``Ad_{h^-1} xi +
    R(-theta_orig) J_orig r_dot - Ad_{h^-1} B_beta r_dot``. The drag matrix is
    ``int U^T diag(1, k) U ds`` with U the (x, y) rows of that map from (xi, r_dot), in the point's frame.
    ``right=True`` gives the right one: a second route to :meth:`SlenderBody.metric` (tested). Only for
    showing the defect is the whole difference (:func:`parity`, the tests); never use it for physics.
    """

    def __init__(self, body: SlenderBody, right: bool = False) -> None:
        modes = "serpenoid" if body.mode_names == ("cos", "sin") else body.general or body.modes
        super().__init__(body.length, modes, integrals=None if modes == "serpenoid" else body.integrals,
                         breaks=body.breaks, drag_ratio=body.drag_ratio, frame=body.frame, panels=body.panels,
                         order=body.order, segments=body.segments, mean_points=body.mean_points,
                         shape_limits=body.shape_limits)
        self.right = right
        self.name = f"{body.name} with sysplotter's frame change" if not right else body.name

    def metric(self, r: ArrayLike) -> FloatArray:
        r = self._shape(r)
        _, w, h_orig, J_orig = self.quadrature_poses(r)
        beta, dbeta = self.frame_pose(r)
        h = SE2.compose(SE2.inverse(beta)[..., None, :], h_orig)                  # (..., Q, 3)
        Ad_inv = SE2.Ad(SE2.inverse(h))                                         # (..., Q, 3, 3)
        def rotate(M: FloatArray, angle: FloatArray) -> FloatArray:            # R(-angle) on the (x, y) rows
            c, s = np.cos(angle)[..., None], np.sin(angle)[..., None]
            return np.stack([c * M[..., 0, :] + s * M[..., 1, :], -s * M[..., 0, :] + c * M[..., 1, :]], -2)

        shift = Ad_inv @ body_jacobian(beta, dbeta)[..., None, :, :]            # Ad_{h^-1} B_beta (..., Q, 3, n)
        if self.right:
            shape_part = rotate(J_orig, h_orig[..., 2]) - shift[..., :2, :]
        else:
            shape_part = rotate(J_orig - shift, h_orig[..., 2] - 2 * beta[..., None, 2])
        U = np.concatenate([Ad_inv[..., :2, :], shape_part], -1)                # (..., Q, 2, 3 + n)
        K = np.array([1.0, self.drag_ratio])[:, None]
        return np.einsum("q,...qai,...qaj->...ij", w, U, K * U)


def with_sysplotter_frame_change(system: LocomotionSystem) -> LocomotionSystem:
    """A continuous body of the catalog in a frame other than 'center', with sysplotter's frame change put back.

    See :data:`FRAME_CHANGE`; only for showing that this is the whole difference between the two
    (:func:`parity`, the tests); never use it for physics.
    """
    if not isinstance(system, SlenderBody) or system.frame == "middle":
        raise TypeError(f"system must be a continuous body of the catalog in a frame other than the middle; got {system!r:.80}")
    return _SysplotterFrameChange(system)


def _continuous_files() -> list[SysplotterFile]:
    """The nine continuous low-Re files; sysplotter's 'center' is "middle", 'tail' the end s = -1/2, 'com-mean' the
    plain mean of x, y, theta over linspace(-1/2, 1/2, 100)."""
    c = _CONTINUOUS
    files = [
        _chain_file("constantcurv2_lowRe", c + ": two constant-curvature halves", 5, 2, lambda: _segments(2, "middle", 5)),
        _chain_file("constantcurv3_lowRe", c + ": three constant-curvature thirds, tail frame", 5, 3,
                    lambda: _segments(3, "tail", 5), differs=FRAME_CHANGE),
        _chain_file("constantcurv4_lowRe", c + ": four constant-curvature quarters", 6, 4, lambda: _segments(4, "middle", 6)),
        _chain_file("serpenoid_lowRe", c + ": serpenoid, mean of 100 points' poses", 12, 2,
                    lambda: _waves((1,), True, "com-mean", 12), differs=FRAME_CHANGE),
        _chain_file("serpenoid_lowRe_hf", c + ": serpenoid of two waves, mean of 100 points' poses", 12, 2,
                    lambda: _waves((2,), True, "com-mean", 12), differs=FRAME_CHANGE),
        _chain_file("serpenoid4_lowRe", c + ": serpenoid of one and two waves", 12, 4,
                    lambda: _waves((1, 2), False, "middle", 12)),
        _chain_file("serpenoid_lowRe_hf_AmpPhase", c + ": serpenoid of two waves in amplitude and phase, mean of 100 "
                    "points' poses", 12, 2, lambda: _continuous(amplitude_phase_curvature(2), "com-mean", 12),
                    differs=FRAME_CHANGE),
        _chain_file("triangle_lowRe", c + ": a triangle wave of curvature", 12, 2,
                    lambda: _continuous(triangle_curvature(1), "middle", 12)),
        _chain_file("triangle_lowRe_two_waves", c + ": a triangle wave of two periods", 12, 2,
                    lambda: _continuous(triangle_curvature(2), "middle", 12)),
    ]
    jumps = {"constantcurv3_lowRe", "constantcurv4_lowRe"}      # constantcurv2 jumps at the middle, where sysplotter breaks
    return [replace(f, rtol=CONTINUOUS_JUMP_RTOL if f.name in jumps else CONTINUOUS_RTOL) for f in files]


def _files() -> dict[str, SysplotterFile]:
    third = 2 * np.pi / 3
    files = [
        _chain_file("three_link_lowRe", "low-Re links, 3 equal", 2.5, 2, lambda: _low_re(3)),
        _chain_file("three_link_lowRe_CoM", "low-Re links, 3 equal, centre of mass", 2.5, 2, lambda: _low_re(3, "com")),
        _chain_file("four_link_lowRe", "low-Re links, 4 equal", 2.5, 3, lambda: _low_re(4)),
        _chain_file("five_link_lowRe", "low-Re links, 5 equal", 2.5, 4, lambda: _low_re(5)),
        _chain_file("nine_link_lowRe_trigmodes", "low-Re links, 9 equal, two trigonometric modes, tail frame", 2.5, 2,
                    lambda: _modal(_low_re(9, "tail"), _trig_modes(), _box(2.5, 2), "nine_link_lowRe_trigmodes"),
                    metric="none"),
        _chain_file("three_link_lowRe_CSmodes", "low-Re links, 3 equal, modes [1 1; 1 -1]", 2.5, 2,
                    lambda: _modal(_low_re(3), [[1, 1], [1, -1]], _box(2.5, 2), "three_link_lowRe_CSmodes")),
        _chain_file("four_link_lowRe_CSmodes", "low-Re links, 4 equal, modes [1 1; 1 0; 1 -1]", 2.5, 2,
                    lambda: _modal(_low_re(4), [[1, 1], [1, 0], [1, -1]], _box(2.5, 2), "four_link_lowRe_CSmodes")),
        _chain_file("three_link_HighRe", "high-Re ellipses (ar 0.1), 3 equal, centre of mass", third, 2,
                    lambda: _high_re(3, frame="com"), differs=PI_OVER_8),
        _chain_file("four_link_HighRe", "high-Re ellipses (ar 0.1), 4 equal", third, 3, lambda: _high_re(4), differs=PI_OVER_8),
        _chain_file("five_link_HighRe", "high-Re ellipses (ar 0.1), 5 equal", third, 4, lambda: _high_re(5), differs=PI_OVER_8),
        _chain_file("six_link_HighRe", "high-Re ellipses (ar 0.1), 6 equal", third, 5, lambda: _high_re(6), differs=PI_OVER_8),
        _chain_file("seven_link_HighRe", "high-Re ellipses (ar 0.1), 7 equal", third, 6, lambda: _high_re(7), differs=PI_OVER_8),
        _chain_file("three_link_floating_ellipse", "floating ellipses (ar 0.01), 3 equal", third, 2,
                    lambda: _floating_ellipses(3, 0.01)),
        _chain_file("four_link_floating_ellipse", "floating ellipses (ar 0.01), 4 equal", third, 3,
                    lambda: _floating_ellipses(4, 0.01)),
        _chain_file("two_mode_CC", "high-Re ellipses, 21 links, 2 constant-curvature blocks", 15, 2,
                    lambda: _modal(_high_re(21), block_modes(20, 2), _box(15, 2), "two_mode_CC"), differs=PI_OVER_8),
        _chain_file("three_mode_CC", "high-Re ellipses, 19 links, 3 constant-curvature blocks", 20, 3,
                    lambda: _modal(_high_re(19), block_modes(18, 3), _box(20, 3), "three_mode_CC"), differs=PI_OVER_8),
        _chain_file("four_mode_CC", "high-Re ellipses, 21 links, 4 constant-curvature blocks", 20, 4,
                    lambda: _modal(_high_re(21), block_modes(20, 4), _box(20, 4), "four_mode_CC"), differs=PI_OVER_8),
        _chain_file("five_mode_CC", "high-Re ellipses, 21 links, 5 constant-curvature blocks", 20, 5,
                    lambda: _modal(_high_re(21), block_modes(20, 5), _box(20, 5), "five_mode_CC"), differs=PI_OVER_8),
        _chain_file("two_mode_serpenoid", "high-Re ellipses, 20 links, serpenoid modes", 0.5, 2,
                    lambda: _modal(_high_re(20), serpenoid_joint_modes(20), _box(0.5, 2), "two_mode_serpenoid"),
                    differs=PI_OVER_8),
        _chain_file("four_mode_serpenoid", "high-Re ellipses, 20 links, serpenoid modes of 1 and 2 waves", 0.5, 4,
                    lambda: _modal(_high_re(20), serpenoid_joint_modes(20, (1, 2)), _box(0.5, 4), "four_mode_serpenoid"),
                    differs=PI_OVER_8),
        _chain_file("three_link_passive", "high-Re ellipses (ar 0.1), 3 equal; s.A as three_link_HighRe's, joint 1 "
                    "a spring/damper (k 0.074, b 0.01): gm_core.systems.passive", np.pi, 2,
                    lambda: _high_re(3), differs=PI_OVER_8, passive=(0,), stiffness=0.074, damping=0.01),
        _chain_file("three_link_HighRe_30multiEllipses", "high-Re: 3 rigid links each of 10 ellipses (30, ar 0.1)", third, 2,
                    lambda: _modal(_high_re(30), _single_joint_modes(29, (9, 19)), _box(third, 2),
                                   "three_link_HighRe_30multiEllipses"), metric_scale=10.0, differs=PI_OVER_8),
        _chain_file("fishTail_HighRe_tapered", "high-Re ellipses, 30 links: head joint and a tail mode", np.pi, 2,
                    lambda: _modal(_high_re(30), _fish_tail_modes(), _box(np.pi, 2), "fishTail_HighRe_tapered"),
                    metric_scale=10.0, differs=PI_OVER_8),
        _chain_file("flapper_highRe", "high-Re ellipses, 5 links, links 2 and 4 inert, 2 modes", 2.0, 2,
                    lambda: _modal(_flapper((1, 0, 1, 0, 1)), [[1, 0], [0, 1], [0, 1], [1, 0]], _box(2.0, 2), "flapper_highRe"),
                    differs=PI_OVER_8),
        _chain_file("flapper_noModes", "high-Re ellipses, 5 links", 2.0, 4, lambda: _high_re(5), metric="identity",
                    differs=PI_OVER_8),
        _chain_file("diffdrive", "differential-drive car (wheel radius 2, half-axle 1)", 2.5, 2,
                    lambda: DifferentialDrive(wheel_radius=2.0, half_width=1.0), metric="none"),
        _chain_file("three_link_granular", "three links in granular media: a measured 21 x 21 table, symmetry-averaged",
                    2.5, 2, _granular, metric="none"),
        _chain_file("twin_rotor", "a body in space (SO(3)) with two rotors on one axis, opposite ways, J / I = 1", 2.5, 2,
                    lambda: Rotors(((0, 0, 1), (0, 0, -1)), (1.0, 1.0), np.eye(3), name="twin_rotor"), metric="none"),
        _chain_file("three_link_kinematic", "three links on wheels (kinematic snake), 3 equal", np.pi / 2, 2,
                    lambda: KinematicSnake((1 / 3,) * 3), metric="none"),
        *_continuous_files(),
        _chain_file("three_link_HighRe_panelMethod", "high-Re ellipses (ar 0.1) with gaps, added mass coupled through the flow",
                    2.5, 2, _panel_chain, metric="identity", differs=PANEL_METHOD),
        *_tape_measure_files(),
    ]
    return {f.name: f for f in files}


#: Panels per ellipse of the catalog's panel-method file: the connection converges at first order in the
#: panel count, to about 2e-3 (relative) at 200 (tests/test_catalog.py).
PANELS = 200

#: sysplotter's panel method (getAddedMass_NLinkChain.m), in the words of the parity table.
PANEL_METHOD = ("sysplotter's panel method (getAddedMass_NLinkChain.m) uses 10 panels per ellipse and atan for the angle a "
                "panel subtends, which there gives a negative added mass (-0.011 pi rho a^2 across a lone link instead of "
                "pi rho a^2), and lumps the links' interaction onto each link; the catalog solves the coupled flow with "
                f"{PANELS} panels per ellipse (with sysplotter's method put back, the two agree to 1e-8)")


def _panel_chain(panels: int = PANELS, model: str = "coupled") -> InteractingChain:
    """three_link_HighRe_panelMethod: 3 ellipses (ar 0.1) with gaps 0.1, lengths over the total 3.2, densities 1."""
    return InteractingChain((1 / 3.2,) * 3, aspect_ratio=10.0, separation=0.1 / 3.2, body_density=1.0, panels=panels,
                            model=model)


def with_sysplotter_panel_method(system: LocomotionSystem) -> LocomotionSystem:
    """The catalog's panel-method chain with sysplotter's own method put back (10 panels, atan, lumped links).

    See :data:`PANEL_METHOD`; only for showing that this is the whole difference between the two
    (:func:`parity`, the tests); never use it for physics.
    """
    if not isinstance(system, InteractingChain):
        raise TypeError(f"system must be the catalog's panel-method chain (an InteractingChain); got {system!r:.80}")
    return system.with_model("sysplotter", panels=10)


def _tape_measure_files() -> list[SysplotterFile]:
    """The symmetric tape measure (sysf_symmetricTapeMeasure.m, tapeMeasure_connectionAndMetric.m) with the file's
    parameters, its metric twice the kinetic energy (:meth:`TapeMeasure.shape_metric`); the asymmetric one
    (sysf_asymmetricTapeMeasure.m, which sysplotter cannot evaluate) built from the same model, an angle per tape."""
    symmetric = SysplotterFile(
        "symmetricTapeMeasure", "a floating looped chain (tape-measure swimmer): head 0.25 (I 1), two tapes of length 1 "
        "buckled into two segments each, added mass rates 1 and 1/8", ((0.0, np.pi / 2), (0.24 / 0.56, 0.45 / 0.56)),
        lambda: TapeMeasure(1.0, head_mass=0.25, head_inertia=1.0, mass_rate=0.001, rotational_inertia_rate=0.01,
                            added_mass_rate=1.0, added_rotational_inertia_rate=1 / 8, name="symmetricTapeMeasure"))
    asymmetric = SysplotterFile(
        "asymmetricTapeMeasure", "the symmetric tape measure's model with an angle per tape (alpha1, alpha2, L): head 0.25 "
        "(I 1), tapes of length 1, added mass rates 0.2 and 5.9", ((0.0, np.pi / 3), (0.0, np.pi / 3), (24 / 56, 45 / 56)),
        lambda: TapeMeasure(1.0, symmetric=False, head_mass=0.25, head_inertia=1.0, mass_rate=0.001,
                            rotational_inertia_rate=1 / 15, added_mass_rate=0.2, added_rotational_inertia_rate=5.9,
                            name="asymmetricTapeMeasure"),
        differs="sysplotter cannot evaluate this file (asymTapeMeasure_localConnection and asymTapeMeasure_metric exist "
                "nowhere in its repository); the catalog builds it from the symmetric tape measure's model "
                "(tapeMeasure_connectionAndMetric.m) with each tape opened by its own angle and the file's rates "
                "(its fluid_density 1000 enters nothing, as in the symmetric file)")
    return [symmetric, asymmetric]


def _not_yet() -> dict[str, SysplotterFile]:
    """The files the catalog cannot load yet, each with what it needs (none: every file of sysplotter loads)."""
    files: list[SysplotterFile] = []
    return {f.name: f for f in files}


def _granular() -> TabulatedConnection:
    """sysplotter's granular three-link swimmer: its table (stored as sysplotter_granular.json by
    tools/sysplotter_reference.py), x and y rows times the length scale 1/3, negated (the file's
    ``A = -...``), averaged over the three-link symmetries (its four_way_symmetry '3link')."""
    data = json.loads(resources.files("gm_core.systems").joinpath("sysplotter_granular.json").read_text())
    scale = np.array([1 / 3, 1 / 3, 1.0])[:, None, None, None]
    T = np.array([[data["Ax1"], data["Ax2"]], [data["Ay1"], data["Ay2"]], [data["Atheta1"], data["Atheta2"]]])
    return TabulatedConnection((data["alpha1"], data["alpha2"]), -scale * T, symmetry="three link",
                               body=_low_re(3), name="three_link_granular")


def _trig_modes() -> FloatArray:
    i = np.arange(1, 9)[:, None] / 8
    return np.hstack([np.sin(2 * np.pi * i), np.cos(2 * np.pi * i)])


_FILES: dict[str, SysplotterFile] | None = None
_LOADED: weakref.WeakKeyDictionary[LocomotionSystem, SysplotterFile] = weakref.WeakKeyDictionary()


def sysplotter_files() -> dict[str, SysplotterFile]:
    """Every file of sysplotter's system library by name, loadable or not (the parity table)."""
    global _FILES
    if _FILES is None:
        _FILES = dict(sorted({**_files(), **_not_yet()}.items(), key=lambda kv: kv[0].lower()))
    return _FILES


def names() -> tuple[str, ...]:
    """The names (sysplotter's file names without ``sysf_`` and ``.m``) that :func:`load` accepts."""
    return tuple(n for n, f in sysplotter_files().items() if f.loadable)


def load(name: str) -> LocomotionSystem:
    """The course's system for sysplotter's file ``sysf_<name>.m``, in the file's frame and shape coordinates."""
    if not isinstance(name, str):
        raise TypeError(f"name must be a sysplotter system name (a str, e.g. 'three_link_lowRe'); got {type(name).__name__}")
    files = sysplotter_files()
    entry = files.get(name.removeprefix("sysf_").removesuffix(".m"))
    if entry is None:
        near = difflib.get_close_matches(name, list(files), n=3)
        hint = f"; did you mean {' or '.join(repr(n) for n in near)}?" if near else "; gm_core.systems.catalog.names() lists them"
        raise ValueError(f"name {name!r} is not one of sysplotter's system files{hint}")
    if entry.build is None:
        raise ValueError(f"name {name!r}: the catalog cannot load this file yet: {entry.missing}")
    system = entry.build()
    _LOADED[system] = entry
    return system


def sysplotter_view(system: LocomotionSystem, shape: ArrayLike) -> tuple[FloatArray, FloatArray | None]:
    """``(A, M)`` at ``shape`` as sysplotter's file returns ``s.A`` and ``s.metric`` (corrected physics).

    ``system`` must come from :func:`load`. ``A`` is the connection (..., 3, n) (xi = -A r_dot, the
    file's frame and shape coordinates); ``M`` the file's metric (..., n, n): the system's own cost
    metric times the file's scale, the identity where the file sets ``eye(n)``, or ``None``.
    """
    entry = _LOADED.get(system) if isinstance(system, LocomotionSystem) else None
    if entry is None:
        raise TypeError(f"system must be a system made by gm_core.systems.catalog.load(name); got {system!r:.80}")
    A = system.connection(shape)
    if entry.metric == "none":
        return A, None
    if entry.metric == "identity":
        return A, np.broadcast_to(np.eye(system.n_shape), A.shape[:-2] + (system.n_shape,) * 2).copy()
    return A, entry.metric_scale * system.shape_metric(shape)


def passive_model(name: str) -> PassiveJoints:
    """The passive-joint model of sysplotter's file ``name``: its system with the file's spring/damper joints.

    ``PassiveJoints(load(name), passive, stiffness, damping)`` with the file's joints, ``s.physics.k`` and
    ``s.physics.b`` (:mod:`gm_core.systems.passive`; sysplotter's ``simulate2DPassiveSwimmer.m``).
    ValueError for a file without passive joints.
    """
    system = load(name)
    entry = _LOADED[system]
    if not entry.passive:
        with_joints = [n for n, f in sysplotter_files().items() if f.passive]
        raise ValueError(f"name {name!r} has no passive joints; the files with them are {', '.join(with_joints)}")
    return PassiveJoints(system, entry.passive, entry.stiffness, entry.damping)


def with_sysplotter_added_mass(system: LocomotionSystem) -> LocomotionSystem:
    """A high-Re system of the catalog with sysplotter's rotational added mass rho (a^2 - b^2)^2 put back.

    sysplotter's ``Inertia_link.m`` lacks the factor pi/8 of :func:`~gm_core.systems.fluids.ellipse_added_mass`;
    everything else is the course's. Only for showing that this factor is the whole difference
    between the two (:func:`parity`, the tests); never use it for physics.
    """
    chain = system.base_system if isinstance(system, AffineRestriction) else system
    if not isinstance(chain, LinkChain) or chain.physics != "high_re":
        raise TypeError(f"system must be a high-Re chain of the catalog (or its modes); got {system!r:.80}")
    d = np.array([np.diag(M) for M in chain.link_matrices()])
    for i, (a, b) in enumerate(chain.semi_axes()):
        if d[i].any():          # links that carry nothing (sysplotter's inactive links) stay zero
            d[i, 2] += chain.fluid_density * (a ** 2 - b ** 2) ** 2 * (1 - np.pi / 8)
    new = LinkChain(chain.lengths, "high_re", aspect_ratio=chain.aspect_ratio, fluid_density=chain.fluid_density,
                    body_density=chain.body_density, link_diagonals=d, frame=chain.frame)
    if isinstance(system, AffineRestriction):
        return AffineRestriction(new, system.matrix, system.offset, shape_names=system.shape_names,
                                 shape_limits=system.shape_limits, name=system.name)
    return new


_REFERENCE: dict[str, Any] | None = None


def reference(name: str | None = None) -> dict[str, Any]:
    """sysplotter's own values, run in GNU Octave by ``tools/sysplotter_reference.py``.

    Without ``name`` the whole record (``sysplotter_commit``, ``octave``, ``files``); with it, that
    file's entry: ``shapes`` (k, n), ``A`` (k, 3, n), ``metric`` (k, n, n) or None, as numpy arrays,
    and ``error`` ("" unless Octave could not evaluate the file).
    """
    global _REFERENCE
    if _REFERENCE is None:
        text = resources.files("gm_core.systems").joinpath("sysplotter_reference.json").read_text()
        _REFERENCE = json.loads(text)
    if name is None:
        return _REFERENCE
    files = _REFERENCE["files"]
    if name not in files:
        raise ValueError(f"name {name!r} has no stored sysplotter values; the files are {', '.join(files)}")
    raw = files[name]
    out = {"error": raw.get("error", ""), "display_name": raw.get("display_name", "")}
    if not out["error"]:
        n = len(raw["shapes"][0])
        out["shapes"] = np.array(raw["shapes"], dtype=float).reshape(-1, n)
        out["A"] = np.array(raw["A"], dtype=float).reshape(-1, 3, n)
        out["metric"] = None if raw["metric"] is None else np.array(raw["metric"], dtype=float).reshape(-1, n, n)
    return out


@dataclass(frozen=True)
class ParityRow:
    """One line of the parity table: the catalog against sysplotter's stored values for one file.

    ``A_difference`` and ``M_difference``: max |catalog - sysplotter| / max |sysplotter| over the
    stored shapes (NaN where there is nothing to compare), to be read against the file's ``rtol``;
    ``status`` one of "agrees", "corrected" (sysplotter is wrong; ``as_sysplotter`` is the
    difference once sysplotter's defect, the pi/8 or the frame change, is put back into the
    catalog), "not in the catalog" or "sysplotter cannot run it".
    """

    name: str
    model: str
    status: str
    A_difference: float
    M_difference: float
    as_sysplotter: float
    reason: str
    rtol: float = CLOSED_FORM_RTOL


def _relative(mine: FloatArray | None, theirs: FloatArray | None) -> float:
    if mine is None or theirs is None:
        return 0.0 if mine is None and theirs is None else float("inf")
    scale = float(np.abs(theirs).max())
    return float(np.abs(mine - theirs).max() / scale) if scale > 0 else float(np.abs(mine).max())


def _compare(system: LocomotionSystem, entry: SysplotterFile, ref: dict[str, Any]) -> tuple[float, float]:
    _LOADED[system] = entry
    views = [sysplotter_view(system, r) for r in ref["shapes"]]
    A = np.stack([v[0] for v in views])
    metrics = [v[1] for v in views if v[1] is not None]
    M = np.stack(metrics) if metrics else None
    return _relative(A, ref["A"]), _relative(M, ref["metric"])


def parity(name: str | None = None) -> list[ParityRow]:
    """The parity table: every sysplotter file (or only ``name``) against sysplotter's stored values."""
    files = sysplotter_files()
    rows = []
    for entry in files.values() if name is None else [files[name]] if name in files else []:
        ref = reference(entry.name) if entry.name in reference()["files"] else {"error": "no stored values"}
        nan = float("nan")
        if entry.build is None:
            status = "sysplotter cannot run it" if ref["error"] and "undefined" in ref["error"] else "not in the catalog"
            rows.append(ParityRow(entry.name, entry.model, status, nan, nan, nan, entry.missing))
            continue
        if ref["error"]:
            rows.append(ParityRow(entry.name, entry.model, "sysplotter cannot run it", nan, nan, nan, entry.differs or ref["error"]))
            continue
        system = entry.build()
        dA, dM = _compare(system, entry, ref)
        if entry.differs:
            with_defect = {FRAME_CHANGE: with_sysplotter_frame_change,
                           PANEL_METHOD: with_sysplotter_panel_method}.get(entry.differs, with_sysplotter_added_mass)
            back = _compare(with_defect(system), entry, ref)
            rows.append(ParityRow(entry.name, entry.model, "corrected", dA, dM, max(back), entry.differs, entry.rtol))
        else:
            rows.append(ParityRow(entry.name, entry.model, "agrees", dA, dM, max(dA, dM), "", entry.rtol))
    if name is not None and not rows:
        raise ValueError(f"name {name!r} is not one of sysplotter's system files")
    return rows


# -- stored tables: sysplotter's grid of A, interpolated -------------------------------------------
#: Agreement of a stored table (:func:`tabulated`) with the live system: max |table - live| over
#: max |live| of the connection, over the file's window (tests/test_catalog_lab.py checks it at a few shapes).
TABLE_RTOL = 2e-3

#: Radius of a disc around the straight shape, per file, left out of :data:`TABLE_RTOL`: the triangle
#: waves' connection has no limit there (it depends on the direction of approach; the live system is
#: NaN at the straight shape), which no interpolation follows; their tables differ by up to 8 % inside it.
TABLE_EXCLUDED = {"triangle_lowRe": 1.5, "triangle_lowRe_two_waves": 1.5}

#: The package file of the stored tables (written by tools/lab_tables.py).
TABLES = "lab_tables.npz"

_TABLES: dict[str, FloatArray] | None = None


def window_slice(name: str) -> LocomotionSystem:
    """File ``name``'s system with two shape variables over the file's window (its ``grid_range``).

    A system with more shape variables is seen on the slice along its first two through its straight
    shape (zeros; a variable whose window excludes 0 is held at the window's nearest edge, as the
    asymmetric tape measure's length); a system of two is itself, with the window as its limits.
    """
    system = load(name)
    window = sysplotter_files()[name].grid_range
    if system.n_shape > 2:
        through = np.clip(np.zeros(system.n_shape), [w[0] for w in window], [w[1] for w in window])
        return shape_slice(system, through, (0, 1), limits=window[:2])
    return AffineRestriction(system, np.eye(2), shape_names=system.shape_names, shape_limits=window[:2], name=system.name)


def _stored_tables() -> dict[str, FloatArray]:
    global _TABLES
    if _TABLES is None:
        with resources.files("gm_core.systems").joinpath(TABLES).open("rb") as f, np.load(f) as data:
            _TABLES = {k: np.asarray(data[k], dtype=float) for k in data.files}
    return _TABLES


def tabulated_names() -> tuple[str, ...]:
    """The files with a stored table of A (:func:`tabulated`), in the catalog's order."""
    return tuple(n for n in names() if n in _stored_tables())


def tabulated(name: str) -> TabulatedConnection:
    """File ``name``'s connection on :func:`window_slice` as its stored table, bicubically interpolated.

    The table holds A (3, 2, n1, n2) at the nodes of a grid spanning the file's window (stored as
    ``name``, ``name/alpha1`` and ``name/alpha2``); it agrees with the live system to :data:`TABLE_RTOL`
    (but near the triangle waves' straight shape, :data:`TABLE_EXCLUDED`), and outside the window it
    is undefined (NaN, singular). ``body`` is the live :func:`window_slice`, for drawing the body at a shape.
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a sysplotter system name (a str); got {type(name).__name__}")
    tables = _stored_tables()
    if name not in tables:
        raise ValueError(f"name {name!r} has no stored table; tabulated_names() lists them ({', '.join(tabulated_names())})")
    axes = (tables[f"{name}/alpha1"], tables[f"{name}/alpha2"])
    return TabulatedConnection(axes, tables[name], method="cubic", body=window_slice(name), name=name)
