"""The power-law normal contact law N*(a*) = a*^p, compiled for the kernels.

Hertz (1882) for the sphere (p = 3/2), cone p = 2, flat punch p = 1 (docs/physics.md). The
pure-Python twin is :mod:`sawdrift.scene.profiles`.
"""

from __future__ import annotations

import math

from numba import njit

JIT_OPTIONS = {"cache": True, "_nrt": False}
"""numba options of every kernel function. The kernels never allocate; without the runtime's
reference counting of the state arrays (atomic operations on every call, which numba does not
prune across the helper calls) a step is several times faster."""


@njit(**JIT_OPTIONS, inline="always")
def normal(z: float, p: float) -> float:
    """N*(z) = z^p for z > 0, else 0."""
    out = 0.0
    if z > 0.0:
        out = z**p
    return out


@njit(**JIT_OPTIONS, inline="always")
def dnormal(z: float, p: float) -> float:
    """N*'(z) = p z^(p-1) for z > 0; 0 at z <= 0 (the convention N*'(0-) = 0).

    The flat punch (p = 1) thus carries its whole dN*' as a point mass at z = 0+.
    """
    out = 0.0
    if z <= 0.0:
        out = 0.0
    elif p == 1.0:
        out = 1.0
    elif p == 1.5:
        out = 1.5 * math.sqrt(z)
    elif p == 2.0:
        out = 2.0 * z
    else:
        out = p * z ** (p - 1.0)
    return out
