"""The deformable sphere shows four regimes (paper section 5, Fig. 3), each where physics puts it.

* contact loss: a heavy particle (m* >= 10) barely moves vertically in one period, so a substrate
  that retreats by A* > 1 (more than the static compression a* = 1) must leave it: every such cell
  is hopping or bouncing;
* weak oscillation without drift: far below the vertical resonance (m* <= 0.0038, a decade under
  m* = 3 / (8 pi^2)) the contact follows the substrate quasi-statically, and where the tangential
  force this needs is at most half the Coulomb limit, Gx <= mu sqrt(1 - Gz^2) / 2, no part of the
  period slides: every such cell is ``stick``;
* drift with and against the wave both appear (the paper's central claim).

The value counts the cells that contradict the first two predictions, plus 100 for each missing
drift direction.
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.validation import MU, NU, Case, CaseResult, regime_class, regime_table

CASE = Case(
    name="four_regimes",
    group="diagrams",
    title="Contact loss wherever m* >= 10 and A* > 1; stick wherever m* <= 0.0038 and "
    "Gx <= mu sqrt(1 - Gz^2) / 2; drift with and against both present; value: contradicting "
    "cells + 100 per missing drift direction",
    tolerance=0,
    models=("mmd", "mdr"),
    quick=True,
)


def run(model: str) -> CaseResult:
    """Check the predicted regions of the shared diagram grid."""
    table = regime_table(model)
    m, amp = table["m_star"].to_numpy(), table["amplitude"].to_numpy()
    classes = np.array([regime_class(g) for g in table["regime"]])
    gz = 4 * math.pi**2 * m * amp
    gx = sd.rayleigh_ratio(NU) * gz
    lost_zone = (m >= 10.0) & (amp > 1.0)
    quiet_zone = (m <= 0.0038) & (gx <= 0.5 * MU * np.sqrt(np.clip(1 - gz**2, 0.0, None)))
    bad_lost = int(np.sum(lost_zone & (classes != "lost")))
    bad_quiet = int(np.sum(quiet_zone & (classes != "stick")))
    missing = [d for d in ("drift_with", "drift_against") if d not in classes]
    return CASE.result(
        bad_lost + bad_quiet + 100 * len(missing),
        model=model,
        require=bool(lost_zone.any() and quiet_zone.any()),
        message=f"contact loss in {int(np.sum(lost_zone & (classes == 'lost')))} of "
        f"{int(lost_zone.sum())} heavy cells with A* > 1; stick in "
        f"{int(np.sum(quiet_zone & (classes == 'stick')))} of {int(quiet_zone.sum())} quasi-static "
        f"cells; drift with: {int(np.sum(classes == 'drift_with'))} cells, against: "
        f"{int(np.sum(classes == 'drift_against'))} cells"
        + (f"; missing: {', '.join(missing)}" if missing else ""),
    )
