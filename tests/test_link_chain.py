"""Chains of any number of links (gm_core.systems.LinkChain): every formula against an independent route.

Routes: the book's three-link closed forms (2.57)-(2.59) assembled link by link (N = 3), the chapter-2 frame graph (kinematics.MobileChain),
finite differences of the forward kinematics, the resistive-force law integrated by quadrature
(fluids.drag_wrench) and momentum summed link by link along integrated gaits, the group's own
inverse and a mirror reflection.
"""
import numpy as np
import pytest

from gm_core import SE2
from gm_core.chains import MobileChain
from gm_core.geometry import centre_of_mass_coordinates, fourier_gait, stokes_estimate
from gm_core.printing import shown
from gm_core.systems import FloatingSnake, HighReSwimmer, LinkChain, LowReSwimmer
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.fluids import drag_wrench
from gm_core.systems.gaits import circle_gait
from gm_core.systems.motion import net_displacement, trajectory

RNG = np.random.default_rng(22)
LENGTHS3 = (1.0, 1.3, 0.7)
BATCHES = [(), (1,), (4,), (3, 1, 2)]


def _shapes(n, batch, scale=2.0):
    return RNG.uniform(-scale, scale, batch + (n,))


# ------------------------------------------------------------------ N = 3: the book's closed forms
def _book_jacobians(alpha, lengths):
    """(2.57)-(2.59) as corrected in the errata, written out: the three links' Jacobians (..., 3, 3, 5)
    from (xi_middle, alpha_dot); the closed form the three-link systems had before they became LinkChain."""
    l1, l2, l3 = lengths
    c1, s1, c2, s2 = np.cos(alpha[..., 0]), np.sin(alpha[..., 0]), np.cos(alpha[..., 1]), np.sin(alpha[..., 1])
    J = np.zeros(alpha.shape[:-1] + (3, 3, 5))
    J[..., 0, 0, :3], J[..., 0, 1, :3] = np.stack([c1, -s1, l2 * s1 / 2], -1), np.stack([s1, c1, -(l2 * c1 + l1) / 2], -1)
    J[..., 0, 1, 3], J[..., 0, 2, 2], J[..., 0, 2, 3] = l1 / 2, 1.0, -1.0
    J[..., 1, :, :3] = np.eye(3)
    J[..., 2, 0, :3], J[..., 2, 1, :3] = np.stack([c2, s2, l2 * s2 / 2], -1), np.stack([-s2, c2, (l2 * c2 + l3) / 2], -1)
    J[..., 2, 1, 4], J[..., 2, 2, 2], J[..., 2, 2, 4] = l3 / 2, 1.0, 1.0
    return J


def _book_poses(alpha, lengths):
    l1, l2, l3 = lengths
    a1, a2 = alpha[..., 0], alpha[..., 1]
    P = np.zeros(alpha.shape[:-1] + (3, 3))
    P[..., 0, :] = np.stack([-l2 / 2 - l1 / 2 * np.cos(a1), l1 / 2 * np.sin(a1), -a1], -1)
    P[..., 2, :] = np.stack([l2 / 2 + l3 / 2 * np.cos(a2), l3 / 2 * np.sin(a2), a2], -1)
    return P


@pytest.mark.parametrize("system, matrices", [
    (LowReSwimmer(LENGTHS3, drag_ratio=3.0), [np.diag([l, 3 * l, 3 * l ** 3 / 12]) for l in LENGTHS3]),
    (LinkChain(LENGTHS3, "low_re", drag_ratio=3.0), [np.diag([l, 3 * l, 3 * l ** 3 / 12]) for l in LENGTHS3]),
    (FloatingSnake(LENGTHS3, masses=(1, 2, 3), frame="middle"),
     [np.diag([m, m, m * l ** 2 / 12]) for m, l in zip((1, 2, 3), LENGTHS3)]),
    (LowReSwimmer(), [np.diag([1, 2, 2 / 12])] * 3),
], ids=["low_re", "chain", "floating", "defaults"])
def test_three_links_are_the_books_closed_forms(system, matrices):
    """N = 3 (the named three-link classes are LinkChain) against (2.57)-(2.59) written out and
    the Pfaffian assembled link by link, sum J_i^T M_i J_i (3.39), (3.44)."""
    for batch in BATCHES:
        r = _shapes(2, batch)
        J = _book_jacobians(r, system.lengths)
        D = sum(np.swapaxes(J[..., i, :, :], -1, -2) @ M @ J[..., i, :, :] for i, M in enumerate(matrices))
        np.testing.assert_allclose(system.link_jacobians(r), J, atol=1e-14)
        np.testing.assert_allclose(system.link_poses(r), _book_poses(r, system.lengths), atol=1e-15)
        np.testing.assert_allclose(system.metric(r), D, atol=1e-13)
        np.testing.assert_allclose(system.pfaffian(r), D[..., :3, :], atol=1e-13)
        np.testing.assert_allclose(system.connection(r), np.linalg.solve(D[..., :3, :3], D[..., :3, 3:]), atol=1e-13)


