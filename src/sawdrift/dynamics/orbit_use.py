"""What a run does with the orbit :mod:`.separated` solves: starts on it, reads its relaxation
rate and the time a particle from rest takes to reach its drift.

* :func:`place_on_orbit` puts the run's speed, height and derivative history on the orbit;
* :func:`orbit_relaxation` is the mean speed's relaxation rate near it, lambda = mu T' / m*;
* :func:`approach_periods` integrates m* dV/dt = -mu <T*>(V) + L along the force-velocity curve
  sampled on the way to it (separation of motions), the time to 90 % of the drift.
"""

from __future__ import annotations

import math

import numpy as np

from . import adams_bashforth as ig
from .separated import SeparatedOrbit
from .stepper import Stepper

__all__ = ["approach_periods", "orbit_relaxation", "place_on_orbit"]


def place_on_orbit(stepper: Stepper, orbit: SeparatedOrbit) -> None:
    """Put the run's velocity, height and derivative history on the orbit at the present step
    (a whole period: sample 0); x* stays, the contact memory re-adapts within a period."""
    k = orbit.eta.size
    m = float(stepper.prm[ig.P_M])
    mu = float(stepper.prm[ig.P_MU])
    load = float(stepper.prm[ig.P_LOAD])  # m* x*'' = -mu T* + L, as the integrator has it
    stepper.y[1] = orbit.drift + orbit.xi_rate[0]
    stepper.y[2] = orbit.mean_compression + orbit.eta[0]
    stepper.y[3] = orbit.eta_rate[0]
    for j in range(4):
        i = (-1 - j) % k
        stepper.fh[j, 0] = orbit.drift + orbit.xi_rate[i]
        stepper.fh[j, 1] = (-mu * orbit.tangential[i] + load) / m
        stepper.fh[j, 2] = orbit.eta_rate[i]
        stepper.fh[j, 3] = (1.0 - orbit.normal[i]) / m
    stepper.moved()  # a flight in closed form would go on from its old anchor


def orbit_relaxation(orbit: SeparatedOrbit, mu: float, m_star: float, slope: float) -> float:
    """lambda = mu T' / m* (per period) of the mean speed near the orbit, T' = d<T*>/dV its
    force-velocity slope, kept within a factor of ten of the rate mu ``slope`` / m* assumed
    without one (a slope across a kink of the curve is no rate)."""
    assumed = slope * mu / m_star
    if not math.isfinite(orbit.slope) or orbit.slope <= 0.0:
        return assumed
    return min(max(mu * orbit.slope / m_star, 0.1 * assumed), 10.0 * assumed)


def approach_periods(orbit: SeparatedOrbit, drift: float, speed: float, mu: float,
                     m_star: float, share: float = 0.9) -> float:
    """Periods a particle starting from rest takes to reach ``share`` of ``drift``, from the
    force-velocity curve sampled on the way to the orbit: m* dV/dt = -mu <T*>(V) + L
    (separation of motions, L the tangential load), so t = integral from 0 to share V of
    m* dV / (-mu <T*>(V) + L), the curve (its samples hold -<T*> + L / mu) interpolated linearly
    between its samples. NaN where the curve does not push towards ``drift`` all the way.
    """
    target = share * drift / speed
    d = np.array([c[0] for c in orbit.curve])
    f = np.array([c[1] for c in orbit.curve])
    if target == 0.0:
        return 0.0
    grid = np.linspace(0.0, target, 201)
    push = np.interp(grid, d, f) * np.sign(target)
    if np.any(push <= 0.0):
        return math.nan
    rate = m_star * speed / (mu * push)  # dt / d(drift ratio)
    return float(abs(np.sum(0.5 * (rate[1:] + rate[:-1]) * np.diff(grid))))
