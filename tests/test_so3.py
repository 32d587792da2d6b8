"""SO(3) in rotation vectors, checked against routes that share no code with gm_core.groups.so3:
scipy's expm, logm and Rotation, 50-digit mpmath, exact rotations, and finite differences of
scipy's composition. The group laws (tests/test_group_laws.py) run over SO(3) as well."""
import mpmath as mp
import numpy as np
import pytest
import scipy.linalg
import scipy.stats
from scipy.spatial.transform import Rotation

from gm_core import SO3
from gm_core.groups.so3 import RANDOM_MARGIN

RNG_SEED = 20240537
ANGLES = [1e-300, 1e-12, 1e-8, 1e-6, 1e-3, 0.5, 1.0, 2.0, 3.0, np.pi - 1e-6, np.pi - 1e-9, np.pi - 1e-12]
AXES = [(1.0, 0.0, 0.0), (0.0, 0.0, -1.0), (1.0, 2.0, 2.0), (-0.3, 0.7, 0.2)]


def unit(a):
    a = np.asarray(a, float)
    return a / np.linalg.norm(a)


def mp_rodrigues(r):
    """exp(r^) in 50 digits: cos th I + (1 - cos th) u u^T + sin th [u]x from the exact r."""
    with mp.workdps(50):
        r = [mp.mpf(float(x)) for x in r]
        th = mp.sqrt(sum(x * x for x in r))
        u = [x / th for x in r]
        c, s = mp.cos(th), mp.sin(th)
        K = mp.matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
        uu = mp.matrix(3, 3)
        for i in range(3):
            for j in range(3):
                uu[i, j] = u[i] * u[j]
        return c * mp.eye(3) + (1 - c) * uu + s * K


def mp_log(M):
    """The rotation vector of the nearest rotation to the (rounded) matrix M, in 50 digits.

    Polar factor by mpmath's SVD, then theta = atan2(|v|, (tr R - 1) / 2) with v = vee(R - R^T) / 2
    = sin(theta) u; near pi the axis comes from the symmetric part (R + R^T) / 2 - cos(theta) I =
    (1 - cos theta) u u^T instead (at 50 digits no step of this loses the 16 that matter).
    """
    with mp.workdps(50):
        U, _, V = mp.svd_r(mp.matrix([[mp.mpf(float(x)) for x in row] for row in M]))
        R = U * V
        v = [(R[2, 1] - R[1, 2]) / 2, (R[0, 2] - R[2, 0]) / 2, (R[1, 0] - R[0, 1]) / 2]
        s, c = mp.sqrt(sum(x * x for x in v)), (R[0, 0] + R[1, 1] + R[2, 2] - 1) / 2
        theta = mp.atan2(s, c)
        if theta < 3:
            return [theta * x / s for x in v] if s else [mp.mpf(0)] * 3
        k = max(range(3), key=lambda i: R[i, i])
        col = [(R[i, k] + R[k, i]) / 2 - (c if i == k else 0) for i in range(3)]
        u = [x / mp.sqrt(col[k] * (1 - c)) for x in col]
        sign = 1 if sum(a * b for a, b in zip(u, v)) >= 0 else -1
        return [sign * theta * x for x in u]


def rel_err(got, ref):
    with mp.workdps(50):
        num = mp.sqrt(sum((mp.mpf(float(g)) - r) ** 2 for g, r in zip(got, ref)))
        return float(num / mp.sqrt(sum(r ** 2 for r in ref)))


# ------------------------------------------------------------------ exp, matrix and log
def test_exp_is_expm_of_the_skew_matrix_at_any_length():
    rng = np.random.default_rng(RNG_SEED)
    xi = rng.normal(size=(40, 3)) * rng.uniform(0.0, 4.0, (40, 1))      # lengths up to ~ 4 pi
    for x, R in zip(xi, SO3.matrix(SO3.exp(xi))):
        np.testing.assert_allclose(R, scipy.linalg.expm(SO3.hat(x)), atol=1e-13)
    assert np.all(np.linalg.norm(SO3.exp(xi), axis=-1) <= np.pi + 1e-15)


@pytest.mark.parametrize("theta", ANGLES)
@pytest.mark.parametrize("axis", AXES)
def test_matrix_is_accurate_to_rounding_at_every_angle(theta, axis):
    r = theta * unit(axis)
    R = SO3.matrix(r)
    ref = mp_rodrigues(r)
    with mp.workdps(50):
        err = max(abs(mp.mpf(float(R[i, j])) - ref[i, j]) for i in range(3) for j in range(3))
        # off-diagonal entries, of order sin(theta) at small angles, keep their relative accuracy:
        # no 1 - cos theta cancellation
        small = max((abs(mp.mpf(float(R[i, j])) - ref[i, j]) / abs(ref[i, j])
                     for i in range(3) for j in range(3) if i != j and ref[i, j] != 0), default=0)
    assert float(err) < 4e-16
    assert float(small) < 1e-15


