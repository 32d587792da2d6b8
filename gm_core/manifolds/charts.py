"""Charts and their overlap (transition) maps of section 1.1, acting on points, tangent vectors and vector fields.

A chart phi: U -> R^n names the points of a region U of a manifold M with n numbers; where two
charts overlap, the overlap map phi_2 o phi_1^-1 (the "Manifolds" box of section 1.1) renames a
point, its Jacobian J_12 renames a tangent vector (the pushforward: v_2 = J_12(q_1) v_1), and a
vector field given in chart 1 reads in chart 2 as X_2(q_2) = J_12(q_1) X_1(q_1) at
q_1 = phi_1 o phi_2^-1(q_2) (fields as in section 1.4, (1.13)-(1.15)).

The manifolds are embedded: a point of the plane is its Cartesian pair (x, y), a point of the
sphere a unit vector (x, y, z). Every chart maps to that embedding and back, with the Jacobians
of both maps; a transition is the composition of one chart's map to the manifold with the other's
map back (the chain rule for its Jacobian), so each formula exists once, in its chart.

chart                  manifold  coordinates  domain U (where the chart is a diffeomorphism)
---------------------  --------  -----------  --------------------------------------------------
CARTESIAN              plane     (x, y)       the whole plane
POLAR                  plane     (r, theta)   the plane minus the ray y = 0, x <= 0; r > 0, -pi < theta < pi
LATITUDE_LONGITUDE     sphere    (lat, lon)   the sphere minus the half meridian y = 0, x <= 0 (both poles on it)
STEREOGRAPHIC_NORTH    sphere    (u, v)       the sphere minus its north pole (projection from the north pole)
STEREOGRAPHIC_SOUTH    sphere    (u, v)       the sphere minus its south pole (projection from the south pole)

Outside its domain a chart refuses a point with ValueError naming the argument: the polar angle
of a point on the ray y = 0, x <= 0 would be either pi or -pi (the chart is not continuous
there) and the origin has no angle at all. The two stereographic charts overlap on the sphere
minus both poles, where the transition is the inversion (u, v) -> (u, v) / (u^2 + v^2).
"""
from __future__ import annotations

import abc
from typing import ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.fields.vector_fields import FieldFunction, VectorField
from gm_core.manifolds.spaces import sphere_xyz
from gm_core.manifolds.tangent import sphere_tangent_basis
from gm_core.validation import BoolArray, FloatArray, as_array, batch_shape

__all__ = [
    "Chart", "Cartesian", "Polar", "LatitudeLongitude", "Stereographic",
    "CARTESIAN", "POLAR", "LATITUDE_LONGITUDE", "STEREOGRAPHIC_NORTH", "STEREOGRAPHIC_SOUTH", "CHARTS",
    "transition_point", "transition_jacobian", "transition_vector", "transition_field", "in_overlap",
    "transition_path",
]

#: How far (relative) a point of the sphere may lie off the unit sphere and still count as on it.
ON_SPHERE_TOL = 1e-9


