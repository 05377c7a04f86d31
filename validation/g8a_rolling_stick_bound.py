"""Rotation: the rigid sphere rolls without gross slip iff Gx <= (1 + 1/kappa) mu sqrt(1 - Gz^2).

A sphere that can turn moves its contact point like a mass m kappa / (1 + kappa) (docs/physics.md,
Rotation); the force that keeps the contact point on the substrate is therefore 1 + 1/kappa times
smaller than for a point of mass m, and the stick bound of the point, Gx <= mu sqrt(1 - Gz^2),
grows by that factor (3.5 for a solid sphere, 2.5 for a thin shell). Gz = 0.3, mu = 0.1, m* = 0.1,
at 0.97 and 1.03 of the bound for kappa = 2/5 and 2/3.
"""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.validation import MU, Case, CaseResult, point_scene

GZ = 0.3
KAPPAS = (0.4, 2.0 / 3.0)

CASE = Case(
    name="rolling_stick_bound",
    group="rotation",
    title="Rigid rolling sphere, Gz = 0.3, mu = 0.1: no gross slip at 0.97 of Gx = (1 + 1/kappa) mu "
    "sqrt(1 - Gz^2), gross slip at 1.03, for kappa = 2/5 and 2/3; value: largest "
    "gross_slip_fraction below the bound",
    tolerance=0.0,
    quick=True,
)


def run() -> CaseResult:
    """Run just below and just above the rolling bound for each kappa."""
    below, notes, above_ok = [], [], True
    for kappa in KAPPAS:
        bound = (1.0 + 1.0 / kappa) * MU * math.sqrt(1.0 - GZ**2)
        res = {}
        for f in (0.97, 1.03):
            scene = point_scene(GZ, f * bound).with_updates(
                **{"effects.rotation": True, "particle.gyration": kappa})
            res[f] = sd.run(scene)
        below.append(res[0.97].gross_slip_fraction)
        above_ok &= res[1.03].gross_slip_fraction > 0.0
        notes.append(f"kappa = {kappa:.4g}: bound Gx = {bound:.4f}; 0.97: {res[0.97].regime}, "
                     f"gross slip {res[0.97].gross_slip_fraction:.3g}; 1.03: {res[1.03].regime}, "
                     f"gross slip {res[1.03].gross_slip_fraction:.3g}")
    return CASE.result(max(below), require=above_ok, message="; ".join(notes))
