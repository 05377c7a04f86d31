"""The travelling Rayleigh wave at one place: an elliptic local orbit of any phase (paper eq. 1).

Normalized (one wave period is one unit of t*), y* pointing into the substrate::

    u_y = A* R(t*) cos(2 pi t*)
    u_x = r A* R(t*) cos(2 pi t* + phase)
        = -r A* R(t*) sin(phase) sin(2 pi t*) + r A* R(t*) cos(phase) cos(2 pi t*)

with the start-up ramp R(t*) (:mod:`.ramp`). ``phase = 90`` degrees is eq. 1 as printed, the
prograde orbit in this frame (the crest moves with the wave); ``-90`` the retrograde orbit of a
Rayleigh wave on an isotropic half-space (the mirror x -> -x); ``0`` and ``180`` a linear
vibration (a standing wave's local motion; a vibratory conveyor with throw angle atan(1/r)); and
``r = 0`` vertical vibration. ``drive.orbit`` names the two Rayleigh orbits. The sine and cosine
of the phase are exact at multiples of 90 degrees, and ``phase + 180`` negates both exactly, so
the mirrored drive gives the mirrored motion to the last bit (docs/physics.md, "The wave and its
orbit").
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np
from numba import njit

from .base import Drive
from .ramp import TWO_PI, phase, ramp, with_phase_table


def unit_phase(degrees: float) -> tuple[float, float]:
    """(sin, cos) of ``degrees``: exact at multiples of 90, and negated exactly by +180."""
    phi = math.fmod(float(degrees), 360.0)
    if phi < 0.0:
        phi += 360.0
    sign = 1.0
    if phi >= 180.0:
        phi -= 180.0
        sign = -1.0
    exact = {0.0: (0.0, 1.0), 90.0: (1.0, 0.0)}
    s, c = exact.get(phi, (math.sin(math.radians(phi)), math.cos(math.radians(phi))))
    return sign * s, sign * c


def phase_of(scene: Any) -> float:
    """The scene's orbit phase in degrees: ``drive.phase``, else 90 (prograde) or -90."""
    drive = scene.drive
    if getattr(drive, "phase", None) is not None:
        return float(drive.phase)
    return 90.0 if drive.orbit == "prograde" else -90.0


