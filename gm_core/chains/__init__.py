"""Kinematic chains (book chapter 2), numpy only.

* :mod:`.chain`: joints (revolute, prismatic, arc, bend), straight and curved links, :class:`Chain`
  and :class:`MobileChain`, forward kinematics and Jacobians of any serial chain (section 2.5);
* :mod:`.continuum`: extensible continuum bodies, curvature and stretch modes (beyond the draft);
* :mod:`.kernels`: batch-last kernels of revolute chains of any length (link poses, body Jacobians);
* :mod:`.jacobians`: world and body Jacobians, finite differences, relative poses;
* :mod:`.arms`: the two-link arms of sections 2.2-2.5 (RR, RP);
* :mod:`.three_link`: the three-link chain of section 2.6 and its middle, beta and centre-of-mass frames;
* :mod:`.holonomic`: holonomic constraints (pinned links, the accessible manifold, section 2.1).
"""
from __future__ import annotations

from gm_core.chains.arms import (
    rp_arm_body_jacobians,
    rp_arm_frames,
    rr_arm_frames,
    rr_arm_jacobian,
    single_link_frames,
)
from gm_core.chains.chain import (
    METHODS,
    Chain,
    Joint,
    Link,
    MobileChain,
    transported_columns,
)
from gm_core.chains.continuum import ContinuumBody
from gm_core.chains.holonomic import (
    accessible_circle,
    circle_constraints,
    pin_constraints,
    pinned_pair,
    sample_accessible_manifold,
    sphere_plane_constraints,
)
from gm_core.chains.jacobians import (
    body_to_world_jacobian,
    finite_difference_jacobians,
    relative_pose,
    world_to_body_jacobian,
)
from gm_core.chains.kernels import (
    chain_arguments,
    chain_jacobians_T,
    chain_poses_T,
    flatten_batch,
    joint_turns,
    link_chain_jacobians,
    link_chain_poses,
    middle_frame_kernel,
    with_trig,
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

__all__ = [
    "transported_columns", "Joint", "Link", "Chain", "MobileChain", "METHODS", "link_chain_poses",
    "link_chain_jacobians", "finite_difference_jacobians", "relative_pose",
    "world_to_body_jacobian", "body_to_world_jacobian", "single_link_frames", "rr_arm_frames",
    "rr_arm_jacobian", "rp_arm_frames", "rp_arm_body_jacobians", "three_link_chain",
    "three_link_frames", "three_link_poses", "three_link_jacobians", "beta_frame_velocity",
    "beta_frame_jacobian", "links_from_beta_frame", "com_frame", "com_frame_jacobians",
    "pin_constraints", "pinned_pair", "circle_constraints", "sphere_plane_constraints",
    "sample_accessible_manifold", "accessible_circle", "chain_arguments", "flatten_batch",
    "chain_poses_T", "joint_turns", "chain_jacobians_T", "with_trig", "middle_frame_kernel",
    "ContinuumBody",
]
