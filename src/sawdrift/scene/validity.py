"""Where a device scene leaves the model's assumptions: its validity warnings.

They depend on the device and on the scene's adhesive law (an adhesive contact at rest is not
the Hertz contact under M g), so they live beside both: every Result carries them, and the
text, JSON, sweep tables, exports, fields and thresholds print them.
"""

from __future__ import annotations

import math

from .adhesion import PULLOFF_FACTOR, adhesive_rest, adhesive_sets_contact, tabor_warning
from .device import Device, device_wavelength, normalized


def device_warnings(device: Device, law: str = "none") -> list[str]:
    """Where the scene leaves the model's assumptions, one sentence each (also in every Result):
    a static compression below 1 nm that adhesion does not set (none, or a pull-off below M g:
    adhesion and roughness then set the contact, not gravity and preload), a sphere's contact
    radius above 0.1 R (beyond small strain; with adhesion the adhesive contact's at rest), a
    cone's half-angle below 60 deg (Sneddon's small-slope solution), a flat punch's
    compression above 0.01 R (its strain a0/R), an adhesive law outside its range by Tabor's
    parameter (:func:`~.adhesion.tabor_warning`). ``law``: the scene's
    ``effects.adhesion``."""
    n = normalized(device)
    part = device.particle
    out = []
    adhesive = device.adhesion > 0.0 and law in PULLOFF_FACTOR
    if n["a0_m"] < 1e-9 and not (adhesive and adhesive_sets_contact(device, law)):
        out.append(f"a0 < 1 nm (a0 = {n['a0_m']:.3g} m): adhesion and roughness, not gravity and "
                   "preload, then set the contact; the model's assumptions do not hold")
    # the contact radius at rest: with adhesion a sphere's is the adhesive contact's
    radius = (adhesive_rest(device, law)["contact_radius_m"] if adhesive and part.shape == "sphere"
              else n["contact_radius_m"])
    if part.shape == "sphere" and radius > 0.1 * float(part.radius):
        out.append(f"contact radius {radius:.3g} m above 0.1 R: beyond Hertz's small-strain "
                   "theory")
    tabor_out = tabor_warning(device, law)
    if tabor_out is not None:
        out.append(tabor_out)
    if part.shape == "flat" and n["a0_m"] > 0.01 * float(part.radius):
        # the punch's strain is a0 / R (a sphere's contact radius 0.1 R is a0 = 0.01 R): a
        # compression of 9 R (a soft, heavy punch) ran without a word
        out.append(f"compression a0 = {n['a0_m']:.3g} m above 0.01 R (strain a0/R = "
                   f"{n['a0_m'] / float(part.radius):.3g}): beyond Boussinesq's small-strain "
                   "solution")
    patch = _patch_warning(device, radius)
    if patch is not None:
        out.append(patch)
    if part.shape == "cone" and float(part.half_angle) < math.radians(60.0):
        # the angle itself: the fixed "27 % at 42 deg" read as the error at every angle
        out.append(f"half-angle {math.degrees(float(part.half_angle)):.3g} deg below 60 deg: "
                   "Sneddon's small-slope solution underestimates the contact radius, more the "
                   "sharper the cone (27 % at 42 deg)")
    return out


#: the largest contact radius, in wavelengths, over which the wave's motion counts as uniform:
#: the phase of the surface motion changes by 2 pi 2 a / lambda = 0.63 rad across the contact
PATCH_WAVELENGTHS = 0.05


def _patch_warning(device: Device, radius: float) -> str | None:
    """The contact ``radius`` above :data:`PATCH_WAVELENGTHS` of the device's wavelength (where it
    is known, :func:`~.device.device_wavelength`): the model moves the contact with the surface
    at one point, and a contact spanning a good part of a wavelength (a 0.5 mm ball, 3 um of
    contact, on a 10 nm wave ran without a word) feels an average of the wave over its patch."""
    lam = device_wavelength(device)
    if lam is None:
        return None
    if not radius > PATCH_WAVELENGTHS * lam:
        return None
    return (f"contact radius {radius:.3g} m is {radius / lam:.2g} wavelengths (wavelength "
            f"{lam:.3g} m): the wave moves the surface by different amounts across the contact, "
            f"which the model takes at one point; keep it below {PATCH_WAVELENGTHS:g} wavelengths")
