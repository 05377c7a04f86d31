"""Material point: contact is lost somewhere in the period if and only if Gz = 4 pi^2 m* A* > 1."""

from __future__ import annotations

import sawdrift as sd
from sawdrift.report.validation import Case, CaseResult, point_scene

CASE = Case(
    name="mp_hop_threshold",
    group="material_point",
    title="Contact kept at Gz = 0.98 and lost at Gz = 1.02 (lost iff Gz > 1); value: |Gz_c - 1| "
    "of the threshold located by bisection",
    tolerance=0.02,
    quick=True,
)


def _lost(gz: float) -> bool:
    return sd.run(point_scene(gz)).contact_lost


def run() -> CaseResult:
    """Run Gz = 0.98 and 1.02, then bisect the threshold between them."""
    kept, lost = not _lost(0.98), _lost(1.02)
    lo, hi = 0.98, 1.02
    if kept and lost:
        for _ in range(14):
            mid = 0.5 * (lo + hi)
            if _lost(mid):
                hi = mid
            else:
                lo = mid
        gz_c = 0.5 * (lo + hi)
        value = abs(gz_c - 1.0)
        where = f"threshold Gz_c = {gz_c:.5f} (bracket width {hi - lo:.1e})"
    else:
        value = float("inf")
        where = "the threshold is not inside [0.98, 1.02]"
    return CASE.result(
        value,
        require=kept and lost,
        message=f"contact kept at Gz = 0.98: {kept}; lost at Gz = 1.02: {lost}; {where}",
    )
