"""Hypothesis fuzz of the other math modules: chains, kinematics, connection, gaits, locomotion,
systems (constructors and methods), fluids, geometry, manifolds, axioms and frames.

The same harness as tests/test_fuzz_math.py (:mod:`fuzzkit`): each row is a valid example call,
and one argument at a time is replaced by a bad or unusual value; allowed outcomes are a finite,
right-shaped result or a ValueError / TypeError naming that argument. Calls that integrate a
gait or solve an optimisation are in ``SLOW_CASES`` and get fewer examples, so the whole fuzz
(both files) stays under a minute.
"""
import os

import numpy as np
import pytest
from fuzzkit import Case, baseline, cases_table, check_each, chunks, fuzz_each
from hypothesis import HealthCheck, settings

from gm_core import SE2, RPlus
from gm_core import chains as CH
from gm_core import geometry as GE
from gm_core import manifolds as MA
from gm_core import systems as SY
from gm_core.chains.arms import (
    rp_arm_body_jacobians,
    rp_arm_frames,
    rr_arm_frames,
    rr_arm_jacobian,
    single_link_frames,
)
from gm_core.chains.holonomic import (
    accessible_circle,
    circle_constraints,
    pin_constraints,
    pinned_pair,
    sample_accessible_manifold,
    sphere_plane_constraints,
)
from gm_core.chains.three_link import (
    beta_frame_jacobian,
    beta_frame_velocity,
    com_frame,
    com_frame_jacobians,
    links_from_beta_frame,
    three_link_chain,
    three_link_frames,
    three_link_jacobians,
    three_link_poses,
)
from gm_core.groups import axioms as AX
from gm_core.manifolds import observers as FR
from gm_core.systems import connection as CO
from gm_core.systems import fluids as FL
from gm_core.systems import gaits as GA
from gm_core.systems import motion as LO
from gm_core.systems import pacing as PA

N = int(os.environ.get("FUZZ_EXAMPLES", 25))
FAST = settings(max_examples=N, deadline=None, derandomize=not os.environ.get("FUZZ_RANDOM"),
                suppress_health_check=list(HealthCheck))
