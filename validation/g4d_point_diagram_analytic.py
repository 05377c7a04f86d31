"""The material point's whole diagram against its closed-form thresholds (docs/physics.md).

Each cell's regime is predicted by :func:`sawdrift.validation.point_prediction` (contact lost
iff Gz > 1; stick iff the slips do not merge; else drift against the wave). Cells next to a
predicted boundary are skipped (the grid cannot resolve it).
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.validation import NU, Case, CaseResult, point_prediction, regime_class, regime_table

CASE = Case(
    name="point_diagram_analytic",
    group="diagrams",
    title="Material point: every diagram cell not adjacent to a predicted boundary has the regime "
    "the closed-form thresholds predict (lost / stick / drift against); value: mismatched cells",
    tolerance=0,
)


def run() -> CaseResult:
    """Compare cell by cell, skipping cells whose 3 x 3 neighbourhood crosses a boundary."""
    table = regime_table("material_point")
    r = sd.rayleigh_ratio(NU)
    masses = np.sort(table["m_star"].unique())
    amps = np.sort(table["amplitude"].unique())
    got = {(m, a): regime_class(g) for m, a, g in zip(table["m_star"], table["amplitude"],
                                                        table["regime"], strict=True)}
    pred = {(m, a): point_prediction(4 * math.pi**2 * m * a, r * 4 * math.pi**2 * m * a)
            for m in masses for a in amps}
    checked, wrong = 0, []
    for i, m in enumerate(masses):
        for j, a in enumerate(amps):
            neigh = {pred[(masses[i2], amps[j2])]
                     for i2 in range(max(0, i - 1), min(masses.size, i + 2))
                     for j2 in range(max(0, j - 1), min(amps.size, j + 2))}
            if len(neigh) > 1:
                continue
            checked += 1
            if got[(m, a)] != pred[(m, a)]:
                wrong.append(f"m* = {m:.3g}, A* = {a:.3g}: {got[(m, a)]} (predicted {pred[(m, a)]})")
    return CASE.result(
        len(wrong),
        require=checked >= 0.5 * len(pred),
        message=f"{checked} of {len(pred)} cells checked (the others border a boundary); "
        + ("; ".join(wrong[:5]) if wrong else "all agree"),
    )
