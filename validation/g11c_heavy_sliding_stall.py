"""The load curve of the point in heavy sliding, and its stall load 2 mu Gz / pi.

When mu / Gx -> 0 the point slides all the time at a nearly constant V = U cos(phi0),
U = 2 pi r A*; under a load L the period-averaged force vanishes where
2 phi0 - pi = 2 Gz sin(phi0) - pi L / mu (docs/physics.md, "Loads, inclines and restitution"),
so the particle stops (phi0 = pi/2) at the stall load L_s = 2 mu Gz / pi. The load curve
(:func:`sawdrift.study.load_curve.load_curve`) brackets the stall by k-section and samples the
speed up to it. Value: the largest relative difference between the stall load found and
2 mu Gz / pi at three Gz (mu / Gx = 0.02, whose corrections are of that order, as in the
unloaded heavy-sliding case).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from sawdrift.study.load_curve import load_curve
from sawdrift.validation import Case, CaseResult, point_scene

MU = 0.1
MU_OVER_GX = 0.02
GZS = (0.3, 0.6, 0.9)

CASE = Case(
    name="heavy_sliding_stall",
    group="loads",
    title="Point in heavy sliding (mu/Gx = 0.02) under a load: stall load against 2 mu Gz / pi "
    "and the curve V(L) against cos(phi0), 2 phi0 - pi = 2 Gz sin(phi0) - pi L / mu (Gz = 0.3, "
    "0.6, 0.9); value: max relative stall error",
    tolerance=0.02,
    quick=True,
)


def limit_ratio(gz: float, load_over_mu: float) -> float:
    """V / U in heavy sliding under the load L = load_over_mu mu."""
    phi0 = brentq(lambda p: 2 * p - math.pi - 2 * gz * math.sin(p) + math.pi * load_over_mu,
                  0.0, math.pi)
    return math.cos(phi0)


def run(quick: bool = False) -> CaseResult:
    """A 6-point load curve at each Gz (one Gz in quick mode)."""
    gzs = GZS[1:2] if quick else GZS
    worst, curves, parts, curve_err = 0.0, [], [], 0.0
    for gz in gzs:
        scene = point_scene(gz, MU / MU_OVER_GX, mu=MU, periods=40, measure_periods=10,
                            settle=True, settle_tolerance=1e-6)
        curve = load_curve(scene, loads=6, workers=1)
        u = 2 * math.pi * scene.horizontal_ratio * scene.drive.amplitude
        stall = 2 * MU * gz / math.pi
        rel = abs(curve.stall_load / stall - 1.0)
        worst = max(worst, rel)
        # the applied load is +F (against the drift to -x)
        got = curve.velocities / u
        want = np.array([-limit_ratio(gz, f / MU) for f in curve.loads])
        curve_err = max(curve_err, float(np.max(np.abs(got - want))))
        curves.append((gz, curve.loads, got, stall))
        parts.append(f"Gz = {gz:g}: stall {curve.stall_load:.5f} (2 mu Gz/pi = {stall:.5f}), "
                     f"{curve.runs} runs")
    return CASE.result(
        worst,
        require=curve_err < 0.01,
        message="; ".join(parts) + f"; curve V/U within {curve_err:.1e} of cos(phi0)",
        figure=_figure(curves),
        details={"curve_error": curve_err},
    )


def _figure(curves):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5.2, 3.8), layout="constrained")
    for gz, loads, got, stall in curves:
        fine = np.linspace(0.0, stall, 101)
        line, = ax.plot(fine / MU, [-limit_ratio(gz, f / MU) for f in fine], "-", lw=1.0)
        ax.plot(loads / MU, got, "o", color=line.get_color(), ms=5, label=f"Gz = {gz:g}")
        ax.axvline(stall / MU, color=line.get_color(), ls=":", lw=0.8)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("load L / mu (against the drift)")
    ax.set_ylabel("speed along the drift, |V| / (2 pi r A*)")
    ax.set_title("Heavy sliding under a load: points load_curve, lines the limit law;\n"
                 "dotted: stall load 2 mu Gz / pi", fontsize=9)
    ax.legend(fontsize=8)
    return fig