SLOW = settings(FAST, max_examples=max(3, N // 5))

G = np.array([0.4, -0.3, 0.8])
H = np.array([-1.0, 0.5, -0.2])
XI = np.array([0.7, 0.2, -0.5])
ALPHA3 = np.array([0.3, -0.4])
LENGTHS = (1.0, 0.8, 1.2)

# ------------------------------------------------------------------ chains and kinematics
ARM = CH.Chain(["revolute", "prismatic"], [1.0, 0.5])
CHAIN_CASES = [
    Case("world_to_body_jacobian", CH.world_to_body_jacobian, {"g": G, "J": np.ones((3, 2))},
         batch=("g", "J")),
    Case("finite_difference_jacobians", CH.finite_difference_jacobians,
         {"fk": lambda a: three_link_poses(a), "alpha": ALPHA3, "eps": 1e-6}, callables={"fk"},
         out_tail=(3, 3, 2)),
    Case("relative_pose", CH.relative_pose, {"g": G, "base": H}, batch=("g", "base"), out_tail=(3,)),
    Case("transported_columns", CH.transported_columns, {"chain": ARM, "alpha": ALPHA3}, objects={"chain"}),
    Case("pin_constraints", pin_constraints, {"g1": G, "g2": H}, batch=("g1", "g2"), out_tail=(2,)),
    Case("pinned_pair", pinned_pair, {"g": G, "alpha": 0.4}, batch=("g", "alpha"), out_tail=(2, 3)),
    Case("beta_frame_velocity", beta_frame_velocity,
         {"beta": G, "dbeta": np.ones((3, 2)), "xi_base": XI, "alpha_dot": np.array([0.5, -0.1])}),
    Case("single_link_frames", single_link_frames, {"alpha": 0.3, "length": 1.5}),
    Case("rr_arm_frames", rr_arm_frames, {"alpha": ALPHA3, "lengths": np.array([1.0, 0.5])}),
    Case("rr_arm_jacobian", rr_arm_jacobian, {"alpha": ALPHA3, "lengths": np.array([1.0, 0.5])},
         out_tail=(3, 2)),
    Case("rp_arm_frames", rp_arm_frames, {"alpha": 0.3, "delta": 0.5, "l1": 1.0, "l2": 0.7, "offset": 0.1}),
    Case("rp_arm_body_jacobians", rp_arm_body_jacobians,
         {"alpha": 0.3, "delta": 0.5, "l1": 1.0, "l2": 0.7, "offset": 0.1}),
    Case("three_link_chain", three_link_chain, {"lengths": np.array(LENGTHS)}),
    Case("three_link_frames", three_link_frames, {"alpha": ALPHA3, "lengths": np.array(LENGTHS), "g": G},
         also_valid={"g": (None,)}),
    Case("three_link_poses", three_link_poses, {"alpha": ALPHA3, "lengths": np.array(LENGTHS)},
         out_tail=(3, 3)),
    Case("three_link_jacobians", three_link_jacobians, {"alpha": ALPHA3, "lengths": np.array(LENGTHS)}),
    Case("beta_frame_jacobian", beta_frame_jacobian, {"beta": G, "dbeta": np.ones((3, 2))},
         batch=("beta", "dbeta")),
    Case("links_from_beta_frame", lambda beta, dbeta: links_from_beta_frame(
        three_link_jacobians(ALPHA3), beta, dbeta), {"beta": G, "dbeta": np.ones((3, 2))}),
    Case("com_frame", com_frame, {"alpha": ALPHA3, "lengths": np.array(LENGTHS),
                                     "weights": np.array([1.0, 2.0, 1.0])}, also_valid={"weights": (None,)}),
    Case("com_frame_jacobians", com_frame_jacobians, {"alpha": ALPHA3, "lengths": np.array(LENGTHS),
                                                         "weights": np.array([1.0, 2.0, 1.0])},
         also_valid={"weights": (None,)}),
    Case("circle_constraints", circle_constraints, {"p": np.array([0.5, 0.2, 1.0])}, out_tail=(2,)),
    Case("sphere_plane_constraints", sphere_plane_constraints, {"p": np.array([0.5, 0.2, 1.0])}),
    Case("sample_accessible_manifold", sample_accessible_manifold,
         {"constraints": circle_constraints, "n": 8, "rng": None, "box": 2.0, "dim": 3,
          "iters": 20, "tol": 1e-12}, callables={"constraints"}, ints={"n", "dim", "iters"}, objects={"rng"},
         also_valid={"rng": (None,)}),
    Case("accessible_circle", accessible_circle, {"n": 12}, ints={"n"}, out_tail=(3,)),
    Case("Chain", CH.Chain, {"joints": ["revolute", "prismatic"], "lengths": np.array([1.0, 0.5])},
         objects={"joints"}),
    Case("Chain.frames", ARM.frames, {"alpha": ALPHA3}),
    Case("MobileChain", CH.MobileChain, {"lengths": np.array(LENGTHS)}),
]

# ------------------------------------------------------------------ connection
OMEGA = SY.KinematicSnake().pfaffian(ALPHA3)
M6 = SY.FloatingSnake().mass_matrix(ALPHA3)
CONNECTION_CASES = [
    # NaN entries give NaN (counted as singular by the callers), a singular Pfaffian a NaN connection
    Case("pfaffian_determinant", CO.pfaffian_determinant, {"omega_xi": OMEGA[:, :3]}, nan_ok={"omega_xi"},
         finite=False),
    Case("connection_from_pfaffian", CO.connection_from_pfaffian, {"omega": OMEGA, "n_position": 3},
         kwonly={"n_position"}, ints={"n_position"}, out_tail=(3, 2), nan_ok={"omega"}, finite=False),
    Case("connection_from_mass_matrix", CO.connection_from_mass_matrix, {"M": M6, "n_position": 3},
         kwonly={"n_position"}, ints={"n_position"}, out_tail=(3, 2), nan_ok={"M"}, finite=False),
    Case("metric_from_jacobians", CO.metric_from_jacobians,
         {"jacobians": list(three_link_jacobians(ALPHA3)), "inertias": [np.eye(3)] * 3},
         objects={"jacobians", "inertias"}),
]

# ------------------------------------------------------------------ gaits
GAIT_CASES = [
    Case("Gait", lambda shape, period: GA.Gait(shape, period)(np.array([0.0, 0.3])),
         {"shape": lambda t: np.stack([np.cos(t), np.sin(t)], -1), "period": 2 * np.pi}, callables={"shape"},
         out_tail=(2,)),
    Case("Gait.from_samples", lambda points, period: GA.Gait.from_samples(points, period)(np.array([0.1])),
         {"points": np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), "period": 1.0}, out_tail=(2,)),
    Case("circle_gait", lambda amplitude, center, period: GA.circle_gait(amplitude, center, period)(0.2),
         {"amplitude": 0.5, "center": np.array([1.0, 0.5]), "period": 2.0}, out_tail=(2,)),
    Case("CircleGait.velocity", lambda t: GA.circle_gait(0.5).velocity(t), {"t": np.array([0.0, 0.3])},
         out_tail=(2,)),
    Case("ellipse_gait", lambda a, b, tilt, center, period: GA.ellipse_gait(a, b, tilt, center, period)(0.2),
         {"a": 0.5, "b": 0.3, "tilt": 0.2, "center": np.array([0.1, 0.2]), "period": 1.0}, out_tail=(2,)),
    Case("serpenoid_gait", lambda amplitude, phase, frequency, center, period:
         GA.serpenoid_gait(amplitude, phase, frequency, center, period)(0.2),
         {"amplitude": 0.5, "phase": 1.0, "frequency": 2, "center": np.array([0.1, 0.2]), "period": 1.0},
         ints={"frequency"}, out_tail=(2,)),
    Case("family_gait", lambda family, size, center, aspect, angle, period:
         GA.family_gait(family, size, center, aspect, angle, period)(0.2),
         {"family": "ellipse", "size": 0.5, "center": np.array([0.1, 0.2]), "aspect": 0.6, "angle": 0.3,
          "period": 1.0}, options={"family"}, out_tail=(2,)),
    Case("sine_pacing", lambda a, period: PA.sine_pacing(a, period)[0](0.3), {"a": 0.2, "period": 1.0}),
    Case("constant_rate_path", lambda r0, r_dot, duration: PA.constant_rate_path(r0, r_dot, duration)(0.5),
         {"r0": np.array([0.0, 0.1]), "r_dot": np.array([1.0, 0.5]), "duration": 2.0}, out_tail=(2,)),
    Case("as_gait", lambda gait, period: GA.as_gait(gait, period)(0.25),
         {"gait": np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), "period": 1.0},
         also_valid={"gait": (GA.circle_gait(0.3),)}, out_tail=(2,)),
]