@pytest.mark.parametrize("theta", ANGLES)
@pytest.mark.parametrize("axis", AXES)
def test_from_matrix_is_accurate_near_zero_and_near_pi(theta, axis):
    """log of the rounded matrix against the 50-digit logm of that same rounded matrix."""
    M = SO3.matrix(theta * unit(axis))
    got = SO3.from_matrix(M)
    assert rel_err(got, mp_log(M)) < 1e-15
    assert np.linalg.norm(got) <= np.pi


@pytest.mark.parametrize("M, expected", [
    (np.diag([1.0, -1.0, -1.0]), [np.pi, 0.0, 0.0]),
    (np.diag([-1.0, -1.0, 1.0]), [0.0, 0.0, np.pi]),
    (np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]]), [np.pi / np.sqrt(2), np.pi / np.sqrt(2), 0.0]),
    (np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]), [0.0, 0.0, np.pi / 2]),
    (np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), [2 * np.pi / 3 / np.sqrt(3)] * 3),
    (np.eye(3), [0.0, 0.0, 0.0]),
])
def test_from_matrix_of_exact_rotations(M, expected):
    got = SO3.from_matrix(M)
    if np.isclose(np.linalg.norm(expected), np.pi):        # a half turn: r and -r are one rotation
        got = got if got @ np.asarray(expected) > 0 else -got
    np.testing.assert_allclose(got, expected, atol=2e-15)
    assert SO3.isclose(got, expected, atol=1e-15)


def test_log_agrees_with_scipy_rotvec():
    R = Rotation.random(200, random_state=RNG_SEED)
    got = SO3.from_matrix(R.as_matrix())
    ref = R.as_rotvec()
    keep = np.linalg.norm(ref, axis=-1) < np.pi - 1e-6          # off the half turns, one principal vector
    np.testing.assert_allclose(got[keep], ref[keep], atol=1e-14)
    assert SO3.isclose(got, ref, atol=1e-12).all()


def test_compose_and_inverse_agree_with_scipy():
    rng = np.random.default_rng(RNG_SEED)
    g, h = SO3.random(rng, 100), SO3.random(rng, 100)
    ref = (Rotation.from_rotvec(g) * Rotation.from_rotvec(h)).as_rotvec()
    assert SO3.isclose(SO3.compose(g, h), ref, atol=1e-13).all()
    assert SO3.isclose(SO3.inverse(g), Rotation.from_rotvec(g).inv().as_rotvec(), atol=1e-15).all()


def test_compose_of_tiny_rotations_keeps_relative_accuracy():
    a, b = np.array([1e-12, 0.0, 0.0]), np.array([0.0, 2e-12, 0.0])
    got = SO3.compose(a, b)
    with mp.workdps(50):
        L = mp.logm(mp_rodrigues(a) * mp_rodrigues(b))          # near e, the principal log is plain
        ref = [mp.re(L[2, 1]), mp.re(L[0, 2]), mp.re(L[1, 0])]
    assert rel_err(got, ref) < 1e-15


# ------------------------------------------------------------------ large vectors and the cut
def reduced(theta):
    """theta modulo 2 pi in (-pi, pi], in enough digits for any double."""
    with mp.workdps(340):
        t = mp.mpf(theta)
        r = t - 2 * mp.pi * mp.floor(t / (2 * mp.pi) + mp.mpf(1) / 2)
        return r + 2 * mp.pi if r <= -mp.pi else r


@pytest.mark.parametrize("length", [4.0, 7.0, 1e3, 1e8, 1e15, 1e300])
def test_long_vectors_reduce_their_angle_exactly(length):
    r = np.array([3.0, 0.0, 4.0]) * (length / 5.0)
    theta = float(np.hypot(r[0], r[2]))
    got = SO3.exp(r)
    ref = reduced(theta)
    signed = np.linalg.norm(got) * np.sign(got @ r)
    assert abs(mp.mpf(float(signed)) - ref) <= 2 * np.spacing(np.pi)
    np.testing.assert_allclose(SO3.matrix(got), SO3.matrix(r), atol=1e-14)     # one rotation


