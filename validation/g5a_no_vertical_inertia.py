"""The later paper's claim (Terzi et al., arXiv 2511.21528): a point mass in permanent contact
does not drift. It holds when the point's normal force is constant, N* = 1 (vertical inertia
switched off); docs/physics.md.

Scene: Gz = 0.5 (permanent contact), mu/Gx = 0.05 (sliding), m* = 0.1, 100 periods.
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.validation import MU, NU, Case, CaseResult

GZ = 0.5
MU_OVER_GX = 0.05

CASE = Case(
    name="point_mass_no_drift",
    group="point_mass",
    title="Material point in permanent contact with vertical inertia off (N* = 1): no drift after "
    "100 periods; value: |V|",
    tolerance=1e-6,
    quick=True,
)


def scene(vertical_inertia: bool) -> sd.Scene:
    """The scene of both group-5 cases, with the point's vertical inertia on or off."""
    m_star = 0.1
    return sd.Scene(
        model="material_point",
        material={"mu": MU, "nu": NU},
        particle={"m_star": m_star},
        drive={"amplitude": GZ / (4 * math.pi**2 * m_star), "horizontal_ratio": (MU / MU_OVER_GX) / GZ},
        numerics={"periods": 100},
        effects={"vertical_inertia": vertical_inertia},
    )


def run() -> CaseResult:
    """Run with inertia off (and on, for the figure)."""
    off = sd.run(scene(False), trajectory=True)
    on = sd.run(scene(True), trajectory=True)
    n_const = bool(np.allclose(off.trajectory["N_star"], 1.0, atol=1e-12))
    return CASE.result(
        abs(off.drift_ratio),
        require=n_const and not off.contact_lost,
        message=f"inertia off: V = {off.drift_ratio:.2e}, N* = 1 throughout: {n_const}, contact kept: "
        f"{not off.contact_lost}; inertia on (eq. 5 as written): V = {on.drift_ratio:.4f}",
        figure=_figure(on, off),
    )


def _figure(on: sd.Result, off: sd.Result):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5.4, 3.6), layout="constrained")
    speed = 2 * math.pi * on.horizontal_ratio * on.amplitude
    for res, label, colour in ((on, "vertical inertia on (paper eq. 5)", "#e6550d"),
                               (off, "vertical inertia off (N* = 1)", "#3182bd")):
        tr = res.trajectory
        ax.plot(tr["t"], tr["x"] / speed, color=colour, lw=1.0, label=f"{label}: V = {res.drift_ratio:.3g}")
    ax.axvline(on.ramp_periods, color="0.6", ls=":", lw=0.8)
    ax.set_xlabel("t* (periods)")
    ax.set_ylabel("x* / (2 pi r A*)")
    ax.set_title("Point mass in permanent contact, Gz = 0.5, mu/Gx = 0.05", fontsize=10)
    ax.legend(fontsize=8)
    return fig
