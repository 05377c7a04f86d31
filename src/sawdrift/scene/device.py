"""Real devices in physical units, converted in this one module to the normalized scene.

A device is a particle (shape, size, density or mass, Young's modulus, Poisson's ratio) on a
substrate (Young's modulus, Poisson's ratio) carrying a Rayleigh wave (frequency, vertical
amplitude, orbit), with friction, gravity and an optional preload. Values are strings with units
parsed by pint ("9.6 MHz", "10 nm", "0.5 mm", "7.35 mN", "210 GPa", "7850 kg/m^3", "80 deg");
bare numbers are SI (an angle in radians).

Conversion (docs/physics.md, "Physical units and two materials"; docs/devices.md)::

    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2          1/G* = (2 - nu1)/G1 + (2 - nu2)/G2
    G_i = E_i / (2 (1 + nu_i))                       M g = m g cos(alpha) + F_ext
    a0: the compression under M g of the particle's profile (see below)
    m* = a0 m f^2 / (M g)      A* = A_y / a0      theta = E* / (4 G*)      r = r(nu2) by default
    L = (F_load - m g sin(alpha)) / (M g)             (particle.load)

with alpha the incline of the substrate (positive: the surface rises towards +x, so gravity
pulls the particle down the slope, towards -x) and F_load an external tangential force along +x.

The static compression a0 solves N(a0) = M g with the profile's elastic normal law N(delta)
(all three in Sneddon 1965, "The relation between load and penetration in the axisymmetric
Boussinesq problem for a punch of arbitrary profile", Int. J. Eng. Sci. 3, 47-57; also K. L.
Johnson, Contact Mechanics, 1985, chapters 3-5)::

    sphere of radius R (Hertz 1882):      N = (4/3) E* R^(1/2) delta^(3/2)
                                          a0 = (9 (M g)^2 / (16 R E*^2))^(1/3)
    cone of half-angle alpha (Sneddon):   N = (2/pi) E* tan(alpha) delta^2
                                          a0 = (pi M g / (2 E* tan(alpha)))^(1/2)
    flat punch of radius R (Boussinesq):  N = 2 E* R delta
                                          a0 = M g / (2 E* R)

so that N / (M g) = (delta / a0)^p with p = 3/2, 2, 1: the normalized laws of
:mod:`sawdrift.scene.profiles`. A power-law or tabulated profile has no dimensional law here and
is refused. theta belongs to the contact (two materials; the ratio of tangential to normal
stiffness 4 G*/E* holds for every axisymmetric profile), r to the substrate's wave. A normalized
speed x*' is x*' a0 f in m/s, a normalized time t* is t*/f in s. x points along the propagation
direction; the device default orbit is the retrograde one of a Rayleigh wave on an isotropic
half-space (the mirror of eq. 1 as printed).

Every quantity has a physical range (:data:`RANGES`, docs/devices.md "Ranges"), and the
normalized quantities its values combine into have one too (:func:`derived_out_of_range`): a
value outside is one line naming the field and the range, never a run.

Which scene fields a device derives, and the error for setting one, live in
:mod:`sawdrift.scene.overrides`.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, model_validator

from ..errors import SceneError
from .bounds import AMPLITUDE_MAX, M_STAR_RANGE, bounded
from .rayleigh import rayleigh_ratio, rayleigh_speed_ratio
from .units import (
    FIELD_KIND,
    RANGES,
    UNITS,
    field_si,
    friction_value,
    half_angle_value,
    in_range,
    to_si,
)

__all__ = ["FIELD_KIND", "RANGES", "UNITS", "field_si", "to_si"]  # imported from here by others

_FROZEN = ConfigDict(frozen=True, extra="forbid")

def _incline(value: Any) -> float:
    out = to_si(value, "angle")
    if not -0.5 * math.pi < out < 0.5 * math.pi:
        # the allowed range of RANGES, as in_range words it for 86 deg (this said (-90, 90) deg)
        raise ValueError(f"is outside the allowed range {RANGES['incline'][2]} (the substrate's "
                         "slope, positive where the surface rises towards +x, e.g. '5 deg'; a "
                         "bare number is in radians)")
    return in_range("incline", out, "rad", value)


def _quantity(kind: str, field: str, positive: bool = True, allow_zero: bool = False):
    """A validator of a device quantity of dimension ``kind``: its sign, then its
    :data:`RANGES` entry ``field``."""
    def check(value: Any) -> float:
        out = to_si(value, kind)
        if positive and (out < 0.0 or (out == 0.0 and not allow_zero)):
            bound = ">= 0" if allow_zero else "> 0"
            article = "an" if kind[0] in "aeiou" else "a"  # "a acceleration" read wrong
            raise ValueError(f"is not {bound}: {article} {kind} in {UNITS[kind][1]} must be "
                             f"{bound}")
        return in_range(field, out, UNITS[kind][1], value)

    return BeforeValidator(check)


Pressure = Annotated[float, _quantity("pressure", "particle.youngs_modulus")]
Poisson = Annotated[float, bounded(-1.0, 0.5, lo_open=True, hi_open=True)]


class DeviceParticle(BaseModel):
    """The particle of a device: its contact shape, size, density or mass, elastic constants.

    ``shape`` sets the profile of the contact and so the law N(delta) that gives a0 (see the
    module text): a ``sphere`` of ``radius`` R (mass from ``density`` or ``mass``), a ``cone`` of
    ``half_angle`` alpha, a ``flat`` punch of ``radius`` R. A cone or a punch is not a sphere, so
    its ``mass`` must be given (``density`` would give the mass of a sphere).
    """

    model_config = _FROZEN

    shape: Literal["sphere", "cone", "flat"] = Field(
        "sphere", description="contact profile: sphere (Hertz), cone (Sneddon), flat punch")
    radius: Annotated[float, _quantity("length", "particle.radius")] | None = Field(
        None, description="sphere radius R, or the flat punch's radius, 1 nm to 10 cm")
    half_angle: Annotated[float, BeforeValidator(half_angle_value)] | None = Field(
        None, description="cone only: half-angle alpha between axis and surface, 1 to 89.9 deg")
    density: Annotated[float, _quantity("density", "particle.density")] | None = Field(
        None, description="or mass")
    mass: Annotated[float, _quantity("mass", "particle.mass")] | None = Field(
        None, description="or density")
    youngs_modulus: Pressure = Field(description="E1, 1 kPa to 2 TPa")
    poisson: Poisson = Field(description="nu1, in (-1, 0.5)")

    @model_validator(mode="after")
    def _geometry(self) -> DeviceParticle:
        shape = self.shape
        if shape in ("sphere", "flat") and self.radius is None:
            what = "the sphere's radius" if shape == "sphere" else "the punch's radius"
            raise ValueError(f"radius is required for a {shape}: {what}, a length in m, "
                             "e.g. '0.5 mm'")
        if shape == "cone":
            if self.half_angle is None:
                raise ValueError("half_angle is required for a cone: the angle between its axis "
                                 "and its surface, e.g. '80 deg'")
            if self.radius is not None:
                raise ValueError("radius is not used by a cone (its a0 depends on half_angle "
                                 "only); remove it")
        elif self.half_angle is not None:
            raise ValueError(f"half_angle applies to a cone only, not to a {shape}; remove it")
        if shape != "sphere" and self.density is not None:
            raise ValueError(f"density gives the mass of a sphere (4/3 pi R^3 rho); a {shape} "
                             "particle needs its mass, e.g. mass = '4.1 mg'")
        if self.density is None and self.mass is None:
            raise ValueError("give exactly one of density (kg/m^3) or mass (kg)")
        if self.density is not None and self.mass is not None:
            # over-determined: accepted only where the two agree (a scene written out in full)
            implied = float(self.density) * 4.0 / 3.0 * math.pi * float(self.radius) ** 3
            if abs(self.mass - implied) > 1e-9 * implied:
                raise ValueError(
                    f"mass = {self.mass:.6g} kg and density = {self.density:.6g} kg/m^3 both "
                    f"given, and they disagree (a sphere of radius {float(self.radius):.6g} m at "
                    f"that density has {implied:.6g} kg): give exactly one of density (kg/m^3) "
                    "or mass (kg)")
        return self

    @property
    def mass_kg(self) -> float:
        """m: the given mass, or density x 4/3 pi R^3 for a sphere."""
        if self.mass is not None:
            return self.mass
        return float(self.density) * 4.0 / 3.0 * math.pi * float(self.radius) ** 3


class DeviceSubstrate(BaseModel):
    """The substrate: elastic constants (and so the Rayleigh ratio r(nu2) by default)."""

    model_config = _FROZEN

    youngs_modulus: Annotated[float, _quantity("pressure", "substrate.youngs_modulus")] = Field(
        description="E2, 1 kPa to 2 TPa")
    poisson: Poisson = Field(description="nu2, in (-1, 0.5)")
    density: Annotated[float, _quantity("density", "substrate.density")] | None = Field(
        None, description="rho2: the Rayleigh speed c_R = xi_R sqrt(G2/rho2) and so the "
        "wavelength c_R/f (two-wave fields and direct runs)")


class Device(BaseModel):
    """A device in physical units (the ``[device]`` table of a scene file)."""

    model_config = _FROZEN

    frequency: Annotated[float, _quantity("frequency", "frequency")] = Field(
        description="wave frequency f, 1 Hz to 100 GHz")
    amplitude: Annotated[float, _quantity("length", "amplitude", allow_zero=True)] = Field(
        description="vertical surface displacement amplitude A_y, 0 to 1 cm")
    orbit: Literal["prograde", "retrograde"] = Field(
        "retrograde", description="retrograde: a Rayleigh wave on an isotropic half-space")
    horizontal_ratio: Annotated[float, bounded(0.0, 100.0)] | None = Field(
        None, description="r; default r(substrate poisson)")
    gravity: Annotated[float, _quantity("acceleration", "gravity", allow_zero=True)] = Field(
        9.81, description="g, 0 to 1e4 m/s^2; 0 allowed with a preload")
    preload: Annotated[float, _quantity("force", "preload", allow_zero=True)] = Field(
        0.0, description="external normal force F_ext, 0 to 1 kN")
    load: Annotated[float, _quantity("force", "load", positive=False)] = Field(
        0.0, description="external tangential force on the particle along +x, -1 kN to 1 kN (a "
        "motor's load is negative against a drift to +x)")
    incline: Annotated[float, BeforeValidator(_incline)] = Field(
        0.0, description="slope alpha of the substrate, -85 deg to 85 deg, positive where the "
        "surface rises towards +x: gravity's normal part m g cos(alpha) holds the particle, its "
        "part m g sin(alpha) pulls it down the slope")
    friction: Annotated[float, BeforeValidator(friction_value)] = Field(description="mu, 0.001 to 10")
    wavelength: Annotated[float, _quantity("length", "wavelength")] | None = Field(
        None, description="surface wavelength, 10 nm to 100 m; overrides c_R/f from device.substrate.density "
        "(anisotropic crystals)")
    adhesion: Annotated[float, _quantity("surface energy", "adhesion", allow_zero=True)] = Field(
        0.0, description="work of adhesion w of the particle-substrate pair (0 to 10 J/m^2, e.g. "
        "'0.05 J/m^2'); with effects.adhesion = 'dmt' or 'jkr' it sets material.adhesion")
    particle: DeviceParticle
    substrate: DeviceSubstrate

    @model_validator(mode="after")
    def _adhesive_sphere(self) -> Device:
        if self.adhesion > 0.0 and self.particle.shape != "sphere":
            raise ValueError(f"adhesion = {self.adhesion:g} J/m^2 needs particle.shape = 'sphere', "
                             f"not {self.particle.shape!r}")
        return self

    @model_validator(mode="after")
    def _held_down(self) -> Device:
        if self.gravity == 0.0 and self.preload == 0.0:
            if self.adhesion > 0.0:
                # adhesion holds it, but the model's unit of force is the normal load M g +
                # preload, and the static compression a0 its unit of length
                raise ValueError("gravity = 0 needs a preload > 0: adhesion holds the particle, "
                                 "but the model measures forces in the normal load M g + "
                                 "preload and lengths in its compression; give a small preload, "
                                 "e.g. preload = '1 nN'")
            raise ValueError("gravity = 0 needs a preload > 0: nothing would hold the particle")
        return self

    @model_validator(mode="after")
    def _plausible_wave(self) -> Device:
        problem = wave_implausibility(self) or derived_out_of_range(self)
        if problem is not None:
            raise ValueError(problem)
        return self


#: Peak surface strain k A_y of a wave the linear-elastic model can stand for. Crystals used for
#: SAW devices crack or turn plastic well below 1 % strain; amplitudes this large are typed in
#: the wrong unit, not measured.
MAX_SURFACE_STRAIN = 1e-2

#: Fastest shear-wave speed of any solid (diamond, about 12.8 km/s), rounded up: a bound on the
#: Rayleigh speed c_R < c_S when the substrate's density and the wavelength are not given.
MAX_WAVE_SPEED = 1.3e4


def rayleigh_wavelength(youngs_modulus: float, poisson: float, density: float,
                        frequency: float) -> float:
    """lambda = c_R / f in m, c_R = xi_R sqrt(G / rho), G = E / (2 (1 + nu)) (SI inputs).

    xi_R = c_R / c_S is the root of the Rayleigh equation (Achenbach 1973, eq. 5.2.7;
    :func:`sawdrift.scene.rayleigh.rayleigh_speed_ratio`): 0.9194 at nu = 0.25.
    """
    if not (density > 0.0 and youngs_modulus > 0.0 and frequency > 0.0):
        raise SceneError("a Rayleigh wavelength needs a density, Young's modulus and frequency > 0")
    shear = youngs_modulus / (2.0 * (1.0 + poisson))
    return rayleigh_speed_ratio(poisson) * math.sqrt(shear / density) / frequency


def device_wavelength(device: Any) -> float | None:
    """The wavelength of a device in m: ``device.wavelength`` if given (anisotropic crystals),
    else from ``device.substrate.density`` and its moduli (:func:`rayleigh_wavelength`), else None.
    """
    given = getattr(device, "wavelength", None)
    if given is not None:
        return float(given)
    sub = device.substrate
    rho = getattr(sub, "density", None)
    if rho is None:
        return None
    return rayleigh_wavelength(sub.youngs_modulus, sub.poisson, float(rho), device.frequency)


def wave_implausibility(device: Device) -> str | None:
    """Why the device's wave cannot be what its numbers say, or None if it can.

    A travelling wave's surface speed over its phase speed is its surface strain:
    v / c = omega A / c = k A = 2 pi A / lambda. So three bounds are one, seen three ways: the
    peak surface speed 2 pi f A_y sqrt(1 + r^2) must stay below the wave speed c = lambda f, the
    amplitude below a fraction of the wavelength, and the strain 2 pi A_y / lambda below
    :data:`MAX_SURFACE_STRAIN`. The wave speed is the device's (``wavelength`` times f, or the
    Rayleigh speed of ``substrate.density``); without either, :data:`MAX_WAVE_SPEED` bounds it,
    which only catches amplitudes typed in the wrong unit (a bare ``amplitude = 10`` is 10 m).
    """
    f, amp = device.frequency, device.amplitude
    if amp == 0.0:
        return None
    lam = device_wavelength(device)
    r = device.horizontal_ratio if device.horizontal_ratio is not None else rayleigh_ratio(
        device.substrate.poisson)
    speed = 2.0 * math.pi * f * amp * math.sqrt(1.0 + r * r)
    given = f"device.amplitude = {amp:.4g} m at device.frequency = {f:.4g} Hz"
    hint = "(a bare number would be metres: write the unit, e.g. amplitude = '10 nm')"
    if lam is None:
        if speed >= MAX_WAVE_SPEED:
            return (f"{given} moves the surface at {speed:.3g} m/s, faster than any elastic wave "
                    f"(below {MAX_WAVE_SPEED:.2g} m/s in every solid) {hint}")
        strain = 2.0 * math.pi * f * amp / MAX_WAVE_SPEED
        where = f"at least {strain:.3g} (with the fastest wave speed of any solid)"
    else:
        c = lam * f
        if speed >= c:
            return (f"{given} moves the surface at {speed:.3g} m/s, faster than the wave itself "
                    f"({c:.4g} m/s) {hint}")
        strain = 2.0 * math.pi * amp / lam
        where = f"{strain:.3g} (wavelength {lam:.4g} m)"
    if strain > MAX_SURFACE_STRAIN:
        return (f"{given} strains the surface by {where}, above {MAX_SURFACE_STRAIN:g}: no "
                f"substrate stays elastic there; the amplitude must be below "
                f"{MAX_SURFACE_STRAIN / (2.0 * math.pi):.2g} wavelengths {hint}")
    return None


def derived_out_of_range(device: Device) -> str | None:
    """Why the device's normalized quantities are outside what the model can integrate, or None.

    Each field may be inside its own range (:data:`RANGES`) while the combination gives an m*
    outside :data:`M_STAR_RANGE` (a 10 cm ball on a 100 GHz wave), or an A* above
    :data:`~.bounds.AMPLITUDE_MAX`. The line names the device fields that set it. The load
    and the pull-off, whose bounds depend on the adhesive law, are checked with the scene's law
    (:func:`~sawdrift.scene.adhesion.adhesive_out_of_range`).
    """
    n = normalized(device)
    m_star, (lo, hi) = n["m_star"], M_STAR_RANGE
    if not lo <= m_star <= hi:
        side = "above" if m_star > hi else "below"
        what = ("lower device.frequency, use a smaller or lighter particle, or raise "
                "device.preload" if m_star > hi else
                "raise device.frequency, use a larger or heavier particle, or lower device.preload")
        return (f"the device gives m* = a0 m f^2 / (M g) = {m_star:.3g}, {side} the range "
                f"{lo:g} to {hi:g} the model integrates (a0 = {n['a0_m']:.3g} m, m = "
                f"{n['mass_kg']:.3g} kg, f = {n['frequency_hz']:.4g} Hz, M g = "
                f"{n['weight_n']:.3g} N): {what}")
    if n["amplitude"] > AMPLITUDE_MAX:
        # the wave itself may be fine (its strain and speed bounds hold) while its amplitude is
        # more than 1e9 static compressions under the weight (a 10 nm silica sphere, a0 = 5e-18
        # m, on a 10 nm wave): named by the device's fields, not by the derived drive.amplitude
        return (f"the device gives A* = A_y / a0 = {n['amplitude']:.3g}, above the "
                f"{AMPLITUDE_MAX:g} the model integrates (a0 = {n['a0_m']:.3g} m, the static "
                f"compression under M g = {n['weight_n']:.3g} N): device.amplitude must be below "
                f"{AMPLITUDE_MAX * n['a0_m']:.3g} m, or raise device.preload or use a larger "
                "particle")
    part = device.particle
    # a contact wider than the sphere (1 kPa on a 0.5 mm ball: 3.4 R, run with a warning), a punch
    # pressed in deeper than its radius (1 um on 1 MPa: a0 = 3.4 mm, the same): no contact at all
    size = {"sphere": ("sphere's Hertz contact radius", n["contact_radius_m"], "Hertz"),
            "flat": ("flat punch's compression", n["a0_m"], "elastic")}.get(part.shape)
    if size is not None and size[1] >= float(part.radius):
        return (f"the {size[0]} under its load, {size[1]:.3g} m, exceeds its radius "
                f"{float(part.radius):.3g} m: no {size[2]} contact (the moduli are far too soft "
                "for the load, or the radius too small); check device.particle.youngs_modulus, "
                "device.substrate.youngs_modulus, device.preload")
    return None


def static_compression(shape: str, load: float, e_star: float, radius: float | None = None,
                       half_angle: float | None = None) -> tuple[float, float]:
    """(a0, contact radius) of a profile pressed by ``load`` onto a half-space of modulus E*.

    Solves N(a0) = load with the profile's elastic normal law (SI units throughout), as given
    for all three by Sneddon (1965, Int. J. Eng. Sci. 3, 47-57) for a rigid punch on a half-space
    of modulus E* (two elastic bodies: 1/E* sums both, Johnson 1985 chapter 4):

    * sphere (paraboloid), radius R (Hertz 1882): N = (4/3) E* R^(1/2) delta^(3/2),
      a0 = (9 N^2 / (16 R E*^2))^(1/3), contact radius sqrt(R a0);
    * cone, half-angle alpha between axis and surface: N = (2/pi) E* tan(alpha) delta^2,
      a0 = (pi N / (2 E* tan(alpha)))^(1/2), contact radius (2/pi) a0 tan(alpha);
    * flat-ended cylindrical punch, radius R (Boussinesq 1885): N = 2 E* R delta,
      a0 = N / (2 E* R), contact radius R.
    """
    if shape == "sphere":
        a0 = (9.0 * load**2 / (16.0 * float(radius) * e_star**2)) ** (1.0 / 3.0)
        return a0, math.sqrt(float(radius) * a0)
    if shape == "cone":
        tan_alpha = math.tan(float(half_angle))
        a0 = math.sqrt(math.pi * load / (2.0 * e_star * tan_alpha))
        return a0, 2.0 / math.pi * a0 * tan_alpha
    if shape == "flat":
        return load / (2.0 * e_star * float(radius)), float(radius)
    raise ValueError(f"no dimensional normal law for a {shape!r} profile")


def normalized(device: Device) -> dict[str, float]:
    """The normalized quantities of ``device`` and the scales that convert back."""
    p, s = device.particle, device.substrate
    e_star = 1.0 / ((1 - p.poisson**2) / p.youngs_modulus + (1 - s.poisson**2) / s.youngs_modulus)
    g1 = p.youngs_modulus / (2 * (1 + p.poisson))
    g2 = s.youngs_modulus / (2 * (1 + s.poisson))
    g_star = 1.0 / ((2 - p.poisson) / g1 + (2 - s.poisson) / g2)
    m = p.mass_kg
    # the normal part of gravity and the preload hold the particle; the slope's part is a load
    # (cos 0 = 1 exactly: a level device converts as before)
    weight = m * device.gravity * math.cos(device.incline) + device.preload
    slope = m * device.gravity * math.sin(device.incline)
    a0, contact = static_compression(p.shape, weight, e_star, p.radius, p.half_angle)
    f = device.frequency
    r = device.horizontal_ratio if device.horizontal_ratio is not None else rayleigh_ratio(s.poisson)
    return {
        "m_star": a0 * m * f**2 / weight,
        "amplitude": device.amplitude / a0,
        "theta": e_star / (4.0 * g_star),
        "horizontal_ratio": r,
        "a0_m": a0,
        "frequency_hz": f,
        "mass_kg": m,
        "weight_n": weight,
        "e_star_pa": e_star,
        "g_star_pa": g_star,
        "contact_radius_m": contact,
        "load": (device.load - slope) / weight,
        "load_n": device.load - slope,
        # the DMT pull-off 2 pi R w (JKR's is 3/4 of it): sawdrift.scene.adhesion
        "pulloff_dmt_n": 2.0 * math.pi * float(p.radius or 0.0) * device.adhesion,
    }



#: exponent p of N / (M g) = (delta / a0)^p of each device shape (sawdrift.scene.profiles)
SHAPE_EXPONENT = {"sphere": 1.5, "cone": 2.0, "flat": 1.0}


def device_outputs(device: Device, drift_velocity: float, regime: str,
                   t90_periods: float | None, detach_time: float = math.nan,
                   drift_se: float = math.nan, acceleration: float = math.nan) -> dict[str, Any]:
    """Physical outputs of a run of a device scene (``sawdrift run device.toml --json``): the
    drift speed and a long-time mean's standard error (``drift_se``, x* per period) in m/s, t90
    and an ejection's detach time (t* in periods) in s, a runaway's mean acceleration (x* per
    period squared) in m/s^2, a load's power."""
    norm = normalized(device)
    speed = drift_velocity * norm["a0_m"] * norm["frequency_hz"]
    se = drift_se * norm["a0_m"] * norm["frequency_hz"]
    still = regime in ("stick", "oscillating_slip", "runaway", "ejected")
    moving = not still and math.isfinite(speed) and speed != 0.0
    out = {
        "normalized": {k: norm[k] for k in ("m_star", "amplitude", "theta", "horizontal_ratio", "a0_m")},
        "drift_speed_m_s": speed,
        "drift_speed_se_m_s": se if math.isfinite(se) else None,
        "direction": ("with" if speed > 0.0 else "against") if moving else "none",
        "t90_s": (t90_periods / norm["frequency_hz"]
                  if t90_periods is not None and math.isfinite(t90_periods) else None),
    }
    out["detach_time_s"] = detach_time / norm["frequency_hz"] if math.isfinite(detach_time) else None
    # a0 f^2: the runaway's acceleration was given in x* per period squared only
    out["mean_acceleration_m_s2"] = (acceleration * norm["a0_m"] * norm["frequency_hz"] ** 2
                                     if math.isfinite(acceleration) else None)
    if norm["load_n"] != 0.0:
        # the tangential load (device.load and the slope's pull) and the power the particle
        # delivers against it, -F v (positive while it advances against the load)
        out["load_n"] = norm["load_n"]
        out["power_w"] = -norm["load_n"] * speed
    return out


