"""Masing unloading and reloading at fixed a*: the doubled virgin curve from each turning point.

Load to a* = 1, b* to B = 0.6 (partial slip), then back to -B and forward to +B again.
Unloading: T* = T1 - 2 [N*(a*) - N*(a* - (B - b*)/2)] (docs/physics.md for the sphere);
reloading is its mirror image, T* = -T1 + 2 [N*(a*) - N*(a* - (b* + B)/2)].
"""

from __future__ import annotations

import numpy as np

from sawdrift.validation import (
    COMPLIANT_MODELS,
    DEVIATION_TOL,
    Case,
    CaseResult,
    dem_spring,
    masing_unloading,
    mindlin_loop,
)

N_SEG = 2000
B = 0.6

CASE = Case(
    name="cm_masing",
    group="mindlin",
    title="Unloading from b* = 0.6 to -0.6 and reloading to +0.6 at a* = 1 (sphere) against "
    "Masing's rule (the doubled Cattaneo-Mindlin curve from the turning point); "
    "value: max |T* - T*_Masing| / N*",
    tolerance=1e-9,
    model_tolerance={"mdr": 1e-3},
    expected_deviation=("hertz_mindlin_dem",),
    deviation_reason={
        "hertz_mindlin_dem": (
            "hertz_mindlin_dem is the DEM spring of Mindlin's initial stiffness "
            "with a Coulomb cap (no partial slip): below the cap it unloads and reloads along one "
            "straight line, not Masing's doubled curve"
        ),
    },
    models=COMPLIANT_MODELS,
    quick=True,
)


def run(model: str) -> CaseResult:
    """Drive one full cycle after the virgin branch and compare both branches."""
    tr = mindlin_loop(model, 1.0, B, cycles=1, samples=N_SEG)
    down = tr.iloc[2 * N_SEG : 3 * N_SEG + 1]
    up = tr.iloc[3 * N_SEG : 4 * N_SEG + 1]
    e_down = np.abs(down["T_star"].to_numpy() - masing_unloading(1.0, B, down["b"].to_numpy()))
    e_up = np.abs(up["T_star"].to_numpy() + masing_unloading(1.0, B, -up["b"].to_numpy()))
    message = f"unloading branch: max error {e_down.max():.2e}; reloading branch: {e_up.max():.2e}"
    matches = None
    if CASE.deviation_expected(model):
        # the DEM spring unloads and reloads along its one straight line (capped at +-N*)
        top = float(dem_spring(1.0, 0.0, 0.0, np.array([B]))[0])
        dem = max(float(np.abs(down["T_star"].to_numpy()
                               - dem_spring(1.0, B, top, down["b"].to_numpy())).max()),
                  float(np.abs(up["T_star"].to_numpy()
                               - dem_spring(1.0, -B, -top, up["b"].to_numpy())).max()))
        matches = dem <= DEVIATION_TOL
        message += f"; against the DEM spring's straight line: {dem:.2e}"
    return CASE.result(float(max(e_down.max(), e_up.max())), model=model, message=message,
                       deviation_matches=matches)
