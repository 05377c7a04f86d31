"""The completely inelastic bouncing ball: its thresholds located on a bifurcation diagram.

The material point with restitution 0 under vertical vibration alone (r = 0) is the completely
inelastic bouncing ball; with Gamma = 4 pi^2 m* A* (m* = 1/(4 pi^2), so A* = Gamma) it lifts off
at Gamma = 1, its period-1 motion loses the phase in which it rests on the surface at
sqrt(1 + pi^2) = 3.2969, and that motion doubles its period at sqrt(4 + pi^2) = 3.7242, where the
multiplier 1 - sqrt(Gamma^2 - pi^2) of the map of take-off phases reaches -1 (Mehta and Luck,
Phys. Rev. Lett. 65, 393, 1990; derived in docs/physics.md, "The inelastic bouncing ball"). The
diagram (21 values, continuation upwards) locates each by bisection to 1e-4 relative.
"""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.study.bifurcation import bifurcation
from sawdrift.validation import Case, CaseResult

EXACT = {"lift_off": 1.0, "sticking_lost": math.sqrt(1.0 + math.pi**2),
         "period_doubling": math.sqrt(4.0 + math.pi**2)}

CASE = Case(
    name="inelastic_bouncing_ball",
    group="bifurcation",
    title="Completely inelastic bouncing ball (material point, e = 0, r = 0): lift-off at "
    "Gamma = 1, loss of the sticking phase at sqrt(1 + pi^2), first period doubling at "
    "sqrt(4 + pi^2), located on the bifurcation diagram; value: largest |located - exact|",
    tolerance=1e-3,
    quick=True,
)


def run() -> CaseResult:
    """Locate the three thresholds and compare."""
    scene = sd.Scene(model="material_point", particle={"m_star": 1.0 / (4.0 * math.pi**2)},
                     drive={"horizontal_ratio": 0.0})
    res = bifurcation(scene, "drive.amplitude", "lin:0.5:4.5:21", samples=32, locate=True,
                      tolerance=1e-4, workers=1, progress=False)
    found = {kind: [b["value"] for b in res.bifurcations if b["kind"] == kind and b["located"]]
             for kind in EXACT}
    errors = {kind: abs(v[0] - EXACT[kind]) if len(v) == 1 else math.inf
              for kind, v in found.items()}
    worst = max(errors, key=errors.get)
    return CASE.result(
        max(errors.values()),
        require=all(len(v) == 1 for v in found.values()),
        message="; ".join(f"{k.replace('_', ' ')} at {found[k][0]:.5f} (exact {EXACT[k]:.5f})"
                          if found[k] else f"{k} not found" for k in EXACT)
        + f"; worst: {worst}",
        figure=_figure(res),
        details={"located": found, "exact": EXACT, "bifurcations": res.bifurcations},
    )


def _figure(res):
    from sawdrift.report.bifurcation_plot import plot_bifurcation

    fig = plot_bifurcation(res, title="Completely inelastic bouncing ball (A* = Gamma)")
    for ax in fig.axes:
        for value in EXACT.values():
            ax.axvline(value, color="k", lw=0.5, alpha=0.4)
    return fig
