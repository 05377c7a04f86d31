"""Long periodic orbits, and irregular transients that end on one: the default run against
brute force.

A rigid point bouncing high can settle on a periodic orbit of tens of periods, which windows of
27 periods see as alternating drifts, and an irregular motion can wander for hundreds of periods
before it falls onto such an orbit for good (transient chaos). The default run finds the orbit
in a window long enough to hold it, or at the end of its long-time mean, and reports the drift
over whole orbits, settled. Brute force: a fixed run from rest of N = max(4000, 40 m*/mu + 2000)
periods measured over its last N/2 (by then every one of these cells is on its orbit). The value
is the largest relative difference; every default run must be settled on an orbit. The quick
subset runs the first cell only.
"""

from __future__ import annotations

import numpy as np

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

#: (m*, A*) of the material point (mu = 0.1): orbits of 54 (found in windows), 26 and 31 (the
#: end of a wandering transient), 20 (a transient ending on a hop of period 20), 38 and 88
#: (heavy points settled in windows)
CELLS = [
    (0.17545579636386113, 8.7),
    (0.9, 1.7105086610184825),
    (1.9859726716975712, 1.2355106192418572),
    (7.0804851318975786, 0.04775936373660705),
    (4.6348224236131665, 0.6445979091716645),
    (10.816653826391969, 0.6445979091716645),
]

CASE = Case(
    name="long_orbits_vs_brute_force",
    group="steady",
    title="material point, long periodic orbits and transients ending on one: default drift "
    "ratio against brute force over N = max(4000, 40 m*/mu + 2000) periods; value: max relative "
    "difference",
    tolerance=1e-6,
    quick=True,
)


def _scene(m: float, a: float, **numerics) -> sd.Scene:
    return sd.Scene(model="material_point", particle={"m_star": m}, drive={"amplitude": a},
                    numerics=numerics)


def run(quick: bool = False) -> CaseResult:
    """Run each cell by default and by brute force."""
    cells = CELLS[:1] if quick else CELLS
    rows = []
    for m, a in cells:
        n = max(4000, int(40 * m / 0.1) + 2000)
        ref = sd.run(_scene(m, a, settle=False, periods=n, measure_periods=n // 2, max_periods=n))
        res = sd.run(_scene(m, a))
        rows.append((ref.drift_ratio, res.drift_ratio, bool(res.settled), res.orbit_period,
                     res.settle_method, res.settle_periods, res.regime))
    b = np.array([r[0] for r in rows])
    d = np.array([r[1] for r in rows])
    rel = np.abs(d / b - 1.0)
    worst = int(rel.argmax())
    on_orbits = all(r[2] and r[3] > 0 for r in rows)
    w = rows[worst]
    return CASE.result(
        float(rel.max()),
        require=on_orbits,
        message=f"{len(cells)} cells, all settled on an orbit: {on_orbits} (orbits of "
        f"{', '.join(str(r[3]) for r in rows)} periods; "
        f"{sum(r[4] == 'mean_then_orbit' for r in rows)} found at the end of a long-time mean); "
        f"worst at m* = {cells[worst][0]:.4g}, A* = {cells[worst][1]:.4g}: {w[1]:.9f} "
        f"({w[6]}, {w[4]}, {w[5]:.0f} periods) against {w[0]:.9f}",
        figure=_figure(cells, rows, rel),
        details={"cells": cells, "brute": b, "default": d,
                 "orbits": [r[3] for r in rows], "methods": [r[4] for r in rows]},
    )


def _figure(cells, rows, rel: np.ndarray):
    import matplotlib.pyplot as plt

    x = np.arange(len(cells))
    fig, ax = plt.subplots(figsize=(5.6, 3.6), layout="constrained")
    ax.axhline(CASE.tolerance, color="0.5", ls="--", lw=0.9, label="tolerance, 1e-6")
    ax.semilogy(x, np.maximum(rel, 1e-16), "o", color="#e6550d", ms=7,
                label="|default / brute force - 1|")
    ax.set_xticks(x, [f"m* {m:.3g}\nA* {a:.3g}\norbit {r[3]}" for (m, a), r in
                      zip(cells, rows, strict=True)], fontsize=7)
    ax.set_ylim(1e-14, 1e-3)
    ax.set_ylabel("relative difference")
    ax.set_title("Long orbits and transients ending on one (material point)", fontsize=9)
    ax.legend(fontsize=8, loc="upper right")
    return fig
