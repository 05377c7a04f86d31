"""Adhesion in the scene: the normalized adhesion of a device, and its consistency checks.

A sphere of radius R pressed onto a flat by the load F with a work of adhesion w (J/m^2) pulls
back with at most

    DMT (Derjaguin, Muller and Toporov 1975):   F_pull = 2 pi R w
    JKR (Johnson, Kendall and Roberts 1971):    F_pull = 1.5 pi R w

``material.adhesion`` is that pull-off force of the law in ``effects.adhesion`` over the static
normal load M g (the scale of every normalized force); a device derives it from
``device.adhesion`` = w. The laws themselves are :mod:`sawdrift.contact.adhesion_law`.
"""

from __future__ import annotations

import math
from typing import Any

from .device import Device, normalized
from .parts import MAX_LOAD_RATIO

#: pull-off force of each adhesive law over the DMT one, 2 pi R w
PULLOFF_FACTOR = {"dmt": 1.0, "jkr": 0.75}

#: The largest pull-off force of a device over its normal load, F_pull / (M g) (the range of
#: ``material.adhesion``).
MAX_PULLOFF_RATIO = 1e12


def load_bound(adhesion: float) -> float:
    """The largest |particle.load| with ``material.adhesion`` = F*_pull:
    :data:`MAX_LOAD_RATIO` (1 + 2 F*_pull), the normalized friction bound at mu = 1 times 100."""
    return MAX_LOAD_RATIO * (1.0 + 2.0 * adhesion)


def adhesive_out_of_range(device: Device, law: str) -> str | None:
    """Why a device's tangential load or pull-off is beyond what the model stands for under the
    adhesive ``law`` (``effects.adhesion``), or None: a load above :func:`load_bound` times M g
    (an adhesive micro-particle held by 6e4 M g of friction may carry far more than 100 M g), a
    pull-off above :data:`MAX_PULLOFF_RATIO` M g. The line names the device fields to change."""
    n = normalized(device)
    pull = normalized_adhesion(device, law)
    bound = load_bound(pull)
    if abs(n["load"]) > bound:
        held = f"M g + 2 F_pull = {n['weight_n'] * (1.0 + 2.0 * pull):.4g} N" if pull > 0.0 else \
            f"M g = {n['weight_n']:.3g} N"
        return (f"device.load = {device.load:.4g} N and device.incline = "
                f"{math.degrees(device.incline):.4g} deg push the particle with "
                f"{n['load_n']:.4g} N, {abs(n['load']) / (1.0 + 2.0 * pull):.3g} times its "
                f"normal load {held}, above {MAX_LOAD_RATIO:g} times: lower "
                "|device.load| or raise device.preload")
    if pull > MAX_PULLOFF_RATIO:
        formula = "1.5 pi R w" if law == "jkr" else "2 pi R w"
        return (f"device.adhesion = {device.adhesion:.4g} J/m^2 pulls the particle with "
                f"{formula} = {pull * n['weight_n']:.3g} N, above {MAX_PULLOFF_RATIO:g} times its "
                f"normal load M g = {n['weight_n']:.3g} N: lower device.adhesion or raise "
                "device.preload")
    return None


def adhesive_sets_contact(device: Device, law: str) -> bool:
    """Whether adhesion rather than the load sets the contact: a pull-off of at least M g."""
    return normalized_adhesion(device, law) >= 1.0


def normalized_adhesion(device: Device, law: str) -> float:
    """material.adhesion of ``device`` under the adhesive ``law``: F_pull / (M g) (module text).

    0 without adhesion (``law = "none"`` or w = 0); an unknown law also gives 0 (the scene's
    own check of ``effects.adhesion`` names it).
    """
    if device.adhesion == 0.0 or law not in PULLOFF_FACTOR:
        return 0.0
    norm = normalized(device)
    return PULLOFF_FACTOR[law] * norm["pulloff_dmt_n"] / norm["weight_n"]


