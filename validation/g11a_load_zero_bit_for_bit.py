"""particle.load = 0 leaves every run as it was, to the last bit (a pinned snapshot).

The load enters both schemes only where it is not zero (the compliant loop's x* equation, the
rigid scheme's stick bound, slip and flight closed forms, a rolling sphere's rolling angle), so
with load 0 they must do exactly the arithmetic of the code before loads existed. The drift
velocities below were computed by that code (commit 1fb3e4f, "Drives as parts") for every
built-in model, with and without rotation, and retaken only where a later change of a law or a
scheme moved them, each with its reason and size below: the values pin the loops' arithmetic, so
a change of the load's path (or any unannounced one) shows. The load's own effect is tested
against closed forms (g11b, g11c, g11e) and by the mirror symmetry of tests/test_loads.py.
Value: the number of runs whose drift velocity differs in any bit.
"""

from __future__ import annotations

from typing import Any

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

#: (scene, drift velocity as float.hex) by the code before loads (commit 1fb3e4f); mdr and jaeger
#: recomputed at 668d660: mdr's N* is the profile's (7.5e-7), jaeger's N* is rounded as
#: z N*'/p (3.4e-15); the rigid rolling sphere recomputed when the rigid scheme's state became the
#: centre x (it stored the contact point c x; now x = s / c after each step and s = c x before it,
#: a rounding per step: 1.5e-13 relative); the hopping material point recomputed when the rigid
#: scheme's lift-off threshold went from N* < -1e-6 to N* < -1e-9 (its lift-offs now fall where
#: N* crosses 0 to 1e-9, not 1e-6: 1.0e-13 relative; with the old threshold the new code gives
#: the old bits); the hopping jaeger and hertz_mindlin_dem runs recomputed when free flights went
#: to closed form (a flight's steps after its 8th are the parabola evaluated, not stepped, which
#: rounds differently: 7e-15 and 4e-15 relative; tests/test_flight.py holds the closed form to
#: the scheme step by step); all but the rigid rolling sphere recomputed when the wave's phase at
#: the steps came from a table of one period (sin and cos of 2 pi j / K, exact, instead of
#: sin(2 pi t*) with t*'s rounding: 3e-15 to 1.2e-14 relative over the 60 periods); mdr
#: recomputed when its T* went on the scale of N*(a*) (its strips' quadrature of N* falls short
#: by O(dz^2), and full sliding stopped short of |T*| = N*): -7.2e-7 relative, 1.05e-5 from mmd
#: before, 9.8e-6 after
BEFORE_LOADS: dict[str, tuple[dict[str, Any], str]] = {
    "mmd": ({}, "0x1.ea8d96206868dp-2"),
    "mdr": ({"model": "mdr"}, "0x1.ea8ed234d142fp-2"),
    "jaeger": ({"model": "jaeger", "particle": {"m_star": 0.3}, "drive": {"amplitude": 0.8}},
               "0x1.b61261c04d8e8p+0"),
    "hertz_mindlin_dem": ({"model": "hertz_mindlin_dem", "particle": {"m_star": 1.0},
                           "drive": {"amplitude": 1.2}}, "0x1.4a6f5f538db4cp+1"),
    "material_point": ({"model": "material_point", "particle": {"m_star": 0.1},
                        "drive": {"amplitude": 0.6}}, "-0x1.4432c8c98beccp+0"),
    "mmd, rotation": ({"effects": {"rotation": True}, "particle": {"m_star": 0.5}},
                      "0x1.9df66134a7e86p-4"),
    "material_point, rotation": ({"model": "material_point", "effects": {"rotation": True},
                                  "particle": {"m_star": 0.3}, "drive": {"amplitude": 0.3}},
                                 "0x1.521e8624de78bp-3"),
}

CASE = Case(
    name="load_zero_bit_for_bit",
    group="loads",
    title="particle.load = 0 leaves the loops' arithmetic as it was: drifts pinned bit for bit "
    "(taken by the code before loads existed, retaken only where a documented change of a law or "
    "a scheme moved them; five models, rotation on and off); value: number of runs that differ",
    tolerance=0.0,
    quick=True,
)


def run() -> CaseResult:
    """Run each scene with an explicit load 0 and compare the drift's bits."""
    differ, parts = [], []
    for name, (data, before) in BEFORE_LOADS.items():
        particle = {**data.get("particle", {}), "load": 0.0}
        # the fixed 60-period run the hexes were taken from (the default now runs on to a
        # periodic orbit or a chaotic cell's long-time mean: what is reported, not the loops)
        got = sd.run(sd.Scene(**{**data, "particle": particle,
                                 "numerics": {"settle": False}})).drift_velocity
        if got.hex() != before:
            differ.append(name)
        parts.append(f"{name}: {got:.17g}")
    return CASE.result(
        float(len(differ)),
        message=f"{len(BEFORE_LOADS)} runs, {len(differ)} differ"
        + (f" ({', '.join(differ)})" if differ else "") + "; " + "; ".join(parts),
        details={"differ": differ},
    )