def test_high_re_three_links_are_the_books_closed_forms():
    s = HighReSwimmer(LENGTHS3, aspect_ratio=6.0, body_density=0.3)
    from gm_core.systems.fluids import ellipse_added_mass

    Ms = [np.diag([m, m, m * (a * a + b * b) / 4]) + ellipse_added_mass(a, b, 1.0)
          for a, b, m in ((l / 2, l / 12, 0.3 * np.pi * l * l / 24) for l in LENGTHS3)]
    r = _shapes(2, (3, 4))
    J = _book_jacobians(r, LENGTHS3)
    D = sum(np.swapaxes(J[..., i, :, :], -1, -2) @ M @ J[..., i, :, :] for i, M in enumerate(Ms))
    np.testing.assert_allclose(s.mass_matrix(r), D, atol=1e-13)
    assert isinstance(s, LinkChain) and s.n_links == 3 and s.name == "high-Reynolds swimmer"


class _BookThreeLinks(LocomotionSystem):
    """The closed form the three-link systems had before they became LinkChain: the Pfaffian
    sum J_i^T M_i J_i (3.39) of the book's Jacobians (2.57)-(2.59), middle-link frame."""

    def __init__(self, lengths, matrices):
        self.lengths, self.matrices = lengths, matrices

    def pfaffian(self, r):
        J = _book_jacobians(self._shape(r), self.lengths)
        return sum((np.swapaxes(J[..., i, :, :], -1, -2) @ M @ J[..., i, :, :])[..., :3, :]
                   for i, M in enumerate(self.matrices))

    def parts(self):
        return []

    def part_poses(self, r):
        return np.zeros(self._shape(r).shape[:-1] + (0, 3))


def test_values_printed_by_the_three_link_notebooks_are_the_closed_forms_to_the_digit():
    """What notebooks 09 and 10 and exercise 4.1 print from LinkChain(N = 3) (body velocity, one
    loop's net displacement, the Stokes estimate), printed through ``shown`` at their digits,
    is the closed form's to the last digit: computed by either route, the student sees the same."""
    L = (1.0, 1.2, 0.8)
    sw = LowReSwimmer(L, drag_ratio=2.0)
    book = _BookThreeLinks(L, [np.diag([l, 2 * l, 2 * l ** 3 / 12]) for l in L])
    r, rd = np.array([0.7, -0.9]), np.array([0.5, 1.0])                    # notebook 09, the drag check
    assert shown(sw.body_velocity(r, rd), 4).tolist() == shown(book.body_velocity(r, rd), 4).tolist()
    unit = _BookThreeLinks((1.0,) * 3, [np.diag([1, 2, 2 / 12])] * 3)
    floating = _BookThreeLinks((1.0,) * 3, [np.diag([1, 1, 1 / 12])] * 3)
    for s, ref, gait, digits in [
            (LowReSwimmer(), unit, circle_gait(1.0), 4),                      # notebook 09, g(T)
            (FloatingSnake(frame="middle"), floating, circle_gait(1.0, (0.5, 0.0)), 5),
            (LowReSwimmer(), unit, circle_gait(2.2), 4)]:                     # exercise 4.1, ring C
        assert shown(net_displacement(s, gait), digits).tolist() == shown(net_displacement(ref, gait), digits).tolist()
    np.testing.assert_array_equal(shown(stokes_estimate(LowReSwimmer(), circle_gait(2.2)), 4),
                                  shown(stokes_estimate(unit, circle_gait(2.2)), 4))
    assert shown(net_displacement(LowReSwimmer(), circle_gait(1.0))[2], 12) == 0.0   # centred: no turn


