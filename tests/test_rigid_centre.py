"""The rigid scheme's state is the centre of a rolling sphere, as in the compliant loop.

Three facts that a scheme storing the contact point s = x + R phi / a0 between steps breaks:
the drive is evaluated where the sphere is (a two-wave field's trap is where the field says),
events are logged in the same coordinates as the trajectory, and the momentum balance
m x'' - L = kappa m psi'' (friction is the only force with a moment about the centre) holds through
impacts under a load.
"""

from __future__ import annotations

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.study.field import drift_field
from sawdrift.study.field_direct import direct_run, nearest_zero


def test_a_rigid_rolling_sphere_runs_into_the_trap_the_field_predicts():
    # the field is computed at fixed positions, so it does not depend on the state convention;
    # the direct run evaluates the drive at the particle's own x*: at c x* (c = 1 + 1/kappa = 3.5)
    # it would stop where start + 3.5 (xi - start) is the trap, 0.083 wavelengths off here
    scene = sd.Scene(model="material_point", particle={"m_star": 0.1}, drive={"backward": 0.5},
                     effects={"rotation": True})
    fld = drift_field(scene, 16, workers=1).fields[0]
    start = 0.12
    trap = nearest_zero(fld, start)
    assert trap is not None and abs(trap - start) > 0.05  # the run must really move
    run = direct_run(scene, start, 1500, fld, wavelength=200.0)
    assert abs(run["final_position"] - trap) < 1e-3


def _hopping(load: float) -> sd.Result:
    scene = sd.Scene(model="material_point", particle={"m_star": 0.1, "load": load},
                     drive={"amplitude": 1.0}, effects={"rotation": True},
                     numerics={"periods": 12, "measure_periods": 4})
    return sd.run(scene, trajectory=True, record_every=1)


def test_rigid_events_are_logged_at_the_centre_like_the_trajectory():
    res = _hopping(0.0)
    tr, evs = res.trajectory, res.events
    t = tr["t"].to_numpy()
    landings = evs[evs["kind"] == "landing"]
    assert len(landings) >= 3
    for _, e in landings.iterrows():
        # the last recorded step end before the landing is in flight (no load: x*' constant)
        i = int(np.searchsorted(t, e["t"])) - 1
        assert tr["a"].iloc[i] < 0.0
        x_flight = tr["x"].iloc[i] + tr["vx"].iloc[i] * (e["t"] - t[i])
        assert e["x"] == pytest.approx(x_flight, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("load", [0.0, 0.2])
def test_a_rigid_rolling_sphere_keeps_its_momentum_balance_through_impacts(load):
    # m* x'' = F + L and kappa m* psi'' = F with F the friction (impulses alike):
    # x*' - kappa psi' - L t / m* is constant
    res = _hopping(load)
    tr = res.trajectory
    # impacts in the window; under a load above mu (0.2 > 0.1) there is no steady drift at all:
    # the mean friction is at most mu times the weight, so the sphere runs away
    assert res.contact_lost
    assert res.regime == ("hopping" if load == 0.0 else "runaway")
    kappa, m = 0.4, 0.1
    inv = tr["vx"] - kappa * tr["spin"] - load * tr["t"] / m
    scale = float(np.abs(tr["vx"]).max())
    assert float(np.abs(inv - inv.iloc[0]).max()) < 1e-9 * scale

