"""LAMMPS pair granular jkr with tangential mindlin_rescale/force against the native adhesive DEM.

The silica sphere of examples/micro_silica_on_linbo3.toml (radius 5 um, 10 um diameter; JKR,
w = 0.05 J/m^2, 20 MHz) in
the wall frame of :mod:`sawdrift.lammps.adhesion` (a still zplane wall, the wall's inertial force
on the particle) against ``hertz_mindlin_dem`` with the JKR contact broken at the pull-off
overlap, as LAMMPS breaks it; 60-period fixed runs. Values: the relative difference of the drift
at 0.01 nm, and of the removal amplitude (out of contact over the run's second half) located by
bisection in each engine between 0.02 and 0.2 nm (10 halvings, 0.1 % of the bracket).
"""

from __future__ import annotations

import math

from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="lammps_adhesion",
    group="adhesion",
    title="LAMMPS jkr + mindlin_rescale/force (wall frame) against the native adhesive DEM on the "
    "silica example: drift at 0.01 nm and removal amplitude, relative differences",
    tolerance=0.01,
    quick=False,
)


def run() -> CaseResult:
    """Drift and removal in both engines."""
    from pathlib import Path

    from sawdrift.lammps import LammpsUnavailableError
    from sawdrift.lammps.adhesion import compare
    from sawdrift.scene.schema import Scene

    # a copy of examples/micro_silica_on_linbo3.toml that ships with the cases (an installed
    # wheel has no examples/; tests/test_validation.py holds the two equal)
    base = Scene.from_toml(Path(__file__).resolve().parent / "data" / "micro_silica_on_linbo3.toml")

    def at(amp: float) -> dict:
        return compare(base.with_updates(**{"device.amplitude": amp}), periods=60)

    try:
        held = at(1e-11)
    except LammpsUnavailableError as exc:
        return CASE.skip(str(exc))
    drift_err = abs(held["drift_lammps"] / held["drift_native"] - 1.0)
    found = {}
    for engine in ("lammps", "native"):
        lo, hi = 2e-11, 2e-10
        for _ in range(10):
            mid = math.sqrt(lo * hi)
            lo, hi = (lo, mid) if at(mid)[f"removed_{engine}"] else (mid, hi)
        found[engine] = math.sqrt(lo * hi)
    removal_err = abs(found["lammps"] / found["native"] - 1.0)
    return CASE.result(max(drift_err, removal_err),
                       message=(f"drift at 0.01 nm: LAMMPS {held['drift_lammps']:.6g}, native "
                                f"{held['drift_native']:.6g} a0 f ({drift_err:.1e}); removal: "
                                f"LAMMPS {found['lammps'] * 1e9:.4f} nm, native "
                                f"{found['native'] * 1e9:.4f} nm ({removal_err:.1e})"),
                       details={"drift": drift_err, "removal": removal_err, **found})