def test_centre_of_mass_frame_is_the_reframed_three_link_system():
    """frame='com' (lengths as weights, mean orientation) = centre_of_mass_coordinates of today's swimmer
    (the generic route: Reframed with a finite-difference frame Jacobian); for the floating chain the
    centre of mass does not move (zero momentum), and its theta row is the section-3.4.3 frame's
    ('com middle': centre of mass, middle-link axes) minus the rate of the mean orientation."""
    r = _shapes(2, (30,))
    np.testing.assert_allclose(LinkChain(LENGTHS3, frame="com").connection(r),
                               centre_of_mass_coordinates(LowReSwimmer(LENGTHS3)).connection(r), atol=1e-8)
    fl = LinkChain(LENGTHS3, "floating", masses=(1, 2, 1.5), frame="com")
    A = fl.connection(r)
    assert np.abs(A[..., :2, :]).max() < 1e-13
    book = FloatingSnake(LENGTHS3, (1, 2, 1.5)).connection(r)          # frame "com middle", (3.38)
    assert np.abs(book[..., :2, :]).max() < 1e-13
    np.testing.assert_allclose(A[..., 2, :], book[..., 2, :] - [-1 / 4.5, 1.5 / 4.5], atol=1e-13)
    np.testing.assert_allclose(FloatingSnake(LENGTHS3, (1, 2, 1.5), frame="com").connection(r), A, atol=1e-15)
    np.testing.assert_allclose(book[..., 2, :], FloatingSnake(LENGTHS3, (1, 2, 1.5), frame="middle").connection(r)[..., 2, :],
                               atol=1e-13)


def test_one_centre_of_mass_frame_across_the_course():
    """"Centre of mass" means position the weighted mean of the link centres and orientation the
    weighted mean of the link orientations everywhere: exercise 2.3's com_frame, CentreOfMassFrame,
    LinkChain(frame='com') for N = 3 and 5, body_frames()['centre of mass'] of every system made of
    links (the floating snake included: its section-3.4.3 frame is listed under another name)."""
    from gm_core.chains.three_link import com_frame
    from gm_core.systems import CentreOfMassFrame, KinematicSnake

    r = _shapes(2, (6,))
    for s in (LowReSwimmer(LENGTHS3), HighReSwimmer(LENGTHS3), FloatingSnake(LENGTHS3, (1, 2, 1.5)),
              KinematicSnake(LENGTHS3), LinkChain(LENGTHS3, "floating", masses=(3, 1, 2))):
        com = s.body_frames(centre_of_mass=True, minimum_perturbation=False)["centre of mass"]
        mid = s.body_frames(centre_of_mass=False, minimum_perturbation=False)["middle link"]
        w = s.link_weights()
        beta, _ = com_frame(r, s.lengths, weights=w)                  # exercise 2.3, relative to the middle link
        np.testing.assert_allclose(com.link_poses(r), SE2.compose(SE2.inverse(beta)[..., None, :], mid.link_poses(r)),
                                   atol=1e-13)
        np.testing.assert_allclose(CentreOfMassFrame(mid).pose(r), beta, atol=1e-13)
        np.testing.assert_allclose(np.einsum("i,...ij->...j", w, com.link_poses(r)), 0.0, atol=1e-13)
    five = LinkChain((1.0, 0.8, 1.2, 0.9, 1.1), "floating", masses=(1, 2, 3, 2, 1), frame="com")
    r5 = _shapes(4, (5,))
    np.testing.assert_allclose(np.einsum("i,...ij->...j", five.link_weights(), five.link_poses(r5)), 0.0, atol=1e-13)
    assert "centre of mass (middle-link axes)" in FloatingSnake().body_frames(minimum_perturbation=False)