# ------------------------------------------------------------------ systems
SNAKE = SY.KinematicSnake()
CAR = SY.DifferentialDrive()
SYSTEM_CASES = [
    Case("DifferentialDrive", SY.DifferentialDrive, {"wheel_radius": 0.3, "half_width": 0.5}),
    Case("Ackerman", SY.Ackerman, {"wheel_radius": 0.3, "wheelbase": 1.5}),
    Case("KinematicSnake", SY.KinematicSnake, {"lengths": np.array(LENGTHS)}),
    Case("FloatingSnake", SY.FloatingSnake, {"lengths": np.array(LENGTHS), "masses": np.array([1.0, 2.0, 1.0]),
                                             "inertias": np.array([0.1, 0.2, 0.1]), "frame": "com"},
         options={"frame"}, also_valid={"inertias": (None,)}),
    Case("LowReSwimmer", SY.LowReSwimmer, {"lengths": np.array(LENGTHS), "drag_ratio": 2.0}),
    Case("HighReSwimmer", SY.HighReSwimmer, {"lengths": np.array(LENGTHS), "aspect_ratio": 8.0,
                                             "fluid_density": 1.0, "body_density": 0.5}),
    Case("ellipse_added_mass", FL.ellipse_added_mass, {"a": 0.5, "b": 0.1, "fluid_density": 1.0}),
    # lengths of any N >= 2 are valid (their bad values are tested in tests/test_link_chain.py)
    Case("LinkChain", lambda physics, drag_ratio, frame: SY.LinkChain(
        (1.0, 0.8, 1.2, 0.9), physics, drag_ratio=drag_ratio, frame=frame).connection(np.array([0.3, -0.2, 0.5])),
        {"physics": "low_re", "drag_ratio": 2.0, "frame": "com"}, options={"physics", "frame"}, out_tail=(3, 3)),
    Case("LinkChain.tapered", lambda links, taper: SY.LinkChain.tapered(links, taper=taper).lengths,
         {"links": 5, "taper": 0.4}, ints={"links"}),
    Case("SlenderBody", lambda length, drag_ratio, panels, order: SY.SlenderBody(
        length, drag_ratio=drag_ratio, panels=panels, order=order).connection(np.array([1.0, -2.0])),
        {"length": 3.0, "drag_ratio": 2.0, "panels": 4, "order": 6}, ints={"panels", "order"}, out_tail=(3, 2)),
]
SYSTEM_CASES.append(Case("TapeMeasure", lambda tape_length, head_mass, added_mass_rate, tape_pieces: SY.TapeMeasure(
    tape_length, head_mass=head_mass, added_mass_rate=added_mass_rate, tape_pieces=tape_pieces).shape_metric(
        np.array([0.4, 0.6 * tape_length])), {"tape_length": 1.0, "head_mass": 0.25, "added_mass_rate": 1.0, "tape_pieces": 12},
    ints={"tape_pieces"}, out_tail=(2, 2)))
