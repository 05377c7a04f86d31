"""Cattaneo-Mindlin monotonic loading at fixed a*: T* = N*(a*) - N*(a* - b*), then T* = N*(a*).

Sphere (p = 3/2: a*^(3/2) - (a* - b*)^(3/2)) and cone (p = 2), loaded to a* = 0.5, 1 and 2 at
b* = 0, then b* from 0 to 1.2 a* (full sliding from b* = a* on). At a* = 1 alone every power of
a* is 1, and a wrong exponent of a* would pass.
"""

from __future__ import annotations

import numpy as np

from sawdrift.validation import (
    COMPLIANT_MODELS,
    DEVIATION_TOL,
    Case,
    CaseResult,
    cattaneo_mindlin,
    dem_spring,
    mindlin_loop,
)

N_SEG = 2000

#: the compressions loaded to (a* = 1 alone cannot tell a wrong exponent of a*)
A_VALUES = (0.5, 1.0, 2.0)

CASE = Case(
    name="cm_monotonic",
    group="mindlin",
    title="Monotonic tangential loading at fixed a* = 0.5, 1, 2 (sphere and cone) against the "
    "Cattaneo-Mindlin curve T* = N*(a*) - N*(a* - b*), full sliding T* = N* beyond b* = a*; "
    "value: max |T* - T*_CM| / N*(a*)",
    tolerance=1e-9,
    model_tolerance={"mdr": 1e-3},
    expected_deviation=("hertz_mindlin_dem",),
    deviation_reason={
        "hertz_mindlin_dem": (
            "hertz_mindlin_dem is the DEM spring of Mindlin's initial stiffness "
            "with a Coulomb cap (no partial slip): T* rises linearly in b* to the cap N* instead of "
            "following the Cattaneo-Mindlin curve"
        ),
    },
    models=COMPLIANT_MODELS,
    quick=True,
)


def run(model: str) -> CaseResult:
    """Drive the virgin branch and compare it with the closed form."""
    worst, dem, parts = 0.0, 0.0, []
    for shape, p in (("sphere", 1.5), ("cone", 2.0)):
        for a in A_VALUES:
            tr = mindlin_loop(model, a, 1.2 * a, cycles=1, samples=N_SEG,
                              profile={"shape": shape})
            seg = tr.iloc[N_SEG : 2 * N_SEG + 1]
            b, t = seg["b"].to_numpy(), seg["T_star"].to_numpy()
            err = np.abs(t - cattaneo_mindlin(a, b, p)) / a**p
            worst = max(worst, float(err.max()))
            dem = max(dem, float(np.abs(t - dem_spring(a, 0.0, 0.0, b, p)).max() / a**p))
            parts.append(f"{shape} a* = {a:g}: max error {err.max():.2e} at b* = "
                         f"{b[int(err.argmax())]:.3f}")
    matches = None
    if CASE.deviation_expected(model):
        # the DEM spring's own closed form: a straight line of Mindlin's initial stiffness to
        # its cap, at most (1 - 1/p)^p of N* off the Cattaneo-Mindlin curve (0.19 sphere,
        # 0.25 cone)
        matches = dem <= DEVIATION_TOL
        parts.append(f"against the DEM spring's straight line to its cap: {dem:.2e}")
    return CASE.result(worst, model=model, message="; ".join(parts), deviation_matches=matches)
