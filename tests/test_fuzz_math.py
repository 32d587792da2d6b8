"""Hypothesis fuzz of every public function and method of gm_core.groups, calculus and fields.

Each row of the table is a :class:`fuzzkit.Case`: a callable, one valid example call, and the
kinds of its arguments. ``test_valid_examples`` checks the valid calls; ``test_bad_input``
replaces one argument at a time with wrong shapes, 0-d and empty arrays, broadcast-incompatible
batches, int/bool/complex/object dtypes, strings, None, NaN/inf, 1e+-300, negative or zero
sizes and unknown options, and accepts only a finite, right-shaped result or a ValueError /
TypeError naming that argument. Other modules extend the table (``CASES += [...]``).
"""
import numpy as np
import pytest
from fuzzkit import Case, baseline, cases_table, check_each, chunks, fuzz_each
from hypothesis import HealthCheck, settings

from gm_core import ALL_GROUPS, S1, SE2, Rn, matvec, wrap_angle
from gm_core import calculus as C
from gm_core import fields as F
from gm_core.groups import check_group

settings.register_profile("fuzz", max_examples=int(__import__("os").environ.get("FUZZ_EXAMPLES", 25)), deadline=None,
                          derandomize=not __import__("os").environ.get("FUZZ_RANDOM"),
                          suppress_health_check=list(HealthCheck))


# ------------------------------------------------------------------ groups
def group_cases(key, G):
    rng = np.random.default_rng(7)
    g, h = G.random(rng, ()), G.random(rng, ())
    xi, eta = rng.uniform(-1, 1, G.tangent_dim), rng.uniform(-1, 1, G.tangent_dim)
    p, m, t = G.param_dim, G.matrix_size, G.tangent_dim
    E, M, A = (p,), (m, m), (t,)
    rows = [
        ("identity", {"batch_shape": (2,)}, dict(shapes={"batch_shape"}, out_tail=E)),
        ("compose", {"g": g, "h": h}, dict(batch=("g", "h"), out_tail=E)),
        ("inverse", {"g": g}, dict(out_tail=E)),
        ("left_lifted_action", {"h": h, "g": g}, dict(batch=("h", "g"), out_tail=(p, p))),
        ("right_lifted_action", {"h": h, "g": g}, dict(batch=("h", "g"), out_tail=(p, p))),
        ("Ad", {"g": g}, dict(out_tail=(t, t))),
        ("Ad_inv", {"g": g}, dict(out_tail=(t, t))),
        ("hat", {"xi": xi}, dict(out_tail=M)),
        ("vee", {"X": G.hat(xi)}, dict(out_tail=A)),
        ("bracket", {"xi1": xi, "xi2": eta}, dict(batch=("xi1", "xi2"), out_tail=A)),
        ("ad", {"xi": xi}, dict(out_tail=(t, t))),
        ("exp", {"xi": xi}, dict(out_tail=E)),
        ("log", {"g": g}, dict(out_tail=A)),
        ("matrix", {"g": g}, dict(out_tail=M)),
        ("from_matrix", {"G": G.matrix(g)}, dict(out_tail=E)),
        ("nearest_element", {"M": G.matrix(g)}, dict(out_tail=E)),
        ("coordinate_matrix", {"q": g}, dict(out_tail=M)),
        ("world_to_body", {"g": g, "g_dot": xi}, dict(batch=("g", "g_dot"), out_tail=A)),
        ("body_to_world", {"g": g, "xi": xi}, dict(batch=("g", "xi"), out_tail=E)),
        ("world_to_spatial", {"g": g, "g_dot": xi}, dict(batch=("g", "g_dot"), out_tail=A)),
        ("spatial_to_world", {"g": g, "xi_s": xi}, dict(batch=("g", "xi_s"), out_tail=E)),
        ("body_to_spatial", {"g": g, "xi": xi}, dict(batch=("g", "xi"), out_tail=A)),
        ("spatial_to_body", {"g": g, "xi_s": xi}, dict(batch=("g", "xi_s"), out_tail=A)),
        ("difference", {"g": g, "h": h}, dict(batch=("g", "h"), out_tail=E)),
        ("isclose", {"g": g, "h": h, "atol": 1e-9}, dict(batch=("g", "h"))),
        ("random", {"rng": 3, "size": (2,), "scale": 1.0},
         dict(objects={"rng"}, shapes={"size"}, also_valid={"rng": (3,)}, out_tail=E)),
        ("numerical_left_lifted_action", {"h": h, "g": g, "eps": 1e-6}, dict(batch=("h", "g"), out_tail=(p, p))),
        ("numerical_right_lifted_action", {"h": h, "g": g, "eps": 1e-6}, dict(batch=("h", "g"), out_tail=(p, p))),
        ("contains", {"g": g}, dict(nan_ok={"g"})),
        ("project", {"g": g}, dict(out_tail=E)),
        ("euler_step", {"g": g, "xi": xi, "dt": 0.1, "side": "left"}, dict(options={"side"}, out_tail=E)),
    ]
    if G is SE2:
        rows.append(("act_on_points", {"g": g, "p": np.array([0.3, -0.2])}, dict(batch=("g", "p"), out_tail=(2,))))
    return [Case(f"{key}.{meth}", getattr(G, meth), args, **kw) for meth, args, kw in rows]