def adhesion_consistent(scene: Any) -> None:
    """material.adhesion and effects.adhesion go together, on a sphere, without normal damping."""
    eff, w = scene.effects, scene.material.adhesion
    if w > 0.0 and eff.adhesion == "none":
        raise ValueError(f"material.adhesion = {w:g} needs effects.adhesion = 'dmt' or 'jkr' "
                         "(or leave material.adhesion at 0)")
    if eff.adhesion != "none" and w == 0.0:
        needs = ('device.adhesion > 0 (the work of adhesion, e.g. "0.05 J/m^2")'
                 if getattr(scene, "device", None) is not None
                 else "material.adhesion > 0 (the pull-off force over M g)")
        raise ValueError(f"effects.adhesion = {eff.adhesion!r} needs {needs}")
    load, bound = scene.particle.load, load_bound(w)
    if abs(load) > bound:
        with_pull = f" = {MAX_LOAD_RATIO:g} (1 + 2 material.adhesion)" if w > 0.0 else ""
        raise ValueError(f"particle.load = {load!r} is outside the allowed range [-{bound:g}, "
                         f"{bound:g}]{with_pull}: beyond it friction holds nothing")
    if eff.adhesion_detach != "instability" and eff.adhesion != "jkr":
        raise ValueError(f"effects.adhesion_detach = {eff.adhesion_detach!r} applies to "
                         "effects.adhesion = 'jkr' only")
    if eff.adhesion == "none":
        return
    shape = scene.particle.profile.shape
    if shape != "sphere":
        raise ValueError(f"effects.adhesion = {eff.adhesion!r} needs particle.profile.shape = "
                         f"'sphere' (the adhesive laws are those of a sphere), not {shape!r}")
    e = scene.material.restitution
    if eff.normal_damping > 0.0 or (e is not None and e < 1.0):
        # e = 1 is the undamped contact, bit for bit: no conflict
        raise ValueError(f"effects.adhesion = {eff.adhesion!r} is undamped: leave "
                         "effects.normal_damping at 0 and material.restitution unset (or 1)")


def adhesive_rest(device: Device, law: str) -> dict[str, float]:
    """The adhesive sphere at rest under its load M g (SI): pull-off force, contact radius a,
    overlap delta, normal stiffness dF/d delta and the particle's natural frequency on it.

    JKR (Johnson 1985, with K = 4 E*/3): a^3 = (R/K) (P + 3 pi w R + sqrt(6 pi w R P +
    (3 pi w R)^2)), delta = a^2/R - sqrt(2 pi w a / E*), and the stiffness the ratio of
    dF/da = 4 E* a^2/R - (3/2) sqrt(8 pi w E*) a^(1/2) to d delta/da = 2 a/R - (1/2) sqrt(2 pi w /
    E*) a^(-1/2). DMT: a^3 = (R/K) (P + 2 pi w R), delta = a^2/R, stiffness 2 E* a. For the 10 um
    silica sphere on lithium niobate (w = 0.05 J/m^2): a = 68 nm, delta = 0.31 nm, 10 MHz (JKR).
    """
    n = normalized(device)
    e_star, radius, w, load = n["e_star_pa"], float(device.particle.radius), device.adhesion, \
        n["weight_n"]
    k = 4.0 * e_star / 3.0
    if law == "jkr":
        third = 3.0 * math.pi * w * radius
        a = (radius / k * (load + third + math.sqrt(2.0 * third * load + third**2))) ** (1 / 3)
        delta = a * a / radius - math.sqrt(2.0 * math.pi * w * a / e_star)
        d_force = 4.0 * e_star * a * a / radius - 1.5 * math.sqrt(8.0 * math.pi * w * e_star * a)
        d_delta = 2.0 * a / radius - 0.5 * math.sqrt(2.0 * math.pi * w / (e_star * a))
        stiffness = d_force / d_delta
    else:
        a = (radius / k * (load + 2.0 * math.pi * w * radius)) ** (1 / 3)
        delta, stiffness = a * a / radius, 2.0 * e_star * a
    return {"pulloff_n": PULLOFF_FACTOR[law] * n["pulloff_dmt_n"], "contact_radius_m": a,
            "overlap_m": delta, "stiffness_n_m": stiffness,
            "natural_hz": math.sqrt(stiffness / n["mass_kg"]) / (2.0 * math.pi)}


#: the range of the surface forces behind Tabor's parameter, m (:func:`tabor`)
SURFACE_FORCE_RANGE = (0.3e-9, 0.4e-9)

#: Tabor's parameter below which DMT holds, above which JKR does (between: Maugis-Dugdale)
DMT_BELOW, JKR_ABOVE = 0.1, 5.0


