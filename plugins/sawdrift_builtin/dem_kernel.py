"""Compiled tangential step of the ``hertz_mindlin_dem`` law (the DEM incremental Mindlin spring).

The law is described in :mod:`sawdrift_builtin.hertz_mindlin_dem`; the framework's slots
(:mod:`sawdrift.contact.slots`) own contact entry, loss and the normal force. Imported on first use.
"""

from __future__ import annotations

import math

from numba import njit

from sawdrift.contact.normal import JIT_OPTIONS, law_normal, law_slope
from sawdrift.contact.slots import takes_normal


@njit(**JIT_OPTIONS)
def secant_slope(law, a0: float, a1: float) -> float:
    """[N*(a1) - N*(a0)] / (a1 - a0) along the path (N*'(a0) when equal; a0 >= 0, a1 > 0).

    For a power law the difference is formed without cancellation (expm1/log1p).
    """
    h = a1 - a0
    if h == 0.0:
        return law_slope(a0, law, 0)
    if a0 <= 0.0:
        return law_normal(a1, law, 0) / a1
    p = law[0]
    if p > 0.0:
        return a0**p * math.expm1(p * math.log1p(h / a0)) / h
    return (law_normal(a1, law, 0) - law_normal(a0, law, 0)) / h


@takes_normal
@njit(**JIT_OPTIONS)
def dem_step(ts, is_, law, tp, a0: float, b0: float, a: float, b: float, n: float) -> float:
    """T* at the end of the straight path (a0, b0) -> (a, b) from the stored T* = ts[0].

    ``n`` is the total normal force the slots hand in (:func:`~sawdrift.contact.slots.
    takes_normal`): N*(a*), plus the normal damping if there is one; the stored force is
    bounded by it, floored at 0 (module docstring of :mod:`sawdrift_builtin.hertz_mindlin_dem`).
    """
    if tp[0] != 0.0 and 0.0 < a < a0:
        # mindlin_rescale: the stored force shrinks with the stiffness
        k0 = law_slope(a0, law, 0)
        k1 = law_slope(a, law, 0)
        t = ts[0] * (k1 / k0) + k1 * (b - b0)
    else:
        t = ts[0] + (b - b0) * secant_slope(law, a0, a)
    bound = n if n > 0.0 else 0.0  # the Coulomb bound of the stored force: total N*, >= 0
    if t > bound:
        t = bound
    elif t < -bound:
        t = -bound
    ts[0] = t
    return t
