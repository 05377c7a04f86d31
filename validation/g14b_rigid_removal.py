"""The removal threshold of a stiff adhesive contact: the rigid limit m (2 pi f)^2 A = F_pull + m g.

A particle held by its adhesive contact follows the surface as long as the contact can pull it
back: the force needed at the surface's largest downward acceleration, m (2 pi f)^2 A - m g,
must stay below the pull-off force. Normalized: contact is lost first where
4 pi^2 m* A* = 1 + F*_pull. The law only matters through its stiffness, so in the limit m* -> 0
(the contact's natural frequency far above the drive) the located threshold tends to it.
Located by bisection (8 halvings) on whether contact is lost in a run with a 100-period ramp,
for JKR and DMT with F*_pull = 10 at m* = 1e-5 (the contact about 100 times faster than the
drive); value: the largest |A*_threshold / A*_rigid - 1|.
"""

from __future__ import annotations

from sawdrift.study.threshold import stiff_removal_lost
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="adhesion_rigid_removal",
    group="adhesion",
    title="Removal of a stiff adhesive contact (JKR, DMT, F*_pull = 10, m* = 1e-5) where "
    "4 pi^2 m* A* = 1 + F*_pull: value |A*_threshold / A*_rigid - 1|",
    tolerance=0.01,
    quick=False,
)


def run() -> CaseResult:
    """Two bisections."""
    found = {}
    for law in ("jkr", "dmt"):
        lo, hi = 0.5, 1.1
        for _ in range(8):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if stiff_removal_lost(law, mid) else (mid, hi)
        found[law] = 0.5 * (lo + hi)
    worst = max(abs(v - 1.0) for v in found.values())
    return CASE.result(worst, message=", ".join(f"{k}: A*/A*_rigid = {v:.4f}"
                                                 for k, v in found.items()), details=found)