TAPE = SY.TapeMeasure(symmetric=False)
SYSTEM_CASES += [
    Case("TapeMeasure.connection", TAPE.connection, {"r": np.array([0.3, 0.9, 0.6])}, out_tail=(3, 3), finite=False),
    Case("TapeMeasure.part_poses", TAPE.part_poses, {"r": np.array([0.3, 0.9, 0.6])}, out_tail=(25, 3), finite=False),
]
CHAIN5 = SY.LinkChain((1.0,) * 5)
SYSTEM_CASES += [
    Case("LinkChain.connection", CHAIN5.connection, {"r": np.array([0.3, -0.2, 0.5, 0.1])}, out_tail=(3, 4)),
    Case("LinkChain.link_poses", CHAIN5.link_poses, {"r": np.array([0.3, -0.2, 0.5, 0.1])}, out_tail=(5, 3)),
    Case("LinkChain.metric", CHAIN5.metric, {"r": np.array([0.3, -0.2, 0.5, 0.1])}, out_tail=(7, 7)),
    Case("shape_slice", lambda through, axes: SY.shape_slice(CHAIN5, through, axes).connection(np.array([0.2, 0.1])),
         {"through": np.array([0.3, -0.2, 0.5, 0.1]), "axes": (1, 3)}, objects={"axes"}, out_tail=(3, 2),
         also_valid={"through": (None,)}),
]
R = np.array([0.4, -0.9])
RD = np.array([0.5, 0.2])
_METHODS = {"connection": (3, 2), "pfaffian": (3, 5), "singularity": None, "is_singular": None,
            "part_poses": (3,), "connection_derivative": None, "link_poses": (3, 3), "link_jacobians": None,
            "middle_link_jacobians": None, "mass_matrix": (5, 5), "drag_matrix": (5, 5),
            "metric": (5, 5), "frame_change": None, "frame_offset": None, "connection_closed_form": (3, 2)}
for key, system in SY.ALL_SYSTEMS.items():
    for meth, tail in _METHODS.items():
        if callable(getattr(system, meth, None)):
            # connections are NaN at singular shapes (documented), so only their shape is checked
            SYSTEM_CASES.append(Case(f"{key}.{meth}", getattr(system, meth), {"r": R}, out_tail=tail,
                                     finite=not (system.may_be_singular and "connection" in meth)))
    SYSTEM_CASES.append(Case(f"{key}.body_velocity", system.body_velocity, {"r": R, "r_dot": RD},
                             batch=("r", "r_dot"), out_tail=(3,)))

