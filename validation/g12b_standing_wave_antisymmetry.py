"""A standing wave (s = 1): the drift field is antisymmetric about xi = 1/4.

With s = 1 the local orbit at 1/4 + d is the mirror (x -> -x) of the one at 1/4 - d, shifted
by half a period: U_y = 2 A* cos(2 pi xi), U_x = -2 i r A* e^{i phi0} sin(2 pi xi). So
V(1/4 + d) = -V(1/4 - d), with zeros at 0 (vertical vibration) and 1/4 (horizontal only). mmd,
m* = 0.1, A* = 0.2, settled, 16 positions. Value: max |V(1/4 + d) + V(1/4 - d)| / (2 pi r A*),
against twice the settle tolerance; required: a trap at 0 and a repeller at 1/4 (prograde orbit).
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.study.field import drift_field
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="standing_wave_antisymmetry",
    group="fields",
    title="s = 1: V(1/4 + d) = -V(1/4 - d) (mirror orbits), trap at 0 and repeller at 1/4 "
    "(mmd, m* = 0.1, A* = 0.2); value: max |V(1/4 + d) + V(1/4 - d)| / (2 pi r A*)",
    tolerance=2e-3,
    quick=True,
)


def run() -> CaseResult:
    """A 16-point settled field of the standing wave."""
    scene = sd.Scene(model="mmd", particle={"m_star": 0.1}, numerics={"settle": True},
                     drive={"backward": 1.0, "amplitude": 0.2})
    fld = drift_field(scene, 16).fields[0]
    v = fld.drift_velocity
    speed = 2.0 * math.pi * scene.horizontal_ratio * 0.2
    pairs = [abs(v[8 - k] + v[8 + k]) for k in range(1, 8)] + [abs(2.0 * v[0])]
    kinds = {round(z["position"], 6): z["kind"] for z in fld.zeros}
    return CASE.result(float(np.max(pairs)) / speed,
                       require=kinds == {0.0: "trap", 0.25: "repeller"},
                       message=f"zeros {kinds}; largest |V| {np.max(np.abs(v)):.4g}")
