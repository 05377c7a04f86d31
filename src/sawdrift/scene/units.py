"""Device quantities: units (parsed by pint) and the physical range of each device field.

A device value is a number (SI; an angle in radians) or a string with units ("9.6 MHz",
"10 nm", "7850 kg/m^3"), converted by :func:`to_si`; :data:`RANGES` bounds each field
(docs/devices.md, "Ranges"). The device itself is :mod:`sawdrift.scene.device`.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import Any

#: expected dimension of each kind of quantity, with an example for error messages
UNITS = {
    "length": ("[length]", "m", "'10 nm'"),
    "frequency": ("1 / [time]", "Hz", "'9.6 MHz'"),
    "force": ("[mass] * [length] / [time] ** 2", "N", "'7.35 mN'"),
    "pressure": ("[mass] / [length] / [time] ** 2", "Pa", "'210 GPa'"),
    "density": ("[mass] / [length] ** 3", "kg/m^3", "'7850 kg/m^3'"),
    "mass": ("[mass]", "kg", "'4.1 mg'"),
    "acceleration": ("[length] / [time] ** 2", "m/s^2", "'9.81 m/s^2'"),
    "angle": ("", "rad", "'80 deg'"),
    "surface energy": ("[mass] / [time] ** 2", "J/m^2", "'0.05 J/m^2'"),
}

#: the kind of quantity of each device field, for messages about a missing one
FIELD_KIND = {"frequency": "frequency", "amplitude": "length", "radius": "length",
              "youngs_modulus": "pressure", "density": "density", "mass": "mass",
              "gravity": "acceleration", "preload": "force", "half_angle": "angle",
              "load": "force", "incline": "angle", "wavelength": "length",
              "adhesion": "surface energy"}


@lru_cache(maxsize=1)
def _registry():
    """pint's unit registry, built on the first unit string of a process and kept.

    Parsing pint's definitions takes about 1 s; pint keeps them parsed in its cache folder
    (``cache_folder=":auto:"``, the user's cache directory), which makes the next process's
    registry about ten times quicker. A cache that cannot be read or written (a read-only home,
    another process writing it) falls back to parsing.
    """
    import pint

    try:
        return pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # noqa: BLE001 - any failure of the cache: parse the definitions instead
        return pint.UnitRegistry()


#: a device value written as a string: one number (no thousands separator, no decimal comma),
#: then, optionally, one unit expression
_NUMBER = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$")

#: digits a unit expression may hold: exponents ("kg/m^3", "m s**-2")
_EXPONENT = re.compile(r"(?:\^|\*\*)\s*\(?\s*[+-]?\d+(?:\.\d+)?\s*\)?")


#: superscript digits and minus, and their plain characters
_SUPERSCRIPT = re.compile("[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+")
_PLAIN = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")


#: units of radioactive activity, per second like a frequency but no wave's ("9.6e6 Bq" ran
#: as 9.6 MHz)
_ACTIVITIES = {"becquerel", "curie", "rutherford"}

#: dimensionless units that are no angle (pint would take them for radians)
_NOT_ANGLES = {"percent", "permille", "ppm", "dimensionless"}


def _split(text: str) -> tuple[float, str] | None:
    """(number, unit expression) of a device value written as a string, or None where it is not
    one number followed by units: pint would evaluate the string as an expression ("9,6 MHz" as
    96 MHz, "10 nm 5" as 50 nm), so anything else is refused before it gets there."""
    # a written exponent ("kg/m³", "m/s²", "s⁻¹") as pint reads one: ^3, ^2, ^-1 (they were
    # refused as not a quantity, while "µm" was taken)
    text = _SUPERSCRIPT.sub(lambda e: "^" + e.group(0).translate(_PLAIN), text)
    m = _NUMBER.fullmatch(text)
    if m is None:
        return None
    unit = m.group(2)
    # a reciprocal unit ("100 1/s", "100 /s"): the 1 is no number of the expression (both were
    # refused as "not a quantity" while "100 s^-1" was taken)
    reciprocal = ""
    for head in ("1/", "/"):
        if unit.startswith(head):
            reciprocal, unit = "1/", unit[len(head):].lstrip()
            if not unit:
                return None
            break
    if unit and (not (unit[0].isalpha() or unit[0] in "µμ°%") or unit[0] in "eE" and (
            len(unit) == 1 or not unit[1].isalpha())):
        return None  # "10e nm": a malformed exponent, not the elementary charge
    if any(ch.isdigit() for ch in _EXPONENT.sub("", unit)):
        return None
    return float(m.group(1)), reciprocal + unit


def to_si(value: Any, kind: str) -> float:
    """The SI magnitude of ``value`` (a number, or a string with units) of dimension ``kind``.

    An angle is returned in radians (a bare number is taken as radians). A frequency given as an
    angular rate ("628 rad/s", "6000 rpm") is its cycles per second, omega / 2 pi (pint counts
    the radian as dimensionless and would take 628 rad/s for 628 Hz). Raises ValueError with a
    plain message when the string is not one number with units, or has another dimension.
    """
    _, unit, example = UNITS[kind]
    if isinstance(value, bool):
        raise ValueError(f"is not {_article(kind)} {kind}: give one in {unit}, e.g. {example}")
    if isinstance(value, (int, float)):
        out = float(value)
    else:
        out = _string_si(str(value), kind)
    if not math.isfinite(out):
        raise ValueError(f"is not finite: give {_article(kind)} {kind} in {unit}, e.g. {example}")
    return out


def _article(kind: str) -> str:
    """'a' or 'an' before the name of a kind of quantity."""
    return "an" if kind[0] in "aeiou" else "a"


def _string_si(text: str, kind: str) -> float:
    """:func:`to_si` of a string."""
    _, unit, example = UNITS[kind]
    parts = _split(text)
    if parts is None:
        raise ValueError(f"is not a quantity: give one number and its unit, e.g. {example} "
                         f"({_article(kind)} {kind} in {unit})")
    number, units = parts
    if not units:
        return number  # a bare number written as a string: SI, as a bare number
    ureg = _registry()
    try:
        q = ureg.Quantity(number, units)
    except Exception:  # noqa: BLE001 - pint raises several kinds for a bad unit
        raise ValueError(f"has no unit '{units}' that this knows: give {_article(kind)} {kind} "
                         f"in {unit}, e.g. {example}") from None
    radians = dict(q.to_base_units().unit_items()).get("radian", 0)
    angular = radians != 0
    wrong = f"is not {_article(kind)} {kind} (wrong dimension): give one in {unit}, e.g. {example}"
    if kind == "angle":
        if not q.dimensionless or _roots(ureg, q) & _NOT_ANGLES:
            # a grade in percent is no angle: "2 %" was read as 0.02 rad (a 50 % grade is
            # 26.6 deg, not 28.6)
            raise ValueError(f"is not an angle: give one in deg or rad, e.g. {example} (a grade "
                             "g in % is the angle atan(g / 100))")
        return _canonical(float(q.to("radian").magnitude))
    if q.dimensionality != ureg.Quantity(1, unit).dimensionality or q.dimensionless:
        raise ValueError(wrong)
    if kind == "frequency" and _roots(ureg, q) & _ACTIVITIES:
        raise ValueError(f"is a radioactive activity, not a frequency: give one in {unit}, "
                         f"e.g. {example}")
    if angular:
        if kind != "frequency" or radians < 0:
            # per radian ("9.6 MHz/rad") is no angular rate: it was divided by 2 pi
            raise ValueError(wrong)
        return _canonical(float(q.to("turn / second").magnitude))  # omega / 2 pi
    return _canonical(float(q.to(unit).magnitude))


def _roots(ureg, q) -> set[str]:
    """The unit names of quantity ``q`` without their prefixes ("9.6 MBq": becquerel; the
    prefixed name megabecquerel passed a check of names)."""
    return {root for name, _ in q.unit_items() for _, root, _ in ureg.parse_unit_name(name)}


def _canonical(value: float) -> float:
    """``value`` to 15 significant figures: a unit's conversion factor leaves a last-bit
    remainder ("5 um" gave 4.9999999999999996e-06 where "5e-6 m" gives 5e-06), and an irregular
    motion's mean then depended on how its radius was written (-6.06e-5 against -6.14e-5 m/s)."""
    return float(f"{value:.15g}")


#: The allowed range of each device quantity, in SI units (an angle in radians): the lowest and
#: highest value, the range as the user reads it, and what it spans. The ranges hold every real
#: device, from a shaker's grain to a nanoparticle on a hypersonic surface wave, with room to
#: spare; a value outside one is a unit left out or mistyped (``radius = "1 parsec"``).
RANGES: dict[str, tuple[float, float, str, str]] = {
    "frequency": (1.0, 1e11, "1 Hz to 100 GHz",
                  "from a shaken plate to a hypersonic surface wave"),
    "amplitude": (0.0, 1e-2, "0 to 1 cm",
                  "from a surface wave's picometres to a vibratory feeder's millimetres"),
    "wavelength": (1e-8, 100.0, "10 nm to 100 m",
                   "from a hypersonic surface wave to a flexural wave on a large plate"),
    "gravity": (0.0, 1e4, "0 to 1e4 m/s^2", "from free fall to a strong centrifuge at 1000 g"),
    "preload": (0.0, 1e3, "0 to 1 kN", "a slider's spring holds it with mN to N"),
    "load": (-1e3, 1e3, "-1 kN to 1 kN", "a motor's load is of mN to N"),
    "adhesion": (0.0, 10.0, "0 to 10 J/m^2",
                 "the work of adhesion of clean solids is below a few J/m^2"),
    "friction": (1e-3, 10.0, "0.001 to 10",
                 "from a superlubric contact to a sticky elastomer"),
    "incline": (-math.radians(85.0), math.radians(85.0), "-85 deg to 85 deg",
                "steeper, the slope's pull exceeds 11 times the normal load"),
    "particle.radius": (1e-9, 0.1, "1 nm to 10 cm", "from a nanoparticle to a large ball"),
    "particle.half_angle": (math.radians(1.0), math.radians(89.9), "1 deg to 89.9 deg",
                            "the angle between the cone's axis and its surface"),
    "particle.density": (1.0, 3e4, "1 kg/m^3 to 3e4 kg/m^3",
                         "from an aerogel to osmium, the densest element at 22590 kg/m^3"),
    "particle.mass": (1e-24, 100.0, "1e-24 kg to 100 kg",
                      "from a nanoparticle to a heavy slider"),
    "particle.youngs_modulus": (1e3, 2e12, "1 kPa to 2 TPa",
                                "from a soft gel to diamond, about 1.1 TPa"),
    "substrate.youngs_modulus": (1e3, 2e12, "1 kPa to 2 TPa",
                                 "from a soft gel to diamond, about 1.1 TPa"),
    "substrate.density": (1.0, 3e4, "1 kg/m^3 to 3e4 kg/m^3",
                          "from an aerogel to osmium, the densest element at 22590 kg/m^3"),
}

#: the hint for a length given as a bare number (SI: metres)
BARE_LENGTH = "a bare number is in m: write the unit, e.g. '10 nm'"


def in_range(field: str, out: float, unit: str, given: Any) -> float:
    """``out`` (SI, of the value ``given``) if inside :data:`RANGES` of ``field``; else a
    ValueError naming the range (and, for a string with units, the value in SI)."""
    lo, hi, text, why = RANGES[field]
    if lo <= out <= hi:
        return out
    bare = not isinstance(given, str)
    shown = "" if bare or unit in ("rad", "") else f"{out:.4g} {unit}, "
    hint = f"; {BARE_LENGTH}" if bare and unit == "m" else ""
    raise ValueError(f"is {shown}outside the allowed range {text} ({why}{hint})")


def friction_value(value: Any) -> float:
    """device.friction: a plain number (or one written as a string: a ``--set`` value; in a
    scene file that is refused, :mod:`sawdrift.scene.quoted`), inside its range."""
    if isinstance(value, str):  # a number written as a string, as the other plain numbers take
        try:
            value = float(value.strip())
        except ValueError:
            raise ValueError("is not a number: give the friction coefficient, e.g. 0.2") from None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError("is not a number: give the friction coefficient, e.g. 0.2")
    if not math.isfinite(value):  # inf and nan said "is not > 0"
        raise ValueError(f"is not finite: the friction coefficient, in {RANGES['friction'][2]}")
    if value <= 0.0:
        raise ValueError("is not > 0: the friction coefficient, e.g. 0.2")
    return in_range("friction", float(value), "", value)


def half_angle_value(value: Any) -> float:
    """device.particle.half_angle: an angle in (0, 90) deg (a bare number in radians)."""
    out = to_si(value, "angle")
    if not 0.0 < out < 0.5 * math.pi:
        raise ValueError("is outside (0, 90) deg: the angle between the cone's axis and its "
                         "surface, e.g. '80 deg' (a bare number is in radians)")
    return in_range("particle.half_angle", out, "rad", value)


def field_si(name: str, value: Any) -> float:
    """The SI value of the device field ``name`` (dotted, ``device.particle.radius``) given as
    ``value`` (a number, or a string with units), checked against its :data:`RANGES` entry if it
    has one (a sweep axis's or a threshold study's value, before any run). ValueError as
    :func:`to_si`, or naming the allowed range."""
    field = name.removeprefix("device.")
    kind = FIELD_KIND.get(field.rsplit(".", 1)[-1])
    out = to_si(value, kind) if kind is not None else float(value)
    if field in RANGES:
        return in_range(field, out, UNITS[kind][1] if kind is not None else "", value)
    return out