def tabor(device: Device) -> tuple[float, float]:
    """Tabor's parameter mu_T = (R w^2 / (E*^2 z0^3))^(1/3) of an adhesive sphere (Tabor 1977,
    J. Colloid Interface Sci. 58, 2), at the two ends of :data:`SURFACE_FORCE_RANGE` z0: the
    elastic neck the adhesion pulls up over the range of the surface forces. Large at the short
    range (the first number), small at the long one."""
    e_star, radius, w = normalized(device)["e_star_pa"], float(device.particle.radius), \
        device.adhesion
    return tuple((radius * w * w / (e_star * e_star * z0**3)) ** (1.0 / 3.0)
                 for z0 in SURFACE_FORCE_RANGE)  # type: ignore[return-value]


def tabor_warning(device: Device, law: str) -> str | None:
    """Where the scene's adhesive law is outside its range by Tabor's parameter: JKR on a sphere
    whose mu_T is below 0.1 even at the shortest range of the surface forces (DMT's regime: a
    stiff, small sphere), DMT where it is above 5 even at the longest (JKR's: soft, large,
    sticky). A 20 nm silica sphere on lithium niobate (mu_T 0.06-0.08) ran JKR without a word.
    None inside, in the transition between them, or without an adhesive sphere."""
    if device.adhesion == 0.0 or law not in PULLOFF_FACTOR or device.particle.shape != "sphere":
        return None
    high, low = tabor(device)
    span = f"Tabor's parameter mu_T = {low:.3g}-{high:.3g} (z0 = 0.3-0.4 nm)"
    regime = _tabor_regime(high, low)
    if law == "jkr" and regime == "dmt":
        return (f"{span}, below {DMT_BELOW:g}: DMT's regime (a stiff, small sphere), not JKR's; "
                "effects.adhesion = 'dmt' describes it")
    if law == "dmt" and regime == "jkr":
        return (f"{span}, above {JKR_ABOVE:g}: JKR's regime (a soft, large, sticky sphere), not "
                "DMT's; effects.adhesion = 'jkr' describes it")
    return None


def _tabor_regime(high: float, low: float) -> str | None:
    """The law Tabor's parameter points to over the whole range of z0 (:func:`tabor`'s two ends):
    'dmt' below :data:`DMT_BELOW` even at the short range, 'jkr' above :data:`JKR_ABOVE` even at
    the long one, None in the Maugis-Dugdale transition."""
    return "dmt" if high < DMT_BELOW else "jkr" if low > JKR_ABOVE else None


def explain_adhesion(device: Device, law: str, mu: float) -> list[str]:
    """The ``--explain`` lines of an adhesive device (:func:`adhesive_rest`): none without."""
    if device.adhesion == 0.0 or law not in PULLOFF_FACTOR:
        return []
    n, rest = normalized(device), adhesive_rest(device, law)
    f, pull, weight = n["frequency_hz"], rest["pulloff_n"], n["weight_n"]
    return [
        f"adhesion ({law.upper()}, work of adhesion w = {device.adhesion:g} J/m^2):",
        f"  pull-off force {pull:.4g} N = {pull / weight:.4g} M g "
        f"({'1.5' if law == 'jkr' else '2'} pi R w)",
        f"  at rest under M g: contact radius {rest['contact_radius_m']:.4g} m, overlap "
        f"{rest['overlap_m']:.4g} m = {rest['overlap_m'] / n['a0_m']:.4g} a0",
        f"  contact (normal) natural frequency on the adhesive contact {rest['natural_hz']:.4g} Hz"
        f" = {rest['natural_hz'] / f:.4g} f",
        f"  the most friction can hold: mu (M g + 2 F_pull) = {mu * (weight + 2.0 * pull):.4g} N "
        "(friction is capped at mu |N + 2 F_pull|)",
    ] + ([_tabor_line(device)] if device.particle.shape == "sphere" else []) + (
        [f"  note: A* > 1: the surface moves {n['amplitude']:.4g} a0, against the adhesive "
          f"contact's rest overlap of {rest['overlap_m'] / n['a0_m']:.4g} a0 (Hertz's a0 under "
          "M g is not the contact's scale here)"] if n["amplitude"] > 1.0 else [])


def _tabor_line(device: Device) -> str:
    """The ``--explain`` line of Tabor's parameter (:func:`tabor`) and the law it points to."""
    high, low = tabor(device)
    regime = _tabor_regime(high, low)
    where = regime.upper() if regime else "the Maugis-Dugdale transition, which JKR and DMT bracket"
    return (f"  Tabor's parameter mu_T = {low:.3g}-{high:.3g} (z0 = 0.3-0.4 nm): {where} "
            f"(DMT below {DMT_BELOW:g}, JKR above {JKR_ABOVE:g})")