GROUP_CASES = [c for key, G in ALL_GROUPS.items() for c in group_cases(key, G)]

MODULE_CASES = [
    Case("wrap_angle", wrap_angle, {"theta": np.array([0.3, 7.0])}),
    Case("matvec", matvec, {"M": np.eye(3), "v": np.ones(3)}, batch=("M", "v")),
    Case("Rn", Rn, {"n": 3}, ints={"n"}),
    Case("S1", S1, {"period": 2.0}),
    Case("check_group", check_group, {"group": SE2}, objects={"group"}),
]

# ------------------------------------------------------------------ calculus
XI = np.array([1.0, 0.2, 0.7])
ROT = np.array([[0.0, -1.0], [1.0, 0.0]])
CALCULUS_CASES = [
    Case("product_integral", C.product_integral,
         {"v": ROT, "a": 0.0, "b": 1.0, "n": 8, "side": "right", "point": "mid", "history": False},
         kwonly={"point", "history"}, ints={"n"}, options={"side", "point"}, flags={"history"},
         also_valid={"v": (3,)}),
    Case("product_integral(callable)", C.product_integral,
         {"v": lambda x: x * ROT, "a": 0.0, "b": 1.0, "n": 8}, ints={"n"}, callables={"v"},
         also_valid={"v": (3,)}),
    Case("quotient_derivative", C.quotient_derivative,
         {"F": lambda x: SE2.matrix([x, 0.0, x]), "x": 0.4, "side": "left", "h": 1e-5, "method": "central"},
         kwonly={"method"}, callables={"F"}, options={"side", "method"}, also_valid={"h": (None,)}),
    Case("element_from_matrix", C.element_from_matrix, {"group": SE2, "M": SE2.matrix(XI)},
         objects={"group"}, out_tail=(3,)),
    Case("convergence_order", C.convergence_order,
         {"n": np.array([1.0, 2.0, 4.0, 8.0]), "error": np.array([1.0, 0.5, 0.26, 0.12]), "floor": 1e-13}),
    Case("binomial_terms", C.binomial_terms, {"n": 7, "k": 3}, ints={"n", "k"}),
    Case("se2_exp_study", C.se2_exp_study, {"thetadots": np.array([0.5, 1.0]), "n": 4, "speed": 1.0},
         ints={"n"}, also_valid={"n": ([2],)}),
]
for fname in ("exp_history", "exp_closed_form", "exp_taylor", "exp_product", "exp_euler", "exp_four_ways"):
    args = {"group": SE2, "xi": XI, "n": 8}
    opts = {"side"}
    if fname == "exp_history":
        args["method"] = "product"
        opts.add("method")
    args["side"] = "left"
    CALCULUS_CASES.append(Case(fname, getattr(C, fname), args, objects={"group"}, ints={"n"}, options=opts,
                               also_valid={"n": ([2],)}))
