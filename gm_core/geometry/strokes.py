"""sysplotter's published optimal strokes for its low-Reynolds three-link swimmer, as Fourier gaits.

sysplotter (OSU-LRAM/GeometricSystemPlotter, files ``shchf_LowRe_MaxDisplacement.m`` and
``shchf_LowRe_MaxEfficiency.m``) defines each stroke as
``u = a1 cos t + a3 cos 3t + a5 cos 5t``, ``v = b1 sin t + b3 sin 3t + b5 sin 5t`` evaluated at
``-t``, then ``(alpha1, alpha2) = R(45 deg) (u, v)``, period 2 pi, for links of length 1/3 and
drag ratio 2. Only the coefficients are used here (numbers, not code).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from gm_core.geometry.optimal import FourierGait, fourier_gait
from gm_core.systems import LowReSwimmer

__all__ = ["SYSPLOTTER_STROKES", "sysplotter_stroke", "sysplotter_swimmer"]

#: (a1, b1, a3, b3, a5, b5) and the values our model gives them (displacement, path length, efficiency).
SYSPLOTTER_STROKES: dict[str, dict[str, Any]] = {
    "displacement": dict(coefficients=(2.017955906441066, 1.353385144748382, 0.013112519773635,
                                       0.263823759269392, -0.031456173657342, -0.003626287235861),
                         displacement=0.10352, path_length=1.0959),
    "efficiency": dict(coefficients=(1.495398722861924, 1.326600886340017, 0.083253854456986,
                                     0.089227148110158, -0.034695750579259, -0.044759551791058),
                       displacement=0.08727, path_length=0.78661, efficiency=0.11095),
}


def sysplotter_swimmer() -> LowReSwimmer:
    """The swimmer those strokes were optimised for: LowReSwimmer(lengths=(1/3,)*3, drag_ratio=2)."""
    return LowReSwimmer(lengths=(1 / 3, 1 / 3, 1 / 3), drag_ratio=2.0)


def sysplotter_stroke(which: str = "displacement") -> FourierGait:
    """sysplotter's max-displacement or max-efficiency stroke as a :func:`fourier_gait` (order 5).

    Substituting -t and rotating by 45 degrees: alpha1 = (u - v)/sqrt 2 and
    alpha2 = (u + v)/sqrt 2 with u(-t) = sum a_k cos kt and v(-t) = -sum b_k sin kt.
    """
    if which not in SYSPLOTTER_STROKES:
        raise ValueError(f"which must be one of {sorted(SYSPLOTTER_STROKES)}; got {which!r}")
    a1, b1, a3, b3, a5, b5 = SYSPLOTTER_STROKES[which]["coefficients"]
    q = 1 / np.sqrt(2)
    a = np.zeros((2, 5))
    b = np.zeros((2, 5))
    for k, ak, bk in ((1, a1, b1), (3, a3, b3), (5, a5, b5)):
        a[:, k - 1] = q * ak
        b[0, k - 1], b[1, k - 1] = q * bk, -q * bk
    return fourier_gait(a, b, period=2 * np.pi, name=f"sysplotter max-{which} stroke")
