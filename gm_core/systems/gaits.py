"""Gaits: closed shape trajectories ``t -> r(t)`` of period T, with their shape velocity (chapter 3).

numpy/scipy only; :mod:`gm_core.systems.motion` integrates them (and re-exports every name here).

* :class:`Gait` from a callable, or :meth:`Gait.from_samples` (periodic cubic spline);
* :func:`circle_gait` (a :class:`CircleGait`), :func:`as_gait`.

A gait also says how finely it must be sampled to see all its features (``feature_time``): a
circle changes on the scale of its period, a spline on the scale of its knot spacing, a general
callable on an unknown scale (then checks sample densely, see
:func:`gm_core.systems.motion.check_gait`).
"""
from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any, Union

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.validation import (
    FloatArray,
    as_array,
    check_int,
    check_option,
    check_positive,
    positive_number,
    real_number,
)

__all__ = [
    "GaitLike",
    "Gait", "CircleGait", "circle_gait", "as_gait", "GaitWarning", "CLOSURE_RTOL", "ellipse_gait",
    "serpenoid_gait", "GAIT_FAMILIES", "family_gait",
]

#: A gait is closed when |r(T) - r(0)| <= CLOSURE_RTOL * max(1, max |r|).
CLOSURE_RTOL = 1e-8

# Eighth-order central difference weights for f'(t) with offsets 1..4.
_FD8 = np.array([4 / 5, -1 / 5, 4 / 105, -1 / 280])


#: What :func:`as_gait` accepts: a :class:`Gait`, a callable ``t -> r`` or closed-path samples ``(K, n)``.
GaitLike = Union["Gait", Callable[[Any], ArrayLike], ArrayLike]

class GaitWarning(UserWarning):
    """A gait was accepted but something about it is probably not what was meant (e.g. an open path)."""


def _samples(points, name):
    pts = as_array(points, name)
    if pts.ndim != 2 or pts.shape[0] < 3 or pts.shape[1] < 1:
        raise ValueError(f"{name} must have shape (K, n) with K >= 3 samples of a closed path; "
                         f"got shape {pts.shape}")
    if np.all(np.abs(pts[0] - pts[-1]) <= 1e-12 * np.abs(pts).max()):     # a repeated first point
        pts = pts[:-1]
    if pts.shape[0] < 3:
        raise ValueError(f"{name} must contain at least 3 distinct samples of a closed path")
    return pts


