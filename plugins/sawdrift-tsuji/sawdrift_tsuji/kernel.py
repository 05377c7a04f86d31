"""Compiled kernel of ``hertz_tsuji``: the DEM spring's kernel plus Tsuji's dashpot.

Imported on first use, so that listing the models needs no numba.
"""

from __future__ import annotations

from numba import njit

from sawdrift_builtin.dem_kernel import dem_force, dem_reset  # noqa: F401 - the pair's reset


@njit(cache=True)
def tsuji_force(fs, is_, pp, a: float, b: float, adot: float, bdot: float):
    """(N*, T*): the DEM kernel's elastic normal force and tangential force, plus the dashpot."""
    n_el, t = dem_force(fs, is_, pp, a, b, adot, bdot)
    if a <= 0.0:
        return 0.0, 0.0
    n = n_el + pp[2] * a ** (0.5 * (pp[0] - 1.0)) * adot
    return max(n, 0.0), t


@njit(cache=True)
def tsuji_normal(fs, is_, pp, a: float, b: float, adot: float, bdot: float):  # noqa: ARG001
    """(N*, 0): the damped normal force alone (the normal slot, used with friction off)."""
    if a <= 0.0:
        return 0.0, 0.0
    return max(a ** pp[0] + pp[2] * a ** (0.5 * (pp[0] - 1.0)) * adot, 0.0), 0.0