class Chart(abc.ABC):
    """A chart phi: U -> R^dim of a manifold embedded in R^ambient_dim (the "Manifolds" box, section 1.1).

    Subclasses give the map to the manifold phi^-1 and the chart map phi with their Jacobians,
    and say which coordinates and which points are outside the chart; the public methods validate
    and name the argument in every error.
    """

    #: Short name used in messages and plots (a class attribute, or set per instance).
    name: str
    #: The manifold the chart covers part of ("plane", "sphere").
    manifold: ClassVar[str]
    #: Dimension of the manifold (number of coordinates).
    dim: ClassVar[int] = 2
    #: Dimension of the space the manifold is embedded in (points are arrays (..., ambient_dim)).
    ambient_dim: ClassVar[int]
    #: Names of the coordinates, in order.
    coords: ClassVar[tuple[str, ...]]
    #: The domain U and the coordinates' range, in words (for error messages).
    domain: str

    # --------------------------------------------------------------------- what a chart defines
    @abc.abstractmethod
    def _to_manifold(self, q: FloatArray) -> FloatArray:
        """phi^-1: coordinates (..., dim) -> points (..., ambient_dim); ``q`` already checked."""

    @abc.abstractmethod
    def _from_manifold(self, p: FloatArray) -> FloatArray:
        """phi: points (..., ambient_dim) -> coordinates (..., dim); ``p`` already checked."""

    @abc.abstractmethod
    def _jacobian_to_manifold(self, q: FloatArray) -> FloatArray:
        """d phi^-1 / dq, (..., ambient_dim, dim): its columns are the coordinate basis vectors at q."""

    @abc.abstractmethod
    def _jacobian_from_manifold(self, p: FloatArray) -> FloatArray:
        """d phi / dp, (..., dim, ambient_dim), of a smooth extension of phi off the manifold."""

    @abc.abstractmethod
    def _outside_coordinates(self, q: FloatArray) -> BoolArray:
        """True where coordinates ``q`` are not in the chart's image phi(U)."""

    @abc.abstractmethod
    def _outside_domain(self, p: FloatArray) -> BoolArray:
        """True where points ``p`` of the manifold are not in the domain U."""

    # --------------------------------------------------------------------------- checked maps
    def check_coordinates(self, q: ArrayLike, name: str = "q") -> FloatArray:
        """``q`` as coordinates ``(..., dim)`` of this chart; ValueError naming ``name`` outside phi(U)."""
        q = as_array(q, name, (self.dim,), what=f" ({', '.join(self.coords)} in the {self.name} chart)")
        bad = self._outside_coordinates(q)
        if np.any(bad):
            first = q[np.nonzero(bad)][0] if q.ndim > 1 else q
            raise ValueError(f"{name} = {np.array2string(first, precision=4)} is outside the {self.name} chart: "
                             f"it covers {self.domain}")
        return q

    def check_point(self, p: ArrayLike, name: str = "p") -> FloatArray:
        """``p`` as points ``(..., ambient_dim)`` of the manifold inside the chart's domain, else ValueError naming ``name``."""
        p = as_array(p, name, (self.ambient_dim,), what=f" (a point of the {self.manifold})")
        off = self._off_manifold(p)
        if np.any(off):
            raise ValueError(f"{name} must lie on the {self.manifold}; {int(np.count_nonzero(off))} point(s) do not")
        bad = self._outside_domain(p)
        if np.any(bad):
            first = p[np.nonzero(bad)][0] if p.ndim > 1 else p
            raise ValueError(f"{name} = {np.array2string(first, precision=4)} is outside the domain of the "
                             f"{self.name} chart: it covers {self.domain}")
        return p

    def _off_manifold(self, p: FloatArray) -> BoolArray:
        return np.zeros(p.shape[:-1], bool)

    def to_manifold(self, q: ArrayLike) -> FloatArray:
        """The point ``(..., ambient_dim)`` phi^-1(q) named by coordinates ``q`` ``(..., dim)``."""
        return self._to_manifold(self.check_coordinates(q))

    def from_manifold(self, p: ArrayLike) -> FloatArray:
        """The coordinates ``(..., dim)`` phi(p) of the point ``p`` ``(..., ambient_dim)``."""
        return self._from_manifold(self.check_point(p))

    def jacobian_to_manifold(self, q: ArrayLike) -> FloatArray:
        """Jacobian ``(..., ambient_dim, dim)`` of phi^-1 at ``q``: column i is the velocity of the point when q_i grows at unit rate."""
        return self._jacobian_to_manifold(self.check_coordinates(q))

    def jacobian_from_manifold(self, p: ArrayLike) -> FloatArray:
        """Jacobian ``(..., dim, ambient_dim)`` of phi at ``p``: it maps a tangent vector of the manifold to coordinate rates."""
        return self._jacobian_from_manifold(self.check_point(p))

    def contains(self, p: ArrayLike) -> BoolArray:
        """True where the points ``p`` of the manifold lie in the chart's domain U."""
        p = as_array(p, "p", (self.ambient_dim,), what=f" (a point of the {self.manifold})")
        return ~self._outside_domain(p) & ~self._off_manifold(p)

    @override
    def __repr__(self) -> str:
        return f"<{self.name} chart of the {self.manifold}>"