class Gait:
    """A shape trajectory ``t -> r(t)`` over one period T, with its shape velocity.

    Build one from a callable (``Gait(lambda t: ..., period=T)``), optionally with an exact
    ``velocity`` callable (otherwise an eighth-order central difference is used), or from a
    sampled closed path with :meth:`from_samples` (periodic cubic spline through the samples at
    equal time steps). Callables should accept an array of times ``(N,)`` and return ``(N, n)``
    (or ``(n, N)``); scalar-only callables also work, more slowly.

    A gait proper is closed, r(T) = r(0) (see :attr:`closure_gap`); an open shape path (say a
    constant-rate drive) is also a valid ``Gait`` for :func:`gm_core.systems.motion.trajectory` over
    one period, but :func:`gm_core.systems.motion.net_displacement` refuses it unless told
    ``check=False``. ``feature_time`` is the shortest time over which the shape changes
    appreciably, if known (None: unknown, so singularity checks sample densely).
    """

    def __init__(self, shape: Any, period: float = 1.0, velocity: Any = None, *, name: str = "gait",
                 knots: ArrayLike | None = None, feature_time: float | None = None) -> None:
        if not callable(shape):
            raise TypeError(f"shape must be a callable t -> r(t); got {type(shape).__name__} "
                            "(use Gait.from_samples for an array of points)")
        if velocity is not None and not callable(velocity):
            raise TypeError(f"velocity must be a callable t -> r_dot(t) or None; got {type(velocity).__name__}")
        self.period = positive_number(period, "period")
        self._shape = shape
        self._velocity = velocity
        self.name = str(name)
        self.knots = None if knots is None else as_array(knots, "knots")
        if feature_time is not None:
            feature_time = min(positive_number(feature_time, "feature_time"), self.period)
        self.feature_time = feature_time
        ends = self._eval(self._shape, np.array([0.0, self.period]))
        if ends.ndim != 2 or ends.shape[-1] < 1:
            raise ValueError(f"shape must return a vector of shape variables r(t) (n,); got {ends.shape[1:]}")
        self.n_shape = ends.shape[-1]
        self.closure_gap = ends[1] - ends[0]

    @staticmethod
    def _layout(f, flat, out):
        """``out`` = f(flat) as (N, n), one shape per time: a callable may return (n, N) (say
        ``np.array([cos(t), sin(t)])``), which is turned; when n = N the two read alike, so f is
        called once more with one time added, whose shape tells them apart. None: neither."""
        N = flat.size
        if out.ndim != 2 or N not in out.shape:
            return None
        if out.shape[0] != N:
            return out.T
        if out.shape[1] != N or N == 1:
            return out
        try:
            wider = np.asarray(f(np.append(flat, flat[0])), dtype=float).shape
        except Exception:  # noqa: BLE001 - undecided: read point by point by the caller
            return None
        return out if wider == (N + 1, N) else out.T if wider == (N, N + 1) else None

    @staticmethod
    def _eval(f, t):
        t = np.asarray(t, dtype=float)
        flat = t.reshape(-1)
        try:
            out = Gait._layout(f, flat, np.asarray(f(flat), dtype=float))
        except Exception:  # noqa: BLE001 - scalar-only callables; retried point by point below
            out = None
        if out is None:
            try:
                out = np.array([np.atleast_1d(np.asarray(f(float(s)), dtype=float)) for s in flat])
            except (TypeError, ValueError) as e:
                raise TypeError(f"the gait's callable must return numbers r(t) (n,) for a time t; "
                                f"calling it failed with {type(e).__name__}: {e}") from None
        if out.ndim != 2:
            raise ValueError(f"the gait's callable must return a vector r(t) (n,) per time; got shape {out.shape}")
        if not np.all(np.isfinite(out)):
            raise ValueError("the gait returned NaN or infinite shapes; every shape must be finite")
        return out.reshape(t.shape + out.shape[-1:])

    def __call__(self, t: ArrayLike) -> FloatArray:
        """Shape r(t), ``(..., n)`` for times ``(...)``."""
        return self._eval(self._shape, as_array(t, "t", what=" (times)"))

    def velocity(self, t: ArrayLike) -> FloatArray:
        """Shape velocity r_dot(t), ``(..., n)``: exact if given, else an 8th-order central difference."""
        t = as_array(t, "t", what=" (times)")
        if self._velocity is not None:
            out = self._eval(self._velocity, t)
            if out.shape[-1] != self.n_shape:
                raise ValueError(f"the gait's velocity callable returned {out.shape[-1]} components per time; "
                                 f"the shape has {self.n_shape}")
            return out
        t = np.asarray(t, dtype=float)
        h = 1e-3 * (self.period if self.feature_time is None else self.feature_time)
        out = np.zeros(t.shape + (self.n_shape,))
        for k, w in enumerate(_FD8, start=1):
            out = out + w * (self(t + k * h) - self(t - k * h))
        return out / h

    def is_closed(self, rtol: float = CLOSURE_RTOL) -> bool:
        """True when r(T) = r(0) to ``rtol`` relative to max(1, |r(0)|, |r(T)|)."""
        r0 = self(np.array([0.0]))[0]
        scale = max(1.0, float(np.max(np.abs(r0))), float(np.max(np.abs(r0 + self.closure_gap))))
        return float(np.max(np.abs(self.closure_gap))) <= rtol * scale

    def require_closed(self, what: str) -> None:
        """Raise ValueError naming the gap when the gait is open; ``what`` says who needs it closed."""
        if not self.is_closed():
            gap = ", ".join(f"{v:.3g}" for v in self.closure_gap)
            raise ValueError(
                f"gait {self.name!r} is not closed: r(T) - r(0) = ({gap}), |gap| = "
                f"{float(np.linalg.norm(self.closure_gap)):.3g}; {what} needs a closed loop in shape space")

    @classmethod
    def from_samples(cls, points: ArrayLike, period: float = 1.0, *, name: str = "sampled gait") -> Gait:
        """A gait through the closed path ``points (K, n)`` visited at equal time steps.

        The path is closed automatically (a last point equal to the first is dropped) and
        interpolated by a periodic cubic spline, whose derivative gives the shape velocity. If
        the closing segment (last point back to the first) is more than four times as long as
        the longest other segment, the samples probably describe an open path and a
        :class:`GaitWarning` names the gap.
        """
        from scipy.interpolate import CubicSpline

        pts = _samples(points, "points")
        unit = max(float(np.abs(pts).max()), np.finfo(float).tiny)     # norms without overflow
        seg = np.linalg.norm(np.diff(pts / unit, axis=0), axis=-1) * unit
        gap = float(np.linalg.norm((pts[0] - pts[-1]) / unit)) * unit
        if gap > 4 * float(seg.max()):
            warnings.warn(f"points look like an open path: the closing segment from the last point back "
                          f"to the first has length {gap:.3g}, the longest other segment {float(seg.max()):.3g}; "
                          "the periodic spline closes it", GaitWarning, stacklevel=2)
        T = positive_number(period, "period")
        K = pts.shape[0]
        # the spline runs over one unit of phase s = t / T, so tiny or huge periods stay exact
        spline = CubicSpline(np.linspace(0.0, 1.0, K + 1), np.vstack([pts, pts[:1]]), bc_type="periodic", axis=0)
        d = spline.derivative()

        def phase(t):
            return np.mod(np.asarray(t, dtype=float) / T, 1.0)

        return cls(lambda t: spline(phase(t)), T, lambda t: d(phase(t)) / T, name=name,
                   knots=T * np.linspace(0.0, 1.0, K + 1), feature_time=T / K)

    def reparameterized(self, tau: Callable[[Any], Any], tau_dot: Callable[[Any], Any] | None = None, *,
                        name: str | None = None) -> Gait:
        """The same path with a new pacing: ``r'(t) = r(tau(t))``, for a map tau of [0, T] onto itself.

        ``tau`` must be increasing with tau(0) = 0 and tau(T) = T; ``tau_dot`` is its derivative
        (optional). This is the time reparameterization of (3.3).
        """
        if not callable(tau):
            raise TypeError("tau must be a callable t -> tau(t)")
        if tau_dot is not None and not callable(tau_dot):
            raise TypeError("tau_dot must be a callable t -> tau'(t) or None")
        T = self.period
        if not (abs(float(tau(0.0))) <= 1e-12 * T and abs(float(tau(T)) - T) <= 1e-12 * T):
            raise ValueError("tau must map [0, T] onto itself with tau(0) = 0 and tau(T) = T")
        base = self
        vel: Callable[[Any], Any] | None = None
        if tau_dot is not None:
            def vel(t: Any) -> Any:
                t = np.asarray(t, dtype=float)
                return base.velocity(tau(t)) * np.asarray(tau_dot(t), dtype=float)[..., None]
        return Gait(lambda t: base(tau(np.asarray(t, dtype=float))), T, vel,
                    name=name or f"{self.name} (repaced)")

    @override
    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r}, period={self.period:g}, n_shape={self.n_shape})"


