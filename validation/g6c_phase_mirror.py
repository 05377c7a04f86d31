"""Any local orbit: phase + 180 degrees is the mirror x -> -x, and +-90 are the named orbits.

u_x = r A* R(t*) cos(2 pi t* + phase). Adding 180 degrees negates u_x exactly; the contact laws
are odd in b*, so the whole motion is mirrored and the drift changes sign to the last bit, for
every model. phase = 90 is the prograde orbit of eq. 1 as printed and -90 the retrograde one,
also to the last bit. Value: the number of (model, check) pairs that are not exact.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.validation import COMPLIANT_MODELS, Case, CaseResult

CASE = Case(
    name="phase_mirror",
    group="device",
    title="phase + 180 deg mirrors the drift exactly, and phase +-90 are the prograde and "
    "retrograde orbits bit for bit, for every model (m* = 0.1, A* = 0.5, phase 30 deg); value: "
    "the number of checks that are not exact",
    tolerance=0.0,
    quick=True,
)


def _drift(model: str, **drive: object) -> float:
    scene = sd.Scene(model=model, particle={"m_star": 0.1},
                     drive={"amplitude": 0.5, **drive}, numerics={"periods": 30})
    return sd.run(scene).drift_velocity


def run() -> CaseResult:
    """Five models, three checks each."""
    misses = []
    for model in ("material_point", *COMPLIANT_MODELS):
        a, b = _drift(model, phase=30.0), _drift(model, phase=210.0)
        if not (a != 0.0 and b == -a):
            misses.append(f"{model}: phase 30 -> {a!r}, 210 -> {b!r}")
        for phase, orbit in ((90.0, "prograde"), (-90.0, "retrograde")):
            if _drift(model, phase=phase) != _drift(model, orbit=orbit):
                misses.append(f"{model}: phase {phase:g} differs from {orbit}")
    return CASE.result(float(len(misses)),
                       message="; ".join(misses) or "all 15 checks exact (mirror drifts "
                       "negated to the bit, phase +-90 identical to the named orbits)")