# ------------------------------------------------------------------------------------ the plane
class Cartesian(Chart):
    """The identity chart of the plane: a point is its own coordinates (x, y)."""

    name = "Cartesian"
    manifold = "plane"
    ambient_dim = 2
    coords = ("x", "y")
    domain = "the whole plane"

    @override
    def _to_manifold(self, q: FloatArray) -> FloatArray:
        return q.copy()

    @override
    def _from_manifold(self, p: FloatArray) -> FloatArray:
        return p.copy()

    @override
    def _jacobian_to_manifold(self, q: FloatArray) -> FloatArray:
        return np.broadcast_to(np.eye(2), q.shape[:-1] + (2, 2)).copy()

    @override
    def _jacobian_from_manifold(self, p: FloatArray) -> FloatArray:
        return np.broadcast_to(np.eye(2), p.shape[:-1] + (2, 2)).copy()

    @override
    def _outside_coordinates(self, q: FloatArray) -> BoolArray:
        return np.zeros(q.shape[:-1], bool)

    @override
    def _outside_domain(self, p: FloatArray) -> BoolArray:
        return np.zeros(p.shape[:-1], bool)


class Polar(Chart):
    """Polar coordinates (r, theta) of the plane minus the ray y = 0, x <= 0: (x, y) = r (cos theta, sin theta)."""

    name = "polar"
    manifold = "plane"
    ambient_dim = 2
    coords = ("r", "theta")
    domain = "the plane minus the ray y = 0, x <= 0 (r > 0, -pi < theta < pi)"

    @override
    def _to_manifold(self, q: FloatArray) -> FloatArray:
        r, th = q[..., 0], q[..., 1]
        return np.stack([r * np.cos(th), r * np.sin(th)], -1)

    @override
    def _from_manifold(self, p: FloatArray) -> FloatArray:
        x, y = p[..., 0], p[..., 1]
        return np.stack([np.hypot(x, y), np.arctan2(y, x)], -1)

    @override
    def _jacobian_to_manifold(self, q: FloatArray) -> FloatArray:
        r, th = q[..., 0], q[..., 1]
        c, s = np.cos(th), np.sin(th)
        return np.stack([np.stack([c, -r * s], -1), np.stack([s, r * c], -1)], -2)

    @override
    def _jacobian_from_manifold(self, p: FloatArray) -> FloatArray:
        x, y = p[..., 0], p[..., 1]
        r = np.hypot(x, y)
        # d r = (x dx + y dy) / r, d theta = (x dy - y dx) / r^2; divide by r twice (no r^2 overflow)
        ux, uy = x / r, y / r
        return np.stack([np.stack([ux, uy], -1), np.stack([-uy / r, ux / r], -1)], -2)

    @override
    def _outside_coordinates(self, q: FloatArray) -> BoolArray:
        return ~((q[..., 0] > 0) & (np.abs(q[..., 1]) < np.pi))

    @override
    def _outside_domain(self, p: FloatArray) -> BoolArray:
        return (p[..., 1] == 0) & (p[..., 0] <= 0)


# ----------------------------------------------------------------------------------- the sphere
class _SphereChart(Chart):
    manifold = "sphere"
    ambient_dim = 3

    @override
    def _off_manifold(self, p: FloatArray) -> BoolArray:
        norm = np.hypot(np.hypot(p[..., 0], p[..., 1]), p[..., 2])
        return ~(np.abs(norm - 1.0) <= ON_SPHERE_TOL)


