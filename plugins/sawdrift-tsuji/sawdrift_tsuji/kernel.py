"""Compiled normal-damping slot of ``hertz_tsuji``: Tsuji's dashpot (imported on first use)."""

from __future__ import annotations

import math

from numba import njit

from sawdrift.contact.normal import JIT_OPTIONS, law_slope


@njit(**JIT_OPTIONS)
def tsuji_damp(dp, law, a: float, adot: float, n_elastic: float) -> float:
    """N* = max(N*_el + c sqrt(N*'(a*) / N*'(1)) a*', 0): Tsuji's dashpot, clamped (a > 0)."""
    k1 = law_slope(1.0, law, 0)
    return max(n_elastic + dp[0] * math.sqrt(law_slope(a, law, 0) / k1) * adot, 0.0)
