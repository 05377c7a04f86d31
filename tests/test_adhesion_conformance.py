"""The conformance suite on the adhesive laws: it passes them and fails a law with a sign error."""

from __future__ import annotations

import math

import pytest
from numba import njit

from sawdrift.contact.adhesion import Adhesion, adhesive_model
from sawdrift.contact.conformance import check_model
from sawdrift.contact.registry import get_model


@pytest.mark.parametrize("model", ["hertz_mindlin_dem", "mmd"])
@pytest.mark.parametrize("law", [("jkr", "instability"), ("jkr", "pulloff"), ("dmt", "instability")])
def test_adhesive_laws_pass(model, law):
    result = check_model(model, adhesion=Adhesion(law[0], 0.1, law[1]))
    assert result.passed, result.table()
    assert result.get("normalization").status == "pass"  # the pull-off is F*_pull
    assert result.get("passivity").status == "pass"
    assert result.get("coulomb_bound").status == "pass"
    assert result.get("split_invariance").status == "declared"


@njit
def jkr_sign_error(a, ad):
    """JKR with the adhesive term's sign flipped: a contact that pushes where it should pull."""
    g = math.sqrt(ad[1] / 3.0)
    s_c = (0.5 * g) ** (1.0 / 3.0)
    s = abs(a) ** 0.25 + (2.0 * g) ** (1.0 / 3.0)
    for _ in range(200):
        f = s**4 - 2.0 * g * s - a
        fp = 4.0 * s**3 - 2.0 * g
        if fp <= 0.0 or f <= 0.0 or s - f / fp <= s_c:
            break
        s -= f / fp
    c = s * s
    return c**3 + 3.0 * g * c * s, c


def test_a_sign_error_fails():
    base = adhesive_model(get_model("hertz_mindlin_dem"))
    wrong = type("WrongJKR", (base,), {"adhesive_law": jkr_sign_error, "__module__": __name__})
    from sawdrift.contact import conformance

    model = wrong(None, None, Adhesion("jkr", 0.1))
    checks = {c.__name__: c(model) for c in (conformance._normalization, conformance._passivity)}
    assert checks["_normalization"].status == "fail"
    # it creates energy on a cycle through contact loss (pushes on the way out, not on the way in)
    assert checks["_passivity"].status == "fail" and checks["_passivity"].value < 0.0