class LatitudeLongitude(_SphereChart):
    """Latitude and longitude on the unit sphere, (x, y, z) = (cos lat cos lon, cos lat sin lon, sin lat), fig. 1.6."""

    name = "latitude/longitude"
    coords = ("lat", "lon")
    domain = "the sphere minus the half meridian y = 0, x <= 0 and the poles (|lat| < pi/2, |lon| < pi)"

    @override
    def _to_manifold(self, q: FloatArray) -> FloatArray:
        return sphere_xyz(q[..., 0], q[..., 1])

    @override
    def _from_manifold(self, p: FloatArray) -> FloatArray:
        x, y, z = p[..., 0], p[..., 1], p[..., 2]
        return np.stack([np.arctan2(z, np.hypot(x, y)), np.arctan2(y, x)], -1)

    @override
    def _jacobian_to_manifold(self, q: FloatArray) -> FloatArray:
        # d/dlat is the north vector, d/dlon is cos(lat) times the east vector (fig. 1.12)
        east, north = sphere_tangent_basis(q[..., 0], q[..., 1])
        return np.stack([north, np.cos(q[..., 0])[..., None] * east], -1)

    @override
    def _jacobian_from_manifold(self, p: FloatArray) -> FloatArray:
        x, y, z = p[..., 0], p[..., 1], p[..., 2]
        rho = np.hypot(x, y)
        n2 = rho * rho + z * z
        # lat = atan2(z, rho), lon = atan2(y, x), differentiated off the sphere too
        dlat = np.stack([-z * x / (rho * n2), -z * y / (rho * n2), rho / n2], -1)
        dlon = np.stack([-y / (rho * rho), x / (rho * rho), np.zeros_like(z)], -1)
        return np.stack([dlat, dlon], -2)

    @override
    def _outside_coordinates(self, q: FloatArray) -> BoolArray:
        return ~((np.abs(q[..., 0]) < np.pi / 2) & (np.abs(q[..., 1]) < np.pi))

    @override
    def _outside_domain(self, p: FloatArray) -> BoolArray:
        return (p[..., 1] == 0) & (p[..., 0] <= 0)


class Stereographic(_SphereChart):
    """Stereographic projection of the unit sphere from a pole onto the equator's plane.

    From the north pole (``pole="north"``, s = 1) or the south pole (s = -1):
    (u, v) = (x, y) / (1 - s z), and back (x, y, z) = (2u, 2v, s (u^2 + v^2 - 1)) / (u^2 + v^2 + 1).
    The chart covers the sphere minus its projection pole; its image is the whole plane.
    """

    manifold = "sphere"
    coords = ("u", "v")

    def __init__(self, pole: Literal["north", "south"]) -> None:
        if pole not in ("north", "south"):
            raise ValueError(f"pole must be 'north' or 'south'; got {pole!r:.40}")
        self.pole = pole
        self.s = 1.0 if pole == "north" else -1.0
        self.name = f"stereographic ({pole})"
        self.domain = f"the sphere minus its {pole} pole"

    @override
    def _to_manifold(self, q: FloatArray) -> FloatArray:
        u, v = q[..., 0], q[..., 1]
        d = 1.0 + u * u + v * v
        return np.stack([2 * u / d, 2 * v / d, self.s * (1.0 - 2.0 / d)], -1)

    @override
    def _from_manifold(self, p: FloatArray) -> FloatArray:
        w = 1.0 - self.s * p[..., 2]
        return p[..., :2] / w[..., None]

    @override
    def _jacobian_to_manifold(self, q: FloatArray) -> FloatArray:
        u, v = q[..., 0], q[..., 1]
        d = 1.0 + u * u + v * v
        a, b = 2.0 / d, 4.0 / (d * d)
        rows = [np.stack([a - b * u * u, -b * u * v], -1),
                np.stack([-b * u * v, a - b * v * v], -1),
                np.stack([self.s * b * u, self.s * b * v], -1)]
        return np.stack(rows, -2)

    @override
    def _jacobian_from_manifold(self, p: FloatArray) -> FloatArray:
        x, y, z = p[..., 0], p[..., 1], p[..., 2]
        w = 1.0 - self.s * z
        zero = np.zeros_like(z)
        return np.stack([np.stack([1.0 / w, zero, self.s * x / (w * w)], -1),
                         np.stack([zero, 1.0 / w, self.s * y / (w * w)], -1)], -2)

    @override
    def _outside_coordinates(self, q: FloatArray) -> BoolArray:
        return np.zeros(q.shape[:-1], bool)

    @override
    def _outside_domain(self, p: FloatArray) -> BoolArray:
        return self.s * p[..., 2] >= 1.0 - 1e-15

    @override
    def __eq__(self, other: object) -> bool:
        return isinstance(other, Stereographic) and other.pole == self.pole

    @override
    def __hash__(self) -> int:
        return hash(("stereographic", self.pole))


