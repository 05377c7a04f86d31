"""Compiled kernel of the ``hertz_mindlin_dem`` model (the DEM incremental Mindlin spring).

The law is described in :mod:`sawdrift_builtin.hertz_mindlin_dem`; this module holds its numba
functions, imported on first use.
"""

from __future__ import annotations

import math

from numba import njit

from .hertz_mindlin_dem import _A, _B, _T


@njit(cache=True)
def _secant_slope(a0: float, a1: float, p: float) -> float:
    """[N*(a1) - N*(a0)] / (a1 - a0) without cancellation (both a > 0; N*'(a) when equal)."""
    h = a1 - a0
    if h == 0.0:
        return p * a0 ** (p - 1.0)
    return a0**p * math.expm1(p * math.log1p(h / a0)) / h


@njit(cache=True)
def dem_tangential_update(
    t0: float, a0: float, b0: float, a1: float, b1: float, p: float, rescale: bool
) -> float:
    """T* at the end of the straight path (a0, b0) -> (a1, b1), both a > 0, from T* = t0."""
    n1 = a1**p
    if rescale and a1 < a0 and p != 1.0:
        k0 = p * a0 ** (p - 1.0)
        k1 = p * a1 ** (p - 1.0)
        t = t0 * (k1 / k0) + k1 * (b1 - b0)
    else:
        t = t0 + (b1 - b0) * _secant_slope(a0, a1, p)
    if t > n1:
        return n1
    if t < -n1:
        return -n1
    return t


@njit(cache=True)
def dem_reset(fs, is_, pp) -> None:
    """Empty history, out of contact at (a*, b*) = (0, 0)."""
    fs[:] = 0.0


@njit(cache=True)
def dem_force(fs, is_, pp, a: float, b: float, adot: float, bdot: float):
    """Advance along the straight path from the committed (a*, b*) to (a, b), commit, (N*, T*)."""
    p = pp[0]
    rescale = pp[1] != 0.0
    a0 = fs[_A]
    b0 = fs[_B]
    t0 = fs[_T]
    fs[_A] = a
    fs[_B] = b
    if a <= 0.0:
        fs[_T] = 0.0
        return 0.0, 0.0
    n1 = a**p
    if a0 <= 0.0:
        # enters contact at a* = 0 with T* = 0; integral k_t db* = lambda N*(a) with lambda = db/da
        t = (b - b0) / (a - a0) * n1
        t = min(max(t, -n1), n1)
    else:
        t = dem_tangential_update(t0, a0, b0, a, b, p, rescale)
    fs[_T] = t
    return n1, t


