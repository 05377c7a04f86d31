"""Material point: contact is lost somewhere in the period if and only if Gz = 4 pi^2 m* A* > 1."""

from __future__ import annotations

import sawdrift as sd
from sawdrift.validation import Case, CaseResult, point_scene

CASE = Case(
    name="mp_hop_threshold",
    group="material_point",
    title="Contact is lost iff Gz > 1: the threshold located by bisection over the wide bracket "
    "Gz in [0.5, 2] (30 halvings, width 1.4e-9); value: |Gz_c - 1|",
    tolerance=1e-4,
    quick=True,
)


def _lost(gz: float) -> bool:
    return sd.run(point_scene(gz)).contact_lost


def run() -> CaseResult:
    """Check the bracket ends, then bisect the threshold between them."""
    lo, hi = 0.5, 2.0
    kept, lost = not _lost(lo), _lost(hi)
    if kept and lost:
        for _ in range(30):
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
        where = "the threshold is not inside [0.5, 2]"
    return CASE.result(
        value,
        require=kept and lost,
        message=f"contact kept at Gz = 0.5: {kept}; lost at Gz = 2: {lost}; {where}",
    )
