"""A light contact near a vertical resonance that stopped sliding may slide again a slow beat
later: its held windows do not settle it as sticking.

References: the beat period in closed form, and a brute-force run of 4000 periods.
"""

from __future__ import annotations

import math

import sawdrift as sd
from sawdrift.dynamics.slip_return import vertical_beat


def test_the_vertical_beat_is_the_distance_of_the_free_frequency_from_its_nearest_harmonic():
    # f = sqrt(1.5 / m*) / (2 pi) = 4.01: a beat of 1 / 0.01 = 100 periods
    m = 1.5 / (2 * math.pi * 4.01) ** 2
    assert abs(vertical_beat(m) - 100.0) < 1e-6
    # f = 2.75: the nearest harmonic is 3, a beat of 4 periods; below 1 the nearest is 1
    assert abs(vertical_beat(1.5 / (2 * math.pi * 2.75) ** 2) - 4.0) < 1e-9
    assert abs(vertical_beat(1.5 / (2 * math.pi * 0.2) ** 2) - 1.25) < 1e-9
    assert vertical_beat(0.01, rigid=True) == 0.0


def test_a_hold_between_two_slips_near_a_vertical_resonance_is_not_settled_as_sticking():
    """mmd m* = 0.00237, A* = 1.26: the free vertical frequency 4.003 beats against the fourth
    harmonic over about 355 periods. The contact slides during the ramp and the first windows,
    holds from period 87 on (the run said settled, sticking, 9.7e-7, at period 114), and slides
    again from period 438: brute force over periods 2000 to 4000 is oscillating slip at -4.8e-4
    in drift ratio. The default run waits for two beats of holding, sees the slip come back and
    does not settle on the hold."""
    m, a = 0.002371373705661655, 1.2589254117941673
    assert 300.0 < vertical_beat(m) < 400.0
    brute = sd.run(sd.Scene(model="mmd", particle={"m_star": m}, drive={"amplitude": a},
                            numerics={"settle": False, "periods": 4000, "measure_periods": 2000,
                                      "max_periods": 4000}))
    assert brute.gross_slip_fraction > 0.0 and brute.drift_ratio < -2e-4
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": m}, drive={"amplitude": a}))
    assert not (res.settled and res.regime == "stick")
    assert not res.settled and any("slid again" in w and "beat" in w for w in res.warnings)
    assert res.gross_slip_fraction > 0.0 and res.drift_ratio < -2e-4
    assert res.periods > 438  # it ran past the slip's return
