"""Steady drift: a settle criterion that follows the slow approach, and reduced horizontal inertia.

A heavy particle changes its horizontal velocity by O(mu / m*) per period, so it needs of order
m* / mu periods to reach its steady drift (docs/physics.md, "Heavy particles"). Two things make
``numerics.settle`` give that steady drift at a cost independent of m*:

1. **Separation of motions** (vibrational mechanics, Blechman 2000, the paper's ref. [5]). For
   m* >> 1 the horizontal velocity hardly changes within a wave period, and the steady drift is
   the velocity v at which the period-averaged friction force <T*>(v) vanishes. That condition
   does not contain the horizontal inertia: m*_x only sets how fast x*' relaxes towards v. The
   normal equation m* y*'' = 1 - N*(a*) does not depend on x* at all. So the run integrates
   ``m*_x x*'' = -mu T*`` with m*_x = min(m*, :data:`HEAVY_MASS`) and the full m* in the normal
   equation: the fixed point is the same, the approach is m* / m*_x times shorter. With m*_x =
   100 the fast motion is still heavy (the velocity changes by mu/100 of the relative sliding
   speed per period); measured against brute-force runs of 19 to 29 approach times the drift
   agrees within 0.3 % (benchmarks/bench_steady.py).
2. **A criterion that follows the approach.** The drift is measured in windows of W periods, W
   growing with m*_x / mu. Successive window means v1, v2, v3 of a relaxation approach
   v_inf + c q^k; the remaining distance is estimated by Aitken's extrapolation,
   (v3 - v2) q / (1 - q) with q = (v3 - v2) / (v2 - v1), and the run stops when both the last change
   and that remainder are below ``numerics.settle_tolerance`` (in drift-ratio units).

The time to reach 90 % of the steady speed is read from the windows and scaled back by
m* / m*_x (the relaxation rate is inversely proportional to the horizontal inertia).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import adams_bashforth as ig
from .stepper import Stepper
from .window import Window, measure_window

#: the horizontal inertia used for heavier particles (see the module docstring)
HEAVY_MASS = 100.0


@dataclass(frozen=True)
class Settling:
    """How a settled run got there."""

    settled: bool
    method: str
    horizontal_inertia: float
    window_periods: int
    periods: float
    t90_periods: float
    history: tuple[float, ...]


def horizontal_inertia(m_star: float, rigid: bool) -> float:
    """m*_x of the reduced-inertia method: min(m*, HEAVY_MASS) for compliant models."""
    return m_star if rigid else min(m_star, HEAVY_MASS)


def window_length(m_star: float, m_x: float, mu: float, minimum: int) -> int:
    """Periods per settle window, at least ``minimum``.

    A tenth of the relaxation time m*_x / mu, and at least three periods of the free vertical
    oscillation 2 pi sqrt(m* / N*'(1)) = 2 pi sqrt(m* / 1.5) (in wave periods), which never decays
    (the normal equation has no damping) and modulates the friction: a window shorter than it
    would see that modulation as a change of the drift.
    """
    vertical = 2.0 * math.pi * math.sqrt(m_star / 1.5) if m_star > 1.0 else 0.0
    return max(int(minimum), int(math.ceil(0.1 * m_x / mu)), int(math.ceil(3.0 * vertical)))


def settle(stepper: Stepper, scene, speed: float, scale: np.ndarray, minimum_window: int,
           max_steps: int) -> tuple[Window, Settling]:
    """Measure windows until the drift has settled (see the module docstring)."""
    num = scene.numerics
    m = scene.particle.m_star
    m_x = horizontal_inertia(m, stepper.rigid)
    if not stepper.rigid:
        stepper.prm[ig.P_MX] = m_x
    w = window_length(m, m_x, scene.material.mu, minimum_window)
    tol = num.settle_tolerance
    start = stepper.step
    values: list[float] = []
    ends: list[float] = []
    settled = False
    win = measure_window(stepper, w, speed, scale)
    values.append(win.drift_ratio)
    ends.append(stepper.step / stepper.k_per)
    while stepper.step + w * stepper.k_per <= max_steps:
        win = measure_window(stepper, w, speed, scale)
        values.append(win.drift_ratio)
        ends.append(stepper.step / stepper.k_per)
        if len(values) >= 3 and _converged(values[-3:], tol):
            settled = True
            break
        if len(values) == 2 and m_x == m and abs(values[-1] - values[-2]) <= 0.1 * tol:
            settled = True  # a light particle already steady from the first windows
            break
    t90 = _t90(values, ends) * (m / m_x)
    info = Settling(settled, "reduced_inertia" if m_x < m else "windows", m_x, w,
                    (stepper.step - start) / stepper.k_per, t90, tuple(values))
    return win, info


def _converged(v: list[float], tol: float) -> bool:
    d1, d2 = v[1] - v[0], v[2] - v[1]
    if abs(d2) > tol:
        return False
    if d1 == 0.0 or d2 == 0.0:
        return True
    q = d2 / d1
    if not 0.0 < q < 1.0:
        return abs(d2) <= 0.1 * tol  # not monotone: only a change far below tol counts
    return abs(d2 * q / (1.0 - q)) <= tol


def _t90(values: list[float], ends: list[float]) -> float:
    """First window end at which the drift reached 90 % of the final value (NaN if no drift)."""
    final = values[-1]
    if final == 0.0:
        return math.nan
    for v, t in zip(values, ends, strict=True):
        if v / final >= 0.9:
            return t
    return ends[-1]
