"""Material point: the motion depends on m* and A* only through the product m* A*."""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.validation import MU, NU, Case, CaseResult

CASE = Case(
    name="mp_scaling",
    group="material_point",
    title="Same regime and drift ratio at (m*, A*), (m*/10, 10 A*) and (10 m*, A*/10) for Gz = 0.5, "
    "0.9 (sliding) and 1.5, 3 (contact lost); value: max |V - V_ref|",
    tolerance=1e-9,
    quick=True,
)


def _run(m_star: float, amp: float) -> sd.Result:
    return sd.run(sd.Scene(model="material_point", material={"mu": MU, "nu": NU},
                           particle={"m_star": m_star}, drive={"amplitude": amp}))


def run() -> CaseResult:
    """Compare each point with its two rescaled copies."""
    worst, ok, parts = 0.0, True, []
    for m_star, gz in [(1.0, 0.5), (0.05, 0.9), (0.3, 1.5), (2.0, 3.0)]:
        amp = gz / (4.0 * math.pi**2 * m_star)
        ref = _run(m_star, amp)
        for k in (0.1, 10.0):
            other = _run(m_star * k, amp / k)
            worst = max(worst, abs(other.drift_ratio - ref.drift_ratio))
            ok &= other.regime == ref.regime
        parts.append(f"Gz = {gz}: {ref.regime}, V = {ref.drift_ratio:.4g}")
    return CASE.result(worst, require=ok, message="regimes equal: " + str(ok) + "; " + "; ".join(parts))
