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

from typing import Any

from .device import Device, normalized

#: pull-off force of each adhesive law over the DMT one, 2 pi R w
PULLOFF_FACTOR = {"dmt": 1.0, "jkr": 0.75}


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
    if eff.adhesion_detach != "instability" and eff.adhesion != "jkr":
        raise ValueError(f"effects.adhesion_detach = {eff.adhesion_detach!r} applies to "
                         "effects.adhesion = 'jkr' only")
    if eff.adhesion == "none":
        return
    shape = scene.particle.profile.shape
    if shape != "sphere":
        raise ValueError(f"effects.adhesion = {eff.adhesion!r} needs particle.profile.shape = "
                         f"'sphere' (the adhesive laws are those of a sphere), not {shape!r}")
    if eff.normal_damping > 0.0 or scene.material.restitution is not None:
        raise ValueError(f"effects.adhesion = {eff.adhesion!r} is undamped: leave "
                         "effects.normal_damping at 0 and material.restitution unset")
