"""Two counter-propagating Rayleigh waves: the local orbit at a place, or a direct run.

The scene's wave (amplitude A*, orbit phase phi0 of :func:`.travelling.phase_of`, ratio r)
travels to +x; its mirror image travels to -x with amplitude ratio s (``drive.backward``) and
phase psi (``drive.backward_phase``, degrees; ``drive.backward_phase_rate`` degrees per period
makes psi(t*) = psi + rate t*). With u = Re(U e^{2 pi i t*}) and xi = X / wavelength::

    U_y = A* (e^{-2 pi i xi} + s e^{i (2 pi xi + psi)})
    U_x = r A* e^{i phi0} (e^{-2 pi i xi} - s e^{i (2 pi xi + psi)})

(docs/physics.md, "Two waves: the local orbit and the drift field"). Both are multiplied by the
start-up ramp R(t*). Two ways to evaluate it:

* **at one place** (``drive.wavelength`` unset): xi = ``drive.position``, one elliptic local
  orbit, whose coefficients of cos(2 pi t*) and sin(2 pi t*) are computed once (parameters
  ``cy, by, cx, bx``); with s = 0 and xi = 0 this is the travelling wave's orbit to rounding;
* **a direct run** (``drive.wavelength`` = L*, wavelength / a0, given, or a phase ramp): each
  wave is evaluated at the particle's own position, xi = ``drive.position`` + x*/L*, with its
  phase 2 pi (t* - xi) (forward) and 2 pi (t* + xi) + psi(t*) (backward).

The derivatives are the partial ones in t* at the contact point: the velocity of the substrate's
material there. The terms x*' d/dx* (surface slope and strain, of relative size x*'/L* against the
wave's speed L* per period) are left out.
"""

from __future__ import annotations

import cmath
import math
from typing import Any, ClassVar

import numpy as np
from numba import njit

from .base import Drive
from .ramp import TWO_PI, ramp
from .travelling import phase_of, unit_phase

__all__ = ["TwoWaves", "field_shift", "local_orbit", "needs_two_waves"]


def needs_two_waves(drive: Any) -> bool:
    """Whether a wave drive needs this module: a second wave, a position, a wavelength or a ramp.

    Otherwise the single travelling wave (:mod:`.travelling`) runs, bit for bit as before.
    """
    return (getattr(drive, "kind", None) == "wave"
            and (drive.backward > 0.0 or drive.position != 0.0 or drive.wavelength is not None
                 or drive.backward_phase_rate != 0.0))


def field_shift(rate: Any, t: Any) -> Any:
    """How far the drift field has moved at t*, in wavelengths, under a phase ramp: -rate t* / 720.

    Every local quantity of the two waves depends on 4 pi xi + psi(t*) (module formula), and
    psi(t*) = psi + ``rate`` t* (degrees), so the field V(xi) of t* = 0 is found at
    xi - rate t* / 720: a trap at z moves to z + :func:`field_shift`. ``rate`` (degrees per period,
    ``drive.backward_phase_rate``) and ``t`` may be arrays. The one place that says so; the drift
    field's prediction and its figure ask here.
    """
    return -rate * t / 720.0


def local_orbit(amplitude: float, ratio: float, phase_deg: float, backward: float,
                backward_phase_deg: float, position: float) -> tuple[complex, complex]:
    """Complex amplitudes (U_x, U_y) of the local orbit at ``position`` = xi (module formula).

    The orbit phase's unit vector comes from :func:`.travelling.unit_phase`, exact at multiples
    of 90 degrees, so that s = 0, xi = 0 gives the travelling wave's coefficients exactly.
    """
    sp, cp = unit_phase(phase_deg)
    alpha = TWO_PI * position
    fwd = complex(1.0, 0.0) if position == 0.0 else cmath.exp(-1j * alpha)
    bwd = backward * cmath.exp(1j * (alpha + math.radians(backward_phase_deg))) if backward else 0j
    u_y = amplitude * (fwd + bwd)
    u_x = ratio * amplitude * complex(cp, sp) * (fwd - bwd)
    return u_x, u_y