# ------------------------------------------------------------------ locomotion (integrating: slow)
GAIT = GA.circle_gait(0.5, (1.0, -0.5))
LOCOMOTION_CASES = [
    Case("body_velocity", LO.body_velocity, {"system": CAR, "r": R, "r_dot": RD}, objects={"system"},
         batch=("r", "r_dot"), out_tail=(3,)),
    Case("connection_curl", GE.connection_curl, {"system": SNAKE, "r": np.array([1.0, -0.5]), "h": 1e-5},
         objects={"system"}, also_valid={"h": (None,)}),
]
SLOW_CASES = [
    Case("check_gait", LO.check_gait, {"system": SNAKE, "gait": GAIT, "samples": 256}, kwonly={"samples"},
         objects={"system", "gait"}, ints={"samples"}, also_valid={"samples": (None,)}),
    Case("net_displacement", LO.net_displacement,
         {"system": SNAKE, "gait": GAIT, "steps": 64, "check": True, "rtol": 1e-8},
         kwonly={"steps", "check", "rtol"}, objects={"system", "gait"}, ints={"steps"}, flags={"check"},
         also_valid={"steps": (None,)}, out_tail=(3,)),
    Case("trajectory", lambda system, gait, n_frames, cycles, g0, substeps: LO.trajectory(
        system, gait, n_frames, cycles=cycles, g0=g0, substeps=substeps).g,
        {"system": SNAKE, "gait": GAIT, "n_frames": 9, "cycles": 2, "g0": G, "substeps": 4},
        objects={"system", "gait"}, ints={"n_frames", "cycles", "substeps"}, also_valid={"substeps": (None,)},
        out_tail=(3,)),
    Case("displacement_until", LO.displacement_until,
         {"system": SNAKE, "gait": GAIT, "t": 0.4, "steps": 32, "g0": G}, kwonly={"steps", "g0"},
         objects={"system", "gait"}, ints={"steps"}, out_tail=(3,)),
    Case("drive", lambda system, r0, r_dot, duration, n_frames: LO.drive(system, r0, r_dot, duration, n_frames).g,
         {"system": CAR, "r0": np.zeros(2), "r_dot": RD, "duration": 2.0, "n_frames": 5},
         objects={"system"}, ints={"n_frames"}, out_tail=(3,)),
    Case("drag_wrench", FL.drag_wrench,
         {"poses": SY.LowReSwimmer().link_poses(R), "velocities": np.ones((3, 3)),
          "lengths": np.array(LENGTHS), "drag_ratio": 2.0, "nodes": 5},
         kwonly={"nodes"}, ints={"nodes"}),
    Case("slender_link_drag", FL.slender_link_drag, {"length": 1.5, "drag_ratio": 2.0}, out_tail=(3, 3)),
    Case("added_mass_bem", FL.added_mass_bem, {"a": 0.5, "b": 0.2, "fluid_density": 1.0, "n": 60, "m": 30},
         kwonly={"n", "m"}, ints={"n", "m"}),
]