class CircleGait(Gait):
    """``r(t) = c + R (cos 2 pi t / T, sin 2 pi t / T)``: see :func:`circle_gait`."""

    def __init__(self, amplitude: ArrayLike, center: ArrayLike = (0.0, 0.0), period: float = 1.0) -> None:
        R = check_positive(amplitude, "amplitude")
        if R.ndim > 1 or R.size not in (1, 2):
            raise ValueError(f"amplitude must be a number or a pair of semi-axes; got shape {R.shape}")
        c = as_array(center, "center", (2,), what=" (the gait's centre in shape space)")
        if c.ndim != 1:
            raise ValueError(f"center must have shape (2,); got shape {c.shape}")
        #: semi-axes (2,) and centre (2,) of the circle (or ellipse)
        self.amplitude = np.broadcast_to(R, (2,)).astype(float)
        self.center = c.copy()
        T = positive_number(period, "period")
        super().__init__(self._r, T, self._r_dot, feature_time=T,
                         name=f"circle R={self.amplitude[0]:g} about ({c[0]:g}, {c[1]:g})")

    def _phase(self, t):
        # the phase 2 pi t / T, computed as 2 pi (t / T) so that tiny or huge periods stay exact
        return 2 * np.pi * (np.asarray(t, dtype=float) / self.period)

    def _r(self, t):
        w = self._phase(t)
        return self.center + self.amplitude * np.stack([np.cos(w), np.sin(w)], -1)

    def _r_dot(self, t):
        w = self._phase(t)
        return (2 * np.pi / self.period) * self.amplitude * np.stack([-np.sin(w), np.cos(w)], -1)


def circle_gait(amplitude: ArrayLike, center: ArrayLike = (0.0, 0.0), period: float = 1.0) -> CircleGait:
    """Circular gait ``r(t) = c + R (cos 2 pi t / T, sin 2 pi t / T)`` in a 2-D shape space.

    ``amplitude`` is the radius R (a positive number, or two positive semi-axes for an ellipse);
    ``center`` is c; the circle is traversed counterclockwise once per ``period``.
    """
    return CircleGait(amplitude, center, period)


def ellipse_gait(a: float, b: float, tilt: float = 0.0, center: ArrayLike = (0.0, 0.0), period: float = 1.0) -> Gait:
    """Tilted ellipse ``r(t) = c + R(tilt) (a cos w, b sin w)``, w = 2 pi t / T, with exact velocity.

    ``a``, ``b`` are the semi-axes (positive), ``tilt`` the angle of the a-axis from the alpha1
    axis; traversed counterclockwise (for a, b > 0) once per period.
    """
    a = positive_number(a, "a")
    b = positive_number(b, "b")
    tilt = real_number(tilt, "tilt", what=" (the ellipse's tilt angle in radians)")
    c = as_array(center, "center", (2,), what=" (the gait's centre in shape space)")
    if c.ndim != 1:
        raise ValueError(f"center must have shape (2,); got shape {c.shape}")
    T = positive_number(period, "period")
    ct, st = np.cos(tilt), np.sin(tilt)
    Rm = np.array([[ct, -st], [st, ct]])

    def r(t):
        w = 2 * np.pi * (np.asarray(t, float) / T)
        return c + np.stack([a * np.cos(w), b * np.sin(w)], -1) @ Rm.T

    def r_dot(t):
        w = 2 * np.pi * (np.asarray(t, float) / T)
        return (2 * np.pi / T) * np.stack([-a * np.sin(w), b * np.cos(w)], -1) @ Rm.T

    return Gait(r, T, r_dot, name=f"ellipse {a:g} x {b:g} tilted {tilt:g}", feature_time=T)


