"""Optimal order-2 strokes of low-Re chains of 3, 4 and 5 links of the same total length (numbers, not code).

Beyond the draft, after Ramasamy & Hatton (ACC 2017; T-RO 2019): for chains of N equal links of
total length 3, drag ratio 2, seen from the centre of mass with the mean orientation
(:func:`chain_swimmer`, ``LinkChain((3 / N,) * N, "low_re", frame="com")``), the Fourier gaits of
order 2 that maximise the efficiency (net translation per unit path length in the power metric).

The efficiency has many local maxima, and where the optimiser ends depends on where it starts.
The stored strokes were chosen as follows. From each of the fifteen named starts of :func:`chain_starts`
(five travelling waves and ten random gaits),
``optimize_chain_gait(chain_swimmer(N), order=2, start=start, maxiter=400, intervals=64)``
climbs to a local maximum, which is then refined at 256 intervals until the exact gradient
vanishes (below 1e-10). :data:`CHAIN_OPTIMA` lists the distinct maxima found, most efficient
first, each with the starts that lead to it (mirror images, reversed bodies and time shifts of
one stroke have the same efficiency and count as one). In some of them two links pass through
each other (:func:`links_cross`), which no body can do; :data:`CHAIN_STROKES` holds, for each N,
the most efficient of the others (:func:`chain_stroke`).

Fifteen starts are not an exhaustive search: :data:`OTHER_CHAIN_OPTIMA` records a three-link
maximum reached from a start outside them, a folded stroke whose links do not cross and which
is more efficient than the stored three-link stroke.

tests/test_chain_optima.py checks these records (its slow tests rerun the optimiser from every
named start); tests/test_link_chain_geometry.py checks that each stored stroke is a maximum.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from gm_core.geometry.optimal import FourierGait, OptimalGait, fourier_gait, optimize_gait, travelling_wave
from gm_core.systems import LinkChain
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.gaits import GaitLike, as_gait
from gm_core.systems.motion import check_gait
from gm_core.validation import check_int, positive_number

__all__ = ["CHAIN_STROKES", "CHAIN_OPTIMA", "OTHER_CHAIN_OPTIMA", "START_LAGS", "START_SEEDS", "chain_swimmer",
           "chain_stroke", "chain_optima", "chain_starts", "links_cross", "random_start", "wave_start",
           "optimize_chain_gait"]

#: For N = 3, 4, 5: the distinct local maxima of the efficiency reached from the named starts of
#: :func:`chain_starts` (see the module's docstring), most efficient first: efficiency and
#: displacement per cycle (at 256 intervals), the names of the starts that lead there, and the
#: gait's ``FourierGait.parameters`` (order 2, period 2 pi).
CHAIN_OPTIMA: dict[int, list[dict[str, Any]]] = {
    3: [
        dict(efficiency=0.0665372571, displacement=0.6652206208,
             starts=("random, seed 6",),
             parameters=(-0.398951292376, -0.442137971421, 2.50075028443, 0.774662380676, -1.84152240204,
                         1.30737964185, 0.443404427879, -0.836441246065, 1.4331873329, 0.0419405070821)),
        dict(efficiency=0.0639086156, displacement=0.2485275896,
             starts=("random, seed 0", "random, seed 3", "random, seed 5", "random, seed 8"),
             parameters=(0.261877590164, -0.176241089014, 0.907809762606, 0.253289866375, 0.923927500032,
                         -0.251045101808, -0.888604074378, 0.281561434436, 0.854484435669, 0.292421545858)),
        dict(efficiency=0.0639012816, displacement=0.2484303573,
             starts=("random, seed 4",),
             parameters=(0.256864338175, -0.180986075725, 0.139716192307, 0.328105852744, 1.2580628596,
                         0.240434725347, -1.25763294639, -0.19323004489, 0.0800141714664, 0.303506098237)),
        dict(efficiency=0.0638609855, displacement=0.2478619243,
             starts=("wave, lag 0.4", "wave, lag 0.8", "wave, lag 1.2", "wave, lag 1.6", "wave, lag 2",
                     "random, seed 9"),
             parameters=(-0.245999950003, -0.268807000255, -0.0329327641636, -0.221801259147, -1.30490847208,
                         0.151955755351, 1.31751267787, -0.202868341043, 0.290094439937, -0.249931884032)),
        dict(efficiency=0.0637663345, displacement=0.4934609402,
             starts=("random, seed 1", "random, seed 2", "random, seed 7"),
             parameters=(-0.0328030041709, -0.0338202313226, -0.00583851679055, -0.680959293525,
                         -0.00743298108265, -1.29260502204, 0.000455876449484, 1.19820582697, 0.000802427226611,
                         -0.483377694654)),
    ],
    4: [
        dict(efficiency=0.0988606502, displacement=0.3523490060,
             starts=("wave, lag 1.2", "wave, lag 1.6", "wave, lag 2"),
             parameters=(-0.0269455512915, -0.368750007909, -0.0269455541976, -0.0581430021219, 0.072761897838,
                         -1.44353491928, 0.283603687552, -0.0581429562225, 0.0727618718928, 1.01077023816,
                         -0.236240876366, -3.46322291053e-08, 1.5033113567e-08, -1.01077024143,
                         0.236240882846)),
        dict(efficiency=0.0988498786, displacement=0.3525752731,
             starts=("random, seed 8",),
             parameters=(-0.28395932431, -0.0502239612235, 0.232678491668, 0.341594692215, -0.184581358896,
                         -1.13449137535, -0.286727044528, -0.522091545672, 0.235865264141, -1.03775033965,
                         -0.230918564345, -0.514186810909, 0.28449243425, 0.942924303303, 0.210571526593)),
        dict(efficiency=0.0988074472, displacement=0.3511632241,
             starts=("random, seed 9",),
             parameters=(-0.254970067258, 0.00691692359544, 0.262053582738, -0.690362379643, -0.137355639201,
                         -1.02428198063, 0.373412947119, 0.524375570063, 0.0886489409547, 0.836193142619,
                         -0.275160068537, -0.699885974294, -0.150599546782, -0.952198660272, 0.291461176925)),
        dict(efficiency=0.0987983171, displacement=0.3502576008,
             starts=("wave, lag 0.4", "wave, lag 0.8", "random, seed 0"),
             parameters=(0.00988912704037, 0.346194037833, 0.0150801425424, 0.698295485916, 0.246029616216,
                         -0.979028590458, 0.0174439433068, -0.778244420147, -0.23457586828, 0.730987190237,
                         0.055304776429, 1.04885194841, 0.287904987893, -0.644169398801, 0.081832316134)),
        dict(efficiency=0.0984589062, displacement=0.6942024284,
             starts=("random, seed 1", "random, seed 7"),
             parameters=(-0.0197261315963, -0.0247099256746, -0.0197261316096, -0.00346835393144,
                         -0.0874829485392, -0.00925933373324, -1.41768577601, -0.00346835395462,
                         -0.0874829427982, -0.000593047961868, 1.11072665025, 1.39279640007e-11,
                         -3.6339883756e-09, 0.000593047994922, -1.1107266507)),
        dict(efficiency=0.0984281530, displacement=0.6919591835,
             starts=("random, seed 5",),
             parameters=(-0.00571952648228, -0.00632796459755, -0.00599295810523, -0.000910271700469,
                         -0.93788262088, -0.000768739520729, 0.66874929048, -0.00115723608461, 1.01943053439,
                         0.000589368313207, 0.602660609926, -6.71556153344e-06, 1.24540472517,
                         -0.000611918811946, -0.449351288055)),
        dict(efficiency=0.0877144616, displacement=0.5878243880,
             starts=("random, seed 2",),
             parameters=(-0.0768646768196, -0.852595600818, 0.882974342818, -0.291065549738, 0.142397443158,
                         -0.904027613572, -1.12050197789, 1.36274878261, -0.38948869342, 0.0624172516342,
                         0.935279119335, -1.10300799223, -0.176565722296, 1.15630089072, 0.122649852017)),
        dict(efficiency=0.0861975285, displacement=0.4737135982,
             starts=("random, seed 4",),
             parameters=(0.150614718797, -0.708827435727, 1.08408197467, -0.71084239749, -0.622766843632,
                         0.743240316645, 0.450284963871, -0.495224127248, 0.327919779344, -0.464638297969,
                         -0.172431659708, -1.70721513449, -0.400342723141, 1.45552048865, -0.5106226346)),
        dict(efficiency=0.0728220252, displacement=0.6224229600,
             starts=("random, seed 6",),
             parameters=(0.525451983205, -1.06442349591, 0.40511928305, 1.10088677229, 1.20454179844,
                         -0.559479558051, 0.0796721197607, 0.719929767554, -0.807105716149, 0.0799762944726,
                         -1.23967297706, 2.38555309313, -0.252526994423, -0.116401391358, 0.181259349832)),
        dict(efficiency=0.0628509045, displacement=1.0550362412,
             starts=("random, seed 3",),
             parameters=(-1.47065779623, -0.0468724066651, -0.0442766081766, 2.35402377203, -0.753899296641,
                         -0.121615014766, -3.18505668258, -0.147745051731, 0.176627012594, -1.06120526479,
                         -2.16871587235, -0.252546856721, 0.78588398593, 0.11891479228, -1.03407449028)),
    ],
    5: [
        dict(efficiency=0.1187029397, displacement=0.4023404323,
             starts=("random, seed 0",),
             parameters=(0.214882068969, 0.178075609087, -0.136783618038, -0.208385557076, -0.660364699434,
                         0.00502731562819, -0.984409870687, -0.352977248293, 0.304945156182, -0.0297930215419,
                         0.961532599863, 0.280279416786, 0.703313307421, 0.265474988638, -0.549824364745,
                         -0.0472060021112, -1.0711786247, -0.366453116889, 0.0349688517177, 0.0182401410023)),
        dict(efficiency=0.1187010463, displacement=0.4022873947,
             starts=("wave, lag 2",),
             parameters=(-0.208798879082, -0.138183310429, 0.175383946901, 0.214852255442, -0.132435375609,
                         -0.268435162094, -1.10766280071, 0.154614562674, -0.369471654706, 0.348196395373,
                         0.808132576705, -0.0965123531044, 0.952638421822, -0.0788992099962, 0.113325293403,
                         -0.333235302826, -1.06552466902, 0.0782038512642, -0.52850457386, 0.247509634279)),
        dict(efficiency=0.1186783573, displacement=0.4005409081,
             starts=("wave, lag 0.4",),
             parameters=(-0.207856338537, 0.0706131085853, 0.307367730028, 0.0532273053112, 0.948248304351,
                         0.299311308404, -0.00909180755667, 0.0202245417807, -1.19831165271, -0.232887498376,
                         -0.396471505164, -0.0992926709065, 0.0809373294115, 0.0109477134457, 1.09765482546,
                         0.337556212767, 0.372423499292, 0.0916134331274, -0.837334288092, -0.155155604883)),
        dict(efficiency=0.1186768984, displacement=0.4004764583,
             starts=("wave, lag 1.6",),
             parameters=(-0.208070223919, 0.0725353715777, 0.306010887854, 0.0522390920645, -0.0339049792096,
                         -0.29751880311, -1.09568355047, -0.0526454917464, -0.428977420669, 0.222706767815,
                         0.818650009918, 0.115338537854, 0.950329880614, 0.0187208607582, 0.0418605434857,
                         -0.333073772642, -1.18185106383, -0.114025262638, -0.436255327377, 0.143221069424)),
        dict(efficiency=0.1186656218, displacement=0.4018766139,
             starts=("wave, lag 0.8", "wave, lag 1.2", "random, seed 1"),
             parameters=(-0.0463358926164, -0.306801231648, -0.0746558600413, 0.209002150694, 0.723825426247,
                         -0.160825385091, -0.642107683359, -0.164675984396, -1.07501001907, 0.173070670084,
                         0.141032578865, 0.269759542279, 0.574455818178, 0.088755339632, 1.08436198278,
                         -0.18918661678, -0.240637709586, -0.288681182264, -0.937764935556, 0.12666001691)),
        dict(efficiency=0.1183654040, displacement=0.7911383781,
             starts=("random, seed 2",),
             parameters=(-0.00632579411013, -0.00845192619208, -0.0091033989236, -0.00620858592423,
                         -0.0016627489044, -1.00006239788, -0.000902965518665, -0.117860439094,
                         -0.00215292658825, 1.14178274595, -0.00099303615509, 0.492855911903, -0.00117701573917,
                         -0.0231283055024, 3.89792167048e-05, -1.233722169, -9.96061904439e-05, -0.480113336411,
                         0.000960773761221, 0.86994920832)),
        dict(efficiency=0.1077181967, displacement=0.4924972044,
             starts=("random, seed 4",),
             parameters=(-0.0655157384949, 0.957418947126, -1.24262644084, 1.09708624417, 0.285855408144,
                         -0.372361137721, 1.52571359692, 0.486531426281, -0.71556839875, 0.488459905412,
                         -0.808701329585, -0.183787649447, 0.646162283511, 0.409599613285, -1.01356494172,
                         -0.109218902216, 1.01619514003, 0.2812953091, -1.29059070926, 0.0213878582746)),
        dict(efficiency=0.1004131954, displacement=0.7824087703,
             starts=("random, seed 5",),
             parameters=(1.13278805752, 0.692879549177, -2.06039159375, 0.0807746294989, 1.48389576539,
                         -0.25199332491, -0.228945146342, -0.0276489809347, -0.490831536777, 1.65739769752,
                         0.177199589124, -0.936418950632, 1.21758667754, 0.0645164052596, 1.74020141756,
                         -0.562005208149, -2.74711538293, 0.628708392809, 0.226720059032, 0.527174284699)),
        dict(efficiency=0.0981718633, displacement=0.6533583888,
             starts=("random, seed 7",),
             parameters=(1.79635018505, -0.361425532011, -0.384823766161, -0.0360709622405, -0.0135127046409,
                         -0.730734093383, -0.0226868890701, 1.01985867483, -0.00487043122852, 0.890009854803,
                         -0.0396865406193, -0.798448619723, -0.0535073585499, 0.839926850219, -0.0382428154029,
                         -0.486671824227, 0.0118052356174, 1.02291676149, 0.0381669932441, 0.58012044205)),
        dict(efficiency=0.0876274508, displacement=0.6837817317,
             starts=("random, seed 6",),
             parameters=(1.37245857946, -1.26840805725, 0.67897712701, -1.30500962227, 1.71346638542,
                         -0.0819869432453, -2.31630671141, -1.13427878709, -0.274958613991, 0.651130624287,
                         2.23555604788, 0.50135569844, -0.736707803236, -0.232477060973, 1.25748544737,
                         0.0942663228859, -0.766995070845, -1.21499340563, -1.18721810891, 0.767826907291)),
        dict(efficiency=0.0827718467, displacement=1.0904060691,
             starts=("random, seed 9",),
             parameters=(-0.834548768327, -0.0422163034143, 0.173565025594, -0.282409377016, -1.25679606936,
                         -1.47467207212, -2.46303705107, 1.05602755419, 0.625664876404, 2.41885868345,
                         0.703675279971, -0.509477562132, -0.193378206464, 0.266131150605, -0.81417841469,
                         -0.412908313664, -0.804077454201, 1.17269905074, 0.309713945261, -1.13959980294)),
        dict(efficiency=0.0783778364, displacement=0.7451458105,
             starts=("random, seed 8",),
             parameters=(-0.649621972941, -0.0978590739959, 0.0560859943479, 0.622085895103, -1.14635220259,
                         -1.51663827741, -0.209422422819, -0.251706741646, -0.204235729381, 1.11414126233,
                         -1.1578015886, 1.36725330748, 0.258580235527, 0.478429207636, 0.0364186684343,
                         1.2716444031, 0.0270174092834, 0.645494547441, 0.20844511796, -0.800007274159)),
        dict(efficiency=0.0688539932, displacement=0.9544624588,
             starts=("random, seed 3",),
             parameters=(0.40543608891, -0.20885821041, -0.520850655619, -0.595212805181, 0.995259496438,
                         -2.68213798561, -0.0414982610236, -1.28309944736, -0.58683166001, -0.0201450106054,
                         -0.279461025564, 1.40576618546, 0.0879037817821, 0.284104760691, -0.260457917767,
                         -0.688921115285, -0.724525854276, -1.78065583206, -0.985249602767, -0.548980944954)),
    ],
}

#: Local maxima reached from starts outside :func:`chain_starts`, in the same form.
OTHER_CHAIN_OPTIMA: dict[int, list[dict[str, Any]]] = {
    3: [
        dict(efficiency=0.0726572583, displacement=0.2770029552,
             starts=("random, seed 72",),
             parameters=(-1.75656237115, 1.65381040319, -0.935617498891, 0.108072462139, -0.470079747096,
                         -0.092578980556, -0.636965777646, -0.0545657938788, 1.04028219775, 0.0598333608106)),
    ],
}

#: The index in CHAIN_OPTIMA[N] of the stored stroke: the most efficient maximum whose links do not cross.
_STORED = {3: 1, 4: 0, 5: 0}


def _coefficients(n_links: int, optimum: dict[str, Any]) -> dict[str, Any]:
    g = FourierGait.from_parameters(optimum["parameters"], n_links - 1, 2)
    return dict(a=g.a.tolist(), b=g.b.tolist(), center=g.center.tolist(),
                efficiency=optimum["efficiency"], displacement=optimum["displacement"])


#: The stored strokes (see the module's docstring): Fourier coefficients (a, b: (N - 1, 2);
#: center: (N - 1,)) and the efficiency and displacement per cycle they give.
CHAIN_STROKES: dict[int, dict[str, Any]] = {N: _coefficients(N, CHAIN_OPTIMA[N][k]) for N, k in _STORED.items()}


def chain_swimmer(n_links: int, total_length: float = 3.0) -> LinkChain:
    """The swimmer of :data:`CHAIN_STROKES`: n_links equal links, drag ratio 2, centre-of-mass frame."""
    return LinkChain((total_length / n_links,) * n_links, "low_re", drag_ratio=2.0, frame="com")


def chain_stroke(n_links: int) -> FourierGait:
    """The stored optimal stroke for ``n_links`` (3, 4 or 5) links as a :func:`fourier_gait` (period 2 pi)."""
    if n_links not in CHAIN_STROKES:
        raise ValueError(f"n_links must be one of {sorted(CHAIN_STROKES)}; got {n_links!r}")
    c = CHAIN_STROKES[n_links]
    return fourier_gait(c["a"], c["b"], c["center"], name=f"optimal {n_links}-link stroke (efficiency, order 2)")


def chain_optima(n_links: int) -> list[FourierGait]:
    """The local maxima of :data:`CHAIN_OPTIMA` for ``n_links`` (3, 4 or 5) links as
    :func:`fourier_gait` s (period 2 pi), most efficient first; each is named after its rank."""
    if n_links not in CHAIN_OPTIMA:
        raise ValueError(f"n_links must be one of {sorted(CHAIN_OPTIMA)}; got {n_links!r}")
    return [FourierGait.from_parameters(o["parameters"], n_links - 1, 2,
                                        name=f"local maximum {k} of the {n_links}-link chain")
            for k, o in enumerate(CHAIN_OPTIMA[n_links], 1)]


def links_cross(chain: LinkChain, gait: GaitLike, samples: int = 1024) -> bool:
    """Does any link of ``chain`` (a :class:`LinkChain`) pass through another during ``gait``? At
    ``samples`` equally spaced instants of one period: a joint angle at or beyond +-pi (two
    neighbours folded onto or through each other), or two links that are not neighbours crossing
    (the segments of length ``chain.lengths`` through the link centres intersect)."""
    if not isinstance(chain, LinkChain):
        raise TypeError(f"chain must be a LinkChain (e.g. chain_swimmer(5)); got {type(chain).__name__}")
    n = check_int(samples, "samples", minimum=8, maximum=1_000_000)
    check_gait(chain, gait)
    gait = as_gait(gait)
    r = np.asarray(gait(np.linspace(0.0, gait.period, n, endpoint=False)), dtype=float)
    if np.any(np.abs(r) >= np.pi):
        return True
    poses = chain.link_poses(r)                                       # (n, N, 3)
    half = 0.5 * np.asarray(chain.lengths)[:, None] * np.stack([np.cos(poses[..., 2]), np.sin(poses[..., 2])], -1)
    p, q = poses[..., :2] - half, poses[..., :2] + half               # link ends

    def side(o, d, x):                                 # which side of the line o + s d the point x is on
        return np.sign(d[..., 0] * (x - o)[..., 1] - d[..., 1] * (x - o)[..., 0])

    for i in range(chain.n_links):
        for j in range(i + 2, chain.n_links):
            di, dj = q[:, i] - p[:, i], q[:, j] - p[:, j]
            # the segments cross where each one's ends lie on opposite sides of the other's line
            straddle_i = side(p[:, i], di, p[:, j]) * side(p[:, i], di, q[:, j]) < 0
            straddle_j = side(p[:, j], dj, p[:, i]) * side(p[:, j], dj, q[:, i]) < 0
            if np.any(straddle_i & straddle_j):
                return True
    return False


def wave_start(n_joints: int, amplitude: float = 0.6, lag: float = 0.8, *, spread: float = 0.05,
               seed: int = 0) -> FourierGait:
    """A start for optimising a chain's gait: the :func:`travelling_wave` (``amplitude``, ``lag``)
    with its Fourier coefficients nudged by a seeded normal ``spread``, so an optimisation leaves
    the symmetric saddle points a perfect wave can sit on (deterministic for a given ``seed``)."""
    w = travelling_wave(n_joints, amplitude, lag)
    spread = positive_number(spread, "spread", allow_zero=True, maximum=1.0)
    rng = np.random.default_rng(check_int(seed, "seed", minimum=0, maximum=2 ** 31))
    return fourier_gait(w.a + spread * rng.standard_normal(w.a.shape), w.b + spread * rng.standard_normal(w.b.shape),
                        name=f"start: wave, amplitude {amplitude:g}, lag {lag:g} rad")


#: lags (rad) of the travelling-wave starts of :func:`chain_starts`
START_LAGS = (0.4, 0.8, 1.2, 1.6, 2.0)
#: seeds of the random starts of :func:`chain_starts`
START_SEEDS = tuple(range(10))


def random_start(n_joints: int, seed: int, *, order: int = 2, scale: float = 0.8,
                 center: float = 0.5) -> FourierGait:
    """A random Fourier gait of ``order`` to start an optimisation from: cosine and sine
    coefficients normal with standard deviation ``scale``, each joint's centre uniform in
    [-center, center] (rad), drawn in that order from ``numpy.random.default_rng(seed)``."""
    n = check_int(n_joints, "n_joints", minimum=1, maximum=200, what=" (the number of joints)")
    K = check_int(order, "order", minimum=1, maximum=50)
    scale = positive_number(scale, "scale")
    center = positive_number(center, "center", allow_zero=True)
    rng = np.random.default_rng(check_int(seed, "seed", minimum=0, maximum=2 ** 31))
    a, b = rng.normal(0.0, scale, (n, K)), rng.normal(0.0, scale, (n, K))
    return fourier_gait(a, b, rng.uniform(-center, center, n), name=f"start: random, seed {seed}")


def chain_starts(n_links: int) -> dict[str, FourierGait]:
    """The named starts the stored strokes were chosen from, for a chain of ``n_links`` links:
    ``"wave, lag L"``, the :func:`wave_start` of amplitude 0.6 and lag L (seed 0) for each L of
    :data:`START_LAGS`, and ``"random, seed k"``, the order-2 :func:`random_start` of seed k for
    each k of :data:`START_SEEDS`."""
    n = check_int(n_links, "n_links", minimum=2, maximum=201, what=" (the number of links)") - 1
    starts = {f"wave, lag {lag:g}": wave_start(n, 0.6, lag) for lag in START_LAGS}
    starts.update({f"random, seed {k}": random_start(n, k) for k in START_SEEDS})
    return starts


def optimize_chain_gait(system: LocomotionSystem, order: int = 1, *, start: Any = None, maxiter: int = 40,
                        intervals: int = 64, callback: Callable[[int, float], Any] | None = None) -> OptimalGait:
    """The most efficient Fourier gait of ``order`` of a chain of any number of links, from
    :func:`wave_start` (or ``start``), measured in the chain's own body frame (use
    ``frame="com"``): :func:`optimize_gait` with ``objective="efficiency"``,
    ``coordinates="given"``. ``maxiter`` and ``intervals`` default to a live run of a second or
    so; ``callback(iteration, efficiency)`` reports progress. Returns the :class:`OptimalGait`."""
    start = wave_start(system.n_shape) if start is None else start
    return optimize_gait(system, "efficiency", order=order, start=start, coordinates="given", maxiter=maxiter,
                         intervals=intervals, callback=callback)