# ------------------------------------------------------------------ kinematics for N = 4, 5, 6
@pytest.mark.parametrize("N", [2, 4, 5, 6])
def test_poses_and_jacobians_against_the_frame_graph(N):
    """Odd N: the middle link is MobileChain's base link; the poses and (xi, alpha_dot) Jacobians agree."""
    lengths = RNG.uniform(0.5, 1.5, N)
    chain = LinkChain(lengths)
    r = _shapes(N - 1, (7,))
    if N % 2:
        mc = MobileChain(lengths)
        np.testing.assert_allclose(chain.link_poses(r), mc.frames(r)["g"], atol=1e-13)
        np.testing.assert_allclose(chain.link_jacobians(r), mc.body_jacobians(r), atol=1e-13)
    else:   # the body frame is the middle joint: halfway between its links' orientations, at the joint
        P = chain.link_poses(r)
        m = N // 2
        np.testing.assert_allclose(P[..., m - 1, 2], -P[..., m, 2], atol=1e-13)
        ends = [SE2.compose(P[..., m - 1, :], [lengths[m - 1] / 2, 0, 0]), SE2.compose(P[..., m, :], [-lengths[m] / 2, 0, 0])]
        np.testing.assert_allclose(ends[0][..., :2], 0.0, atol=1e-13)
        np.testing.assert_allclose(ends[1][..., :2], 0.0, atol=1e-13)


@pytest.mark.parametrize("N, frame", [(4, "middle"), (5, "middle"), (6, "middle"), (5, "com"), (4, "com")])
def test_pfaffian_from_finite_differences_of_forward_kinematics(N, frame):
    """Link body velocities by differencing world link poses g exp(t xi) Q_i(r + t r_dot); then the
    Pfaffian's rows are sum_i J_i^T M_i xi_i for every (xi, r_dot), here from those differences."""
    lengths = RNG.uniform(0.5, 1.5, N)
    for physics in ("low_re", "floating", "high_re"):
        chain = LinkChain(lengths, physics, frame=frame, masses=RNG.uniform(0.5, 2, N))
        r = _shapes(N - 1, (), 1.5)
        M = chain.link_matrices()
        h = 1e-6
        cols = []
        for q in np.eye(3 + N - 1):
            xi, rd = q[:3], q[3:]

            def world(t):
                return SE2.compose(SE2.exp(t * xi)[None], chain.link_poses(r + t * rd))

            g0 = world(0.0)
            V = (SE2.log(SE2.compose(SE2.inverse(g0), world(h))) - SE2.log(SE2.compose(SE2.inverse(g0), world(-h)))) / (2 * h)
            cols.append(V)
        V = np.stack(cols, -1)                                          # (N, 3, 3 + n): link velocities per column
        np.testing.assert_allclose(chain.link_jacobians(r), V, atol=1e-8)
        pf = sum(V[i][:, :3].T @ M[i] @ V[i] for i in range(N))
        np.testing.assert_allclose(chain.pfaffian(r), pf, atol=1e-8)
        np.testing.assert_allclose(chain.metric(r), sum(V[i].T @ M[i] @ V[i] for i in range(N)), atol=1e-8)


@pytest.mark.parametrize("batch", BATCHES, ids=str)
def test_batch_shapes(batch):
    chain = LinkChain((1.0, 0.8, 1.2, 0.9), "high_re")
    r = _shapes(3, batch)
    A = chain.connection(r)
    assert A.shape == batch + (3, 3)
    flat = chain.connection(r.reshape(-1, 3))
    np.testing.assert_allclose(A.reshape(-1, 3, 3), flat, atol=1e-15)
    assert chain.link_poses(r).shape == batch + (4, 3)
    assert chain.metric(r).shape == batch + (6, 6)
    assert chain.shape_metric(r).shape == batch + (3, 3)
    assert chain.part_poses(r).shape == batch + (4, 3)


# ------------------------------------------------------------------ physics along integrated gaits
def _wave(n, amp=0.7, order=1, phase=None):
    a, b = np.zeros((n, order)), np.zeros((n, order))
    ph = np.linspace(0, np.pi, n) if phase is None else phase
    a[:, 0], b[:, 0] = amp * np.cos(ph), amp * np.sin(ph)
    return fourier_gait(a, b, period=2 * np.pi)


def _world_links(chain, tr):
    return SE2.compose(tr.g[:, None, :], chain.link_poses(tr.r))


