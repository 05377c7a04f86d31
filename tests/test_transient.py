"""An irregular transient that ends on a periodic orbit within the long-time mean's budget is
reported as the orbit, settled, not as the mean of its wandering.

References: fixed runs long past the transient, measured over a whole number of orbits (the
drift over whole orbits of an exact periodic orbit is its long-time drift).
"""

from __future__ import annotations

import numpy as np

import sawdrift as sd


def _point(m: float, a: float, **numerics) -> sd.Result:
    return sd.run(sd.Scene(model="material_point", particle={"m_star": m},
                           drive={"amplitude": a}, numerics=numerics))


def test_a_wandering_rigid_point_that_locks_onto_a_long_orbit_reports_the_orbit():
    """m* = 0.9, A* = 1.71, mu = 0.1: irregular for about a thousand periods, then an orbit of
    26 periods. The long-time mean over the wandering gave 0.0635 +- 0.0061, 2.8 errors from the
    orbit's 0.046173 (brute force over 2000 and 4000 periods, 0.0461727 both)."""
    m, a = 0.9, 1.7105086610184825
    ref = _point(m, a, settle=False, periods=3000, measure_periods=1300)  # 50 orbits
    res = _point(m, a)
    assert ref.orbit_period == 26
    assert res.settled is True and res.settle_method == "mean_then_orbit"
    assert res.orbit_period == 26 and res.regime == "bouncing"  # longer than a hop (24)
    assert res.drift_ratio_se != res.drift_ratio_se  # NaN: a settled orbit, not a mean
    assert abs(res.drift_ratio - ref.drift_ratio) <= 1e-9 * abs(ref.drift_ratio)
    assert res.measure_periods % 26 == 0 and res.measure_periods >= 2 * 26


def test_a_transient_that_ends_on_a_short_orbit_is_a_hop_of_that_period():
    """m* = 7.08, A* = 0.0478: bouncing irregularly over the fixed run's window (0.652), then an
    orbit of 20 periods with 8 lift-offs, at 0.66618114. Brute force from rest: 0.6661811 over
    periods 2416 to 4832 and 4832 to 9664. (Its stroboscopic state repeats to 1e-8, while the
    heavy point's speed still creeps at the 1e-7 level: runs of 1200 to 8000 periods find
    "orbits" of 40 to 380 periods with drifts within 5e-8 of each other.) It was settled after
    627 periods by a long-time mean that ended on the orbit; its full-inertia windows now settle
    on the orbit once one of them ends on it, after 330."""
    m, a = 7.0804851318975786, 0.04775936373660705
    ref = _point(m, a, settle=False, periods=4832, measure_periods=2416)
    res = _point(m, a)
    assert res.settled is True and res.settle_method == "fixed_then_windows"
    assert res.settle_periods <= 400
    assert res.regime == "hopping" and res.hop_period == 20 and res.orbit_period == 20
    assert res.liftoffs_per_hop == len(res.liftoff_phases) == 8
    assert res.chaotic is False
    assert abs(res.drift_ratio - ref.drift_ratio) <= 1e-6 * abs(ref.drift_ratio)


def test_a_run_recording_its_trajectory_gives_the_same_orbit_and_ends_its_path_on_it():
    """The orbit is run on the copy the mean ran on: a run recording its trajectory reports the
    same settled orbit, and its trajectory is its own up to its window, then the orbit window's
    rows (the mean's periods between them are not recorded), so that its last periods show the
    orbit the run reports."""
    m, a = 0.9, 1.7105086610184825
    res = _point(m, a)
    traced = sd.run(sd.Scene(model="material_point", particle={"m_star": m},
                             drive={"amplitude": a}), trajectory=True)
    assert traced.settled is True and traced.settle_method == "mean_then_orbit"
    assert traced.drift_ratio == res.drift_ratio
    t = traced.trajectory["t"].to_numpy()
    x = traced.trajectory["x"].to_numpy()
    assert abs(t[-1] - traced.periods) < 1e-6
    start = traced.periods - traced.measure_periods
    i0 = int(np.flatnonzero(t >= start - 1e-9)[0])
    assert t[i0] - start < 0.01  # the orbit window's first row (one step in)
    assert np.diff(t).max() > 100.0  # the long-time mean's periods, not recorded
    # the drift over one orbit of the recorded window, from any phase, is the reported one
    p = traced.orbit_period
    i1 = int(np.argmin(np.abs(t - (t[i0] + p))))
    assert abs(t[i1] - t[i0] - p) < 1e-9
    speed = 2 * np.pi * abs(traced.horizontal_ratio) * a
    assert abs((x[i1] - x[i0]) / p / speed - traced.drift_ratio) < 1e-9