class TravellingWave(Drive):
    """The scene's wave (``drive.kind = "wave"``) at the particle: one elliptic local orbit."""

    kind: ClassVar[str] = "wave"
    module: ClassVar[str] = __name__
    names: ClassVar[tuple[str, ...]] = ("amplitude", "ratio", "ramp", "horizontal", "vertical",
                                        "sin_phase", "cos_phase")

    def for_steps(self, dp: np.ndarray, k_per: int) -> np.ndarray:
        """``dp`` with the table of the wave's phase at the steps of one period
        (:func:`~.ramp.with_phase_table`)."""
        return with_phase_table(dp, k_per)

    def parameters(self, scene: Any) -> dict[str, float]:
        s, c = unit_phase(phase_of(scene))
        eff = scene.effects
        return {"amplitude": scene.drive.amplitude, "ratio": scene.horizontal_ratio,
                "ramp": scene.drive.ramp_periods, "horizontal": 1.0 if eff.horizontal_wave else 0.0,
                "vertical": 1.0 if eff.vertical_wave else 0.0, "sin_phase": s, "cos_phase": c}

    def ramp_periods(self, scene: Any) -> float:
        return scene.drive.ramp_periods

    def horizontal_speed(self, scene: Any) -> float:
        """2 pi r A*, the drift ratio's scale; 0 with the horizontal wave off (as for r = 0: a
        drift ratio of 0.0 there and None at r = 0 told one motion two ways)."""
        if not scene.effects.horizontal_wave:
            return 0.0
        return 2.0 * math.pi * scene.horizontal_ratio * scene.drive.amplitude

    def vertical_amplitude(self, scene: Any) -> float:
        return scene.drive.amplitude

    def surface_bound(self, scene: Any) -> float:
        """|A*|: u_y = A* R(t*) cos(2 pi t*) with the ramp R in [0, 1]; 0 with the vertical wave
        off."""
        return abs(scene.drive.amplitude) if scene.effects.vertical_wave else 0.0

    def state_scale(self, scene: Any) -> np.ndarray:
        """2 pi r A*, 1 + A*, 2 pi (1 + A*): the sizes of x*', y*, y*'."""
        amp, r = scene.drive.amplitude, scene.horizontal_ratio
        return np.array([2 * math.pi * max(abs(r) * amp, 1e-12), 1.0 + amp,
                         2 * math.pi * (1.0 + amp)])

    def orbit_name(self, scene: Any) -> str:
        phase = phase_of(scene)
        s, c = unit_phase(phase)
        if (s, c) == (1.0, 0.0):
            return "prograde"
        if (s, c) == (-1.0, 0.0):
            return "retrograde"
        return f"phase {phase:g}"

    def describe(self, scene: Any) -> list[str]:
        eff = scene.effects
        amp, r = scene.drive.amplitude, scene.horizontal_ratio
        phase = phase_of(scene)
        lines = []
        if eff.horizontal_wave:
            name = self.orbit_name(scene)
            if name == "prograde":
                lines.append(f"u_x = -A* r R(t*) sin(2 pi t*), A* = {amp:g}, r = {r:.6g}")
                lines.append("prograde orbit (eq. 1 as printed, y* into the substrate): at the "
                             "crest the surface moves with the wave, +x")
            elif name == "retrograde":
                lines.append(f"u_x = +A* r R(t*) sin(2 pi t*), A* = {amp:g}, r = {r:.6g} "
                             "(retrograde orbit: at the crest the surface moves against the "
                             "propagation direction, -x)")
            else:
                lines.append(f"u_x = A* r R(t*) cos(2 pi t* + {phase:g} deg), A* = {amp:g}, "
                             f"r = {r:.6g}")
        if eff.vertical_wave:
            lines.append(f"u_y = A* R(t*) cos(2 pi t*), A* = {amp:g}")
        if not (eff.horizontal_wave or eff.vertical_wave):
            lines.append("substrate at rest (both wave components off)")
        ramp_p = scene.drive.ramp_periods
        lines.append(f"R(t*) = sin^2(pi t* / (2 x {ramp_p:g})) ramp" if ramp_p > 0 else "no ramp")
        return lines


#: length of the drive's own parameter vector; the table of the wave's phase follows it
N_PARAMS = len(TravellingWave.names)


@njit(cache=True)
def kinematics(t, x, dp):
    """(u_x, u_x', u_x'', u_y, u_y', u_y'') at t* (the local orbit does not depend on x*)."""
    rr, rd, rdd = ramp(t, dp[2])
    s2, c2 = phase(t, dp, N_PARAMS)
    k2 = TWO_PI * TWO_PI
    h = -dp[0] * dp[1] * dp[3]
    bx = h * dp[5]  # coefficient of sin(2 pi t*) in u_x / R
    cx = -h * dp[6]  # coefficient of cos(2 pi t*)
    ay = dp[0] * dp[4]
    ux = bx * rr * s2 + cx * rr * c2
    uxd = bx * (rd * s2 + rr * TWO_PI * c2) + cx * (rd * c2 - rr * TWO_PI * s2)
    uxdd = (bx * (rdd * s2 + 2.0 * rd * TWO_PI * c2 - rr * k2 * s2)
            + cx * (rdd * c2 - 2.0 * rd * TWO_PI * s2 - rr * k2 * c2))
    uy = ay * rr * c2
    uyd = ay * (rd * c2 - rr * TWO_PI * s2)
    uydd = ay * (rdd * c2 - 2.0 * rd * TWO_PI * s2 - rr * k2 * c2)
    return ux, uxd, uxdd, uy, uyd, uydd


@njit(cache=True)
def surface(t, x, dp):
    """(u_x, u_x', u_y, u_y') at t* (see :func:`kinematics`)."""
    rr, rd, _ = ramp(t, dp[2])
    s2, c2 = phase(t, dp, N_PARAMS)
    h = -dp[0] * dp[1] * dp[3]
    bx = h * dp[5]
    cx = -h * dp[6]
    ay = dp[0] * dp[4]
    return (bx * rr * s2 + cx * rr * c2,
            bx * (rd * s2 + rr * TWO_PI * c2) + cx * (rd * c2 - rr * TWO_PI * s2),
            ay * rr * c2, ay * (rd * c2 - rr * TWO_PI * s2))
