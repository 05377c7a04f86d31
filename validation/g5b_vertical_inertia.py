"""With paper eq. 5 as written (vertical inertia on), the same point mass in permanent contact
drifts against the wave: N* = 1 + Gz cos(phi) modulates friction over the period
(docs/physics.md). Same scene as ``point_mass_no_drift``.
"""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.validation import MU, NU, Case, CaseResult, heavy_sliding_v

GZ = 0.5
MU_OVER_GX = 0.05

CASE = Case(
    name="point_mass_inertia_drifts",
    group="point_mass",
    title="The same point with vertical inertia on (eq. 5) keeps contact and drifts against the wave "
    "by at least 10 % of the surface speed; value: V",
    tolerance=-0.1,
    quick=True,
)


def run() -> CaseResult:
    """Run the scene of ``point_mass_no_drift`` with vertical inertia on."""
    m_star = 0.1
    res = sd.run(sd.Scene(
        model="material_point",
        material={"mu": MU, "nu": NU},
        particle={"m_star": m_star},
        drive={"amplitude": GZ / (4 * math.pi**2 * m_star), "horizontal_ratio": (MU / MU_OVER_GX) / GZ},
        numerics={"periods": 100},
    ))
    return CASE.result(
        res.drift_ratio,
        require=not res.contact_lost and res.regime == "drift_against",
        message=f"V = {res.drift_ratio:.4f}, regime {res.regime} (heavy-sliding limit "
        f"mu/Gx -> 0: {heavy_sliding_v(GZ):.4f})",
    )
