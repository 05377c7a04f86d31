"""The backward wave's phase psi moves every zero of the field by -psi / (4 pi) wavelengths.

Every local quantity depends on 4 pi xi + psi (U_y = A* e^{-2 pi i xi} (1 + s e^{i (4 pi xi +
psi)}), likewise U_x), so the field at psi is the field at 0 shifted by -psi / (4 pi). mmd,
m* = 0.1, s = 0.5, settled, 16 positions with two regula-falsi runs per zero, psi = 50 and 130
degrees. Value: the largest distance (wavelengths, modulo 1/2) between a zero and the shifted zero
of the same kind at psi = 0.
"""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.study.field import PERIOD, drift_field
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="phase_moves_traps",
    group="fields",
    title="psi moves every trap and repeller by -psi/(4 pi) wavelengths (mmd, m* = 0.1, s = 0.5, "
    "psi = 50, 130 deg); value: largest miss in wavelengths",
    tolerance=1e-3,
    quick=False,
)


def run() -> CaseResult:
    """Fields at psi = 0, 50 and 130 degrees."""
    base = sd.Scene(model="mmd", particle={"m_star": 0.1}, numerics={"settle": True},
                    drive={"backward": 0.5})
    ref = drift_field(base, 16).fields[0]
    worst, same = 0.0, bool(ref.zeros)
    for psi in (50.0, 130.0):
        fld = drift_field(base.with_updates(**{"drive.backward_phase": psi}), 16).fields[0]
        same = same and len(fld.zeros) == len(ref.zeros)
        for z in ref.zeros:
            moved = z["position"] - math.radians(psi) / (4.0 * math.pi)
            near = min(fld.zeros, key=lambda q: abs(math.remainder(q["position"] - moved, PERIOD)))
            same = same and near["kind"] == z["kind"]
            worst = max(worst, abs(math.remainder(near["position"] - moved, PERIOD)))
    return CASE.result(worst, require=same,
                       message="zeros at psi = 0: " + ", ".join(
                           f"{z['kind']} {z['position']:.5f}" for z in ref.zeros))