class TwoWaves(Drive):
    """The scene's wave and its counter-propagating mirror image (``drive.kind = "wave"``)."""

    kind: ClassVar[str] = "wave"
    module: ClassVar[str] = __name__
    names: ClassVar[tuple[str, ...]] = (
        "ramp", "direct", "cx", "bx", "cy", "by",  # the local orbit (direct = 0)
        "amplitude", "ratio", "sin_phase", "cos_phase", "backward", "psi", "psi_rate",
        "position", "inv_wavelength", "horizontal", "vertical",  # a direct run (direct = 1)
    )

    @staticmethod
    def direct(scene: Any) -> bool:
        """Whether the drive is evaluated at the particle's position (or psi changes with t*)."""
        drive = scene.drive
        return drive.wavelength is not None or drive.backward_phase_rate != 0.0

    def orbit(self, scene: Any) -> tuple[complex, complex]:
        """(U_x, U_y) at ``drive.position`` (the start of a direct run)."""
        d = scene.drive
        return local_orbit(d.amplitude, scene.horizontal_ratio, phase_of(scene), d.backward,
                           d.backward_phase, d.position)

    def parameters(self, scene: Any) -> dict[str, float]:
        d, eff = scene.drive, scene.effects
        hor = 1.0 if eff.horizontal_wave else 0.0
        ver = 1.0 if eff.vertical_wave else 0.0
        u_x, u_y = self.orbit(scene)
        s, c = unit_phase(phase_of(scene))
        return {
            "ramp": d.ramp_periods, "direct": 1.0 if self.direct(scene) else 0.0,
            # u = Re(U e^{2 pi i t*}) = Re(U) cos(2 pi t*) - Im(U) sin(2 pi t*)
            "cx": hor * u_x.real, "bx": -hor * u_x.imag, "cy": ver * u_y.real, "by": -ver * u_y.imag,
            "amplitude": d.amplitude, "ratio": scene.horizontal_ratio, "sin_phase": s,
            "cos_phase": c, "backward": d.backward, "psi": math.radians(d.backward_phase),
            "psi_rate": math.radians(d.backward_phase_rate), "position": d.position,
            "inv_wavelength": 1.0 / d.wavelength if d.wavelength is not None else 0.0,
            "horizontal": hor, "vertical": ver,
        }

    def ramp_periods(self, scene: Any) -> float:
        return scene.drive.ramp_periods

    def horizontal_speed(self, scene: Any) -> float:
        """2 pi |U_x| at ``drive.position``; for a direct run the forward wave's 2 pi r A*; 0
        with the horizontal wave off."""
        if not scene.effects.horizontal_wave:
            return 0.0
        if self.direct(scene):
            return self.forward_speed(scene)
        return TWO_PI * abs(self.orbit(scene)[0])

    @staticmethod
    def forward_speed(scene: Any) -> float:
        """2 pi r A*: the forward wave's horizontal surface speed alone (the same at every xi)."""
        return TWO_PI * scene.horizontal_ratio * scene.drive.amplitude

    @staticmethod
    def field_shift(scene: Any, t: Any) -> Any:
        """:func:`field_shift` of the scene's ``drive.backward_phase_rate`` at t*."""
        return field_shift(scene.drive.backward_phase_rate, t)

    def vertical_amplitude(self, scene: Any) -> float:
        """|U_y| at ``drive.position``; for a direct run its largest value A* (1 + s)."""
        if self.direct(scene):
            return scene.drive.amplitude * (1.0 + scene.drive.backward)
        return abs(self.orbit(scene)[1])

    def surface_bound(self, scene: Any) -> float:
        """|A*| (1 + |s|) for a direct run (the two waves' vertical amplitudes added), else
        |U_y| of the local orbit; 0 with the vertical wave off. The ramp is in [0, 1]."""
        if not scene.effects.vertical_wave:
            return 0.0
        if self.direct(scene):
            return abs(scene.drive.amplitude) * (1.0 + abs(scene.drive.backward))
        return abs(self.orbit(scene)[1])

    def state_scale(self, scene: Any) -> np.ndarray:
        """2 pi |U_x|, 1 + |U_y|, 2 pi (1 + |U_y|): the sizes of x*', y*, y*'."""
        amp = self.vertical_amplitude(scene)
        return np.array([max(self.horizontal_speed(scene), TWO_PI * 1e-12), 1.0 + amp,
                         TWO_PI * (1.0 + amp)])

    def orbit_name(self, scene: Any) -> str:
        d = scene.drive
        where = ("direct" if d.wavelength is not None else f"xi {d.position:g}")
        return f"two waves s {d.backward:g} psi {d.backward_phase:g} ({where})"

    def describe(self, scene: Any) -> list[str]:
        d = scene.drive
        r, phase = scene.horizontal_ratio, phase_of(scene)
        lines = [f"two waves: forward A* = {d.amplitude:g}, r = {r:.6g}, orbit phase "
                 f"{phase:g} deg; backward s = {d.backward:g}, psi = {d.backward_phase:g} deg"
                 + (f" + {d.backward_phase_rate:g} deg per period" if d.backward_phase_rate else ""),
                 "U_y = A* (e^{-2 pi i xi} + s e^{i(2 pi xi + psi)}), "
                 "U_x = r A* e^{i phi0} (e^{-2 pi i xi} - s e^{i(2 pi xi + psi)}), "
                 "u = R(t*) Re(U e^{2 pi i t*})"]
        if d.wavelength is not None:
            lines.append(f"direct run: evaluated at the particle, xi = {d.position:g} + x*/L*, "
                         f"L* = {d.wavelength:g}")
        else:
            u_x, u_y = self.orbit(scene)
            rel = math.degrees(cmath.phase(u_x) - cmath.phase(u_y)) if abs(u_x) and abs(u_y) else 0.0
            lines.append(f"local orbit at xi = {d.position:g}: |U_y| = {abs(u_y):.6g}, |U_x| = "
                         f"{abs(u_x):.6g}, phase {math.remainder(rel, 360.0):.4g} deg; drift ratio "
                         f"scale 2 pi |U_x| = {TWO_PI * abs(u_x):.6g}")
        ramp_p = d.ramp_periods
        lines.append(f"R(t*) = sin^2(pi t* / (2 x {ramp_p:g})) ramp" if ramp_p > 0 else "no ramp")
        return lines