CALCULUS_CASES.append(Case("ExpHistory.path", lambda n: C.exp_euler(SE2, XI, 8).path(n), {"n": 4},
                           ints={"n"}, also_valid={"n": (None,)}))

# ------------------------------------------------------------------ fields
ROT_FIELD = F.VectorField(lambda q, t: np.stack([-q[..., 1], q[..., 0]], -1), 2, name="rotation")
FIELD_CASES = [
    Case("VectorField", F.VectorField, {"func": lambda q, t: -q, "dim": 2},
         callables={"func"}, ints={"dim"}),
    Case("VectorField.__call__", ROT_FIELD, {"q": np.array([1.0, 0.5]), "t": 0.0}, out_tail=(2,)),
    Case("VectorField.on_grid", lambda a0, a1, at: ROT_FIELD.on_grid(a0, a1, at=at),
         {"axes_values[0]": np.linspace(-1, 1, 3), "axes_values[1]": np.linspace(-1, 1, 4),
          "at": np.zeros(2)}, also_valid={"at": (None,)}),
    Case("integral_curve", F.integral_curve,
         {"field": ROT_FIELD, "q0": np.array([1.0, 0.0]), "t_span": np.array([0.0, 1.0]),
          "t_eval": np.array([0.0, 0.5, 1.0])}, objects={"field"}, also_valid={"t_eval": (None,)},
         also_raises=(RuntimeError,)),
    Case("left_invariant_field", lambda group, xi, q: F.left_invariant_field(group, xi)(q),
         {"group": SE2, "xi": XI, "q": np.array([1.0, 2.0, 0.3])}, objects={"group"}, out_tail=(3,)),
    Case("right_invariant_field", lambda group, xi_s, q: F.right_invariant_field(group, xi_s)(q),
         {"group": SE2, "xi_s": XI, "q": np.array([1.0, 2.0, 0.3])}, objects={"group"}, out_tail=(3,)),
    Case("group_geodesic", F.group_geodesic,
         {"group": SE2, "xi": XI, "t": np.array([-0.5, 0.0, 1.0]), "side": "right",
          "g0": np.array([1.0, 2.0, 0.3]), "method": "exp"}, also_valid={"g0": (None,)},
         kwonly={"method"}, objects={"group"}, options={"side", "method"}, out_tail=(3,)),
    Case("group_geodesic(integrate)", F.group_geodesic,
         {"group": SE2, "xi": XI, "t": np.array([-0.5, 0.0, 1.0]), "side": "left",
          "g0": np.array([1.0, 2.0, 0.3]), "method": "integrate"}, also_valid={"g0": (None,)},
         kwonly={"method"}, objects={"group"}, options={"side", "method"}, out_tail=(3,),
         also_raises=(RuntimeError,)),
    Case("se2_helix", F.se2_helix, {"xi": XI, "side": "left", "g0": np.array([1.0, 2.0, 0.3])},
         options={"side"}, batch=("xi", "g0"), also_valid={"g0": (None,)}, finite=False),
    Case("HelixGeometry.circle_points", lambda num: F.se2_helix(XI).circle_points(num), {"num": 16},
         ints={"num"}),
    Case("se2_helices", F.se2_helices, {"thetadot": np.array([0.5, 2.0]), "t": np.linspace(0, 1, 3),
                                        "speed": 1.0}, finite=False),
    Case("puck_vs_arc", F.puck_vs_arc, {"t": np.linspace(0, 1, 3), "xi": XI}),
    Case("rplus_geodesics", F.rplus_geodesics, {"xi": np.array([-1.0, 0.5]), "t": np.linspace(0, 1, 3),
                                                "g0": 2.0}),
]

CASES = cases_table(GROUP_CASES, MODULE_CASES, CALCULUS_CASES, FIELD_CASES)


@pytest.mark.parametrize("cases", chunks(CASES))
def test_valid_examples(cases):
    check_each(cases, baseline)


@pytest.mark.parametrize("cases", chunks(CASES))
def test_bad_input(cases):
    fuzz_each(cases, settings.get_profile("fuzz"))
