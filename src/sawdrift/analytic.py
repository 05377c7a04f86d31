"""Closed-form results used as oracles (docs/physics.md).

Material point (Verma & DasGupta 2013), with Gz = 4 pi^2 m* A* and Gx = r Gz; and the
Cattaneo-Mindlin / Masing laws of a power-law profile at fixed a* (Mindlin & Deresiewicz 1953).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

MU = 0.1
"""The paper's friction coefficient (Fig. 3)."""


def heavy_sliding_v(gz: float) -> float:
    """Drift ratio of the material point for mu / Gx -> 0: V = cos(phi0), 2 phi0 - pi = 2 Gz sin(phi0)."""
    phi0 = brentq(lambda p: 2.0 * p - math.pi - 2.0 * gz * math.sin(p), 0.0, math.pi)
    return math.cos(phi0)


def point_prediction(gz: float, gx: float, mu: float = MU) -> str:
    """Regime of the material point from closed-form thresholds: lost, stick or drift_against.

    Gz > 1: contact lost. R = hypot(Gx/mu, Gz) <= 1: stick. Otherwise the point slips; in
    psi = phi - delta (R cos delta = Gx/mu, R sin delta = Gz) a slip starting from stick at
    psi1 = arcsin(1/R) ends where R (cos psi1 - cos psi) = psi - psi1, and the backward slip,
    its mirror image (no net drift), starts pi - 2 delta later: drift appears only when the
    first slip lasts that long (the slips merge into continuous sliding, against the wave).
    """
    if gz > 1.0:
        return "lost"
    big_r = math.hypot(gx / mu, gz)
    if big_r <= 1.0:
        return "stick"
    psi1 = math.asin(1.0 / big_r)
    delta = math.atan2(gz, gx / mu)

    def f(psi: float) -> float:
        return big_r * (math.cos(psi1) - math.cos(psi)) - (psi - psi1)

    lo = math.pi - psi1
    hi = lo + 2.0 * math.pi
    if f(hi) > 0.0:
        return "drift_against"
    psi2 = brentq(f, lo, hi)
    return "drift_against" if psi2 - psi1 >= math.pi - 2.0 * delta else "stick"


def cattaneo_mindlin(a: float, b: np.ndarray | float, p: float = 1.5) -> np.ndarray:
    """Monotonic loading from b* = 0 at fixed a*: T* = N*(a*) - N*(a* - b*), then T* = N*(a*)."""
    b = np.asarray(b, dtype=float)
    return a**p - np.clip(a - b, 0.0, None) ** p


#: how closely a model that deviates by design must follow its own deviation's closed form
DEVIATION_TOL = 1e-9


def dem_spring(a: float, b_from: float, t_from: float, b: np.ndarray, p: float = 1.5
               ) -> np.ndarray:
    """T* of the DEM spring at fixed a* (hertz_mindlin_dem's documented deviation): from
    (``b_from``, ``t_from``) along Mindlin's initial stiffness k = p a*^(p-1) (the slope of
    a*^p - (a* - b*)^p at b* = 0), capped at the Coulomb bound +-a*^p (N*; T* in units of mu);
    ``b`` runs one way from ``b_from``."""
    k, cap = p * a ** (p - 1.0), a**p
    return np.clip(t_from + k * (np.asarray(b, dtype=float) - b_from), -cap, cap)


def masing_unloading(a: float, b1: float, b: np.ndarray | float, p: float = 1.5) -> np.ndarray:
    """Unloading from the turning point (b1, T1) of virgin loading, fixed a* (Masing's rule).

    T* = T1 - 2 [N*(a*) - N*(a* - (b1 - b*)/2)]; for the sphere this is docs/physics.md's
    T1 - 2 a*^(3/2) [1 - (1 - (b1 - b*)/(2 a*))^(3/2)].
    """
    b = np.asarray(b, dtype=float)
    t1 = float(cattaneo_mindlin(a, b1, p))
    return t1 - 2.0 * (a**p - np.clip(a - (b1 - b) / 2.0, 0.0, None) ** p)


def loop_area(a: float, q: float) -> float:
    """Energy dissipated per cycle between +-q N* (sphere, fixed a*), docs/physics.md."""
    s = 1.0 - q
    return 4.8 * a**2.5 * (1.0 - s ** (5.0 / 3.0) - (5.0 * q / 6.0) * (1.0 + s ** (2.0 / 3.0)))


def amplitude_for_force_ratio(a: float, q: float) -> float:
    """Displacement amplitude B at which virgin loading reaches T* = q N* (sphere)."""
    return a * (1.0 - (1.0 - q) ** (2.0 / 3.0))
