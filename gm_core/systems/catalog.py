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
  (the parity table: agrees, differs and why, or not in the catalog yet and why).

Where sysplotter is wrong the catalog gives the right value, never the defect. The one defect
that touches the files loaded here: sysplotter's added mass of an ellipse
(``Inertia_link.m``) lacks the factor pi/8 of the rotational entry (the course's
:func:`~gm_core.systems.fluids.ellipse_added_mass` has it, and its panel method agrees), which
changes every high-Reynolds file. ``tests/test_catalog.py`` shows the catalog agrees with
sysplotter run in Octave (``tools/sysplotter_reference.py``) to 1e-8 where sysplotter computes in
closed form, and that with sysplotter's added mass put back it reproduces even the high-Re files.

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
from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.systems.base import LocomotionSystem
from gm_core.systems.diff_drive import DifferentialDrive
from gm_core.systems.kinematic_snake import KinematicSnake
from gm_core.systems.link_chain import LinkChain
from gm_core.systems.restricted import AffineRestriction
from gm_core.systems.rotors import Rotors
from gm_core.systems.tabulated import TabulatedConnection
from gm_core.validation import FloatArray

__all__ = ["SysplotterFile", "ParityRow", "names", "load", "sysplotter_view", "sysplotter_files", "reference", "parity",
           "with_sysplotter_added_mass", "CLOSED_FORM_RTOL"]

#: Relative agreement asked of the catalog where sysplotter computes in closed form (max |difference|
#: over max |sysplotter's value|, per file over its stored shapes).
CLOSED_FORM_RTOL = 1e-8

#: The added-mass defect of sysplotter's ``Inertia_link.m``, in the words of the parity table.
PI_OVER_8 = ("sysplotter's rotational added mass of an ellipse (Inertia_link.m) lacks the factor pi/8; "
             "the catalog has it (with sysplotter's value put back, the two agree to 1e-8)")


@dataclass(frozen=True)
class SysplotterFile:
    """One of sysplotter's system files and how the catalog stands to it.

    ``metric`` is ``"physical"`` (the file's ``s.metric`` is the system's own cost metric, times
    ``metric_scale``), ``"identity"`` (the file sets ``eye(n)``) or ``"none"`` (no ``s.metric``).
    ``differs`` says why the catalog's value is not sysplotter's ("" where they agree);
    ``missing`` why the catalog cannot load the file yet ("" where it can).
    """

    name: str
    model: str
    grid_range: tuple[tuple[float, float], ...]
    build: Callable[[], LocomotionSystem] | None = None
    metric: str = "physical"
    metric_scale: float = 1.0
    differs: str = ""
    missing: str = ""

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
        _chain_file("three_link_passive", "high-Re ellipses (ar 0.1), 3 equal; passive-joint gait model not in s.A", np.pi, 2,
                    lambda: _high_re(3), differs=PI_OVER_8),
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
    ]
    return {f.name: f for f in files}


_CONTINUOUS = "a continuous low-Re body (resistive force theory along a curvature-mode backbone)"


def _not_yet() -> dict[str, SysplotterFile]:
    """The files the catalog cannot load yet, each with what it needs."""
    body = "needs the continuous body in this file's curvature modes and frame (gm_core.systems.SlenderBody)"
    files = [
        SysplotterFile("constantcurv2_lowRe", _CONTINUOUS + ": two constant-curvature halves", _box(5, 2), missing=body),
        SysplotterFile("constantcurv3_lowRe", _CONTINUOUS + ": three constant-curvature thirds, tail frame", _box(5, 3),
                       missing=body),
        SysplotterFile("constantcurv4_lowRe", _CONTINUOUS + ": four constant-curvature quarters", _box(5, 4), missing=body),
        SysplotterFile("serpenoid_lowRe", _CONTINUOUS + ": serpenoid, centre-of-mass mean of 100 points", _box(10, 2),
                       missing=body),
        SysplotterFile("serpenoid_lowRe_hf", _CONTINUOUS + ": serpenoid of two waves", _box(10, 2), missing=body),
        SysplotterFile("serpenoid4_lowRe", _CONTINUOUS + ": serpenoid of one and two waves", _box(10, 4), missing=body),
        SysplotterFile("serpenoid_lowRe_hf_AmpPhase", _CONTINUOUS + ": serpenoid of two waves in amplitude and phase",
                       _box(6, 2), missing=body),
        SysplotterFile("triangle_lowRe", _CONTINUOUS + ": a triangle wave of curvature", _box(12, 2), missing=body),
        SysplotterFile("triangle_lowRe_two_waves", _CONTINUOUS + ": a triangle wave of two periods", _box(12, 2),
                       missing=body),
        SysplotterFile("three_link_HighRe_panelMethod", "high-Re ellipses interacting through a panel method", _box(2.0, 2),
                       missing="needs interacting added mass between links (sysplotter's panel method)"),
        SysplotterFile("symmetricTapeMeasure", "a floating looped chain (tape-measure swimmer)", _box(1.0, 2),
                       missing="needs closed (looped) bodies with their constraint"),
        SysplotterFile("asymmetricTapeMeasure", "an asymmetric looped chain", _box(1.0, 3),
                       missing="needs closed bodies; sysplotter itself cannot evaluate this file (it calls two "
                               "functions that exist nowhere in its repository)"),
    ]
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
    stored shapes (NaN where there is nothing to compare); ``status`` one of "agrees",
    "corrected" (sysplotter is wrong; ``as_sysplotter`` is the difference once sysplotter's
    defect is put back into the catalog), "not in the catalog" or "sysplotter cannot run it".
    """

    name: str
    model: str
    status: str
    A_difference: float
    M_difference: float
    as_sysplotter: float
    reason: str


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
            rows.append(ParityRow(entry.name, entry.model, "sysplotter cannot run it", nan, nan, nan, ref["error"]))
            continue
        system = entry.build()
        dA, dM = _compare(system, entry, ref)
        if entry.differs:
            back = _compare(with_sysplotter_added_mass(system), entry, ref)
            rows.append(ParityRow(entry.name, entry.model, "corrected", dA, dM, max(back), entry.differs))
        else:
            rows.append(ParityRow(entry.name, entry.model, "agrees", dA, dM, max(dA, dM), ""))
    if name is not None and not rows:
        raise ValueError(f"name {name!r} is not one of sysplotter's system files")
    return rows
