"""The one rule for a scene with a ``[device]`` table (the overrides of scene fields follow it).

A device (``sawdrift.scene.device``) is the source of truth for the normalized fields it
derives: ``particle.m_star``, ``particle.profile``, ``particle.preload``, ``particle.load``,
``drive.amplitude``, ``drive.horizontal_ratio``, ``drive.orbit``, ``material.mu``, ``material.nu``
and ``material.theta`` (:data:`DERIVED`). On a device scene:

* device fields override in device units (``device.amplitude = "5 nm"``, a sweep axis over
  ``device.preload``): every derived field is computed again from the device;
* a derived field given with another value than the device's is an error, one line naming the
  device field to set instead; the same value (a saved scene written out in full) is accepted;
* a device scene dumps (``model_dump``, TOML, JSON) without its derived fields, so a copy with
  new device fields never carries stale ones.

Every path applies this rule through :func:`apply_device`: :func:`sawdrift.scene.build_scene`,
``Scene(**data)`` and ``Scene.model_validate`` (a before-validator), ``Scene.with_updates``, and
:func:`sawdrift.scene.apply_overrides` (beside the Scene, in :mod:`sawdrift.scene.schema`, whose
fields it checks), the function the command line and the sweeps call to set dotted fields.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from typing import Any

from pydantic import BaseModel, ValidationError

from ..errors import SceneError
from .adhesion import adhesive_out_of_range, load_bound, normalized_adhesion
from .device import FIELD_KIND, UNITS, Device, derived_out_of_range, normalized
from .dotted import get_dotted, set_dotted
from .messages import format_validation_error
from .profiles import Profile

#: Each scene field a device derives, and the device fields that set it.
DERIVED: dict[str, str] = {
    "particle.m_star": "device.particle (radius, density or mass), device.frequency, "
                       "device.gravity or device.preload",
    "particle.profile": "device.particle.shape (sphere, cone with device.particle.half_angle, "
                        "flat)",
    "particle.preload": "device.preload (it enters m* through M g = m g + F_ext)",
    "particle.load": "device.load (a force, e.g. '1 mN') or device.incline (e.g. '5 deg')",
    "drive.amplitude": "device.amplitude",
    "drive.horizontal_ratio": "device.horizontal_ratio",
    "drive.orbit": "device.orbit",
    "material.mu": "device.friction",
    "material.nu": "device.substrate.poisson",
    "material.theta": "device.particle and device.substrate youngs_modulus and poisson",
    "material.adhesion": "device.adhesion (the work of adhesion, e.g. '0.05 J/m^2') with "
                         "effects.adhesion",
}


class DerivedFieldError(SceneError):
    """A derived field given another value than its device derives (one line, see the module).

    Carries the ``field``, the ``value`` given, the ``derived`` value and the device's static
    compression ``a0_m`` (in m), so that the command line can name its own option.
    """

    def __init__(self, message: str, field: str, value: Any, derived: Any, a0_m: float,
                 instead: str | None = None) -> None:
        super().__init__(message)
        self.field, self.value, self.derived, self.a0_m = field, value, derived, a0_m
        #: the device setting that gives the value asked for (:func:`instead_for`), or None
        self.instead = instead


#: The sections of a scene that hold derived fields.
_SECTIONS = ("particle", "drive", "material")


def derived_values(device: Device, adhesion: str = "none") -> dict[str, Any]:
    """The value of every :data:`DERIVED` field for ``device`` (docs/devices.md); ``adhesion``
    is the scene's ``effects.adhesion`` (the pull-off force depends on the law)."""
    norm = normalized(device)
    return {
        "particle.m_star": norm["m_star"],
        "particle.profile": {"shape": device.particle.shape},
        "particle.preload": 0.0,
        "particle.load": norm["load"],
        "drive.amplitude": norm["amplitude"],
        "drive.horizontal_ratio": norm["horizontal_ratio"],
        "drive.orbit": device.orbit,
        "material.mu": device.friction,
        "material.nu": device.substrate.poisson,
        "material.theta": norm["theta"],
        "material.adhesion": normalized_adhesion(device, adhesion),
    }


def _same(given: Any, derived: Any, field: str) -> bool:
    if field == "particle.profile":
        try:
            return Profile.model_validate(given) == Profile.model_validate(derived)
        except (ValidationError, TypeError):
            return False
    if isinstance(derived, float):
        # the value as shown (:func:`_shown`, six figures: in an error line, in a saved scene's
        # comment) repeats the device's own
        return (isinstance(given, (int, float)) and not isinstance(given, bool)
                and _as_shown(float(given), derived))
    return given == derived


