"""Optimal order-2 strokes of low-Re chains of 3, 4 and 5 links of the same total length (numbers, not code).

Beyond the draft, after Ramasamy & Hatton (ACC 2017; T-RO 2019): for chains of N equal links of
total length 3, drag ratio 2, seen from the centre of mass with the mean orientation
(``LinkChain((3 / N,) * N, "low_re", frame="com")``), the Fourier gaits of order 2 that
maximise the efficiency (net translation per unit path length in the power metric), found by
:func:`gm_core.geometry.optimize_gait` from a travelling-wave start (phases spread over pi).
tests/test_link_chain_geometry.py checks that each is stationary (the exact gradient vanishes)
and reproduces the stored efficiency and displacement.
"""
from __future__ import annotations

from ..systems import LinkChain
from .optimal import fourier_gait

__all__ = ["CHAIN_STROKES", "chain_swimmer", "chain_stroke"]

#: Fourier coefficients (a, b: (N - 1, 2); center: (N - 1,)) and the values they give.
CHAIN_STROKES = {
    3: dict(a=[[0.871746260052, 0.251905876442],
              [-0.871746260272, -0.251905874941]],
             b=[[0.912213522679, 0.287624276418],
              [0.912213523578, 0.287624277304]],
             center=[-0.218869912568, 0.218869913791],
             efficiency=0.063856, displacement=0.247544),
    4: dict(a=[[1.11099907307, -8.51628324813e-09],
              [-6.57026874636e-11, -5.7708690265e-09],
              [-1.11099907319, 4.14122905368e-09]],
             b=[[0.087111180395, 6.27945117509e-09],
              [1.41363323446, 2.25863444925e-08],
              [0.0871111804649, 1.19899045041e-08]],
             center=[6.21155169867e-09, 2.73366727466e-09, -6.82309371081e-09],
             efficiency=0.098425, displacement=0.346029),
    5: dict(a=[[0.869361172028, 5.21536676547e-08],
              [0.734343412342, 6.6388882086e-08],
              [-0.734343412563, -2.63883750107e-09],
              [-0.869361172123, -3.42850024779e-08]],
             b=[[-0.493418487842, -4.14708448012e-08],
              [0.998458518453, -1.6480264944e-07],
              [0.998458518487, -1.8953755447e-07],
              [-0.493418487756, -6.87850930347e-08]],
             center=[-3.64247462565e-08, -6.39617763094e-08, 5.33323624103e-08, 4.73453258423e-08],
             efficiency=0.118359, displacement=0.395648),
}


def chain_swimmer(n_links, total_length=3.0):
    """The swimmer of :data:`CHAIN_STROKES`: n_links equal links, drag ratio 2, centre-of-mass frame."""
    return LinkChain((total_length / n_links,) * n_links, "low_re", drag_ratio=2.0, frame="com")


def chain_stroke(n_links):
    """The stored optimal stroke for ``n_links`` (3, 4 or 5) links as a :func:`fourier_gait` (period 2 pi)."""
    if n_links not in CHAIN_STROKES:
        raise ValueError(f"n_links must be one of {sorted(CHAIN_STROKES)}; got {n_links!r}")
    c = CHAIN_STROKES[n_links]
    return fourier_gait(c["a"], c["b"], c["center"], name=f"optimal {n_links}-link stroke (efficiency, order 2)")
