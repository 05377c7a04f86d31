"""A bi-harmonic vibration of the substrate (``drive.kind = "biharmonic"``): Blekhman's asymmetric
excitation of vibrational transport.

The plate moves as a whole (no wave, no dependence on x*), with the first two harmonics on each
axis (scene type :class:`sawdrift.scene.parts.Biharmonic`)::

    u_x = R(t*) (X1 cos(2 pi t*) + X2 cos(4 pi t* + phi_x))
    u_y = R(t*) (Y1 cos(2 pi t*) + Y2 cos(4 pi t* + phi_y))

A horizontal harmonic alone is symmetric (t* -> t* + 1/2 with x -> -x maps the motion onto
itself) and transports nothing; an inclined one (X1 and Y1 both non-zero: gravity makes the
vertical axis one-sided) transports through the coupling of the two axes, as a vibratory
conveyor does; the second harmonic breaks the symmetry in time and transports along either axis
alone (I. I. Blekhman, Vibrational Mechanics, World Scientific 2000, ch. 5; "vibrational
transport" with bi-harmonic excitation).
With X2 = Y2 = 0 and X1 = r A*, Y1 = A* this is the travelling wave's linear orbit
(``drive.phase = 0``), term for term: the same floating-point operations, so the same run bit
for bit. The contact of a rigid point is lost when m* max(u_y'') > 1 (N* = 1 - m* u_y'').
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np
from numba import njit

from .base import Drive
from .ramp import TWO_PI, phase, ramp, with_phase_table
from .travelling import unit_phase

FOUR_PI = 2.0 * TWO_PI


class Biharmonic(Drive):
    """Two harmonics per axis (module docstring); parameters with the effects' switches applied."""

    kind: ClassVar[str] = "biharmonic"
    module: ClassVar[str] = __name__
    names: ClassVar[tuple[str, ...]] = ("ramp", "x1", "y1", "x2c", "x2s", "y2c", "y2s")

    def for_steps(self, dp: np.ndarray, k_per: int) -> np.ndarray:
        """``dp`` with the table of the fundamental's phase at the steps of one period, as the
        travelling wave's (:func:`~.ramp.with_phase_table`)."""
        return with_phase_table(dp, k_per)

    def parameters(self, scene: Any) -> dict[str, float]:
        d, eff = scene.drive, scene.effects
        hor = 1.0 if eff.horizontal_wave else 0.0
        ver = 1.0 if eff.vertical_wave else 0.0
        sx, cx = unit_phase(d.second_horizontal_phase)
        sy, cy = unit_phase(d.second_phase)
        # X2 cos(4 pi t* + phi) = X2 cos(phi) cos(4 pi t*) - X2 sin(phi) sin(4 pi t*)
        return {"ramp": d.ramp_periods, "x1": d.horizontal * hor, "y1": d.amplitude * ver,
                "x2c": d.second_horizontal * cx * hor, "x2s": -d.second_horizontal * sx * hor,
                "y2c": d.second * cy * ver, "y2s": -d.second * sy * ver}

    def ramp_periods(self, scene: Any) -> float:
        return scene.drive.ramp_periods

    def horizontal_speed(self, scene: Any) -> float:
        """2 pi (|X1| + 2 |X2|): the bound of |u_x'|, the drift ratio's scale (0 with the
        horizontal motion off)."""
        if not scene.effects.horizontal_wave:
            return 0.0
        d = scene.drive
        return 2.0 * math.pi * (abs(d.horizontal) + 2.0 * abs(d.second_horizontal))

    def vertical_amplitude(self, scene: Any) -> float:
        """|Y1| + 16 |Y2|: the bound of |u_y''''| / (2 pi)^4 that the rigid scheme's search for a
        dip of N* inside a step needs (it is |u_y|'s amplitude for a single harmonic)."""
        d = scene.drive
        return abs(d.amplitude) + 16.0 * abs(d.second)

    def surface_bound(self, scene: Any) -> float:
        """|Y1| + |Y2|: u_y = R(t*) (Y1 cos(2 pi t*) + Y2 cos(4 pi t* + phi)), R in [0, 1]; 0
        with the vertical wave off."""
        if not scene.effects.vertical_wave:
            return 0.0
        return abs(scene.drive.amplitude) + abs(scene.drive.second)

    def state_scale(self, scene: Any) -> np.ndarray:
        """2 pi (|X1| + 2 |X2|), 1 + |Y1| + |Y2|, 2 pi (1 + |Y1| + |Y2|): sizes of x*', y*, y*'."""
        d = scene.drive
        amp = abs(d.amplitude) + abs(d.second)
        return np.array([2 * math.pi * max(abs(d.horizontal) + 2.0 * abs(d.second_horizontal), 1e-12),
                         1.0 + amp, 2 * math.pi * (1.0 + amp)])

    def orbit_name(self, scene: Any) -> str:
        return "biharmonic"

    def describe(self, scene: Any) -> list[str]:
        d = scene.drive
        lines = [f"u_x = R(t*) ({d.horizontal:g} cos(2 pi t*) + {d.second_horizontal:g} "
                 f"cos(4 pi t* + {d.second_horizontal_phase:g} deg))",
                 f"u_y = R(t*) ({d.amplitude:g} cos(2 pi t*) + {d.second:g} "
                 f"cos(4 pi t* + {d.second_phase:g} deg)) (bi-harmonic vibration, Blekhman)"]
        ramp_p = d.ramp_periods
        lines.append(f"R(t*) = sin^2(pi t* / (2 x {ramp_p:g})) ramp" if ramp_p > 0 else "no ramp")
        return lines