def _as_shown(given: float, derived: float) -> bool:
    """Whether ``given`` is ``derived`` to the six figures it is shown with (:func:`_shown`):
    within half a unit of its sixth figure. 929.27 is not 929.267, nor 6.7708 6.77078 (a
    relative 5e-6 took both)."""
    if given == derived:
        return True
    if derived == 0.0 or not math.isfinite(derived):
        return False
    half_unit = 0.5 * 10.0 ** (math.floor(math.log10(abs(derived))) - 5)
    return abs(given - derived) <= half_unit * (1.0 + 1e-9)


def _shown(value: Any) -> str:
    if isinstance(value, dict) and set(value) == {"shape"}:
        return f"shape {value['shape']!r}"
    return f"{value:.6g}" if isinstance(value, float) else repr(value)


def derived_error(field: str, value: Any, derived: Any, a0_m: float = math.nan,
                  device: Device | None = None) -> DerivedFieldError:
    """The one-line error for a derived ``field`` given as ``value`` on a device scene."""
    given = value.model_dump(exclude_none=True) if isinstance(value, BaseModel) else value
    instead = instead_for(field, given, device, derived) if device is not None else None
    return DerivedFieldError(f"{field} = {_shown(given)}: a device scene derives {field} from its "
                             f"[device] table (here {_shown(derived)}); set {DERIVED[field]} "
                             "instead", field, given, derived, a0_m, instead)