CARTESIAN = Cartesian()
POLAR = Polar()
LATITUDE_LONGITUDE = LatitudeLongitude()
STEREOGRAPHIC_NORTH = Stereographic("north")
STEREOGRAPHIC_SOUTH = Stereographic("south")
#: Every chart of the module by a short key.
CHARTS: dict[str, Chart] = {"cartesian": CARTESIAN, "polar": POLAR, "latlon": LATITUDE_LONGITUDE,
                            "north": STEREOGRAPHIC_NORTH, "south": STEREOGRAPHIC_SOUTH}


# ----------------------------------------------------------------------------------- transitions
def _check_pair(chart1: Chart, chart2: Chart) -> None:
    for name, c in (("chart1", chart1), ("chart2", chart2)):
        if not isinstance(c, Chart):
            raise TypeError(f"{name} must be a Chart (e.g. gm_core.manifolds.charts.POLAR); got {type(c).__name__}")
    if chart1.manifold != chart2.manifold:
        raise ValueError(f"chart1 and chart2 must cover one manifold; got a chart of the {chart1.manifold} "
                         f"and a chart of the {chart2.manifold}")


def _overlap_point(q1: ArrayLike, chart1: Chart, chart2: Chart, name: str) -> tuple[FloatArray, FloatArray]:
    """``q1`` checked in chart 1 and its point checked in chart 2's domain (errors name ``name``)."""
    _check_pair(chart1, chart2)
    q1 = chart1.check_coordinates(q1, name)
    p = chart1._to_manifold(q1)
    bad = chart2._outside_domain(p)
    if np.any(bad):
        first = q1[np.nonzero(bad)][0] if q1.ndim > 1 else q1
        raise ValueError(f"{name} = {np.array2string(first, precision=4)} ({chart1.name}) is outside the overlap: "
                         f"its point is outside the {chart2.name} chart, which covers {chart2.domain}")
    return q1, p


def in_overlap(q1: ArrayLike, chart1: Chart, chart2: Chart) -> BoolArray:
    """True ``(...)`` where coordinates ``q1`` of chart 1 name a point that chart 2 also covers."""
    _check_pair(chart1, chart2)
    q1 = as_array(q1, "q1", (chart1.dim,), what=f" (coordinates in the {chart1.name} chart)")
    ok = ~chart1._outside_coordinates(q1)
    p = chart1._to_manifold(np.where(ok[..., None], q1, 1.0))   # placeholder coordinates where not ok
    return ok & ~chart2._outside_domain(p)


def transition_point(q1: ArrayLike, chart1: Chart, chart2: Chart) -> FloatArray:
    """Coordinates ``(..., dim)`` in chart 2 of the point named ``q1`` in chart 1: the overlap map phi_2 o phi_1^-1 (section 1.1)."""
    q1, p = _overlap_point(q1, chart1, chart2, "q1")
    return chart2._from_manifold(p)


def transition_jacobian(q1: ArrayLike, chart1: Chart, chart2: Chart) -> FloatArray:
    """Jacobian ``(..., dim, dim)`` of the overlap map phi_2 o phi_1^-1 at ``q1``, by the chain rule
    J_12 = (d phi_2 / dp)(p) (d phi_1^-1 / dq)(q1)."""
    q1, p = _overlap_point(q1, chart1, chart2, "q1")
    return chart2._jacobian_from_manifold(p) @ chart1._jacobian_to_manifold(q1)


def transition_vector(q1: ArrayLike, v1: ArrayLike, chart1: Chart, chart2: Chart) -> tuple[FloatArray, FloatArray]:
    """A tangent vector ``v1`` at ``q1`` (chart 1) in chart 2: ``(q2, v2)`` with v2 = J_12(q1) v1, the pushforward."""
    q1, p = _overlap_point(q1, chart1, chart2, "q1")
    v1 = as_array(v1, "v1", (chart1.dim,), what=f" (a tangent vector in the {chart1.name} chart)")
    batch_shape(("q1", q1, 1), ("v1", v1, 1))
    J = chart2._jacobian_from_manifold(p) @ chart1._jacobian_to_manifold(q1)
    v2 = np.einsum("...ij,...j->...i", J, v1)
    q2 = np.broadcast_to(chart2._from_manifold(p), v2.shape).copy()
    return q2, v2


