"""Real devices in physical units, converted in this one module to the normalized scene.

A device is a particle (radius, density or mass, Young's modulus, Poisson's ratio) on a substrate
(Young's modulus, Poisson's ratio) carrying a Rayleigh wave (frequency, vertical amplitude,
orbit), with friction, gravity and an optional preload. Values are strings with units parsed by
pint ("9.6 MHz", "10 nm", "0.5 mm", "7.35 mN", "210 GPa", "7850 kg/m^3"); bare numbers are SI.

Conversion (docs/physics.md, "Physical units and two materials")::

    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2          1/G* = (2 - nu1)/G1 + (2 - nu2)/G2
    G_i = E_i / (2 (1 + nu_i))                       M g = m g + F_ext
    a0 = (9 (M g)^2 / (16 R E*^2))^(1/3)             (Hertz: the compression under M g)
    m* = a0 m f^2 / (M g)      A* = A_y / a0      theta = E* / (4 G*)      r = r(nu2) by default

theta belongs to the contact (two materials), r to the substrate's wave. A normalized speed
x*' is x*' a0 f in m/s, a normalized time t* is t*/f in s. x points along the propagation
direction; the device default orbit is the retrograde one of a Rayleigh wave on an isotropic
half-space (the mirror of eq. 1 as printed).
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Annotated, Any, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, model_validator

from ..errors import SceneError

_FROZEN = ConfigDict(frozen=True, extra="forbid")

#: expected dimension of each kind of quantity, with an example for error messages
_UNITS = {
    "length": ("[length]", "m", "'10 nm'"),
    "frequency": ("1 / [time]", "Hz", "'9.6 MHz'"),
    "force": ("[mass] * [length] / [time] ** 2", "N", "'7.35 mN'"),
    "pressure": ("[mass] / [length] / [time] ** 2", "Pa", "'210 GPa'"),
    "density": ("[mass] / [length] ** 3", "kg/m^3", "'7850 kg/m^3'"),
    "mass": ("[mass]", "kg", "'4.1 mg'"),
    "acceleration": ("[length] / [time] ** 2", "m/s^2", "'9.81 m/s^2'"),
}


@lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry()


def to_si(value: Any, kind: str) -> float:
    """The SI magnitude of ``value`` (a number, or a string with units) of dimension ``kind``.

    Raises ValueError with a plain message when the string is not a quantity or has another
    dimension.
    """
    dims, unit, example = _UNITS[kind]
    if isinstance(value, bool):
        raise ValueError(f"is not a {kind}: give one in {unit}, e.g. {example}")
    if isinstance(value, (int, float)):
        out = float(value)
    else:
        ureg = _registry()
        try:
            q = ureg.Quantity(str(value).strip())
        except Exception:  # noqa: BLE001 - pint raises several kinds for a bad string
            raise ValueError(f"is not a quantity: give a {kind} in {unit}, e.g. {example}") from None
        if q.dimensionless:
            out = float(q.magnitude)
        else:
            if q.dimensionality != ureg.Quantity(1, unit).dimensionality:
                raise ValueError(f"is not a {kind} (wrong dimension): give one in {unit}, "
                                 f"e.g. {example}")
            out = float(q.to(unit).magnitude)
    if not math.isfinite(out):
        raise ValueError("is not finite")
    return out


def _quantity(kind: str, positive: bool = True, allow_zero: bool = False):
    def check(value: Any) -> float:
        out = to_si(value, kind)
        if positive and (out < 0.0 or (out == 0.0 and not allow_zero)):
            bound = ">= 0" if allow_zero else "> 0"
            raise ValueError(f"is not {bound}: a {kind} in {_UNITS[kind][1]} must be {bound}")
        return out

    return BeforeValidator(check)


#: the kind of quantity of each device field, for messages about a missing one
_FIELD_KIND = {"frequency": "frequency", "amplitude": "length", "radius": "length",
               "youngs_modulus": "pressure", "density": "density", "mass": "mass",
               "gravity": "acceleration", "preload": "force"}

Length = Annotated[float, _quantity("length")]
Pressure = Annotated[float, _quantity("pressure")]
Poisson = Annotated[float, Field(gt=-1.0, lt=0.5)]


class DeviceParticle(BaseModel):
    """The particle of a device: a sphere of radius R, density or mass, elastic constants."""

    model_config = _FROZEN

    radius: Length = Field(description="sphere radius R")
    density: Annotated[float, _quantity("density")] | None = Field(None, description="or mass")
    mass: Annotated[float, _quantity("mass")] | None = Field(None, description="or density")
    youngs_modulus: Pressure = Field(description="E1")
    poisson: Poisson = Field(description="nu1, in (-1, 0.5)")

    @model_validator(mode="after")
    def _one_of_density_or_mass(self) -> DeviceParticle:
        if (self.density is None) == (self.mass is None):
            raise ValueError("give exactly one of density (kg/m^3) or mass (kg)")
        return self

    @property
    def mass_kg(self) -> float:
        """m: the given mass, or density x 4/3 pi R^3."""
        if self.mass is not None:
            return self.mass
        return float(self.density) * 4.0 / 3.0 * math.pi * self.radius**3


class DeviceSubstrate(BaseModel):
    """The substrate: elastic constants (and so the Rayleigh ratio r(nu2) by default)."""

    model_config = _FROZEN

    youngs_modulus: Pressure = Field(description="E2")
    poisson: Poisson = Field(description="nu2, in (-1, 0.5)")


class Device(BaseModel):
    """A device in physical units (the ``[device]`` table of a scene file)."""

    model_config = _FROZEN

    frequency: Annotated[float, _quantity("frequency")] = Field(description="wave frequency f")
    amplitude: Annotated[float, _quantity("length", allow_zero=True)] = Field(
        description="vertical surface displacement amplitude A_y")
    orbit: Literal["prograde", "retrograde"] = Field(
        "retrograde", description="retrograde: a Rayleigh wave on an isotropic half-space")
    horizontal_ratio: Annotated[float, Field(ge=0.0, le=100.0)] | None = Field(
        None, description="r; default r(substrate poisson)")
    gravity: Annotated[float, _quantity("acceleration", allow_zero=True)] = Field(
        9.81, description="g; 0 allowed with a preload")
    preload: Annotated[float, _quantity("force", allow_zero=True)] = Field(
        0.0, description="external normal force F_ext")
    friction: Annotated[float, Field(gt=0.0, le=10.0)] = Field(description="mu")
    particle: DeviceParticle
    substrate: DeviceSubstrate

    @model_validator(mode="after")
    def _held_down(self) -> Device:
        if self.gravity == 0.0 and self.preload == 0.0:
            raise ValueError("gravity = 0 needs a preload > 0: nothing would hold the particle")
        return self


def normalized(device: Device) -> dict[str, float]:
    """The normalized quantities of ``device`` and the scales that convert back."""
    from .rayleigh import rayleigh_ratio

    p, s = device.particle, device.substrate
    e_star = 1.0 / ((1 - p.poisson**2) / p.youngs_modulus + (1 - s.poisson**2) / s.youngs_modulus)
    g1 = p.youngs_modulus / (2 * (1 + p.poisson))
    g2 = s.youngs_modulus / (2 * (1 + s.poisson))
    g_star = 1.0 / ((2 - p.poisson) / g1 + (2 - s.poisson) / g2)
    m = p.mass_kg
    weight = m * device.gravity + device.preload
    a0 = (9.0 * weight**2 / (16.0 * p.radius * e_star**2)) ** (1.0 / 3.0)
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
        "contact_radius_m": math.sqrt(p.radius * a0),
    }


def apply_device(data: dict[str, Any]) -> dict[str, Any]:
    """Fill the normalized fields of a scene dict from its ``device`` block (if any).

    The device is the source of truth: m*, A*, theta, mu, r and the orbit are derived from it,
    and nu is the substrate's. Raises SceneError naming the device field on bad input.
    """
    block = data.get("device")
    if block is None:
        return data
    from pydantic import ValidationError

    from .schema import format_validation_error, set_dotted

    try:
        device = block if isinstance(block, Device) else Device.model_validate(block)
    except ValidationError as exc:
        line = format_validation_error(exc)
        leaf = line.split(" ")[0].rsplit(".", 1)[-1]
        if line.endswith("is required") and leaf in _FIELD_KIND:
            _, unit, example = _UNITS[_FIELD_KIND[leaf]]
            line += f": a {_FIELD_KIND[leaf]} in {unit}, e.g. {example}"
        raise SceneError(f"device.{line}" if not line.startswith("scene:") else line) from None
    norm = normalized(device)
    out = dict(data)
    out["device"] = device.model_dump()
    set_dotted(out, "particle.m_star", norm["m_star"])
    set_dotted(out, "drive.amplitude", norm["amplitude"])
    set_dotted(out, "drive.horizontal_ratio", norm["horizontal_ratio"])
    set_dotted(out, "drive.orbit", device.orbit)
    set_dotted(out, "material.mu", device.friction)
    set_dotted(out, "material.nu", device.substrate.poisson)
    set_dotted(out, "material.theta", norm["theta"])
    return out


def device_outputs(device: Device, drift_velocity: float, regime: str,
                   t90_periods: float | None) -> dict[str, Any]:
    """Physical outputs of a run of a device scene (see ``sawdrift run device.toml --json``)."""
    norm = normalized(device)
    speed = drift_velocity * norm["a0_m"] * norm["frequency_hz"]
    moving = regime not in ("stick", "oscillating_slip") and speed != 0.0
    return {
        "normalized": {k: norm[k] for k in ("m_star", "amplitude", "theta", "horizontal_ratio", "a0_m")},
        "drift_speed_m_s": speed,
        "direction": ("with" if speed > 0.0 else "against") if moving else "none",
        "t90_s": (t90_periods / norm["frequency_hz"]
                  if t90_periods is not None and math.isfinite(t90_periods) else None),
    }


def explain_device(device: Device, mu: float) -> list[str]:
    """Derived quantities with units, time scales, and where the scene leaves the model."""
    n = normalized(device)
    f = n["frequency_hz"]
    lines = [
        "device (physical units):",
        f"  particle mass m = {n['mass_kg']:.4g} kg, load M g = m g + F_ext = {n['weight_n']:.4g} N",
        f"  E* = {n['e_star_pa']:.4g} Pa, G* = {n['g_star_pa']:.4g} Pa, theta = E*/(4 G*) = "
        f"{n['theta']:.6g}",
        f"  static compression a0 = {n['a0_m']:.4g} m, contact radius sqrt(R a0) = "
        f"{n['contact_radius_m']:.4g} m",
        f"  m* = {n['m_star']:.6g}, A* = {n['amplitude']:.6g}, r = {n['horizontal_ratio']:.6g}, "
        f"orbit {device.orbit}",
        f"  speed scale a0 f = {n['a0_m'] * f:.4g} m/s, time scale 1/f = {1 / f:.4g} s",
    ]
    # small-amplitude normal natural frequency: omega^2 = N*'(1)/m* = 1.5/m* per unit t*
    f_n = math.sqrt(1.5 / n["m_star"]) / (2 * math.pi) * f
    lines.append(f"  contact (normal) natural frequency {f_n:.4g} Hz = {f_n / f:.4g} f")
    approach = n["m_star"] / mu
    lines.append(f"  expected approach to the steady drift ~ m*/mu = {approach:.4g} periods = "
                 f"{approach / f:.4g} s")
    if n["a0_m"] < 1e-9:
        lines.append("  WARNING: a0 < 1 nm: adhesion and roughness, not gravity and preload, then "
                     "set the contact; the model's assumptions do not hold")
    if n["contact_radius_m"] > 0.1 * device.particle.radius:
        lines.append("  WARNING: contact radius above 0.1 R: beyond Hertz's small-strain theory")
    if n["amplitude"] > 1.0:
        lines.append("  note: A* > 1: the substrate moves further than the static compression; "
                     "expect contact loss for a heavy particle")
    return lines