@njit(cache=True)
def _waves(t, x, dp):
    """(g_x, g_x', g_x'', g_y, g_y', g_y'') before the ramp: the local orbit or the direct sum."""
    k2 = TWO_PI * TWO_PI
    if dp[1] == 0.0:
        s2 = math.sin(TWO_PI * t)
        c2 = math.cos(TWO_PI * t)
        cx, bx, cy, by = dp[2], dp[3], dp[4], dp[5]
        return (cx * c2 + bx * s2, TWO_PI * (bx * c2 - cx * s2), -k2 * (cx * c2 + bx * s2),
                cy * c2 + by * s2, TWO_PI * (by * c2 - cy * s2), -k2 * (cy * c2 + by * s2))
    amp, r, sp, cp, s = dp[6], dp[7], dp[8], dp[9], dp[10]
    xi = dp[13] + x * dp[14]
    tf = TWO_PI * (t - xi)
    wb = TWO_PI + dp[12]
    tb = wb * t + TWO_PI * xi + dp[11]
    cf, sf = math.cos(tf), math.sin(tf)
    cb, sb = math.cos(tb), math.sin(tb)
    ay = amp * dp[16]
    ax = r * amp * dp[15]
    # forward: cos(tf + phi0) = cp cf - sp sf; backward enters u_x with a minus sign
    gx = ax * ((cp * cf - sp * sf) - s * (cp * cb - sp * sb))
    gxd = ax * (-TWO_PI * (cp * sf + sp * cf) + s * wb * (cp * sb + sp * cb))
    gxdd = ax * (-k2 * (cp * cf - sp * sf) + s * wb * wb * (cp * cb - sp * sb))
    gy = ay * (cf + s * cb)
    gyd = ay * (-TWO_PI * sf - s * wb * sb)
    gydd = ay * (-k2 * cf - s * wb * wb * cb)
    return gx, gxd, gxdd, gy, gyd, gydd


@njit(cache=True)
def kinematics(t, x, dp):
    """(u_x, u_x', u_x'', u_y, u_y', u_y'') at t* and x* (the ramp times :func:`_waves`)."""
    rr, rd, rdd = ramp(t, dp[0])
    gx, gxd, gxdd, gy, gyd, gydd = _waves(t, x, dp)
    return (rr * gx, rd * gx + rr * gxd, rdd * gx + 2.0 * rd * gxd + rr * gxdd,
            rr * gy, rd * gy + rr * gyd, rdd * gy + 2.0 * rd * gyd + rr * gydd)


@njit(cache=True)
def surface(t, x, dp):
    """(u_x, u_x', u_y, u_y') at t* and x* (see :func:`kinematics`)."""
    rr, rd, _ = ramp(t, dp[0])
    gx, gxd, _, gy, gyd, _ = _waves(t, x, dp)
    return rr * gx, rd * gx + rr * gxd, rr * gy, rd * gy + rr * gyd
