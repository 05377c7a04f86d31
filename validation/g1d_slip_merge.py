"""Material point: drift appears exactly where the two slips of a period merge.

The closed form (:func:`sawdrift.validation.point_prediction`) gives the Gx at which the forward
slip lasts until the backward one would start; below it the slips are mirror images (no drift),
above it the point slides continuously against the wave. The simulated onset of drift is located
by bisection and compared with it.
"""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.validation import MU, Case, CaseResult, point_prediction, point_scene

CASE = Case(
    name="mp_slip_merge",
    group="material_point",
    title="Onset of drift (|V| > 1e-9) at the analytic merging of the two slips, Gz = 0.3, 0.6, "
    "0.9; drift is against the wave above it; value: max relative error of the onset Gx",
    tolerance=0.01,
    quick=True,
)


def _analytic_factor(gz: float) -> float:
    bound = MU * math.sqrt(1.0 - gz * gz)
    lo, hi = 1.0, 20.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if point_prediction(gz, mid * bound) == "stick":
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _drift(gz: float, factor: float) -> float:
    return sd.run(point_scene(gz, factor * MU * math.sqrt(1.0 - gz * gz))).drift_ratio


def run() -> CaseResult:
    """Bisect the simulated onset in [0.9, 1.1] x the analytic factor."""
    worst, ok, parts = 0.0, True, []
    for gz in (0.3, 0.6, 0.9):
        f_an = _analytic_factor(gz)
        lo, hi = 0.9 * f_an, 1.1 * f_an
        if abs(_drift(gz, lo)) > 1e-9 or not _drift(gz, hi) < -1e-4:
            ok = False
            parts.append(f"Gz = {gz}: no onset inside +-10 % of the analytic {f_an:.4f}")
            worst = math.inf
            continue
        for _ in range(12):
            mid = 0.5 * (lo + hi)
            if abs(_drift(gz, mid)) > 1e-9:
                hi = mid
            else:
                lo = mid
        f_num = 0.5 * (lo + hi)
        worst = max(worst, abs(f_num / f_an - 1.0))
        parts.append(f"Gz = {gz}: onset at {f_num:.4f} x the stick bound (analytic {f_an:.4f})")
    return CASE.result(worst, require=ok, message="; ".join(parts))