#: length of the drive's own parameter vector; the table of the fundamental's phase follows it
N_PARAMS = len(Biharmonic.names)


@njit(cache=True)
def _second(t, c, s):
    """(g, g', g'') of g = c cos(4 pi t*) + s sin(4 pi t*)."""
    c4 = math.cos(FOUR_PI * t)
    s4 = math.sin(FOUR_PI * t)
    g = c * c4 + s * s4
    return g, FOUR_PI * (s * c4 - c * s4), -FOUR_PI * FOUR_PI * g


@njit(cache=True)
def kinematics(t, x, dp):
    """(u_x, u_x', u_x'', u_y, u_y', u_y'') at t* (the plate moves as a whole: x* unused).

    The fundamental's terms are written as :func:`.travelling.kinematics` writes them, so that
    with no second harmonic the values are the linear orbit's to the last bit.
    """
    rr, rd, rdd = ramp(t, dp[0])
    s2, c2 = phase(t, dp, N_PARAMS)
    k2 = TWO_PI * TWO_PI
    x1, y1 = dp[1], dp[2]
    gx, gxd, gxdd = _second(t, dp[3], dp[4])
    gy, gyd, gydd = _second(t, dp[5], dp[6])
    ux = x1 * rr * c2 + rr * gx
    uxd = x1 * (rd * c2 - rr * TWO_PI * s2) + (rd * gx + rr * gxd)
    uxdd = (x1 * (rdd * c2 - 2.0 * rd * TWO_PI * s2 - rr * k2 * c2)
            + (rdd * gx + 2.0 * rd * gxd + rr * gxdd))
    uy = y1 * rr * c2 + rr * gy
    uyd = y1 * (rd * c2 - rr * TWO_PI * s2) + (rd * gy + rr * gyd)
    uydd = (y1 * (rdd * c2 - 2.0 * rd * TWO_PI * s2 - rr * k2 * c2)
            + (rdd * gy + 2.0 * rd * gyd + rr * gydd))
    return ux, uxd, uxdd, uy, uyd, uydd


@njit(cache=True)
def surface(t, x, dp):
    """(u_x, u_x', u_y, u_y') at t* (see :func:`kinematics`)."""
    rr, rd, _ = ramp(t, dp[0])
    s2, c2 = phase(t, dp, N_PARAMS)
    x1, y1 = dp[1], dp[2]
    gx, gxd, _ = _second(t, dp[3], dp[4])
    gy, gyd, _ = _second(t, dp[5], dp[6])
    return (x1 * rr * c2 + rr * gx, x1 * (rd * c2 - rr * TWO_PI * s2) + (rd * gx + rr * gxd),
            y1 * rr * c2 + rr * gy, y1 * (rd * c2 - rr * TWO_PI * s2) + (rd * gy + rr * gyd))