def serpenoid_gait(amplitude: ArrayLike, phase: float = np.pi / 2, frequency: int = 1, center: ArrayLike = (0.0, 0.0),
                   period: float = 1.0) -> Gait:
    """Serpenoid family ``r(t) = c + A (sin w, sin(k w + phase))``, w = 2 pi t / T, exact velocity.

    The joint angles of a serpenoid wave are two sinusoids with a phase lag. With ``frequency``
    k = 1 the loop is an ellipse (a circle for phase = pi/2, a segment traced back and forth for
    phase = 0); with k = 2 and phase 0 it is a figure eight (a lemniscate of Gerono), whose two
    lobes are circled in opposite senses (phase pi/2 folds it onto an arc traced back and forth). ``amplitude`` is a number or a pair (A1, A2).
    """
    A = check_positive(amplitude, "amplitude")
    if A.ndim > 1 or A.size not in (1, 2):
        raise ValueError(f"amplitude must be a number or a pair (A1, A2); got shape {A.shape}")
    A = np.broadcast_to(A, (2,)).astype(float)
    if isinstance(frequency, (float, np.floating)) and np.isfinite(frequency) and frequency != int(frequency):
        raise ValueError(f"frequency must be a positive integer (so the loop closes); got {frequency!r}")
    k = check_int(frequency, "frequency", minimum=1, maximum=1000, what=" (so the loop closes)")
    ph = real_number(phase, "phase", what=" (the phase lag of the second joint in radians)")
    c = as_array(center, "center", (2,), what=" (the gait's centre in shape space)")
    if c.ndim != 1:
        raise ValueError(f"center must have shape (2,); got shape {c.shape}")
    T = positive_number(period, "period")

    def r(t):
        w = 2 * np.pi * (np.asarray(t, float) / T)
        return c + A * np.stack([np.sin(w), np.sin(k * w + ph)], -1)

    def r_dot(t):
        w = 2 * np.pi * (np.asarray(t, float) / T)
        return (2 * np.pi / T) * A * np.stack([np.cos(w), k * np.cos(k * w + ph)], -1)

    name = "figure eight" if k == 2 else f"serpenoid k={k}"
    return Gait(r, T, r_dot, name=f"{name}, phase {ph:g}", feature_time=T / k)


#: The gait shapes a panel offers, with the parameters each takes from (size, aspect, angle):
#: size = radius or amplitude, aspect = b / a (ellipse) or A2 / A1, angle = tilt or phase.
GAIT_FAMILIES = ("circle", "ellipse", "serpenoid", "figure eight")


def family_gait(family: str, size: float, center: ArrayLike = (0.0, 0.0), aspect: float = 1.0, angle: float = 0.0,
                period: float = 1.0) -> Gait:
    """A gait of one of :data:`GAIT_FAMILIES` from three common parameters (for panels).

    ``circle``: radius ``size``; ``ellipse``: semi-axes (size, aspect * size) tilted by
    ``angle``; ``serpenoid``: amplitudes (size, aspect * size), phase ``angle``; ``figure eight``:
    the same with the second joint at twice the frequency.
    """
    family = check_option(family, "family", GAIT_FAMILIES)
    size = positive_number(size, "size")
    aspect = positive_number(aspect, "aspect")
    angle = real_number(angle, "angle")
    if family == "circle":
        return circle_gait(size, center, period)
    if family == "ellipse":
        return ellipse_gait(size, aspect * size, angle, center, period)
    if family == "serpenoid":
        return serpenoid_gait((size, aspect * size), angle, 1, center, period)
    return serpenoid_gait((size, aspect * size), angle, 2, center, period)


def as_gait(gait: GaitLike, period: float = 1.0) -> Gait:
    """A :class:`Gait` from a Gait, a callable ``t -> r`` (period ``period``) or samples ``(K, n)``."""
    if isinstance(gait, Gait):
        return gait
    if callable(gait):
        return Gait(gait, period)
    if gait is None or isinstance(gait, (str, bytes)):
        raise TypeError(f"gait must be a Gait, a callable t -> r(t) or an array of shapes; got {gait!r}")
    return Gait.from_samples(_samples(gait, "gait"), period)
