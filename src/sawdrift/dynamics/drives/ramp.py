"""What the drives share: the start-up ramp R(t*) (docs/physics.md, "The wave and its orbit") and
the table of the wave's phase at the steps of one period."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

TWO_PI = 2.0 * math.pi


@njit(cache=True)
def ramp(t: float, t_ramp: float) -> tuple[float, float, float]:
    """R(t*), R'(t*) and R''(t*) of the smooth ramp sin^2(pi t*/(2 T_ramp))."""
    if t_ramp <= 0.0 or t >= t_ramp:
        return 1.0, 0.0, 0.0
    w = 0.5 * math.pi / t_ramp
    s = math.sin(w * t)
    return s * s, w * math.sin(2.0 * w * t), 2.0 * w * w * math.cos(2.0 * w * t)


def with_phase_table(dp: np.ndarray, k_per: int) -> np.ndarray:
    """``dp`` followed by sin(2 pi j h) and cos(2 pi j h), j = 0 .. k_per - 1, h = 1 / k_per: the
    wave's phase at the steps of one period, which :func:`phase` reads instead of evaluating the
    sine and cosine at every step (measured: 13 % of a contact step of mmd)."""
    h = 1.0 / k_per
    arg = TWO_PI * (np.arange(k_per) * h)
    return np.concatenate((dp, np.sin(arg), np.cos(arg)))


@njit(cache=True, inline="always")
def phase(t, dp, n_params):
    """(sin(2 pi t*), cos(2 pi t*)): from the table of :func:`with_phase_table` behind the
    drive's ``n_params`` parameters where t* is on the step grid of the table's period (the
    step's phase within its period, so the same at every period: exact, where sin(2 pi t*) loses
    the digits of t*'s integer part), else computed."""
    n = (dp.size - n_params) // 2
    if n > 0:
        u = (t - math.floor(t)) * n
        j = math.floor(u + 0.5)
        if abs(u - j) <= 1e-7:
            i = n_params + (int(j) if j < n else 0)
            return dp[i], dp[i + n]
    return math.sin(TWO_PI * t), math.cos(TWO_PI * t)
