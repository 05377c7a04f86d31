"""A load above mu M g slides a particle off a still substrate at (L - mu sgn L) / m*.

On a substrate at rest N* = 1; once the tangential law is in full slip T* = N* exactly (every
model's Coulomb limit), so x*'' = (L - mu sgn L) / m*, for the rigid point from the first
instant. Below mu the rigid point does not move at all. Value: the largest relative error of
the acceleration (after 5 periods, from the velocity's increments) over five models and two
loads.
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.validation import COMPLIANT_MODELS, Case, CaseResult

M_STAR, MU = 0.5, 0.1

CASE = Case(
    name="still_substrate_slide",
    group="loads",
    title="Loads L = 0.25 and -0.3 (mu = 0.1) on a still substrate: acceleration "
    "(L - mu sgn L)/m* for every model, and a rigid point held at |L| < mu; value: max relative "
    "error of the acceleration",
    tolerance=1e-9,
    quick=True,
)


def _trajectory(model: str, load: float):
    scene = sd.Scene(model=model, particle={"m_star": M_STAR, "load": load}, material={"mu": MU},
                     drive={"amplitude": 0.0}, numerics={"periods": 20})
    return sd.run(scene, trajectory=True).trajectory


def run() -> CaseResult:
    """Two loads above mu for every model; one below for the point."""
    worst, parts = 0.0, []
    for model in ("material_point", *COMPLIANT_MODELS):
        for load in (0.25, -0.3):
            tr = _trajectory(model, load)
            late = tr[tr.t > 5.0]
            acc = np.diff(late["vx"].to_numpy()) / np.diff(late["t"].to_numpy())
            want = (load - MU * math.copysign(1.0, load)) / M_STAR
            err = float(np.max(np.abs(acc / want - 1.0)))
            worst = max(worst, err)
        parts.append(f"{model}: {err:.1e}")
    held = _trajectory("material_point", 0.09)
    still = bool((held["x"] == 0.0).all())
    return CASE.result(worst, require=still,
                       message="; ".join(parts) + f"; point at L = 0.09 < mu held still: {still}")