def test_principal_vectors_and_the_half_turn():
    u = unit([1.0, -2.0, 0.5])
    half = np.pi * u
    assert SO3.contains(half) and SO3.contains(-half)
    assert not SO3.contains(1.5 * np.pi * u)
    np.testing.assert_allclose(SO3.project(1.5 * np.pi * u), -0.5 * np.pi * u, atol=1e-15)
    np.testing.assert_array_equal(SO3.project(0.5 * u), 0.5 * u)
    # r and -r at |r| = pi are one rotation: zero difference, and the same matrix
    np.testing.assert_allclose(SO3.difference(half, -half), 0.0, atol=1e-15)
    assert SO3.isclose(half, -half) and SO3.isclose(-half, half)
    np.testing.assert_allclose(SO3.matrix(half), SO3.matrix(-half), atol=1e-15)
    # just across the cut: the difference is the small step, measured in the chart around g
    a, b = (np.pi - 1e-7) * u, -(np.pi - 2e-7) * u            # 3e-7 apart through the half turn
    np.testing.assert_allclose(SO3.difference(a, b), -3e-7 * u, atol=1e-15)
    np.testing.assert_allclose(SO3.difference(b, a), 3e-7 * u, atol=1e-15)
    assert not SO3.isclose(half, 0.5 * half, atol=1.0)


def test_exp_log_round_trip_on_the_principal_ball_and_beyond():
    u = unit([0.3, 0.4, -1.0])
    for t in (0.0, 1e-9, 1.0, np.pi - 1e-9):
        np.testing.assert_array_equal(SO3.log(SO3.exp(t * u)), t * u)
    # a vector beyond pi comes back as the other representative of its rotation
    np.testing.assert_allclose(SO3.log(SO3.exp((np.pi + 0.5) * u)), -(np.pi - 0.5) * u, atol=1e-15)


# ------------------------------------------------------------------ lifted actions and adjoint
def scipy_compose(a, b):
    return (Rotation.from_rotvec(a) * Rotation.from_rotvec(b)).as_rotvec()


def fd_jacobian(f, x, eps=1e-6):
    cols = []
    for j in range(3):
        d = np.zeros(3)
        d[j] = eps
        cols.append(SO3.difference(f(x + d), f(x - d)) / (2 * eps))
    return np.stack(cols, -1)


@pytest.mark.parametrize("seed", range(8))
def test_lifted_actions_are_derivatives_of_scipys_composition(seed):
    rng = np.random.default_rng(seed)
    h, g = SO3.random(rng), SO3.random(rng)
    if seed == 0:
        g = 1e-9 * unit([1.0, 2.0, 3.0])                     # near the identity
    if seed == 1:
        g = (np.pi - 1e-3) * unit([1.0, 1.0, 0.0])           # near the half turn
    np.testing.assert_allclose(SO3.left_lifted_action(h, g), fd_jacobian(lambda x: scipy_compose(h, x), g), atol=1e-8)
    np.testing.assert_allclose(SO3.right_lifted_action(h, g), fd_jacobian(lambda x: scipy_compose(x, h), g), atol=1e-8)


def test_lifted_actions_at_the_identity_and_the_velocity_of_a_rotating_body():
    """T_e L_g xi is the rate of the rotation vector of g(t) = g exp(t xi) (spinning in the body frame)."""
    rng = np.random.default_rng(RNG_SEED)
    g, xi = SO3.random(rng), rng.normal(size=3)
    e = SO3.identity()
    for lifted, path in ((SO3.left_lifted_action, lambda t: scipy_compose(g, t * xi)),
                         (SO3.right_lifted_action, lambda t: scipy_compose(t * xi, g))):
        rate = SO3.difference(path(1e-6), path(-1e-6)) / 2e-6
        np.testing.assert_allclose(lifted(g, e) @ xi, rate, atol=1e-8)
    np.testing.assert_allclose(SO3.left_lifted_action(e, g), np.eye(3), atol=1e-15)


def nearest_representative(p, target):
    """Of the principal vector p and its other representative p - 2 pi p/|p|, the one nearer target."""
    other = p - 2 * np.pi * p / np.linalg.norm(p)
    return other if np.linalg.norm(other - target) < np.linalg.norm(p - target) else p


def test_velocities_past_the_cut_are_in_the_elements_own_chart():
    """An Euler state or ODE state past |r| = pi keeps its chart: T_e L_g xi is the rate of the
    coordinates that continue g (not of the principal ones), read from scipy's composition."""
    u, xi = unit([1.0, -1.0, 0.5]), np.array([0.3, 0.8, -0.4])
    g = (np.pi + 0.4) * u                                     # past the cut, a valid chart up to 2 pi
    assert np.array_equal(SO3.compose(g, SO3.identity()), g) and np.array_equal(SO3.compose(SO3.identity(), g), g)
    for lifted, path in ((SO3.left_lifted_action, lambda t: scipy_compose(g, t * xi)),
                         (SO3.right_lifted_action, lambda t: scipy_compose(t * xi, g))):
        ahead, behind = (nearest_representative(path(t), g) for t in (1e-6, -1e-6))
        np.testing.assert_allclose(lifted(g, SO3.identity()) @ xi, (ahead - behind) / 2e-6, atol=1e-8)
    # the body velocity read back at g is xi again
    np.testing.assert_allclose(SO3.world_to_body(g, SO3.body_to_world(g, xi)), xi, atol=1e-14)


