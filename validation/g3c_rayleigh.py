"""The Rayleigh ratio r(nu) of horizontal to vertical surface amplitude (docs/physics.md)."""

from __future__ import annotations

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

#: Independently checked values quoted in docs/physics.md (six decimals).
R_VALUES = {0.20: 0.704932, 0.25: 0.681250, 0.30: 0.656264, 0.40: 0.602488}
SPEED_RATIO_03 = 0.927413

CASE = Case(
    name="rayleigh_ratio",
    group="convergence",
    title="r(nu) at nu = 0.2, 0.25, 0.3, 0.4 and c_R/c_S at nu = 0.3 against the six-decimal values "
    "of docs/physics.md; value: max absolute difference",
    tolerance=1e-6,
    quick=True,
)


def run() -> CaseResult:
    """Compare the solver with the quoted values."""
    got = {f"r({nu})": (sd.rayleigh_ratio(nu), r) for nu, r in R_VALUES.items()}
    got["c_R/c_S(0.3)"] = (sd.rayleigh_speed_ratio(0.3), SPEED_RATIO_03)
    diffs = {k: abs(v - want) for k, (v, want) in got.items()}
    return CASE.result(
        max(diffs.values()),
        message="; ".join(f"{k} = {v:.7f} (quoted {want})" for k, (v, want) in got.items()),
        details=diffs,
    )
