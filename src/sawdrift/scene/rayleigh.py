"""Rayleigh surface wave: velocity ratio and the horizontal-to-vertical amplitude ratio r(nu).

The Rayleigh equation in the form used in docs/physics.md:

    (2 - eta)^2 = 4 sqrt(1 - eta) sqrt(1 - k^2 eta),   k^2 = (1 - 2 nu) / (2 (1 - nu)),

with eta = (c_R / c_S)^2 the unique root in (0, 1). The surface amplitude ratio is

    r = (2 - eta) / (2 sqrt(1 - k^2 eta)).
"""

from __future__ import annotations

import math
from functools import lru_cache

from ..errors import SceneError


def _check_nu(nu: float) -> None:
    if not (math.isfinite(nu) and -1.0 < nu < 0.5):
        raise SceneError(f"nu = {nu!r} is outside the allowed range (-1, 0.5)")


def _rayleigh_residual(eta: float, k2: float) -> float:
    # Rationalised form divided by eta: its only root in (0, 1) is the Rayleigh root, and it is
    # smooth (no square roots), so bracketing is robust for every nu in (-1, 0.5).
    return eta**3 - 8.0 * eta**2 + (24.0 - 16.0 * k2) * eta - 16.0 * (1.0 - k2)


@lru_cache(maxsize=256)
def eta_rayleigh(nu: float) -> float:
    """Return eta = (c_R / c_S)^2 for Poisson's ratio ``nu`` in (-1, 0.5).

    The cubic eta^3 - 8 eta^2 + (24 - 16 k^2) eta - 16 (1 - k^2) = 0 follows from squaring the
    Rayleigh equation (Achenbach, *Wave Propagation in Elastic Solids*, 1973, eq. 5.2.7). It is
    negative at eta = 0 and positive (= 1) at eta = 1, so bisection on [0, 1] finds the root (to
    the last bit: 60 halvings; plain Python, so that importing sawdrift does not import scipy).
    """
    _check_nu(nu)
    k2 = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _rayleigh_residual(mid, k2) < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def rayleigh_speed_ratio(nu: float) -> float:
    """Return c_R / c_S, the Rayleigh to shear wave speed ratio (0.927413 at nu = 0.3)."""
    return math.sqrt(eta_rayleigh(nu))


def rayleigh_ratio(nu: float) -> float:
    """Return r(nu), horizontal over vertical surface displacement amplitude of a Rayleigh wave.

    r = (2 - eta) / (2 sqrt(1 - k^2 eta)) (docs/physics.md); r(0.3) = 0.656264.
    """
    eta = eta_rayleigh(nu)
    k2 = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))
    return (2.0 - eta) / (2.0 * math.sqrt(1.0 - k2 * eta))


def theta(nu: float) -> float:
    """Mindlin compliance ratio theta = (2 - nu) / (2 (1 - nu)) (paper, after eq. 3)."""
    _check_nu(nu)
    return (2.0 - nu) / (2.0 * (1.0 - nu))
