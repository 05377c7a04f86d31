"""The start-up ramp R(t*) shared by the drives (docs/physics.md, "The wave and its orbit")."""

from __future__ import annotations

import math

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
