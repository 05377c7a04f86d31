"""Rayleigh-wave ratios against the values of docs/physics.md."""

import math

import pytest

from sawdrift import rayleigh_ratio, rayleigh_speed_ratio, theta
from sawdrift.errors import SceneError


@pytest.mark.parametrize(
    ("nu", "expected"), [(0.20, 0.704932), (0.25, 0.681250), (0.30, 0.656264), (0.40, 0.602488)]
)
def test_rayleigh_ratio_matches_reference_values(nu, expected):
    # docs/physics.md quotes six decimals: agreement to rounding (5e-7) and better than 1e-6
    assert abs(rayleigh_ratio(nu) - expected) <= 1e-6


def test_speed_ratio_at_nu_03():
    assert abs(rayleigh_speed_ratio(0.3) - 0.927413) <= 1e-6


@pytest.mark.parametrize("nu", [-0.999, -0.9, -0.5, 0.0, 0.1, 0.263, 0.45, 0.499, 0.4999])
def test_root_satisfies_unsquared_rayleigh_equation(nu):
    # the cubic comes from squaring; the root must satisfy the original equation to 1e-12
    eta = rayleigh_speed_ratio(nu) ** 2
    k2 = (1 - 2 * nu) / (2 * (1 - nu))
    lhs = (2 - eta) ** 2
    rhs = 4 * math.sqrt(1 - eta) * math.sqrt(1 - k2 * eta)
    assert 0 < eta < 1
    assert abs(lhs - rhs) <= 1e-12


def test_ratio_is_monotone_decreasing_in_nu():
    values = [rayleigh_ratio(-0.99 + 0.01 * i) for i in range(149)]
    assert all(b < a for a, b in zip(values, values[1:], strict=False))


@pytest.mark.parametrize("nu", [-1.0, 0.5, 0.7, float("nan")])
def test_nu_out_of_range_is_refused(nu):
    with pytest.raises(SceneError, match=r"allowed range \(-1, 0.5\)"):
        rayleigh_ratio(nu)


def test_theta():
    assert theta(0.3) == pytest.approx(1.7 / 1.4, rel=1e-15)