# ------------------------------------------------------------------ geometry (slow)
SWIMMER = SY.LowReSwimmer()
GEOMETRY_CASES = [
    Case("constraint_curvature", GE.constraint_curvature, {"system": SWIMMER, "r": R, "method": "auto"},
         kwonly={"method"}, objects={"system"}, options={"method"}, out_tail=(3,)),
    Case("connection_derivative", GE.connection_derivative, {"system": SNAKE, "r": R, "method": "fd"},
         kwonly={"method"}, objects={"system"}, options={"method"}),
    Case("centre_of_mass", GE.centre_of_mass, {"system": SWIMMER, "r": R}, objects={"system"}, out_tail=(3,)),
    Case("dissipation_metric", GE.dissipation_metric, {"system": SWIMMER, "r": R}, objects={"system"},
         out_tail=(2, 2)),
    Case("fourier_gait", lambda a, b, center: GE.fourier_gait(a, b, center)(0.3),
         {"a": np.array([[0.5], [0.0]]), "b": np.array([[0.0], [0.5]]), "center": np.array([0.1, 0.0])},
         also_valid={"b": (None,), "center": (None,)}, out_tail=(2,)),
    Case("sysplotter_stroke", GE.sysplotter_stroke, {"which": "displacement"}, options={"which"}),
    Case("travelling_wave", lambda n_joints, amplitude, lag: GE.travelling_wave(n_joints, amplitude, lag)(0.3),
         {"n_joints": 4, "amplitude": 0.8, "lag": 1.2}, ints={"n_joints"}, out_tail=(4,)),
    Case("shaped_gait", lambda c1, c2, a, b, tilt, bend: GE.shaped_gait(c1, c2, a, b, tilt, bend)(0.3),
         {"c1": 0.1, "c2": -0.2, "a": 0.8, "b": 0.5, "tilt": 0.4, "bend": 0.2}, out_tail=(2,)),
    Case("row_scaled", GE.row_scaled, {"values": np.array([[0.2, 1e-15, -0.1], [0.19, 0.0, -0.1]]), "floor": 0.05}),
    Case("field_rms", GE.field_rms, {"system": SWIMMER, "grid": np.array([[0.4, -0.9], [0.1, 0.2]])},
         objects={"system"}, out_tail=(3,)),
    Case("random_start", lambda n_joints, seed, scale, center: GE.random_start(
        n_joints, seed, scale=scale, center=center)(0.3), {"n_joints": 3, "seed": 4, "scale": 0.8, "center": 0.5},
         ints={"n_joints", "seed"}, out_tail=(3,)),
    Case("links_cross", lambda chain, gait, samples: np.array(GE.links_cross(chain, gait, samples)),
         {"chain": GE.chain_swimmer(3), "gait": GE.chain_stroke(3), "samples": 64}, objects={"chain", "gait"},
         ints={"samples"}),
]
SLOW_CASES += [
    Case("stokes_estimate", GE.stokes_estimate, {"system": SWIMMER, "gait": GAIT, "rtol": 1e-6},
         kwonly={"rtol"}, objects={"system", "gait"}, out_tail=(3,)),
    Case("body_velocity_integral", GE.body_velocity_integral, {"system": SWIMMER, "gait": GAIT, "rtol": 1e-8},
         kwonly={"rtol"}, objects={"system", "gait"}, out_tail=(3,)),
    Case("drift_and_turn", GE.drift_and_turn, {"system": SWIMMER, "gait": GAIT}, objects={"system", "gait"}),
    Case("displacement_estimates", lambda system, gait, interactive: GE.displacement_estimates(
        system, gait, interactive=interactive).as_array(), {"system": SWIMMER, "gait": GAIT, "interactive": True},
         objects={"system", "gait"}, flags={"interactive"}, out_tail=(3, 3)),
    Case("path_length", GE.path_length, {"system": SWIMMER, "gait": GAIT}, objects={"system", "gait"}),
    Case("efficiency", GE.efficiency, {"system": SWIMMER, "gait": GAIT}, objects={"system", "gait"}),
    Case("gait_objective", GE.gait_objective,
         {"system": SWIMMER, "gait": GE.fourier_gait(np.array([[0.5], [0.0]]), np.array([[0.0], [0.5]])),
          "objective": "displacement", "intervals": 64},
         kwonly={"intervals"}, objects={"system", "gait"}, options={"objective"}, ints={"intervals"}),
]

