"""A compliant model's bifurcation points converge as the time step shrinks.

mmd with viscous normal damping 0.3, m* = 0.1, mu = 0.1 and the Rayleigh ratio of nu = 0.3, along
A* from 0.3 to 1.2: the particle lifts off (a grazing of a* = 0), loses its period, and passes a
window of period 2. Every change between neighbouring values is located by bisection (1e-4
relative) at 512 and at 1024 steps per period; the same changes must be found at both, at the
same places. The value is the largest relative difference between the two located points.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.study.bifurcation import bifurcation
from sawdrift.validation import Case, CaseResult

STEPS = (512, 1024)

CASE = Case(
    name="bifurcation_step_convergence",
    group="bifurcation",
    title="mmd (normal damping 0.3, m* = 0.1): the located lift-off and changes of period along "
    "A* in [0.3, 1.2] at 512 and at 1024 steps per period; value: largest relative difference",
    tolerance=3e-3,
)


def _located(steps: int) -> list[dict]:
    scene = sd.Scene(model="mmd", particle={"m_star": 0.1}, effects={"normal_damping": 0.3},
                     numerics={"steps_per_period": steps})
    res = bifurcation(scene, "drive.amplitude", "lin:0.3:1.2:10", samples=32, locate=True,
                      tolerance=1e-4, workers=1, progress=False)
    return [b for b in res.bifurcations if b["located"]]


def run() -> CaseResult:
    """Locate at both resolutions and compare kind by kind, in order."""
    coarse, fine = (_located(n) for n in STEPS)
    same = [(a["kind"], a["from_period"], a["to_period"]) for a in coarse] == [
        (b["kind"], b["from_period"], b["to_period"]) for b in fine]
    rel = [abs(a["value"] / b["value"] - 1.0) for a, b in zip(coarse, fine, strict=False)]
    value = max(rel) if same and rel else float("inf")
    lines = [f"{a['kind']} {a['from_period']}->{a['to_period']}: {a['value']:.6f} / {b['value']:.6f}"
             for a, b in zip(coarse, fine, strict=False)]
    return CASE.result(
        value,
        require=same and len(coarse) >= 2,
        message=f"{len(coarse)} changes at {STEPS[0]} and {len(fine)} at {STEPS[1]} steps per "
        "period (A* located): " + "; ".join(lines),
        details={"coarse": coarse, "fine": fine},
    )