def test_adjoint_is_the_rotation_and_bracket_the_cross_product():
    rng = np.random.default_rng(RNG_SEED)
    g = SO3.random(rng, 5)
    x, y = rng.normal(size=(2, 5, 3))
    np.testing.assert_allclose(SO3.Ad(g), Rotation.from_rotvec(g).as_matrix(), atol=1e-15)
    np.testing.assert_allclose(SO3.Ad_inv(g), np.linalg.inv(Rotation.from_rotvec(g).as_matrix()), atol=1e-15)
    cross = np.stack([x[..., 1] * y[..., 2] - x[..., 2] * y[..., 1], x[..., 2] * y[..., 0] - x[..., 0] * y[..., 2],
                      x[..., 0] * y[..., 1] - x[..., 1] * y[..., 0]], -1)
    np.testing.assert_allclose(SO3.bracket(x, y), cross, atol=1e-15)
    np.testing.assert_allclose(SO3.ad(x[0]) @ y[0], cross[0], atol=1e-15)


# ------------------------------------------------------------------ random, nearest element
def test_random_is_uniform_and_clear_of_the_cut():
    g = SO3.random(np.random.default_rng(RNG_SEED), (20000,))
    theta = np.linalg.norm(g, axis=-1)
    assert theta.max() < np.pi - RANDOM_MARGIN
    # Haar measure: the angle has density (1 - cos t) / pi on [0, pi]; the axis is uniform
    cdf = lambda t: (t - np.sin(t)) / np.pi                  # noqa: E731
    assert scipy.stats.kstest(theta, cdf).pvalue > 1e-3
    assert np.abs(SO3.matrix(g).mean(axis=0)).max() < 0.03   # E[R] = 0 for the uniform rotation
    assert np.all(SO3.random(3, (4,), scale=0.1) == 0.1 * SO3.random(3, (4,)))
    assert SO3.random(np.random.default_rng(1), (2, 3)).shape == (2, 3, 3)


def test_nearest_element_is_the_polar_factor():
    rng = np.random.default_rng(RNG_SEED)
    g = SO3.random(rng, 6)
    M = 1.7 * SO3.matrix(g) + 0.05 * rng.normal(size=(6, 3, 3))
    for m, got in zip(M, SO3.nearest_element(M)):
        P, _ = scipy.linalg.polar(m)
        np.testing.assert_allclose(SO3.matrix(got), P, atol=1e-13)
    assert SO3.isclose(SO3.nearest_element(SO3.matrix(g)), g, atol=1e-14).all()
    assert np.isfinite(SO3.nearest_element(np.zeros((3, 3)))).all()
    np.testing.assert_allclose(SO3.nearest_element(1e300 * SO3.matrix(g[0])), g[0], atol=1e-14)


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize("G", [
    np.diag([2.0, 1.0, 1.0]),                                            # scaling
    np.diag([1.0, 1.0, -1.0]),                                           # reflection, det -1
    np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),       # shear
    -np.eye(3),                                                          # point reflection
    np.diag([1.000004, 1.000004, 1.0]),                                  # off by more than the tolerance
], ids=["scaling", "reflection", "shear", "point-reflection", "nearly"])
def test_from_matrix_refuses_non_rotations(G):
    with pytest.raises(ValueError, match=r"^G is not a rotation: it must satisfy G\^T G = I and det G = \+1"):
        SO3.from_matrix(G)


def test_wrong_shapes_and_values_are_named():
    with pytest.raises(ValueError, match=r"^G must have shape \(\.\.\., 3, 3\)"):
        SO3.from_matrix(np.eye(2))
    with pytest.raises(ValueError, match=r"^g must have shape \(\.\.\., 3\)"):
        SO3.matrix([1.0, 2.0])
    with pytest.raises(ValueError, match=r"^h must have shape"):
        SO3.compose([0.0, 0.0, 0.0], [1.0, 2.0, 3.0, 4.0])
    with pytest.raises(ValueError, match=r"^X must be a skew-symmetric so\(3\) matrix"):
        SO3.vee(np.eye(3))
    with pytest.raises(ValueError, match=r"^g is too large"):
        SO3.matrix([1.7e308, 1.7e308, 0.0])
    with pytest.raises(ValueError, match=r"^xi is too large"):
        SO3.exp([1.5e308, -1.5e308, 1.5e308])
    with pytest.raises(ValueError, match=r"^h is too large"):
        SO3.difference([0.0, 0.0, 0.0], [1.5e308, 1.5e308, 0.0])
    with pytest.raises(TypeError, match=r"^g must be a numeric array"):
        SO3.log("r")
    assert not SO3.contains([1.5e308, 1.5e308, 0.0])
