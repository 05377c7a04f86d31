"""Substrate kinematics of the Rayleigh wave: the one home of paper eq. 1 and its start-up ramp.

Normalized (one wave period is one unit of t*), with y* pointing into the substrate::

    u_x = -s A* r R(t*) sin(2 pi t*)        u_y = A* R(t*) cos(2 pi t*)
    R(t*) = sin^2(pi t* / (2 T_ramp)) for t* < T_ramp, else 1

``s`` is the horizontal factor passed as ``horiz``: 1 for the orbit of eq. 1 as printed (prograde
in this frame: the crest moves with the wave), -1 for the retrograde orbit of a Rayleigh wave on
an isotropic half-space (the mirror x -> -x), 0 with the horizontal component switched off
(see docs/physics.md, "The orbit"). ``vert`` is 1 or 0 for the vertical component.
"""

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


@njit(cache=True)
def kinematics(t: float, amp: float, r: float, t_ramp: float, horiz: float, vert: float):
    """(u_x, u_x', u_x'', u_y, u_y', u_y'') of paper eq. 1 times the ramp R(t*)."""
    rr, rd, rdd = ramp(t, t_ramp)
    s2 = math.sin(TWO_PI * t)
    c2 = math.cos(TWO_PI * t)
    k2 = TWO_PI * TWO_PI
    ax = -amp * r * horiz
    ay = amp * vert
    ux = ax * rr * s2
    uxd = ax * (rd * s2 + rr * TWO_PI * c2)
    uxdd = ax * (rdd * s2 + 2.0 * rd * TWO_PI * c2 - rr * k2 * s2)
    uy = ay * rr * c2
    uyd = ay * (rd * c2 - rr * TWO_PI * s2)
    uydd = ay * (rdd * c2 - 2.0 * rd * TWO_PI * s2 - rr * k2 * c2)
    return ux, uxd, uxdd, uy, uyd, uydd


@njit(cache=True)
def surface(t: float, amp: float, r: float, t_ramp: float, horiz: float, vert: float):
    """Substrate displacement and velocity (u_x, u_x', u_y, u_y') (see :func:`kinematics`)."""
    rr, rd, _ = ramp(t, t_ramp)
    s2 = math.sin(TWO_PI * t)
    c2 = math.cos(TWO_PI * t)
    ax = -amp * r * horiz
    ay = amp * vert
    return (ax * rr * s2, ax * (rd * s2 + rr * TWO_PI * c2),
            ay * rr * c2, ay * (rd * c2 - rr * TWO_PI * s2))
