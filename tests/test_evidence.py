"""Regime evidence: one window, synchronous hopping, gross slip, chaos, events, rigid-scheme errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.dynamics import rigid as rg
from sawdrift.dynamics.lyapunov import (
    ALIGN_PERIODS,
    EARLY_CHECKS,
    LYAPUNOV_PERIODS,
    is_chaotic,
    lyapunov_statistics,
    verdict_clear,
)
from sawdrift.dynamics.synchrony import synchrony
from sawdrift.errors import NonFiniteStateError


@pytest.mark.parametrize("m_star, amplitude", [(0.3, 1.5), (10.0, 1.2), (3.0, 1.0)])
def test_synchronous_jumping_is_hopping_with_one_liftoff_per_period(m_star, amplitude):
    # The later paper's jumping regime: one rebound per period at a fixed phase, with drift.
    r = sd.run(sd.Scene(model="mmd", particle={"m_star": m_star}, drive={"amplitude": amplitude},
                        numerics={"periods": 200}))
    assert r.regime == "hopping"
    assert r.hop_period == 1
    assert r.liftoffs_per_period == pytest.approx(1.0, abs=1e-12)
    # phases repeat: circular spread below 5 % of the period
    assert r.liftoff_phase_spread < 0.05
    assert 0.0 <= r.liftoff_phase < 1.0
    assert math.isfinite(r.drift_ratio) and abs(r.drift_ratio) > 0.05


def _point_at_stick_bound(fraction: float, gz: float = 0.3, mu: float = 0.1) -> sd.Result:
    # Gx = r Gz set to ``fraction`` of the closed-form stick bound mu sqrt(1 - Gz^2)
    m = 0.1
    gx = fraction * mu * math.sqrt(1.0 - gz**2)
    scene = sd.Scene(model="material_point", material={"mu": mu}, particle={"m_star": m},
                     drive={"amplitude": gz / (4 * math.pi**2 * m), "horizontal_ratio": gx / gz})
    return sd.run(scene)


def test_point_below_stick_bound_sticks_without_gross_slip():
    r = _point_at_stick_bound(0.97)
    assert r.regime == "stick"
    assert r.gross_slip_fraction == 0.0


def test_point_above_stick_bound_slips_with_zero_drift():
    # the forward and backward slips cancel exactly (the forcing is odd under a half-period shift)
    r = _point_at_stick_bound(1.03)
    assert r.regime == "oscillating_slip"
    assert r.gross_slip_fraction > 0.05
    assert abs(r.drift_ratio) < 1e-12


def test_transient_liftoff_is_not_evidence():
    # an abrupt start (no ramp) lifts the particle off early; damping then settles it into
    # permanent contact: the window after the transient must not report contact loss
    scene = sd.Scene(model="mmd", particle={"m_star": 1.0},
                     drive={"amplitude": 0.6, "ramp_periods": 0.0},
                     effects={"normal_damping": 0.5}, numerics={"periods": 60})
    r = sd.run(scene, trajectory=True)
    early = r.trajectory[r.trajectory["t"] < 10.0]
    assert (early["a"] <= 0.0).any(), "the scene should lift off in its transient"
    assert not r.contact_lost
    assert r.liftoffs_per_period == 0.0
    # the regime is the one of a run long enough for the transient not to matter
    long = sd.run(scene.with_updates(**{"numerics.periods": 1000}))
    assert long.regime == "drift_with" and not long.contact_lost
    assert r.regime == long.regime


def test_events_agree_with_evidence_for_bouncing():
    # a fixed run: its window is its last measure_periods (a default run of this chaotic cell
    # goes on to a long-time mean on a copy of the run, whose periods count in r.periods)
    r = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.01}, drive={"amplitude": 5.0},
                        numerics={"periods": 100, "settle": False}))
    assert r.regime == "bouncing"
    ev = r.events
    lifts = int((ev["kind"] == "lift_off").sum())
    lands = int((ev["kind"] == "landing").sum())
    assert lifts == round(r.liftoffs_per_period * r.measure_periods) and lifts > 0
    assert abs(lifts - lands) <= 1
    t0 = r.periods - r.measure_periods
    assert ev["t"].min() >= t0 - 1e-9 and ev["t"].max() <= r.periods + 1e-9


def test_elastic_bouncing_point_is_chaotic_and_inelastic_hopping_is_not():
    # The later paper: a material point with elastic rebounds (restitution 1) is chaotic.
    elastic = sd.run(sd.Scene(model="material_point", model_params={"restitution": 1.0},
                              particle={"m_star": 0.1}, drive={"amplitude": 1.0},
                              numerics={"periods": 400}))
    assert elastic.regime == "bouncing"
    assert elastic.chaotic is True
    assert elastic.lyapunov > 0.05
    plastic = sd.run(sd.Scene(model="material_point", model_params={"restitution": 0.0},
                              particle={"m_star": 0.1}, drive={"amplitude": 0.5},
                              numerics={"periods": 400}))
    assert plastic.regime == "hopping"
    assert plastic.chaotic is False
    assert plastic.lyapunov < 0.0


def test_synchrony_finds_period_two_and_rejects_scattered_phases():
    rng = np.random.default_rng(1)
    period_two = 100.0 + np.arange(0, 40, 2) + 0.3 + rng.normal(0, 0.002, 20)
    s = synchrony(period_two, 100.0, 40)
    assert (s.hop_period, s.liftoffs_per_hop) == (2, 1)
    assert s.phase == pytest.approx(0.3, abs=0.01)
    scattered = 100.0 + np.arange(40) + rng.uniform(0, 1, 40)
    assert synchrony(scattered, 100.0, 40).hop_period == 0


def test_a_wandering_period_one_hop_is_no_hop_of_two_or_four():
    """One lift-off a period, its phase wandering 0.53 to 0.76 over a 9-period cycle (mmd m* =
    1.15, A* = 4.7, mu = 0.3: resultant 0.89 as a hop of 1): cut into blocks of 2 or 4 periods
    the same scatter counted 2 or 4 times less, and it passed as a hop of 2 with two equal phases.
    Judged in periods, it is no hop; a hop of 2 with a jitter of 0.02 of a period still is."""
    k = np.arange(27)
    wandering = 249.0 + k + 0.645 + 0.115 * np.sin(2 * np.pi * k / 9.0)
    assert synchrony(wandering, 249.0, 27).hop_period == 0
    rng = np.random.default_rng(2)
    jittered = 100.0 + np.arange(0, 40, 2) + 0.4 + rng.normal(0, 0.02, 20)
    s = synchrony(jittered, 100.0, 40)
    assert (s.hop_period, s.liftoffs_per_hop) == (2, 1)
    assert s.spread == pytest.approx(0.02, rel=0.5)  # in periods, not in blocks


def test_lyapunov_statistics_tell_exponential_from_linear_growth():
    rng = np.random.default_rng(3)
    j = np.arange(ALIGN_PERIODS, ALIGN_PERIODS + LYAPUNOV_PERIODS)
    # exponential separation at 0.2 per period with noisy stretchings: chaos
    lam, err = lyapunov_statistics(0.2 + rng.normal(0.0, 0.3, j.size))
    assert lam == pytest.approx(0.2, abs=3 * err) and is_chaotic(lam, err)
    # a shear along a neutral direction (separation 1 + c t), renormalized every period: for
    # every c the mean stretching stays below ln(9)/64, never chaos
    for c in (0.01, 0.1, 1.0, 50.0, 1e4):
        lam, err = lyapunov_statistics(np.log((1 + c * (j + 1)) / (1 + c * j)))
        assert 0.0 < lam < math.log(9) / 64 and not is_chaotic(lam, err)
    # a stable orbit shrinks the separation; an erased one is -inf
    assert not is_chaotic(*lyapunov_statistics(np.full(64, math.log(0.5))))
    assert lyapunov_statistics(np.array([0.1, -math.inf]))[0] == -math.inf


def test_early_lyapunov_stop_only_where_the_verdict_is_decided():
    rng = np.random.default_rng(5)
    n = EARLY_CHECKS[0]
    assert verdict_clear(0.3 + rng.normal(0.0, 0.15, n))  # chaos well above the floor
    assert verdict_clear(rng.normal(0.0, 0.01, n))  # neutral, like a quasi-periodic bouncer
    assert verdict_clear(np.append(np.zeros(n - 1), -math.inf))  # separation erased
    # an exponent near the floor (0.06 per period), or one too noisy to place, runs the full
    # length: stopping there could flip the verdict of the longer estimate
    assert not verdict_clear(0.06 + rng.normal(0.0, 0.02, n))
    assert not verdict_clear(rng.normal(0.0, 0.5, n))
    # chaos is called on 64 stretchings at the earliest, never on the first 32
    assert not verdict_clear(0.3 + rng.normal(0.0, 0.15, n), chaos=False)


def test_a_hopping_orbit_lyapunov_stops_early_with_the_full_verdict():
    # mmd m* 0.237, A* 0.891 hops once a period: its window asks for 64 stretchings and the
    # first 32 decide (0.010 +- 0.003, far below the chaos floor); the full series agrees with
    # them within three combined uncertainties and is not chaos either. (The quasi-periodic heavy
    # bouncers this was first measured on stopped at 32 while their speed was off the drift; at
    # the drift their stretchings run the full length, as they should where 64 do not decide.)
    from sawdrift.dynamics import window as wn

    calls = []
    original = wn.stretching_logs

    def spy(*args, **kwargs):
        logs = original(*args, **kwargs)
        full = original(*args, **{**kwargs, "early": ()})
        calls.append((logs, full))
        return logs

    r = None
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(wn, "stretching_logs", spy)
        r = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.2371373705661655},
                            drive={"amplitude": 0.8912509381337456}))
    assert r.regime == "hopping" and r.hop_period == 1 and not r.chaotic
    # the estimate of the window the evidence comes from: the last (an orbit search after the
    # fixed window estimates its own window again)
    logs, full = calls[-1]
    assert logs.size in EARLY_CHECKS and logs.size < full.size
    (lam, err), (lam_full, err_full) = lyapunov_statistics(logs), lyapunov_statistics(full)
    assert verdict_clear(logs) and not is_chaotic(lam_full, err_full)
    assert abs(lam - lam_full) <= 3.0 * math.hypot(err, err_full)


def test_a_moderate_positive_exponent_is_chaos():
    # mmd, m* 0.1, A* 1: drift -0.255 / -0.093 / +0.537 at 128 / 256 / 512 steps per period,
    # exponent 0.2-0.4 per period; the former growth-by-1e7 rule called none of them chaotic
    for steps in (128, 256, 512):
        r = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 1.0},
                            numerics={"steps_per_period": steps}))
        assert r.regime == "bouncing" and r.chaotic and r.lyapunov > 0.15


def test_rigid_scheme_raises_instead_of_falling_behind(monkeypatch):
    # the python engine reads the event cap at call time: a cap of 2 events per step must end
    # the run with an error naming t*, never a silent state left behind in time
    monkeypatch.setattr(rg, "_MAX_EVENTS", 2)
    scene = sd.Scene(model="material_point", model_params={"restitution": 0.9},
                     particle={"m_star": 0.1}, drive={"amplitude": 0.5}, numerics={"periods": 40})
    with pytest.raises(NonFiniteStateError, match=r"events .* at t\* = "):
        sd.run(scene, engine="python")


def test_tsuji_damping_is_kept_with_friction_off():
    # With friction off the integrator calls the model's own normal law (its normal slot):
    # the Tsuji dashpot must still dissipate, and the elastic law must still rebound fully.
    pytest.importorskip("sawdrift_tsuji")
    base = dict(model="hertz_tsuji", particle={"m_star": 10.0},
                drive={"kind": "impact", "velocity": 1.0})
    off = sd.run(sd.Scene(**base, model_params={"damping": 0.5}, effects={"friction": False}))
    on = sd.run(sd.Scene(**base, model_params={"damping": 0.5}))
    assert 0.0 < off.extra["rebound_ratio"] < 0.9
    assert on.extra["rebound_ratio"] == pytest.approx(off.extra["rebound_ratio"], rel=1e-9)
    elastic = sd.run(sd.Scene(**base, model_params={"damping": 0.0}, effects={"friction": False}))
    assert elastic.extra["rebound_ratio"] == pytest.approx(1.0, abs=1e-4)
    import json

    json.dumps(on.summary())  # no numpy scalars left in the summary


def test_hop_liftoffs_follow_their_rule_on_random_event_logs():
    """A lift-off counts as a hop when its flight (to the next landing, or the window's end)
    lasts MIN_FLIGHT, or, with rebounds_only, when it takes off from contact held MIN_FLIGHT
    (since the last landing, or the window's start): the rule read lift-off by lift-off, on
    2000 random logs with other events mixed in."""
    from sawdrift.dynamics import evidence as ev
    from sawdrift.dynamics.synchrony import MIN_FLIGHT
    from sawdrift.dynamics.window import hop_liftoffs

    def by_rule(events, t0, t1, rebounds_only):
        t, kind = events[:, 0], events[:, 1]
        lands = t[kind == ev.EV_LANDING]
        out = []
        for ti in t[kind == ev.EV_LIFT_OFF]:
            later, earlier = lands[lands > ti], lands[lands < ti]
            flight = (later[0] if later.size else t1) - ti
            held = ti - (earlier[-1] if earlier.size else t0)
            if flight >= MIN_FLIGHT or (rebounds_only and held >= MIN_FLIGHT):
                out.append(ti)
        return np.array(out)

    rng = np.random.default_rng(2)
    kinds = [ev.EV_LIFT_OFF, ev.EV_LANDING, ev.EV_SLIP_START, ev.EV_SLIP_END]
    for _ in range(1000):
        n = int(rng.integers(0, 40))
        events = np.zeros((n, ev.EV_W))
        events[:, 0] = np.sort(rng.uniform(10.0, 10.0 + rng.uniform(0.01, 5.0), n))
        events[:, 1] = rng.choice(kinds, n)
        for rebounds_only in (True, False):
            assert np.array_equal(hop_liftoffs(events, 10.0, 15.0, rebounds_only),
                                  by_rule(events, 10.0, 15.0, rebounds_only))


def test_lift_offs_at_one_phase_have_a_spread_of_zero_not_minus_zero():
    """A period-one hop lifts off at one phase every period: the circular resultant is R = 1 and
    the spread sqrt(-2 ln R) is 0; it came out as -0.0 (sqrt(-0.0)), printed "-0" by `run`."""
    from sawdrift.dynamics.synchrony import _circular

    _mean, r, spread = _circular(np.full(12, 0.6875))
    assert r == 1.0 and spread == 0.0 and math.copysign(1.0, spread) == 1.0