def instead_for(field: str, value: Any, device: Device, derived: Any = None) -> str | None:
    """The device setting (``--set`` form) that gives the derived ``field`` the ``value`` asked
    for: the friction for mu, A* a0 for the amplitude, the load L M g (plus the slope's pull)
    for the load, the work of adhesion w F*_pull / F*_pull(w) for the pull-off (linear in w;
    ``derived``: the device's own F*_pull), the particle's radius for m* (:func:`_radius_for`);
    None for the others (theta: several device fields enter; m* of a cone, whose mass and angle
    set it). The examples that a device field sets m* or the pull-off gave the file's own value,
    which is not the one asked for."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        return None
    simple = {"material.mu": "device.friction", "material.nu": "device.substrate.poisson",
              "drive.horizontal_ratio": "device.horizontal_ratio", "drive.orbit": "device.orbit"}
    if field in simple:
        return f"{simple[field]}={value:g}" if not isinstance(value, str) else \
            f"{simple[field]}={value}"
    if isinstance(value, str):
        return None
    norm = normalized(device)
    # six figures, as a derived value is shown and repeated (:func:`_as_shown`): four gave
    # device.amplitude="10 nm", the file's own value, for an A* of 0.5516 against its 0.551578
    if field == "drive.amplitude":
        return f'device.amplitude="{value * norm["a0_m"] * 1e9:.6g} nm"'
    if field == "particle.load":
        # a load beyond the most any adhesive law lets the device take is no hint (L = 3e7 named
        # a device.load that was itself refused)
        most = load_bound(normalized_adhesion(device, "dmt") if device.adhesion > 0.0 else 0.0)
        if abs(value) > most:
            return None
        # L = (F - m g sin(alpha)) / (m g cos(alpha) + F_ext): F = L (M g) + the slope's pull
        force = value * norm["weight_n"] + (device.load - norm["load_n"])
        return f'device.load="{force * 1e3:.6g} mN"'
    if field == "material.adhesion" and isinstance(derived, float) and derived > 0.0 and value > 0:
        return f'device.adhesion="{device.adhesion * value / derived:.6g} J/m^2"'
    if field == "particle.m_star" and value > 0:
        radius = _radius_for(value, device)
        if radius is not None:
            scale, unit = next((s, u) for s, u in ((1e-3, "mm"), (1e-6, "um"), (1e-9, "nm"))
                               if radius >= s or u == "nm")
            return f'device.particle.radius="{radius / scale:.6g} {unit}"'
    return None


def _radius_for(m_star: float, device: Device) -> float | None:
    """The particle radius (m) at which ``device`` has the mass ratio ``m_star``, the rest of it
    as it is (its density or its mass, the preload, the frequency), within the radii a device
    allows (1 nm to 10 cm); None for a cone or where no radius there gives it."""
    from scipy.optimize import brentq

    if device.particle.radius is None:
        return None

    def gap(log_r: float) -> float:
        particle = device.particle.model_copy(update={"radius": math.exp(log_r)})
        return math.log(normalized(device.model_copy(update={"particle": particle}))["m_star"]
                        / m_star)

    lo, hi = math.log(1e-9), math.log(0.1)
    try:
        if gap(lo) * gap(hi) > 0.0:
            return None
        radius = math.exp(brentq(gap, lo, hi, xtol=1e-12))
    except (ValueError, ZeroDivisionError, OverflowError):
        return None
    # a radius the device would then refuse is no hint (m* 1e-11 on the motor named 2.9 nm, a
    # contact 18.7 times wider than the sphere)
    particle = device.particle.model_copy(update={"radius": radius})
    return None if derived_out_of_range(device.model_copy(update={"particle": particle})) \
        else radius


def plain_section(value: Any) -> Any:
    """A deep copy of a scene section as plain dicts (a model gives the fields it was given)."""
    if isinstance(value, BaseModel):
        out = value.model_dump(exclude_unset=True)
        if "kind" in type(value).model_fields:
            out["kind"] = value.kind  # type: ignore[attr-defined]
        return out
    return copy.deepcopy(value)


def validate_device(block: Any) -> Device:
    """The validated Device of a ``[device]`` table; bad input is one line naming the field."""
    if isinstance(block, Device):
        return block
    if not isinstance(block, Mapping):  # it was "scene: Input should be a valid dictionary ..."
        raise SceneError(f"device = {block!r}: the device is a table of fields ([device], with "
                         "frequency, amplitude, particle, substrate)")
    try:
        return Device.model_validate(block)
    except ValidationError as exc:
        line = format_validation_error(exc)
        leaf = line.split(" ")[0].rsplit(".", 1)[-1]
        if line.endswith("is required") and leaf in FIELD_KIND:
            _, unit, example = UNITS[FIELD_KIND[leaf]]
            line += f": a {FIELD_KIND[leaf]} in {unit}, e.g. {example}"
        raise SceneError(f"device.{line}" if not line.startswith("scene:") else line) from None


def apply_device(data: Mapping[str, Any]) -> dict[str, Any]:
    """Fill the derived fields of a scene dict from its ``device`` table (if it has one).

    Returns a new dict (``data`` is not changed); without a device, ``data`` itself.

    Raises
    ------
    SceneError
        One line: a bad device field (naming it and its unit), a drive other than the wave, or
        a derived field given with another value than the device's (naming the device field to
        set instead).
    """
    block = data.get("device")
    if block is None:
        return data  # type: ignore[return-value]
    device = validate_device(block)
    out = {key: (plain_section(value) if key in _SECTIONS else value) for key, value in data.items()}
    for section in _SECTIONS:
        if out.get(section) is None:
            out[section] = {}
        elif not isinstance(out[section], dict):
            raise SceneError(f"{section} must be a table of fields, not {out[section]!r}")
    kind = out["drive"].get("kind", "wave")
    if kind != "wave":
        raise SceneError(f"drive.kind = {kind!r}: a device scene is driven by its wave; remove "
                         "the [device] table for a prescribed or impact drive")
    effects = plain_section(out.get("effects")) or {}
    law = effects.get("adhesion", "none") if isinstance(effects, dict) else "none"
    if device.adhesion > 0.0 and law == "none":
        raise SceneError(f"device.adhesion = {device.adhesion:g} J/m^2 needs effects.adhesion = "
                         "'dmt' or 'jkr'")
    problem = adhesive_out_of_range(device, law)
    if problem is not None:
        raise SceneError(problem)
    values = derived_values(device, law)
    for field, derived in values.items():
        given = get_dotted(out, field)
        if given is not None and not _same(given, derived, field):
            raise derived_error(field, given, derived, normalized(device)["a0_m"], device)
    out["device"] = device.model_dump()
    for field, derived in values.items():
        set_dotted(out, field, copy.deepcopy(derived))
    return out


def strip_derived(data: dict[str, Any]) -> dict[str, Any]:
    """Remove every derived field from a device scene's dict, in place; returns ``data``."""
    for field in DERIVED:
        section, _, leaf = field.partition(".")
        node = data.get(section)
        if isinstance(node, dict):
            node.pop(leaf, None)
    return data


#: device fields of which a particle gives one: setting one drops the other
EITHER_OR: dict[str, str] = {"device.particle.mass": "device.particle.density",
                             "device.particle.density": "device.particle.mass"}


def drop_replaced(data: dict[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    """Remove from a scene dict, in place, the device field an override replaces (a mass set on
    a particle given by its density, or the other way round: :data:`EITHER_OR`), unless the
    overrides set both; returns ``data``."""
    for key, other in EITHER_OR.items():
        if overrides.get(key) is not None and overrides.get(other) is None:
            section, _, leaf = other.rpartition(".")
            node = data
            for part in section.split("."):
                node = node.get(part) if isinstance(node, dict) else None
            if isinstance(node, dict):
                node.pop(leaf, None)
    return data


def nearest(key: str, known: list[str], listing: bool = True) -> str:
    """``"; did you mean 'x'?"`` for the known name nearest to ``key`` (difflib), or the list
    (``listing``)."""
    import difflib

    close = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
    if close:
        return f"; did you mean {close[0]!r}?"
    return f" (known: {', '.join(sorted(known))})" if known and listing else ""
