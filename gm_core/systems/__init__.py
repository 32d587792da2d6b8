"""The locomotion systems of chapter 3, one small module each (numpy only).

Every system has ``connection(r)`` (..., 3, n) with ``xi = -A(r) r_dot`` (3.10), ``pfaffian(r)``
(..., 3, 3 + n), ``body_velocity(r, r_dot)``, ``singularity(r)`` / ``is_singular(r)``, and
``parts()`` / ``part_poses(r)`` for drawing. Systems made of links also have ``link_poses(r)`` and
``link_jacobians(r)`` (from :mod:`gm_core.chains`, in the system's body frame). The ones defined
by a balance over the links are :class:`LinkChain` for any number of links; the floating snake
and the two swimmers of section 3.4 are its N = 3 cases (named subclasses that add only their
book names and signatures), with ``link_matrices()`` and ``metric(r)``, called ``mass_matrix(r)``
or ``drag_matrix(r)``. :class:`ThreeLinkSystem` is the base of the kinematic snake. Fluid
coefficients come from :mod:`gm_core.systems.fluids`. These modules import :mod:`gm_core.systems.motion`,
never the other way round.
"""
from gm_core.systems.ackerman import Ackerman
from gm_core.systems.base import LocomotionSystem, SystemPart
from gm_core.systems.diff_drive import DifferentialDrive
from gm_core.systems.floating_snake import FloatingSnake
from gm_core.systems.high_re import HighReSwimmer
from gm_core.systems.kinematic_snake import KinematicSnake
from gm_core.systems.link_chain import LinkChain
from gm_core.systems.low_re import LowReSwimmer
from gm_core.systems.minimum_perturbation import MinimumPerturbationFrame
from gm_core.systems.panel_method import InteractingChain
from gm_core.systems.reframed import BodyFrame, CentreOfMassFrame, PoseFrame, Reframed
from gm_core.systems.restricted import AffineRestriction, shape_slice
from gm_core.systems.rotors import Rotors
from gm_core.systems.slender_body import SlenderBody, chain_approximation, serpenoid_modes
from gm_core.systems.tabulated import TabulatedConnection
from gm_core.systems.tape_measure import TapeMeasure
from gm_core.systems.three_link import ThreeLinkSystem

__all__ = ["LocomotionSystem", "SystemPart", "ThreeLinkSystem", "DifferentialDrive", "Ackerman",
           "KinematicSnake", "FloatingSnake", "LowReSwimmer", "HighReSwimmer",
           "LinkChain", "InteractingChain", "BodyFrame", "PoseFrame", "CentreOfMassFrame", "Reframed", "MinimumPerturbationFrame",
           "AffineRestriction", "shape_slice", "SlenderBody", "chain_approximation", "serpenoid_modes",
           "TabulatedConnection", "Rotors", "TapeMeasure", "ALL_SYSTEMS"]


#: One default instance of each system of chapter 3, keyed by class name (like ALL_GROUPS): the
#: system laws of tests/test_systems.py, the benchmarks and the demos run over every entry.
ALL_SYSTEMS: dict[str, LocomotionSystem] = {
    "DifferentialDrive": DifferentialDrive(), "Ackerman": Ackerman(),
    "KinematicSnake": KinematicSnake(), "FloatingSnake": FloatingSnake(),
    "LowReSwimmer": LowReSwimmer(), "HighReSwimmer": HighReSwimmer(),
}
