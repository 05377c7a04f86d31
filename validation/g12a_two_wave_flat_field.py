"""Two waves with s = 0 are the travelling wave: the drift field is flat at the single-wave drift.

With no backward wave the local orbit at xi is the travelling wave's, shifted in time by xi
periods (U = A* e^{-2 pi i xi}), so the steady drift is the same everywhere. mmd, m* = 0.1,
A* = 0.316, settled, 8 positions over the field's period. Value: the largest |V(xi) - V_single|
over the forward wave's horizontal speed 2 pi r A*, against the settle tolerance 1e-3.
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.study.field import drift_field
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="two_wave_flat_field",
    group="fields",
    title="s = 0: the two-wave field equals the single travelling wave's settled drift at every "
    "position (mmd, m* = 0.1); value: max |V - V_single| / (2 pi r A*)",
    tolerance=1e-3,
    quick=True,
)


def run() -> CaseResult:
    """One single-wave run and an 8-point field with s = 0."""
    base = dict(model="mmd", particle={"m_star": 0.1}, numerics={"settle": True})
    single = sd.run(sd.Scene(**base))
    fld = drift_field(sd.Scene(**base, drive={"backward": 0.0}), 8).fields[0]
    speed = 2.0 * math.pi * sd.Scene().horizontal_ratio * 0.316
    dev = float(np.max(np.abs(fld.drift_velocity - single.drift_velocity)) / speed)
    return CASE.result(dev, require=not fld.zeros,
                       message=f"V_single = {single.drift_velocity:.6g}; field {fld.summary}")
