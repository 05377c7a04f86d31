"""The periodic orbit of a heavy particle solved directly (sawdrift.dynamics.separated).

The orbit is checked against the integrator itself (placed on it, the run must stay on it: the
same displacement every period, the same state at every period's start), and the default runs
that start their windows at it against brute-force runs at full inertia from rest (no settle,
N >= 40 m*/mu + 2000 periods, measured over the last 30 %).
"""

from __future__ import annotations

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.contact.binding import model_for
from sawdrift.dynamics.assembly import assemble
from sawdrift.dynamics.full_inertia import full_window_length
from sawdrift.dynamics.separated import place_on_orbit, separated_orbit
from sawdrift.dynamics.stepper import Stepper
from sawdrift.dynamics.window import measure_window


def scene(m: float, a: float, mu: float, model: str = "mmd", **numerics) -> sd.Scene:
    return sd.Scene(model=model, particle={"m_star": m}, material={"mu": mu},
                    drive={"amplitude": a}, numerics=numerics)


def stepper_after_ramp(sc: sd.Scene) -> tuple[Stepper, float, np.ndarray]:
    model = model_for(sc)
    plan = assemble(sc, "compiled", model)
    st = Stepper(sc, model, plan, False)
    st.advance(20 * st.k_per)
    return st, plan.drive.horizontal_speed(sc), plan.drive.state_scale(sc)


def test_the_orbit_is_a_periodic_solution_of_the_run():
    """Placed on the orbit, the integrator repeats it: per-period displacement constant to 1e-9
    of itself over 40 periods, the height at each period's start to 1e-9, orbit period one."""
    sc = scene(1000.0, 0.3, 0.1)
    st, speed, scale = stepper_after_ramp(sc)
    orbit = separated_orbit(st, sc, speed, 1e-4)
    assert orbit is not None and orbit.drift > 0.0
    place_on_orbit(st, orbit)
    measure_window(st, 2, speed, scale)  # the contact memory re-adapts to the orbit
    heights = []
    x0 = st.y[0]
    steps = []
    for _ in range(40):
        st.advance(st.k_per)
        steps.append(st.y[0] - x0)
        x0 = st.y[0]
        heights.append(st.y[2])
    steps = np.array(steps)
    assert np.ptp(steps) <= 1e-9 * abs(steps.mean())
    assert np.ptp(heights) <= 1e-9
    assert steps.mean() == pytest.approx(orbit.drift, rel=1e-6)
    win = measure_window(st, 12, speed, scale)
    assert win.orbit_period == 1


def test_a_creeping_contact_has_no_orbit_and_one_that_loses_contact_is_not_used():
    """mmd m* = 1e3, A* = 0.5, mu = 0.5 creeps (its spring loads further every period: no
    period-one orbit); A* = 3 hops (the run's own free vertical oscillation moves the drift)."""
    for a, mu in ((0.5, 0.5), (3.0, 0.1)):
        sc = scene(1000.0, a, mu)
        st, speed, _ = stepper_after_ramp(sc)
        assert separated_orbit(st, sc, speed, 1e-4) is None


def test_a_heavy_sliding_cell_starts_its_windows_at_the_orbit():
    """m* = 1e3 and 1e4 (mmd, A* = 0.6, mu = 0.1): no reduced-inertia stage, at most 12 windows
    at full inertia (the reduced stage alone took 13000 to 20000 periods)."""
    for m in (1e3, 1e4):
        res = sd.run(scene(m, 0.6, 0.1))
        w = full_window_length(m, 1.2142857142857142, 60)
        assert res.settled is True and res.settle_method == "orbit_then_full"
        assert res.settle_periods <= 12 * w, (m, res.settle_periods, w)
        assert res.regime == "drift_with"


@pytest.mark.slow
def test_a_heavy_sliding_cell_agrees_with_brute_force_from_rest():
    """mmd m* = 300, A* = 0.6, mu = 0.1: within 1e-3 relative of a 122000-period run from rest."""
    m, a, mu = 300.0, 0.6, 0.1
    n = int(40 * m / mu) + 2000
    ref = sd.run(scene(m, a, mu, settle=False, periods=n, measure_periods=int(0.3 * n),
                       max_periods=n))
    res = sd.run(scene(m, a, mu))
    assert res.settle_method == "orbit_then_full"
    assert abs(res.drift_ratio - ref.drift_ratio) <= 1e-3 * abs(ref.drift_ratio), (
        res.drift_ratio, ref.drift_ratio)
    assert res.regime == ref.regime == "drift_with"
