"""Geometry of locomotion beyond the draft: curvature, Stokes estimate, coordinates, costs, optimal gaits.

numpy/scipy only. Follows Hatton & Choset (2011-2015) for the constraint curvature and the
choice of body frame, and Ramasamy & Hatton (2019) for gait optimisation; conventions are the
book's (``xi = -A(r) r_dot``, (3.10)).

* :mod:`.curvature`: ``constraint_curvature``, ``stokes_estimate``, ``body_velocity_integral``;
* :mod:`.coordinates`: ``reframe``, ``centre_of_mass``, ``drift_and_turn``, ``centre_of_mass_coordinates``, ``minimum_perturbation_coordinates``;
* :mod:`.metrics`: ``dissipation_metric``, ``path_length``, ``efficiency``;
* :mod:`.optimal`: ``fourier_gait``, ``fourier_fit``, ``optimize_gait``; :mod:`.strokes`: ``sysplotter_stroke``;
  :mod:`.chain_strokes`: optimal strokes of 3-, 4- and 5-link chains (``chain_stroke``), the local
  maxima they were chosen from (``chain_optima``, ``chain_starts``) and ``links_cross``;
* :mod:`.estimates`: ``shaped_gait``, ``displacement_estimates``, ``row_scaled``, ``field_rms`` (notebook 10's panels).
"""
from gm_core.geometry.chain_strokes import (
    CHAIN_OPTIMA,
    CHAIN_STROKES,
    OTHER_CHAIN_OPTIMA,
    chain_optima,
    chain_starts,
    chain_stroke,
    chain_swimmer,
    links_cross,
    optimize_chain_gait,
    random_start,
    wave_start,
)
from gm_core.geometry.coordinates import (
    centre_of_mass,
    centre_of_mass_coordinates,
    drift_and_turn,
    minimum_perturbation_coordinates,
    reframe,
)
from gm_core.geometry.curvature import (
    body_velocity_integral,
    connection_curl,
    connection_derivative,
    constraint_curvature,
    stokes_estimate,
)
from gm_core.geometry.estimates import FRAMES, Estimates, displacement_estimates, field_rms, row_scaled, shaped_gait
from gm_core.geometry.metrics import dissipation_metric, efficiency, path_length
from gm_core.geometry.optimal import (
    FourierGait,
    OptimalGait,
    fourier_fit,
    fourier_gait,
    gait_objective,
    optimize_gait,
    travelling_wave,
)
from gm_core.geometry.strokes import SYSPLOTTER_STROKES, sysplotter_stroke, sysplotter_swimmer

__all__ = ["constraint_curvature", "connection_derivative", "connection_curl", "stokes_estimate", "body_velocity_integral",
           "reframe", "centre_of_mass", "drift_and_turn", "centre_of_mass_coordinates", "minimum_perturbation_coordinates",
           "dissipation_metric", "path_length", "efficiency",
           "FourierGait", "OptimalGait", "fourier_fit", "fourier_gait", "travelling_wave", "gait_objective", "optimize_gait",
           "SYSPLOTTER_STROKES", "sysplotter_stroke", "sysplotter_swimmer",
           "CHAIN_STROKES", "chain_stroke", "chain_swimmer", "wave_start", "optimize_chain_gait",
           "CHAIN_OPTIMA", "OTHER_CHAIN_OPTIMA", "chain_optima", "chain_starts", "links_cross", "random_start",
           "FRAMES", "Estimates", "displacement_estimates", "field_rms", "row_scaled", "shaped_gait"]