def explain_device(device: Device, mu: float, warnings: tuple[str, ...] = ()) -> list[str]:
    """Derived quantities with units, time scales, and where the scene leaves the model (its
    ``warnings``, :func:`~sawdrift.scene.validity.device_warnings`)."""
    n = normalized(device)
    f = n["frequency_hz"]
    part = device.particle
    law = {"sphere": "Hertz sphere", "cone": "Sneddon cone", "flat": "Boussinesq flat punch"}
    lines = [
        "device (physical units):",
        (f"  particle mass m = {n['mass_kg']:.4g} kg, load M g = m g + F_ext = {n['weight_n']:.4g} N"
         if device.incline == 0.0 else
         f"  particle mass m = {n['mass_kg']:.4g} kg, normal load M g = m g cos(alpha) + F_ext = "
         f"{n['weight_n']:.4g} N on the incline alpha = {math.degrees(device.incline):.6g} deg"),
        f"  E* = {n['e_star_pa']:.4g} Pa, G* = {n['g_star_pa']:.4g} Pa, theta = E*/(4 G*) = "
        f"{n['theta']:.6g}",
        f"  static compression a0 = {n['a0_m']:.4g} m ({law[part.shape]}), contact radius "
        f"{n['contact_radius_m']:.4g} m" + (" (without adhesion: the scale of x*, a*; the "
                                            "adhesive contact below)" if device.adhesion > 0.0
                                            else ""),
        f"  m* = {n['m_star']:.6g}, A* = {n['amplitude']:.6g}, r = {n['horizontal_ratio']:.6g}, "
        f"orbit {device.orbit}",
        f"  speed scale a0 f = {n['a0_m'] * f:.4g} m/s, time scale 1/f = {1 / f:.4g} s",
    ]
    if n["load_n"] != 0.0:
        lines.append(f"  tangential load F = device.load - m g sin(alpha) = {n['load_n']:.4g} N "
                     f"(along +x): particle.load L = F / (M g) = {n['load']:.6g}"
                     + (f"; the most friction can hold is mu M g = {mu * n['weight_n']:.4g} N"
                        if device.adhesion == 0.0 else ""))
    # small-amplitude normal natural frequency: omega^2 = N*'(1)/m* = p/m* per unit t*
    f_n = math.sqrt(SHAPE_EXPONENT[part.shape] / n["m_star"]) / (2 * math.pi) * f
    lines.append(f"  contact (normal) natural frequency {f_n:.4g} Hz = {f_n / f:.4g} f"
                 + (" without adhesion (with it: below)" if device.adhesion > 0.0 else ""))
    approach = n["m_star"] / mu
    lines.append(f"  expected approach to the steady drift ~ m*/mu = {approach:.4g} periods = "
                 f"{approach / f:.4g} s" if approach >= 1.0 else
                 f"  m*/mu = {approach:.4g}: the horizontal speed follows the surface within a "
                 "period (no slow approach to the steady drift)")
    lines.extend(f"  WARNING: {w}" for w in warnings)
    if n["amplitude"] > 1.0 and device.adhesion == 0.0:
        lines.append("  note: A* > 1: the substrate moves further than the static compression; "
                     "expect contact loss for a heavy particle")
    return lines
