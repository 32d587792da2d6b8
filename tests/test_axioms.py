"""gm_core.groups.axioms: the axiom residuals and membership test, over every group, checked against
direct computations (matrix products for associativity, known non-elements)."""
import numpy as np
import pytest

from gm_core import ALL_GROUPS, SE2, RPlus
from gm_core.groups.axioms import AXIOMS, axiom_residuals, powers


@pytest.mark.parametrize("name", list(ALL_GROUPS))
def test_every_group_satisfies_the_axioms(name):
    G = ALL_GROUPS[name]
    r = axiom_residuals(G, np.random.default_rng(1), n=30)
    assert r["closure"]
    assert max(r[a] for a in AXIOMS) < 1e-9
    big = axiom_residuals(G, np.random.default_rng(2), n=30, scale=4.0)
    assert big["closure"] and max(big[a] for a in AXIOMS) < 1e-8


@pytest.mark.parametrize("name", list(ALL_GROUPS))
def test_associativity_residual_equals_matrix_route(name):
    """Independent route: associativity of the matrix product, mapped back with from_matrix."""
    G = ALL_GROUPS[name]
    rng = np.random.default_rng(5)
    g1, g2, g3 = (G.random(rng, 10) for _ in range(3))
    M = G.matrix(g1) @ G.matrix(g2) @ G.matrix(g3)
    assert np.all(G.isclose(G.from_matrix(M), G.compose(G.compose(g1, g2), g3), atol=1e-9))


def test_closure_is_read_from_the_groups_own_membership():
    """axiom_residuals' closure flag is G.contains of products and inverses: a group whose
    membership test refuses every product must fail closure (a mutant of (R+, x))."""
    class NoProducts(type(RPlus)):
        def _in_domain(self, g):
            return np.all(np.abs(g - 1.0) < 0.0, axis=-1)        # nothing is an element

    assert axiom_residuals(RPlus, np.random.default_rng(0), n=5)["closure"]
    assert not axiom_residuals(NoProducts(), np.random.default_rng(0), n=5)["closure"]


def test_powers_match_matrix_powers():
    g = np.array([1.0, 1.0, np.pi / 2])
    P = powers(SE2, g, 4)
    assert P.shape == (5, 3)
    for k in range(5):
        assert SE2.isclose(SE2.from_matrix(np.linalg.matrix_power(SE2.matrix(g), k)), P[k])
    with pytest.raises(ValueError, match="n must be a non-negative integer"):
        powers(SE2, g, -1)


# ------------------------------------------------------------------ group or not? (Structure)
from fractions import Fraction  # noqa: E402

from gm_core.groups.axioms import (  # noqa: E402
    GROUP_AXIOMS,
    STRUCTURES,
    check_axioms,
    group_structure,
    is_group,
    structure,
    try_elements,
)


def test_the_real_groups_pass_every_axiom():
    for name in ("(ℤ, +)", "(ℝ⁺, ×)", "SE(2)"):
        v = check_axioms(name)
        assert list(v) == list(GROUP_AXIOMS)
        assert all(x.holds for x in v.values()), (name, v)
        assert is_group(name)
    for name, G in ALL_GROUPS.items():
        assert is_group(group_structure(G, name)), name


def test_integers_under_multiplication_lack_inverses():
    v = check_axioms("(ℤ, ×)")
    assert v["closure"].holds and v["associativity"].holds and v["identity"].holds
    assert not v["inverse"].holds
    a, x = v["inverse"].witness
    # independent route: exact rational arithmetic, 2 x = 1 has the single solution 1/2, not an integer
    assert a == 2 and Fraction(1, a) == Fraction(x).limit_denominator() and Fraction(1, a).denominator != 1
    assert "2 × x = 1" in v["inverse"].why


def test_positive_reals_under_addition_have_no_identity():
    v = check_axioms("(ℝ⁺, +)")
    assert v["closure"].holds and v["associativity"].holds
    assert not v["identity"].holds and v["identity"].witness == (0.0,)      # a + x = a forces x = 0 ∉ ℝ⁺
    assert not v["inverse"].holds
    a, x = v["inverse"].witness
    assert a + x == 0 and x < 0


def test_subtraction_is_not_associative_and_has_only_a_right_identity():
    v = check_axioms("(ℝ, −)")
    assert v["closure"].holds
    a, b, c = v["associativity"].witness
    assert len({a, b, c}) == 3                                   # a readable counterexample
    assert (a - b) - c != a - (b - c)                            # checked with plain numbers
    assert (a, b, c) == (3.0, 2.0, 1.0) and "(3 − 2) − 1 = 0" in v["associativity"].why
    assert not v["identity"].holds
    e, a = v["identity"].witness
    assert a - e == a and e - a != a                             # right identity only
    assert not v["inverse"].holds


def test_other_failures_closure_and_zero():
    v = check_axioms("(odd ℤ, +)")
    a, b = v["closure"].witness
    assert a % 2 == 1 and b % 2 == 1 and (a + b) % 2 == 0
    v = check_axioms("(ℝ, ×)")
    assert v["identity"].holds and not v["inverse"].holds and v["inverse"].witness == (0.0,)


def test_every_structure_has_a_verdict_for_each_axiom_and_a_reason():
    for name in STRUCTURES:
        v = check_axioms(name)
        assert set(v) == set(GROUP_AXIOMS)
        for x in v.values():
            assert x.why and (x.holds or x.why)
    with pytest.raises(ValueError, match="unknown structure 'Z'"):
        check_axioms("Z")


def test_try_elements_writes_the_axioms_at_the_users_numbers():
    t = try_elements("(ℝ, −)", 3.0, 2.0, 1.0)
    assert t["associativity"].startswith("✗") and "= 0" in t["associativity"] and "= 2" in t["associativity"]
    t = try_elements("(ℤ, ×)", 2.0, 3.0, 1.0)
    assert t["closure"] == "✓ a × b = 6" and t["inverse"].startswith("✗") and "0.5 ∉ ℤ" in t["inverse"]
    t = try_elements("(ℤ, +)", 2.0, 0.5, 1.0)
    assert t["closure"].startswith("✗") and "b = 0.5 ∉ ℤ" in t["closure"]
    t = try_elements("SE(2)", 0.5, -1.0, 0.3)
    assert all(s.startswith("✓") for s in t.values())
    S = structure("SE(2)")
    a, b = S.element(0.5, 0), S.element(-1.0, 1)
    M = SE2.matrix(a) @ SE2.matrix(b)                        # independent route: matrix product
    assert S.equal(SE2.from_matrix(M), S.op(a, b))


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

small = st.integers(-50, 50).map(float)


@settings(max_examples=80, deadline=None)
@given(small, small, small)
def test_try_elements_agrees_with_plain_arithmetic(a, b, c):
    """Property: the axioms written out at any numbers match arithmetic done here by hand."""
    t = try_elements("(ℝ, −)", a, b, c)
    # (a - b) - c and a - (b - c) differ by 2c: subtraction is associative only when c = 0
    assert t["associativity"].startswith("✓" if c == 0 else "✗")
    t = try_elements("(ℤ, ×)", a, b, c)
    assert t["closure"] == f"✓ a × b = {int(a * b)}"
    has_inverse = a in (1.0, -1.0)
    assert t["inverse"].startswith("✓" if has_inverse else "✗")
    t = try_elements("(ℤ, +)", a, b, c)
    assert all(s.startswith("✓") for s in t.values())
