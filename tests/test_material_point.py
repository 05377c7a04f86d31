"""The rigid material point against the analytic results of docs/physics.md.

Gz = 4 pi^2 m* A*, Gx = r Gz; mu = 0.1 throughout.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.analytic import heavy_sliding_v
from sawdrift.validation import point_scene

MU = 0.1


def test_heavy_sliding_formula_matches_quoted_values():
    for gz, v in [(0.1, -0.099), (0.3, -0.284), (0.5, -0.435), (0.9, -0.639)]:
        assert heavy_sliding_v(gz) == pytest.approx(v, abs=6e-4)


@pytest.mark.parametrize(("gz", "lost"), [(0.98, False), (1.02, True)])
def test_contact_lost_iff_gz_above_one(gz, lost):
    res = sd.run(point_scene(gz))
    assert res.contact_lost is lost
    assert (res.regime in sd.regimes.CONTACT_LOST) is lost


@pytest.mark.parametrize("gz", [0.3, 0.9])
def test_no_slip_below_stick_bound(gz):
    # Gx <= mu sqrt(1 - Gz^2): the point follows the substrate for the whole period, so the
    # friction force never reaches the Coulomb limit and the drift is zero to round-off.
    gx = 0.97 * MU * math.sqrt(1 - gz**2)
    res = sd.run(point_scene(gz, gx), trajectory=True)
    tr = res.trajectory[res.trajectory.t > res.ramp_periods]
    assert (tr["T_star"].abs() < tr["N_star"]).all()
    assert abs(res.drift_ratio) < 1e-12
    assert res.regime == "stick"


@pytest.mark.parametrize("gz", [0.3, 0.9])
def test_slip_above_stick_bound(gz):
    # At 1.03 of the bound the point slips twice per period (|T*| = N* on part of it). The two
    # slips are exact mirror images: the forcing (Gx/mu) sin(phi) -+ (1 + Gz cos(phi)) equals
    # R sin(phi -+ delta) -+ 1, so the backward slip is the forward one negated and shifted by
    # pi, and the net drift vanishes while stick separates them (measured 1e-16).
    gx = 1.03 * MU * math.sqrt(1 - gz**2)
    res = sd.run(point_scene(gz, gx), trajectory=True)
    tr = res.trajectory[res.trajectory.t > res.ramp_periods]
    slipping = np.isclose(tr["T_star"].abs(), tr["N_star"], rtol=1e-12) & (tr["N_star"] > 0)
    assert slipping.mean() > 0.01
    assert abs(res.drift_ratio) < 1e-9


def test_drift_appears_once_slips_merge():
    # Twice the stick bound: the slip phases merge into continuous sliding and the point
    # drifts against the wave.
    gz = 0.3
    res = sd.run(point_scene(gz, 2.0 * MU * math.sqrt(1 - gz**2)))
    assert res.regime == "drift_against"
    assert res.drift_ratio < -1e-3


@pytest.mark.parametrize("gz", [0.3, 0.9])
def test_heavy_sliding_drift(gz):
    # mu / Gx = 0.02: within 2 % of the limit law (measured: 0.16 % and 0.22 %)
    res = sd.run(
        point_scene(gz, MU / 0.02, periods=40, measure_periods=10, settle=True,
                    settle_tolerance=1e-5)
    )
    assert res.drift_ratio == pytest.approx(heavy_sliding_v(gz), rel=0.02)
    assert res.regime == "drift_against"


@pytest.mark.parametrize(("m_star", "gz"), [(1.0, 0.5), (0.05, 0.9), (0.3, 1.5), (2.0, 3.0)])
def test_depends_on_m_star_times_amplitude_only(m_star, gz):
    amp = gz / (4 * math.pi**2 * m_star)
    a = sd.run(sd.Scene(model="material_point", particle={"m_star": m_star},
                        drive={"amplitude": amp}))
    b = sd.run(sd.Scene(model="material_point", particle={"m_star": m_star / 10},
                        drive={"amplitude": 10 * amp}))
    assert a.regime == b.regime
    assert b.drift_ratio == pytest.approx(a.drift_ratio, rel=1e-9, abs=1e-12)


@pytest.mark.slow
def test_never_drifts_with_the_wave_on_a_grid():
    """Settled runs (the default: heavy cells run on to 5e4 periods), 15 s of CPU: the quick loop
    checks the same fact on fixed runs of a finer grid, in
    tests/test_sweep.py::test_material_point_diagram_matches_analytic_thresholds."""
    regimes = set()
    for m_star in np.logspace(-3, 2, 10):
        for amp in np.logspace(-2, 1, 10):
            res = sd.run(sd.Scene(model="material_point", particle={"m_star": m_star},
                                  drive={"amplitude": amp}, numerics={"periods": 30}))
            assert res.regime != "drift_with", (m_star, amp, res.drift_ratio)
            regimes.add(res.regime)
    assert {"stick", "drift_against", "bouncing"} <= regimes


def test_vertical_inertia_off_gives_constant_normal_force():
    # The later paper's assumption N* = 1 (docs/physics.md): with it, the point's drift in
    # permanent contact vanishes; with eq. 5 as written it drifts against the wave.
    gz = 0.5
    kwargs = dict(particle={"m_star": 0.1}, drive={"amplitude": gz / (4 * math.pi**2 * 0.1),
                  "horizontal_ratio": (MU / 0.05) / gz})
    on = sd.run(sd.Scene(model="material_point", **kwargs), trajectory=True)
    off = sd.run(sd.Scene(model="material_point", effects={"vertical_inertia": False},
                          numerics={"periods": 100}, **kwargs), trajectory=True)
    assert on.drift_ratio < -0.1
    # the start-up transient decays exponentially; after 100 periods it is below 1e-6
    assert abs(off.drift_ratio) < 1e-6
    assert np.allclose(off.trajectory["N_star"], 1.0, atol=1e-15)


@pytest.mark.parametrize(("gamma", "period", "periods"),
                         [(1.8, 1, 200), (2.34, 1, 3000), (2.78, 1, 3000), (3.6, 1, 200),
                          (3.9, 2, 200), (4.118, 2, 1500), (4.6, 2, 200)])
def test_vertical_vibration_is_the_inelastic_bouncing_ball(gamma, period, periods):
    # r = 0, restitution 0: the completely inelastic bouncing ball (Mehta and Luck 1990). Its
    # period-1 orbit doubles at Gamma = sqrt(4 + pi^2) = 3.724, so 3.6 repeats every period and
    # 3.9 and 4.6 every second one; nothing moves horizontally and nothing may slip. At 1.8 (t* 48),
    # 2.34, 2.78 (t* ~2600) and 4.118 (t* 1088) a lift-off falls in the last 1e-5 of a step: the
    # flight's gap at the step's end rounds to contact, which the scheme took for a landing and
    # then lifted again at once, 4096 times (now: no landing while the point does not approach
    # a surface that accelerates away)
    m = 1.0 / (4 * math.pi**2)
    scene = sd.Scene(model="material_point", particle={"m_star": m},
                     drive={"amplitude": gamma / (4 * math.pi**2 * m), "horizontal_ratio": 0.0},
                     numerics={"periods": periods, "measure_periods": 100})
    res = sd.run(scene, trajectory=True)
    assert res.orbit_period == period
    assert res.liftoffs_per_period > 0.0 and res.settled is True
    kinds = res.events["kind"].value_counts()
    assert kinds["slip_start"] == 0 and kinds["slip_end"] == 0
    assert (res.trajectory["x"] == 0.0).all() and (res.trajectory["vx"] == 0.0).all()


@pytest.mark.parametrize("excess", [-1e-6, 1e-6, 1e-4])
def test_the_points_hopping_onset_is_gz_one(excess):
    # contact is lost iff Gz = 4 pi^2 m* A* > 1 (every Gz); 1e-6 above it the point dips below
    # N* = 0 for 9e-4 of a period, inside one step of 1/256: the scheme must look inside steps,
    # and the take-off from sustained contact is a (period-1) hop however short its flight
    m = 0.1
    res = sd.run(sd.Scene(model="material_point", particle={"m_star": m}, material={"mu": 0.1},
                          drive={"amplitude": (1.0 + excess) / (4 * math.pi**2 * m)}))
    if excess < 0:
        assert not res.contact_lost and res.regime == "drift_against"
        return
    assert res.contact_lost and res.orbit_period == 1
    assert res.regime == "hopping" and res.hop_period == 1 and res.liftoffs_per_hop == 1
    # the flight is short, ~sqrt(Gz - 1): it was dropped as a micro-rebound before
    assert 0.0 < res.out_of_contact_fraction < 0.01


def test_a_period_two_bouncing_ball_reports_both_take_off_phases():
    # r = 0, restitution 0, Gamma = 3.9 > sqrt(4 + pi^2) = 3.724: the take-offs alternate between
    # two phases (Mehta and Luck 1990); hop period and orbit period are 2, and both phases are
    # reported, not their circular mean
    m = 0.1
    res = sd.run(sd.Scene(model="material_point", model_params={"restitution": 0.0},
                          particle={"m_star": m},
                          drive={"amplitude": 3.9 / (4 * math.pi**2 * m), "horizontal_ratio": 0.0},
                          numerics={"periods": 200}))
    assert res.orbit_period == 2 and res.hop_period == 2 and res.liftoffs_per_hop == 2
    a, b = res.liftoff_phases
    lifts = res.events[res.events["kind"] == "lift_off"]["t"].to_numpy() % 1.0
    assert min(abs(lifts - a).min(), abs(lifts - b).min()) < 1e-9  # both are real take-offs
    assert abs(a - b) > 0.02 and res.liftoff_phase == a


def test_period_one_bouncing_ball_multiplier_is_the_lyapunov_exponent():
    # period-1 inelastic bouncing ball: the map of take-off phases has the multiplier
    # 1 - sqrt(Gamma^2 - pi^2) (Mehta and Luck 1990); the exponent is ln|multiplier|
    m = 0.1
    gamma = 3.5
    res = sd.run(sd.Scene(model="material_point", model_params={"restitution": 0.0},
                          particle={"m_star": m},
                          drive={"amplitude": gamma / (4 * math.pi**2 * m), "horizontal_ratio": 0.0},
                          numerics={"periods": 200}))
    assert res.hop_period == 1 and not res.chaotic
    assert res.lyapunov == pytest.approx(math.log(abs(1 - math.sqrt(gamma**2 - math.pi**2))),
                                         abs=0.01)


@pytest.mark.slow
def test_an_inelastic_ball_collapses_onto_the_plate_late_in_a_long_run():
    """e = 0.8, Gamma = 1.01: every period the ball lifts off and its bounces collapse onto the
    plate. The collapse ended on a floor of the located impact speeds set by the gap function's
    rounding at t* of order 1; the drive's phase 2 pi t* is known to a few ulps of t*, and by
    t* = 1e4 that error is a hundred times larger: the ball kept bouncing on rounding until a
    step held 4096 events (exit 2 at t* = 10437). It hops with period 1 to the end."""
    scene = sd.Scene(model="material_point", particle={"m_star": 0.025330295910584444},
                     material={"restitution": 0.8},
                     drive={"amplitude": 1.01, "horizontal_ratio": 0.0},
                     numerics={"settle": False, "periods": 11000})
    res = sd.run(scene)
    assert res.regime == "hopping" and res.hop_period == 1 and res.orbit_period == 1
