"""Material point in heavy sliding: the drift against the wave follows V(Gz) (mu / Gx -> 0)."""

from __future__ import annotations

import numpy as np

import sawdrift as sd
from sawdrift.validation import MU, Case, CaseResult, heavy_sliding_v, point_scene

#: mu / Gx of the runs (the limit law has corrections of order mu / Gx).
MU_OVER_GX = 0.02

CASE = Case(
    name="mp_heavy_sliding",
    group="material_point",
    title="Drift ratio V in heavy sliding (mu/Gx = 0.02, settled) against the limit law V = cos(phi0), "
    "2 phi0 - pi = 2 Gz sin(phi0), Gz = 0.05..0.95; value: max |V/V_limit - 1|",
    tolerance=0.02,
    quick=True,
)


def run(quick: bool = False) -> CaseResult:
    """Run the settled drift at 19 Gz values (7 in quick mode) and plot it over the curve."""
    gzs = np.linspace(0.05, 0.95, 7 if quick else 19)
    got = []
    for gz in gzs:
        res = sd.run(point_scene(float(gz), MU / MU_OVER_GX, periods=40, measure_periods=10,
                                 settle=True, settle_tolerance=1e-6))
        got.append(res.drift_ratio)
    got_a = np.array(got)
    want = np.array([heavy_sliding_v(float(g)) for g in gzs])
    rel = np.abs(got_a / want - 1.0)
    worst = float(rel.max())
    return CASE.result(
        worst,
        require=bool(np.all(got_a < 0.0)),
        message=f"{gzs.size} values of Gz, all against the wave: {bool(np.all(got_a < 0))}; worst at "
        f"Gz = {gzs[int(rel.argmax())]:.2f} (V = {got_a[int(rel.argmax())]:.4f}, limit "
        f"{want[int(rel.argmax())]:.4f})",
        figure=_figure(gzs, got_a),
        details={"gz": gzs, "drift_ratio": got_a, "limit": want},
    )


def _figure(gzs: np.ndarray, got: np.ndarray):
    import matplotlib.pyplot as plt

    fine = np.linspace(0.0, 1.0, 201)
    fig, ax = plt.subplots(figsize=(5.2, 3.8), layout="constrained")
    ax.plot(fine, [heavy_sliding_v(float(g)) for g in fine], "k-", lw=1.2,
            label="limit law V(Gz), mu/Gx -> 0")
    ax.plot(gzs, got, "o", color="#e6550d", ms=5, label=f"material point, mu/Gx = {MU_OVER_GX}")
    ax.axhline(0.0, color="0.7", lw=0.8)
    ax.set_xlabel("Gz = 4 pi^2 m* A*")
    ax.set_ylabel("drift ratio V = <x*'> / (2 pi r A*)")
    ax.set_title("Heavy sliding: drift against the wave", fontsize=10)
    ax.legend(fontsize=8)
    return fig
