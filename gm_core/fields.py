"""Vector fields, integral curves and group geodesics of chapter 1 (numpy + scipy only).

==============================  ===========================================================  ===============
name                            what it is                                                   book
==============================  ===========================================================  ===============
VectorField                     X(q, t) -> q_dot, batched over q; ``on_grid`` for quiver     (1.13)-(1.15)
integral_curve                  flow of X from q0 by scipy's solve_ivp (tight tolerances)    (1.15)-(1.18)
left_invariant_field            X_L(g) = T_e L_g xi (constant body velocity xi)               (1.46)
right_invariant_field           X_R(g) = T_e R_g xi_s (constant spatial velocity xi_s)        (1.47)
group_geodesic                  g0 o exp(t xi) (left) or exp(t xi_s) o g0 (right), or solved  section 1.6.2, 1.6.4
se2_helix                       circle / helix geometry of an SE(2) geodesic                 fig. 1.18, ex. 1.4c
se2_helices                     the family exp(t (v, 0, thetadot)) of fig. 1.18              fig. 1.18
puck_vs_arc                     (R^2 x S^1, +) "spinning puck" path vs the SE(2) arc          fig. 1.19
rplus_geodesics                 accelerating / decelerating geodesics of (R+, x)             fig. 1.17
==============================  ===========================================================  ===============

Time-invariant fields are written ``X(q, t)`` anyway, so a field is always a function of (q, t) as
in (1.13)-(1.14); the ``t`` argument is ignored by the invariant fields.

SE(2) geodesic geometry (exercise 1.4c), derived here rather than taken from the draft: for
xi = (vx, vy, w) with w != 0, the left-invariant flow from e has theta(t) = w t and
(x, y)(t) = int_0^t R(w s) (vx, vy) ds = c + R(w t)(-c) with c = (-vy, vx) / w. So the xy-projection
is a circle through the origin, tangent there to (vx, vy), with centre c, radius |v| / |w| and
diameter 2 |v| / |w|, traversed at constant speed |v| = sqrt(vx^2 + vy^2) with period 2 pi / |w|.
In (x, y, theta) space the curve is a circular helix whose pitch (rise of theta per turn) is
2 pi for every xi (the sign of w gives the handedness); the xi-dependent quantities are the radius,
the xy arclength |v| t and the helix slope d theta / d s = w / |v| (theta gained per unit of xy
arclength, the signed curvature of the circle). One unit-time flow (exp(xi) itself) covers
xy arclength |v|, i.e. w / (2 pi) turns. For w = 0 the path is a straight line (radius infinite).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ._validate import as_array, batch_shape, check_int, check_option, check_positive
from .groups import SE2, R2xS1, check_group, matvec

#: Largest configuration-space dimension of a :class:`VectorField`.
MAX_FIELD_DIM = 10_000
#: Keyword arguments :func:`integral_curve` passes on to scipy's solve_ivp.
SOLVE_IVP_OPTIONS = frozenset({"method", "rtol", "atol", "dense_output", "events", "vectorized",
                               "first_step", "max_step", "min_step", "jac", "jac_sparsity",
                               "lband", "uband"})

__all__ = [
    "VectorField", "IntegralCurve", "integral_curve", "left_invariant_field",
    "right_invariant_field", "group_geodesic", "HelixGeometry", "se2_helix", "se2_helices",
    "PuckVsArc", "puck_vs_arc", "rplus_geodesics", "DEFAULT_RTOL", "DEFAULT_ATOL",
]

#: solve_ivp defaults used by :func:`integral_curve` (override with rtol=..., atol=...).
DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-12
DEFAULT_METHOD = "DOP853"
#: Default cap on field evaluations in :func:`integral_curve` (DOP853 uses 12 per step).
MAX_EVALUATIONS = 50_000


def _check_side(side):
    if not isinstance(side, str) or side not in ("left", "right"):  # a longer message than check_option's
        raise ValueError(
            f"side must be 'left' (left-invariant field, body velocity, (1.46)) or 'right' "
            f"(right-invariant field, spatial velocity, (1.47)); got {side!r}"
        )
    return side


def _check_solve_ivp_kw(kw, where):
    unknown = sorted(set(kw) - SOLVE_IVP_OPTIONS)
    if unknown:
        raise TypeError(f"{where} got unknown keyword argument(s) {', '.join(unknown)}; "
                        f"solve_ivp options are {', '.join(sorted(SOLVE_IVP_OPTIONS))}")


def _time(t, name="t"):
    t = as_array(t, name, what=" (times)")
    return t


# ---------------------------------------------------------------------------------- vector fields
class VectorField:
    """A (possibly time-varying) vector field X: (q, t) -> q_dot on R^dim, (1.13)-(1.15).

    Parameters
    ----------
    func : callable
        ``func(q, t)`` with ``q`` of shape ``(..., dim)`` and a float ``t``, returning an array of
        the same shape. With ``vectorized=False`` it is called once per point with ``q`` of shape
        ``(dim,)`` and the results are stacked.
    dim : int
        Dimension of the configuration space.
    name : str
        A label for plots and error messages.
    group : LieGroup, optional
        The group the field lives on (set by the invariant-field constructors); informational.

    Calling ``X(q, t=0.0)`` validates ``q`` (shape ``(..., dim)``, finite) and returns ``q_dot``.
    """

    def __init__(self, func, dim, *, name="X", vectorized=True, group=None):
        if not callable(func):
            raise TypeError(f"func must be a callable (q, t) -> q_dot; got {type(func).__name__}")
        if isinstance(dim, bool) or not isinstance(dim, (int, np.integer)):
            raise TypeError(f"dim must be a positive integer; got {type(dim).__name__} {dim!r:.40}")
        if not 1 <= dim <= MAX_FIELD_DIM:
            raise ValueError(f"dim must be a positive integer (at most {MAX_FIELD_DIM}); got {dim!r}")
        self.func = func
        self.dim = int(dim)
        self.name = str(name)
        self.vectorized = bool(vectorized)
        self.group = group

    def __repr__(self):
        return f"VectorField({self.name!r}, dim={self.dim})"

    def _eval(self, q, t):
        what = f" (the value of field {self.name!r})"
        if self.vectorized:
            out = as_array(self.func(q, t), "X(q, t)", what=what, allow_nan=True)
            if out.shape != q.shape and out.ndim and out.shape[-1] == self.dim:
                try:  # e.g. a constant field returning one (dim,) vector for every q
                    out = np.broadcast_to(out, q.shape)
                except ValueError:
                    pass
        else:
            flat = q.reshape(-1, self.dim)
            vals = [as_array(self.func(p, t), "X(q, t)", what=what, allow_nan=True) for p in flat]
            if any(v.shape != (self.dim,) for v in vals):
                raise ValueError(f"field {self.name!r} must return a vector of shape ({self.dim},) per point")
            out = np.stack(vals).reshape(q.shape) if vals else np.empty(q.shape)
        if out.shape != q.shape:
            raise ValueError(
                f"field {self.name!r} returned shape {out.shape} for q of shape {q.shape}; "
                f"it must return one velocity per configuration"
            )
        return out

    def __call__(self, q, t=0.0):
        q = as_array(q, "q", (self.dim,), what=f", a configuration for field {self.name!r}")
        t = as_array(t, "t", what=" (a time)")
        if t.ndim != 0:
            raise ValueError(f"t must be a single time; got shape {t.shape}")
        return self._eval(q, float(t))

    def on_grid(self, *axes_values, t=0.0, axes=None, at=None):
        """Evaluate the field on a grid for ``quiver``: returns ``(*meshes, *components)``.

        ``axes_values`` are 1-D arrays of coordinate values, one per plotted coordinate; ``axes``
        says which coordinates they are (default ``0, 1, ...``); the other coordinates are held at
        ``at`` (a full configuration, default zeros; e.g. theta for a planar slice of SE(2)). For a
        2-D slice this returns ``X, Y, U, V`` with ``X, Y = meshgrid(xs, ys)``.
        """
        if not axes_values:
            raise ValueError("on_grid needs at least one 1-D array of coordinate values")
        vals = [as_array(v, f"axes_values[{i}]", what=" (1-D coordinate values)")
                for i, v in enumerate(axes_values)]
        for i, v in enumerate(vals):
            if v.ndim != 1:
                raise ValueError(f"axes_values[{i}] must be a 1-D array; got shape {v.shape}")
        if axes is None:
            axes = tuple(range(len(vals)))
        else:
            if isinstance(axes, (str, bytes)) or not hasattr(axes, "__iter__"):
                raise TypeError(f"axes must be a sequence of coordinate indices; got {axes!r:.40}")
            axes = tuple(check_int(a, "axes[i]", minimum=0, maximum=self.dim - 1) for a in axes)
        if len(axes) != len(vals) or len(set(axes)) != len(axes) or not all(0 <= a < self.dim for a in axes):
            raise ValueError(
                f"axes must name {len(vals)} distinct coordinates in 0..{self.dim - 1}; got {axes}"
            )
        base = np.zeros(self.dim) if at is None else as_array(at, "at", (self.dim,))
        if base.ndim != 1:
            raise ValueError(f"at must be one configuration of shape ({self.dim},); got shape {base.shape}")
        meshes = np.meshgrid(*vals, indexing="xy")
        q = np.broadcast_to(base, meshes[0].shape + (self.dim,)).copy()
        for a, m in zip(axes, meshes):
            q[..., a] = m
        qdot = self(q, t)
        return (*meshes, *(qdot[..., a] for a in axes))


def _as_field(field, dim=None):
    if isinstance(field, VectorField):
        return field
    if callable(field):
        if dim is None:
            raise ValueError("a plain callable field needs the dimension; wrap it in VectorField(func, dim)")
        return VectorField(field, dim, name=getattr(field, "__name__", "X"))
    raise TypeError(f"field must be a VectorField or a callable (q, t) -> q_dot; got {type(field).__name__}")


@dataclass(frozen=True)
class IntegralCurve:
    """Samples of an integral curve gamma of a field, (1.16)-(1.18).

    ``t`` (m,) are the times, ``q`` (m, ..., dim) the configurations gamma(t); ``solution`` is
    scipy's OdeResult (``.sol`` is a dense interpolant when ``dense_output=True``).
    Unpacks as ``t, q = integral_curve(...)``.
    """

    t: np.ndarray
    q: np.ndarray
    solution: object

    def __iter__(self):
        yield self.t
        yield self.q


class _TooManyEvaluations(Exception):
    pass


def integral_curve(field, q0, t_span, t_eval=None, *, max_evaluations=MAX_EVALUATIONS, **solve_ivp_kw):
    """Integral curve of ``field`` from ``q0``: solves q_dot = X(q, t), q(t_span[0]) = q0, (1.15).

    ``field`` is a :class:`VectorField` (or a callable ``(q, t)`` if ``q0`` fixes the dimension).
    ``q0`` may be a batch ``(..., dim)`` of starting points; they are integrated together as one
    system and ``q`` comes back with shape ``(len(t), ..., dim)``. ``t_span = (t0, t1)`` (t1 < t0
    integrates backwards); ``t_eval`` selects output times inside the span. Keyword arguments go
    to :func:`scipy.integrate.solve_ivp`; defaults are ``method="DOP853"``, ``rtol=1e-10``,
    ``atol=1e-12``. Raises ``RuntimeError`` if the solver fails, and ``ValueError`` naming
    ``t_span`` if it needs more than ``max_evaluations`` evaluations of the field (a span far
    longer than the field's time scale would otherwise run for hours).
    """
    q0_arr = as_array(q0, "q0", what=" (a starting configuration)")
    if q0_arr.ndim == 0:
        q0_arr = q0_arr.reshape(1)
    X = _as_field(field, dim=q0_arr.shape[-1])
    q0_arr = as_array(q0_arr, "q0", (X.dim,), what=f", a starting configuration for field {X.name!r}")
    span = as_array(t_span, "t_span", (2,), what=" (start and end times)")
    if span.ndim != 1:
        raise ValueError(f"t_span must be a pair (t0, t1); got shape {span.shape}")
    if span[0] == span[1]:
        raise ValueError(f"t_span must have t0 != t1; got {tuple(span)}")
    if t_eval is not None:
        t_eval = as_array(t_eval, "t_eval", what=" (output times)")
        t_eval = np.atleast_1d(t_eval)
        if t_eval.ndim != 1 or t_eval.size == 0:
            raise ValueError(f"t_eval must be a non-empty 1-D array of times; got shape {t_eval.shape}")
        lo, hi = min(span), max(span)
        tol = 1e-12 * max(1.0, abs(lo), abs(hi))
        if np.any(t_eval < lo - tol) or np.any(t_eval > hi + tol):
            raise ValueError(f"t_eval must lie inside t_span {tuple(span)}")
        t_eval = np.clip(t_eval, lo, hi)
    batch = q0_arr.shape[:-1]
    shape = q0_arr.shape

    calls = [0]

    def rhs(t, y):
        calls[0] += 1
        if calls[0] > max_evaluations:
            raise _TooManyEvaluations
        return X._eval(y.reshape(shape), t).ravel()

    _check_solve_ivp_kw(solve_ivp_kw, "integral_curve")
    max_evaluations = check_int(max_evaluations, "max_evaluations", minimum=1, maximum=10**9)
    kw = {"method": DEFAULT_METHOD, "rtol": DEFAULT_RTOL, "atol": DEFAULT_ATOL}
    kw.update(solve_ivp_kw)
    try:
        with np.errstate(over="ignore", invalid="ignore"):   # overflow shows as failure below
            sol = solve_ivp(rhs, (float(span[0]), float(span[1])), q0_arr.ravel(), t_eval=t_eval, **kw)
    except _TooManyEvaluations:
        raise ValueError(
            f"t_span ({span[0]:g}, {span[1]:g}) is too long for field {X.name!r} at these tolerances: the solver "
            f"needed more than max_evaluations={max_evaluations} evaluations; shorten t_span or "
            f"raise max_evaluations"
        ) from None
    if not sol.success:
        raise RuntimeError(f"integral_curve: solve_ivp failed for field {X.name!r}: {sol.message}")
    if not np.all(np.isfinite(sol.y)):
        raise RuntimeError(f"integral_curve: the curve of field {X.name!r} from q0 overflowed (blew up)")
    q = sol.y.T.reshape((len(sol.t),) + batch + (X.dim,))
    return IntegralCurve(t=sol.t, q=q, solution=sol)


# ---------------------------------------------------------------------------------- invariant fields
def _field_value(v, g, name):
    if v.shape != np.shape(g):
        raise ValueError(f"{name} (shape {v.shape[:-1] + v.shape[-1:]}) gives velocities of shape {v.shape} "
                         f"at configurations of shape {np.shape(g)}: its batch must broadcast to g's")
    return v


def left_invariant_field(group, xi):
    """Left-invariant field X_L(g) = T_e L_g xi of the body velocity ``xi``, (1.46).

    ``xi`` is a Lie-algebra vector ``(dim,)`` (or a batch broadcasting against g). Its flows have
    constant body velocity xi; from g0 the flow is g0 o exp(t xi).
    """
    group = check_group(group)
    xi = as_array(xi, "xi", (group.dim,), what=f", a body velocity in the Lie algebra of {group.name}")
    e = group.identity()

    def X_L(g, t=0.0):
        return _field_value(matvec(group.left_lifted_action(g, e), xi), g, "xi")

    return VectorField(X_L, group.dim, name=f"X_L[{group.name}]", group=group)


def right_invariant_field(group, xi_s):
    """Right-invariant field X_R(g) = T_e R_g xi_s of the spatial velocity ``xi_s``, (1.47).

    Its flows have constant spatial velocity xi_s; from g0 the flow is exp(t xi_s) o g0.
    """
    group = check_group(group)
    xi_s = as_array(xi_s, "xi_s", (group.dim,),
                    what=f", a spatial velocity in the Lie algebra of {group.name}")
    e = group.identity()

    def X_R(g, t=0.0):
        return _field_value(matvec(group.right_lifted_action(g, e), xi_s), g, "xi_s")

    return VectorField(X_R, group.dim, name=f"X_R[{group.name}]", group=group)


def group_geodesic(group, xi, t, side="left", g0=None, *, method="exp", **solve_ivp_kw):
    """The group geodesic through ``g0`` (default e) generated by ``xi``, sampled at times ``t``.

    ``side="left"``: flow of the left-invariant field (1.46) of the body velocity ``xi``,
    g(t) = g0 o exp(t xi). ``side="right"``: flow of the right-invariant field (1.47) of the spatial
    velocity ``xi``, g(t) = exp(t xi) o g0. ``method="exp"`` uses these closed forms;
    ``method="integrate"`` solves the flow numerically with :func:`integral_curve` instead
    (forwards from t = 0 for positive times, backwards for negative ones; ``t`` in any order).

    Returns elements of shape ``t.shape + (dim,)`` (angles are not wrapped; compare with
    ``group.isclose``). ``xi`` must be a single vector ``(dim,)``; ``g0`` an element ``(dim,)``.
    """
    group = check_group(group)
    side = _check_side(side)
    method = check_option(method, "method", ("exp", "integrate"))
    _check_solve_ivp_kw(solve_ivp_kw, "group_geodesic")
    if method == "exp" and solve_ivp_kw:
        raise TypeError(f"group_geodesic got solve_ivp option(s) {', '.join(sorted(solve_ivp_kw))}, "
                        f"which only apply with method='integrate'")
    xi = as_array(xi, "xi", (group.dim,), what=f", a Lie-algebra vector of {group.name}")
    if xi.ndim != 1:
        raise ValueError(f"xi must be one vector of shape ({group.dim},); got shape {xi.shape}")
    t = _time(t)
    g0 = group.identity() if g0 is None else group._element(g0, "g0")
    if g0.ndim != 1:
        raise ValueError(f"g0 must be one element of shape ({group.dim},); got shape {g0.shape}")
    if method == "exp":
        steps = group.exp(t[..., None] * xi)
        return group.compose(g0, steps) if side == "left" else group.compose(steps, g0)
    field = left_invariant_field(group, xi) if side == "left" else right_invariant_field(group, xi)
    flat = t.ravel()
    out = np.empty(flat.shape + (group.dim,))
    out[flat == 0] = g0
    # Integrate forward from 0 for t > 0 and backward for t < 0, so g(0) = g0 exactly; solve_ivp
    # needs strictly monotone output times, so solve at the sorted unique times and scatter back.
    for mask, backward in ((flat > 0, False), (flat < 0, True)):
        if not mask.any():
            continue
        vals, inv = np.unique(flat[mask], return_inverse=True)
        if backward:
            vals, inv = vals[::-1], len(vals) - 1 - inv
        try:
            curve = integral_curve(field, g0, (0.0, float(vals[-1])), t_eval=vals, **solve_ivp_kw)
        except ValueError as exc:
            raise ValueError(f"t reaches {vals[-1]:g}: {exc}") from None
        out[mask] = curve.q[inv]
    return out.reshape(t.shape + (group.dim,))


# ---------------------------------------------------------------------------------- SE(2) helices
@dataclass(frozen=True)
class HelixGeometry:
    """Geometry of the SE(2) geodesic(s) generated by xi = (vx, vy, w) (exercise 1.4c).

    Arrays broadcast over the batch of ``xi``. ``centre`` (..., 2) and ``radius`` describe the
    xy-projection (a circle; ``straight`` marks w = 0, where radius is inf and centre NaN);
    ``diameter = 2 |v| / |w|``; ``speed = |v|`` (xy speed, so the unit-time flow exp(xi) covers xy
    arclength ``arclength = |v|``); ``period = 2 pi / |w|``; ``pitch`` = theta gained per full turn
    (2 pi sign(w), independent of the magnitudes); ``slope = w / |v|`` = theta gained per unit xy
    arclength (signed curvature of the circle); ``turns = w / (2 pi)`` turns in unit time;
    ``arclength_per_turn = 2 pi |v| / |w|``.
    """

    xi: np.ndarray
    centre: np.ndarray
    radius: np.ndarray
    diameter: np.ndarray
    speed: np.ndarray
    arclength: np.ndarray
    period: np.ndarray
    pitch: np.ndarray
    slope: np.ndarray
    turns: np.ndarray
    arclength_per_turn: np.ndarray
    straight: np.ndarray

    def circle_points(self, num=200):
        """Points (..., num, 2) around the full xy circle (NaN rows for straight paths)."""
        phi = np.linspace(0.0, 2 * np.pi, check_int(num, "num", minimum=2, maximum=10**6))
        r = np.where(self.straight, np.nan, self.radius)[..., None]
        return np.stack([self.centre[..., None, 0] + r * np.cos(phi),
                         self.centre[..., None, 1] + r * np.sin(phi)], -1)


def se2_helix(xi, side="left", g0=None):
    """Helix and circle geometry of the SE(2) geodesic generated by ``xi`` (exercise 1.4c).

    With ``g0=None`` the geodesic is exp(t xi) (the same for both sides). For a start ``g0`` the
    xy circle moves with it: ``side="left"`` (g0 o exp(t xi), constant body velocity) has centre
    g0 applied to the body-frame centre (-vy, vx)/w; ``side="right"`` (exp(t xi_s) o g0, constant
    spatial velocity) always turns about the fixed world point (-vy, vx)/w, with radius the
    distance from there to g0's position. See the module docstring for the derivation.
    """
    xi = as_array(xi, "xi", (3,), what=", an se(2) velocity (vx, vy, w)")
    side = _check_side(side)
    vx, vy, w = xi[..., 0], xi[..., 1], xi[..., 2]
    # |w| tiny but nonzero overflows to radius = inf, which is the right limit: silence it
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        speed = np.hypot(vx, vy)
        straight = w == 0
        wsafe = np.where(straight, 1.0, w)
        c = np.stack([-vy / wsafe, vx / wsafe], -1) + 0.0  # + 0.0 turns -0.0 into 0.0
        c = np.where(straight[..., None], np.nan, c)
        radius = np.where(straight, np.inf, speed / np.abs(wsafe))
        if g0 is not None:
            g0 = SE2._element(g0, "g0")
            batch_shape(("xi", xi, 1), ("g0", g0, 1))
            finite_c = np.where(straight[..., None], 0.0, c)      # straight paths have no centre
            if side == "left":
                c = np.where(straight[..., None], np.nan, SE2.act_on_points(g0, finite_c))
            else:
                radius = np.where(straight, np.inf, np.linalg.norm(g0[..., :2] - finite_c, axis=-1))
        period = np.where(straight, np.inf, 2 * np.pi / np.abs(wsafe))
        slope = np.where(speed > 0, w / np.where(speed > 0, speed, 1.0), np.copysign(np.inf, w))
        per_turn = np.where(straight, np.inf, 2 * np.pi * speed / np.abs(wsafe))
        return HelixGeometry(
            xi=xi, centre=c, radius=radius, diameter=2 * radius, speed=speed, arclength=speed,
            period=period, pitch=2 * np.pi * np.sign(w), slope=slope, turns=w / (2 * np.pi),
            arclength_per_turn=per_turn, straight=straight,
        )


def se2_helices(thetadot, t, speed=1.0):
    """SE(2) geodesics exp(t xi) for body velocities xi = (speed, 0, thetadot), fig. 1.18.

    Returns ``(paths, geometry)``: ``paths`` of shape ``thetadot.shape + t.shape + (3,)`` and the
    :class:`HelixGeometry` of each xi (circles through the origin tangent to the x axis, centres
    (0, speed/thetadot)).
    """
    thetadot = as_array(thetadot, "thetadot", what=" (rotation rates)")
    t = _time(t)
    speed = as_array(speed, "speed", what=" (forward speed)")
    batch_shape(("thetadot", thetadot, 0), ("speed", speed, 0))
    xi = np.stack(np.broadcast_arrays(speed * np.ones_like(thetadot), np.zeros_like(thetadot),
                                      thetadot), -1)
    xi_b = xi.reshape(xi.shape[:-1] + (1,) * t.ndim + (3,))
    paths = SE2.exp(t[..., None] * xi_b)
    return paths, se2_helix(xi)


# ---------------------------------------------------------------------------------- fig. 1.19, fig. 1.17
@dataclass(frozen=True)
class PuckVsArc:
    """The two constant-velocity paths of fig. 1.19 from the identity, sampled at ``t``.

    ``puck``: flow of g_dot = T_e L_g xi on (R^2 x S^1, +) (a straight line while spinning);
    ``arc``: the same on SE(2) (a circular arc). ``puck_body_velocity`` and ``arc_body_velocity``
    are each path's SE(2) body velocity T_g L_{g^-1} g_dot (1.32) along it: constant for the arc,
    oscillating forward/backward for the puck.
    """

    t: np.ndarray
    xi: np.ndarray
    puck: np.ndarray
    arc: np.ndarray
    puck_body_velocity: np.ndarray
    arc_body_velocity: np.ndarray


def puck_vs_arc(t, xi=(1.0, 1.0, 1.0)):
    """(R^2 x S^1, +) versus SE(2) geodesics from e with the same generator ``xi``, fig. 1.19."""
    t = _time(t)
    xi = as_array(xi, "xi", (3,), what=", a velocity (vx, vy, w)")
    if xi.ndim != 1:
        raise ValueError(f"xi must be a single vector of shape (3,); got shape {xi.shape}")
    puck = group_geodesic(R2xS1, xi, t)
    arc = group_geodesic(SE2, xi, t)
    puck_dot = np.broadcast_to(matvec(R2xS1.left_lifted_action(puck, R2xS1.identity()), xi), puck.shape)
    arc_dot = SE2.body_to_world(arc, xi)
    return PuckVsArc(t=t, xi=xi, puck=puck, arc=arc,
                     puck_body_velocity=SE2.world_to_body(puck, puck_dot),
                     arc_body_velocity=SE2.world_to_body(arc, arc_dot))


def rplus_geodesics(xi, t, g0=1.0):
    """Geodesics g(t) = g0 exp(t xi) of (R+, x), fig. 1.17, and their velocities g_dot = xi g.

    ``xi`` (numbers, any shape) are the generating velocities: xi > 0 accelerates, xi < 0
    decelerates. Returns ``(g, g_dot)`` of shape ``xi.shape + t.shape``. Left and right geodesics
    coincide because (R+, x) is commutative, (1.24)-(1.25).
    """
    xi = as_array(xi, "xi", what=" (generating velocities)")
    t = _time(t)
    g0 = check_positive(g0, "g0")
    if g0.ndim != 0:
        raise ValueError(f"g0 must be a single positive number (an element of (R+, x)); got shape {g0.shape}")
    xi_b = xi.reshape(xi.shape + (1,) * t.ndim)
    with np.errstate(over="ignore", invalid="ignore"):
        g = g0 * np.exp(xi_b * t)
        g_dot = xi_b * g
    if not (np.isfinite(g).all() and np.isfinite(g_dot).all()):
        raise ValueError("xi and t are too large together: g0 exp(xi t) overflows a float "
                         "(keep |xi t| below about 700)")
    return g, g_dot