def transition_field(field: VectorField | FieldFunction, chart1: Chart, chart2: Chart) -> VectorField:
    """The vector field ``field`` given in chart 1 re-expressed in chart 2:
    X_2(q2, t) = J_12(q1) X_1(q1, t) at q1 = phi_1 o phi_2^-1(q2).

    ``field`` is a :class:`~gm_core.fields.VectorField` of dimension ``chart1.dim`` or a callable
    ``(q, t) -> q_dot`` taking arrays ``(..., dim)``. The new field refuses (ValueError naming ``q``)
    points of chart 2 outside the overlap.
    """
    _check_pair(chart1, chart2)
    if isinstance(field, VectorField):
        X1 = field
        if X1.dim != chart1.dim:
            raise ValueError(f"field must have dimension {chart1.dim} (the {chart1.name} chart's); got {X1.dim}")
    elif callable(field):
        X1 = VectorField(field, chart1.dim, name=getattr(field, "__name__", "X"))
    else:
        raise TypeError(f"field must be a VectorField or a callable (q, t) -> q_dot; got {type(field).__name__}")

    def in_chart2(q2: FloatArray, t: float) -> FloatArray:
        q2c, p = _overlap_point(q2, chart2, chart1, "q")
        q1 = chart1._from_manifold(p)
        J = chart2._jacobian_from_manifold(p) @ chart1._jacobian_to_manifold(q1)
        return np.einsum("...ij,...j->...i", J, X1(q1, t))

    return VectorField(in_chart2, chart2.dim, name=f"{X1.name} in the {chart2.name} chart")


def transition_path(q1: ArrayLike, chart1: Chart, chart2: Chart) -> list[FloatArray]:
    """A path sampled in chart 1, ``q1`` of shape ``(m, dim)``, drawn in chart 2: a list of ``(k, dim)`` pieces.

    The path is cut where a sample is outside the overlap and where it crosses the edge of chart 2
    between two samples (the polar chart's ray, where theta jumps by 2 pi): there the image of the
    step's midpoint is far from the midpoint of the imaged step. Pieces of one point are dropped.
    """
    _check_pair(chart1, chart2)
    q1 = as_array(q1, "q1", (chart1.dim,), what=f" (a path in the {chart1.name} chart)")
    if q1.ndim != 2:
        raise ValueError(f"q1 must be a path of shape (m, {chart1.dim}); got shape {q1.shape}")
    ok = in_overlap(q1, chart1, chart2)
    safe = np.where(ok[:, None], q1, q1[np.argmax(ok)] if ok.any() else 0.0)
    q2 = chart2._from_manifold(chart1._to_manifold(safe)) if ok.any() else np.zeros_like(q1)
    mid1 = 0.5 * (q1[1:] + q1[:-1])
    mid_ok = in_overlap(mid1, chart1, chart2) & ok[1:] & ok[:-1]
    mid_safe = np.where(mid_ok[:, None], mid1, safe[:-1])
    mid2 = chart2._from_manifold(chart1._to_manifold(mid_safe))
    step = np.hypot.reduce(q2[1:] - q2[:-1], axis=-1)          # hypot: no overflow of squares
    bend = np.hypot.reduce(mid2 - 0.5 * q2[1:] - 0.5 * q2[:-1], axis=-1)
    joined = mid_ok & (bend <= 0.25 * step + 1e-12)
    pieces: list[FloatArray] = []
    start = 0
    for i in range(len(q1)):
        if i == len(q1) - 1 or not joined[i]:
            piece = q2[start:i + 1][ok[start:i + 1]]
            if len(piece) > 1:
                pieces.append(piece)
            start = i + 1
    return pieces
