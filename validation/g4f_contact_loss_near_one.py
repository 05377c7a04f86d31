"""For m* >> 1 the deformable particle loses contact near A* = 1 (paper section 5).

A heavy particle barely moves, so the contact opens when the substrate's vertical amplitude
exceeds the static compression: a* = 1 - A* cos(2 pi t*) < 0 for A* > 1. At m* = 100 the
smallest A* with contact loss is located by a scan over [0.2, 5] and bisection.
"""

from __future__ import annotations

import numpy as np

import sawdrift as sd
from sawdrift.report.validation import COMPLIANT_MODELS, MU, NU, Case, CaseResult

M_STAR = 100.0

CASE = Case(
    name="contact_loss_near_one",
    group="diagrams",
    title="At m* = 100 the smallest A* with contact loss, A*_c, is within a factor 1.5 of 1 "
    "(40 periods); value: max(A*_c, 1/A*_c)",
    tolerance=1.5,
    models=COMPLIANT_MODELS,
)


def _lost(model: str, amp: float) -> bool:
    scene = sd.Scene(model=model, material={"mu": MU, "nu": NU}, particle={"m_star": M_STAR},
                     drive={"amplitude": float(amp)}, numerics={"periods": 40})
    return sd.run(scene).contact_lost


def run(model: str) -> CaseResult:
    """Scan 41 log-spaced A*, then bisect between the last kept and the first lost."""
    amps = np.geomspace(0.2, 5.0, 41)
    lost = [_lost(model, a) for a in amps]
    if not any(lost) or lost[0]:
        return CASE.result(float("inf"), model=model,
                           message=f"contact loss at A* = 0.2: {lost[0]}, at 5: {lost[-1]}")
    k = lost.index(True)
    lo, hi = amps[k - 1], amps[k]
    for _ in range(10):
        mid = float(np.sqrt(lo * hi))
        if _lost(model, mid):
            hi = mid
        else:
            lo = mid
    a_c = float(np.sqrt(lo * hi))
    regained = [a for a, flag in zip(amps[k:], lost[k:], strict=True) if not flag]
    return CASE.result(
        max(a_c, 1.0 / a_c),
        model=model,
        message=f"A*_c = {a_c:.4f}" + (f"; contact kept again at A* = {regained[0]:.3g}" if regained
                                       else "; contact lost at every larger A* of the scan"),
    )