@pytest.mark.parametrize("N, frame", [(4, "middle"), (5, "com"), (6, "middle")])
def test_zero_net_drag_wrench_along_integrated_gaits(N, frame):
    """Low Re: the world motion of every link, differenced from the integrated trajectory, meets zero
    total drag force and moment, with the drag integrated along the links by quadrature (fluids)."""
    chain = LinkChain(RNG.uniform(0.6, 1.4, N), drag_ratio=2.5, frame=frame)
    tr = trajectory(chain, _wave(N - 1), n_frames=801)
    G = _world_links(chain, tr)
    dt = tr.t[1] - tr.t[0]
    V = (G[2:] - G[:-2]) / (2 * dt)
    F = drag_wrench(G[1:-1], V, np.array(chain.lengths), 2.5)
    scale = np.abs(drag_wrench(G[1:-1], np.abs(V), np.array(chain.lengths), 2.5)).max()
    assert np.abs(F).max() < 2e-4 * scale
    assert scale > 0.1


@pytest.mark.parametrize("N", [4, 5])
def test_zero_momentum_of_the_floating_chain_along_integrated_gaits(N):
    chain = LinkChain(RNG.uniform(0.6, 1.4, N), "floating", masses=RNG.uniform(0.5, 2, N))
    tr = trajectory(chain, _wave(N - 1, 0.9), n_frames=801)
    G = _world_links(chain, tr)
    dt = tr.t[1] - tr.t[0]
    V = (G[2:] - G[:-2]) / (2 * dt)
    m, I = np.array(chain.masses), np.array(chain.inertias)
    P = (m[:, None] * V[..., :2]).sum(1)
    p = G[1:-1, :, :2]
    L = (I * V[..., 2] + m * (p[..., 0] * V[..., 1] - p[..., 1] * V[..., 0])).sum(1)
    scale = (m * np.abs(V[..., :2]).sum(-1)).sum(1).max()
    assert np.abs(P).max() < 1e-4 * scale and np.abs(L).max() < 1e-4 * scale


# ------------------------------------------------------------------ symmetries
@pytest.mark.parametrize("N", [4, 5])
def test_reversed_gait_reverses_the_motion(N):
    chain = LinkChain(RNG.uniform(0.6, 1.4, N))
    g = _wave(N - 1, 0.8)
    back = fourier_gait(g.a, -g.b, g.center, period=g.period)     # r(-t): the same loop backwards
    np.testing.assert_allclose(net_displacement(chain, back), SE2.inverse(net_displacement(chain, g)), atol=1e-10)


@pytest.mark.parametrize("N", [4, 5, 6])
def test_mirrored_shapes_give_the_mirrored_motion(N):
    """Reflecting every joint angle reflects the chain in its body x axis: (x, y, theta) -> (x, -y, -theta)."""
    chain = LinkChain(RNG.uniform(0.6, 1.4, N), "high_re")
    g = _wave(N - 1, 0.6)
    mirror = fourier_gait(-g.a, -g.b, -g.center, period=g.period)
    d, dm = net_displacement(chain, g), net_displacement(chain, mirror)
    np.testing.assert_allclose(dm, d * [1, -1, -1], atol=1e-10)
    assert abs(d[0]) > 1e-3


# ------------------------------------------------------------------ bad input
def test_bad_input_is_named():
    for bad, match in [((1.0,), "lengths"), ("abc", "lengths"), ((1, 0, 1), "lengths"), ((1,) * 201, "lengths"),
                       ((1, np.nan, 1), "lengths")]:
        with pytest.raises((ValueError, TypeError), match=match):
            LinkChain(bad)
    with pytest.raises(ValueError, match="physics"):
        LinkChain((1, 1, 1), "viscous")
    with pytest.raises(ValueError, match="frame"):
        LinkChain((1, 1, 1), frame="head")
    with pytest.raises(ValueError, match="drag_ratio"):
        LinkChain((1, 1, 1), drag_ratio=-1)
    with pytest.raises(ValueError, match="masses"):
        LinkChain((1, 1, 1), "floating", masses=(1, 1))
    with pytest.raises(ValueError, match="aspect_ratio"):
        LinkChain((1, 1, 1), "high_re", aspect_ratio=0.5)
    with pytest.raises(ValueError, match="bounds and nodes"):
        LinkChain((1, 1, 1), bounds=((-1, 1), (-1, 1)))
    chain = LinkChain((1, 1, 1, 1))
    with pytest.raises(ValueError, match=r"r must have shape \(\.\.\., 3\)"):
        chain.connection(np.zeros(2))
    with pytest.raises(TypeError, match="r"):
        chain.connection("0 0 0")
