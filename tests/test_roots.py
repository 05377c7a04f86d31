"""sawdrift.dynamics.roots.brentq is SciPy's Brent method step for step: the same roots to the last bit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq as scipy_brentq

from sawdrift.dynamics.roots import brentq, first_passed

CASES = [
    (lambda x: x**3 - 2.0 * x - 5.0, 2.0, 3.0),  # Wallis' cubic
    (lambda x: math.cos(x) - x, 0.0, 1.0),
    (lambda x: math.exp(x) - 1e3, 0.0, 20.0),
    (lambda x: math.tanh(50.0 * (x - 0.3)), -1.0, 1.0),  # nearly a step
    (lambda x: (x - 0.7) ** 3, 0.0, 1.0),  # a triple root
    (lambda x: x * math.exp(-x) - 0.1, 0.0, 1.0),
    (lambda x: 1e-12 * (x - 1e-3), -1.0, 1.0),  # tiny values
    (lambda x: 2.0 * x - math.pi - 2.0 * 0.9 * math.sin(x), 0.0, math.pi),
]


@pytest.mark.parametrize("xtol, rtol", [(2e-12, 4 * np.finfo(float).eps), (1e-4, 1e-10),
                                        (1e-7, 1e-13)])
@pytest.mark.parametrize("case", range(len(CASES)))
def test_same_root_and_same_evaluations_as_scipy(case, xtol, rtol):
    f, a, b = CASES[case]
    ours, theirs = [], []
    root = brentq(lambda x: ours.append(x) or f(x), a, b, xtol=xtol, rtol=rtol)
    ref = scipy_brentq(lambda x: theirs.append(x) or f(x), a, b, xtol=xtol, rtol=rtol)
    assert root == ref  # to the last bit
    assert ours == theirs  # the same points, in the same order
    # and a root: f changes sign within the tolerance around it
    step = xtol + rtol * abs(root)
    assert f(root) == 0.0 or f(root - step) * f(root + step) <= 0.0


def test_errors_are_scipys():
    with pytest.raises(ValueError, match="different signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(ValueError, match="NaN"):
        brentq(lambda x: math.nan if x > 0.5 else -1.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="xtol"):
        brentq(lambda x: x, -1.0, 1.0, xtol=0.0)
    with pytest.raises(RuntimeError, match="converge"):
        brentq(lambda x: math.tanh(50.0 * (x - 0.3)), -1.0, 1.0, maxiter=3)
    # a zero at an end is returned as it is
    assert brentq(lambda x: x, 0.0, 1.0) == 0.0 and brentq(lambda x: x - 1.0, 0.0, 1.0) == 1.0


@pytest.mark.parametrize("case", range(len(CASES)))
def test_known_end_values_are_not_evaluated_again(case):
    """f(a), f(b) given: the same root to the last bit, from two evaluations fewer (a bracket
    search has them already; each one integrates the fast motion)."""
    f, a, b = CASES[case]
    plain, given = [], []
    root = brentq(lambda x: plain.append(x) or f(x), a, b, xtol=1e-7, rtol=1e-13)
    again = brentq(lambda x: given.append(x) or f(x), a, b, xtol=1e-7, rtol=1e-13,
                   fa=f(a), fb=f(b))
    assert again == root
    assert given == plain[2:] and plain[:2] == [a, b]


@pytest.mark.parametrize("zero", [0.03, 0.1, 0.25, 0.7, 0.95, 2.5])
def test_first_passed_finds_the_grid_pair_of_a_point_by_point_search(zero):
    """A curve that changes sign once: the same pair of grid points as visiting each point, from
    about half the evaluations; None when no point is passed."""
    grid = [0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.8, 1.0, 1.5, 2.0, 3.0]
    seen = []

    def f(x):
        seen.append(x)
        return zero - x

    pair = first_passed(f, grid, 0.0, lambda v: v < 0.0)
    k = next(i for i, g in enumerate(grid) if g > zero)
    assert pair == ((grid[k - 1] if k else 0.0), grid[k])
    assert len(seen) <= (k + 2) // 2 + 1  # point by point: k + 1
    assert first_passed(lambda x: 1.0, grid, 0.0, lambda v: v < 0.0) is None
