"""Steady drift of heavy particles: ``numerics.settle`` against brute-force runs.

A heavy particle reaches its steady drift only after of order m*/mu periods. The settled run
(reduced horizontal inertia plus a criterion that follows the approach) must agree with a plain
run of 40 m*/mu + 2000 periods, measured over its last 30 %, within 1 %, and say
``settled = true``. The quick subset runs the cheapest cell only.
"""

from __future__ import annotations

import numpy as np

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

#: (m*, A*, mu) cells with a clear drift; the first is the quick one
CELLS = [(30.0, 0.7, 0.3), (300.0, 0.7, 0.3), (300.0, 0.25, 0.1), (3000.0, 0.6, 0.3)]

CASE = Case(
    name="settle_vs_brute_force",
    group="steady",
    title="mmd, m* = 30 to 3000: settled drift ratio against brute-force runs of 40 m*/mu + 2000 "
    "periods; value: max relative difference",
    tolerance=0.01,
    quick=True,
)


def _scene(m: float, a: float, mu: float, **numerics) -> sd.Scene:
    return sd.Scene(model="mmd", particle={"m_star": m}, material={"mu": mu},
                    drive={"amplitude": a}, numerics=numerics)


def run(quick: bool = False) -> CaseResult:
    """Run each cell both ways."""
    cells = CELLS[:1] if quick else CELLS
    brute, settled, flags, periods = [], [], [], []
    for m, a, mu in cells:
        n = int(40 * m / mu) + 2000
        ref = sd.run(_scene(m, a, mu, periods=n, measure_periods=int(0.3 * n), max_periods=n))
        res = sd.run(_scene(m, a, mu, settle=True, max_periods=1e6))
        brute.append(ref.drift_ratio)
        settled.append(res.drift_ratio)
        flags.append(bool(res.settled))
        periods.append((n, res.settle_periods))
    b, s = np.array(brute), np.array(settled)
    rel = np.abs(s / b - 1.0)
    worst = int(rel.argmax())
    return CASE.result(
        float(rel.max()),
        require=all(flags) and bool(np.all(np.abs(b) > 0.05)),
        message=f"{len(cells)} cells, all settled: {all(flags)}; worst at m* = {cells[worst][0]:g}, "
        f"A* = {cells[worst][1]:g}, mu = {cells[worst][2]:g} (settled {s[worst]:.5f} in "
        f"{periods[worst][1]:.0f} periods, brute force {b[worst]:.5f} in {periods[worst][0]} "
        "periods)",
        figure=_figure(cells, b, s),
        details={"cells": cells, "brute": b, "settled": s, "periods": periods},
    )


def _figure(cells, brute: np.ndarray, settled: np.ndarray):
    import matplotlib.pyplot as plt

    x = np.arange(len(cells))
    fig, ax = plt.subplots(figsize=(5.2, 3.6), layout="constrained")
    ax.axhspan(-1.0, 1.0, color="0.9", label="tolerance, 1 %")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.plot(x, 100.0 * (settled / brute - 1.0), "o", color="#e6550d", ms=7,
            label="numerics.settle vs brute force")
    for xi, b in zip(x, brute, strict=True):
        ax.annotate(f"V = {b:.4f}", (xi, 0.0), textcoords="offset points", xytext=(0, -14),
                    ha="center", fontsize=7)
    ax.set_xticks(x, [f"m* {m:g}\nA* {a:g}, mu {mu:g}" for m, a, mu in cells], fontsize=8)
    ax.set_xlim(-0.5, len(cells) - 0.5)
    ax.set_ylim(-1.5, 1.5)
    ax.set_ylabel("settled / brute force - 1 (%)")
    ax.set_title("Steady drift of heavy particles (brute force: 40 m*/mu + 2000 periods)",
                 fontsize=9)
    ax.legend(fontsize=8, loc="upper right")
    return fig