# ------------------------------------------------------------------ manifolds, axioms, frames
MANIFOLD_CASES = [
    Case("cylinder_xyz", MA.cylinder_xyz, {"s": np.array([0.1, 0.5]), "a": np.array([1.0, 2.0]), "radius": 1.0},
         batch=("s", "a")),
    Case("torus_xyz", MA.torus_xyz, {"a": np.array([0.1, 0.5]), "b": np.array([1.0, 2.0]), "R": 2.0, "r": 0.7},
         batch=("a", "b")),
    Case("sphere_xyz", MA.sphere_xyz, {"lat": np.array([0.1, 0.5]), "lon": np.array([1.0, 2.0]), "radius": 1.0},
         batch=("lat", "lon")),
    Case("wrap_segments", MA.wrap_segments, {"a": np.linspace(0, 7, 5), "b": np.linspace(0, 3, 5),
                                             "period_a": 2 * np.pi, "period_b": 2 * np.pi}),
    Case("chart_speed", MA.chart_speed, {"lat": np.array([0.1, 0.5]), "heading": np.array([1.0, 2.0])},
         batch=("lat", "heading")),
    Case("polar_chart_velocity", MA.polar_chart_velocity, {"lat": 0.3, "lon": 0.2, "heading": 1.0}),
    Case("circle_point_velocity", MA.circle_point_velocity, {"a": np.array([0.1, 0.5]), "a_dot": 1.0,
                                                             "radius": 1.0}),
    Case("sphere_tangent_basis", MA.sphere_tangent_basis, {"lat": 0.3, "lon": 0.2}),
    Case("sphere_velocity", MA.sphere_velocity, {"lat": 0.3, "lon": 0.2, "lat_dot": 0.5, "lon_dot": -0.1,
                                                 "radius": 1.0}),
    Case("great_circle", MA.great_circle, {"p": np.array([1.0, 0.0, 0.0]), "v": np.array([0.0, 1.0, 0.0]),
                                           "t": np.linspace(0, 1, 4), "radius": 1.0}),
    Case("cylinder_geodesic", MA.cylinder_geodesic, {"s0": 0.0, "a0": 0.5, "s_dot": 1.0, "a_dot": 0.3,
                                                     "t": np.linspace(0, 1, 4), "radius": 1.0}),
    Case("transition_point", MA.transition_point, {"q1": np.array([[1.0, 2.0], [0.5, -1.0]]), "chart1": MA.CARTESIAN,
                                                   "chart2": MA.POLAR}, objects={"chart1", "chart2"}, out_tail=(2,)),
    Case("transition_jacobian", MA.transition_jacobian, {"q1": np.array([0.4, 1.0]), "chart1": MA.LATITUDE_LONGITUDE,
                                                         "chart2": MA.STEREOGRAPHIC_NORTH},
         objects={"chart1", "chart2"}, out_tail=(2, 2)),
    Case("transition_vector", MA.transition_vector, {"q1": np.array([1.0, 0.5]), "v1": np.array([0.3, -0.2]),
                                                     "chart1": MA.POLAR, "chart2": MA.CARTESIAN},
         objects={"chart1", "chart2"}, batch=("q1", "v1")),
    Case("in_overlap", MA.in_overlap, {"q1": np.array([[1.0, 2.0], [-1.0, 0.0]]), "chart1": MA.CARTESIAN,
                                       "chart2": MA.POLAR}, objects={"chart1", "chart2"}),
    Case("transition_path", MA.transition_path, {"q1": np.array([[-1.0, -1.0], [-1.0, -0.5], [-1.0, 0.5]]),
                                                 "chart1": MA.CARTESIAN, "chart2": MA.POLAR},
         objects={"chart1", "chart2"}),
]
AXIOM_CASES = [
    Case("axiom_residuals", AX.axiom_residuals, {"G": SE2, "rng": 1, "n": 5, "scale": 1.0},
         objects={"G", "rng"}, ints={"n"}, also_valid={"rng": (1, 3)}),
    Case("powers", AX.powers, {"G": RPlus, "g": np.array([1.5]), "n": 4}, objects={"G"}, ints={"n"},
         out_tail=(1,)),
    Case("group_structure", lambda G, seed, n: AX.is_group(AX.group_structure(G, seed=seed, n=n)),
         {"G": SE2, "seed": 0, "n": 3}, objects={"G"}, ints={"seed", "n"}, also_valid={"seed": (0,)}),
    Case("structure", AX.structure, {"name": "(ℤ, +)"}, options={"name"}),
]
FRAME_CASES = [
    Case("observed_velocity", FR.observed_velocity, {"g": G, "xi": XI, "h": H}, batch=("g", "xi", "h"),
         out_tail=(3,)),
    Case("icr", FR.icr, {"xi": XI, "tol": 1e-9}),
    Case("point_in_frame", FR.point_in_frame, {"g": G, "p": np.array([0.3, 0.1])}, batch=("g", "p"),
         out_tail=(2,)),
    Case("conjugation", FR.conjugation, {"g": G, "xi": XI}, batch=("g", "xi")),
    Case("point_velocities", FR.point_velocities, {"g": G, "g_dot": XI, "points": np.array([[0.3, 0.1]])},
         out_tail=(2,)),
]

CASES = cases_table(CHAIN_CASES, CONNECTION_CASES, GAIT_CASES, SYSTEM_CASES, LOCOMOTION_CASES, GEOMETRY_CASES,
                    MANIFOLD_CASES, AXIOM_CASES, FRAME_CASES)
SLOW_CASES = cases_table(SLOW_CASES)


@pytest.mark.parametrize("cases", chunks(CASES + SLOW_CASES))
def test_valid_examples(cases):
    check_each(cases, baseline)


@pytest.mark.parametrize("cases", chunks(CASES))
def test_bad_input(cases):
    fuzz_each(cases, FAST)


@pytest.mark.parametrize("cases", chunks(SLOW_CASES))
def test_bad_input_integrating(cases):
    fuzz_each(cases, SLOW)
