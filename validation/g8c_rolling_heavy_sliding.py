"""Rotation: heavy sliding of the rigid rolling sphere, V = kappa / (1 + kappa) cos(phi0).

Derivation (docs/physics.md, Rotation). The contact point s = x + R phi has the mass
m_s = m kappa / (1 + kappa) and obeys m_s s'' = -mu N sgn(s' - u_x'), while the centre obeys
m x'' = -mu N sgn(s' - u_x'); from rest, s = (1 + 1/kappa) x at all times. In heavy sliding
(mu / Gx_s -> 0 with Gx_s = Gx kappa / (1 + kappa)) the contact point keeps a nearly constant
velocity V_s, at which the period-averaged friction vanishes: the same condition as for a point,
so V_s / (2 pi r A*) = cos(phi0) with 2 phi0 - pi = 2 Gz sin(phi0) (N* = 1 - m* u_y'' uses the whole
mass). The centre drifts at V = V_s kappa / (1 + kappa): 2/7 of the point's drift for a solid
sphere, 2/5 for a thin shell; the sphere spins at R phi' = V / kappa.

mu / Gx_s = 0.02 (as the point's heavy-sliding case), settled; Gz = 0.3, 0.5, 0.9.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.validation import MU, Case, CaseResult, heavy_sliding_v, point_scene

GZS = (0.3, 0.5, 0.9)
KAPPAS = (0.4, 2.0 / 3.0)
MU_OVER_GX_S = 0.02

CASE = Case(
    name="rolling_heavy_sliding",
    group="rotation",
    title="Rigid rolling sphere in heavy sliding (mu/Gx_s = 0.02, settled): centre drift "
    "V = kappa/(1 + kappa) cos(phi0), 2 phi0 - pi = 2 Gz sin(phi0), kappa = 2/5 and 2/3, "
    "Gz = 0.3, 0.5, 0.9; value: max |V/V_limit - 1|",
    tolerance=0.02,
    quick=True,
)


def run() -> CaseResult:
    """Settled drift of the rolling sphere against the closed form."""
    worst, notes = 0.0, []
    for kappa in KAPPAS:
        c = 1.0 + 1.0 / kappa
        for gz in GZS:
            scene = point_scene(gz, MU * c / MU_OVER_GX_S, periods=40, measure_periods=10,
                                settle=True, settle_tolerance=1e-6)
            scene = scene.with_updates(**{"effects.rotation": True, "particle.gyration": kappa})
            got = sd.run(scene).drift_ratio
            want = heavy_sliding_v(gz) / c
            worst = max(worst, abs(got / want - 1.0))
            notes.append(f"kappa {kappa:.3g}, Gz {gz:g}: V = {got:.5f} (limit {want:.5f})")
    return CASE.result(worst, message="; ".join(notes))
