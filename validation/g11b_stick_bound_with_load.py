"""The rigid point sticks under a load as long as |m* u_x'' - L| <= mu N* at every phase.

With u_x'' and N* - 1 in quadrature, |Gx sin(phi) - L| <= mu (1 + Gz cos(phi)) for all phi
holds iff Gx <= sqrt((mu - |L|)^2 - (mu Gz)^2) (docs/physics.md, "Loads, inclines and
restitution"). At 0.99 of that bound the point never slips and its largest |T*|/N* is the
analytic maximum of |Gx sin(phi) - L| / (mu (1 + Gz cos(phi))); at 1.01 it slips. Value: the
largest difference between the measured and the analytic peak of |T*|/N*.
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

MU = 0.3
M_STAR = 0.1
#: (L, Gz) cells
CELLS = [(0.05, 0.3), (0.1, 0.5), (-0.1, 0.5), (0.15, 0.4), (-0.2, 0.2)]

CASE = Case(
    name="stick_bound_with_load",
    group="loads",
    title="Rigid point under a load L: sticks at Gx = 0.99 sqrt((mu - |L|)^2 - (mu Gz)^2) with "
    "the analytic peak |T*|/N*, slips at 1.01 (five (L, Gz) cells, mu = 0.3); value: max |peak - "
    "analytic peak| (sampled 200 times a period)",
    tolerance=2e-4,
    quick=True,
)


def scene(load: float, gz: float, fraction: float) -> sd.Scene:
    """The point at ``fraction`` of the stick bound with the load."""
    gx = fraction * math.sqrt((MU - abs(load)) ** 2 - (MU * gz) ** 2)
    return sd.Scene(model="material_point", particle={"m_star": M_STAR, "load": load},
                    material={"mu": MU}, numerics={"periods": 40},
                    drive={"amplitude": gz / (4 * math.pi**2 * M_STAR),
                           "horizontal_ratio": gx / gz})


def run() -> CaseResult:
    """Each cell below and above its bound."""
    worst, ok, parts = 0.0, True, []
    phi = np.linspace(0.0, 2.0 * math.pi, 400_001)
    for load, gz in CELLS:
        below = scene(load, gz, 0.99)
        res = sd.run(below, trajectory=True)
        tr = res.trajectory[res.trajectory.t > res.ramp_periods]
        peak = float((tr["T_star"].abs() / tr["N_star"]).max())
        gx = below.horizontal_ratio * gz
        want = float(np.max(np.abs(gx * np.sin(phi) - load) / (MU * (1.0 + gz * np.cos(phi)))))
        above = sd.run(scene(load, gz, 1.01))
        worst = max(worst, abs(peak - want))
        ok &= (res.regime == "stick" and res.gross_slip_fraction == 0.0
               and above.gross_slip_fraction > 0.0)
        parts.append(f"L = {load:g}, Gz = {gz:g}: peak {peak:.5f} (analytic {want:.5f}), "
                     f"{res.regime}; 1 % above: slip fraction {above.gross_slip_fraction:.3f}")
    return CASE.result(worst, require=ok, message="; ".join(parts))
