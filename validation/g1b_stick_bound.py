"""Material point: below Gx = mu sqrt(1 - Gz^2) it sticks for the whole period.

The friction force needed to stick, relative to the Coulomb limit, peaks at
Gx / (mu sqrt(1 - Gz^2)) once per period, so at 0.97 of the bound max |T*| / N* = 0.97 exactly
(T* is normalized by mu).
"""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.validation import MU, Case, CaseResult, point_scene

FRACTION = 0.97

CASE = Case(
    name="mp_stick_bound",
    group="material_point",
    title=f"At Gx = {FRACTION} mu sqrt(1 - Gz^2) (Gz = 0.3, 0.6, 0.9) the point never slips: "
    f"max |T*|/N* = {FRACTION} (analytic), zero drift, regime stick; value: max |max(|T*|/N*) - "
    f"{FRACTION}|",
    tolerance=1e-3,
    quick=True,
)


def run() -> CaseResult:
    """Measure max |T*|/N* after the ramp, the drift and the regime at three Gz."""
    worst, ok, parts = 0.0, True, []
    for gz in (0.3, 0.6, 0.9):
        res = sd.run(point_scene(gz, FRACTION * MU * math.sqrt(1.0 - gz * gz)), trajectory=True)
        tr = res.trajectory[res.trajectory.t > res.ramp_periods]
        peak = float((tr["T_star"].abs() / tr["N_star"]).max())
        worst = max(worst, abs(peak - FRACTION))
        below = bool((tr["T_star"].abs() < tr["N_star"]).all())
        ok &= res.regime == "stick" and abs(res.drift_ratio) < 1e-12 and below
        parts.append(f"Gz = {gz}: max|T*|/N* = {peak:.5f}, V = {res.drift_ratio:.1e}, {res.regime}")
    return CASE.result(worst, require=ok, message="; ".join(parts))
