"""Chaotic cells: the long-time mean drift with an honest standard error (batch means)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.dynamics.batch_means import blocked_error, blocking


def test_blocking_recovers_the_error_of_a_correlated_series():
    """AR(1), phi = 0.9, unit innovations: the error of the mean of n samples is
    1 / ((1 - phi) sqrt(n)) asymptotically; the naive sigma / sqrt(n) is 4.4 times smaller."""
    rng = np.random.default_rng(7)
    n, phi = 2**16, 0.9
    e = rng.standard_normal(n)
    x = np.empty(n)
    x[0] = e[0] / math.sqrt(1 - phi**2)
    for i in range(1, n):
        x[i] = phi * x[i - 1] + e[i]
    mean, se, batches = blocked_error(x)
    exact = 1.0 / ((1.0 - phi) * math.sqrt(n))
    assert 0.7 * exact <= se <= 1.4 * exact, (se, exact)
    assert batches >= 16
    naive = x.std(ddof=1) / math.sqrt(n)
    assert se > 3.0 * naive


def test_a_chaotic_cell_reports_a_mean_consistent_with_a_ten_times_longer_run():
    """mmd, m* = 0.1, A* = 1, mu = 0.1 bounces chaotically (long-time mean -0.014 +- 0.016 over
    4e5 periods; the old default printed one 27-period sample, -0.255). The default's mean must
    agree with a run ten times longer within 3 combined standard errors."""
    base = {"model": "mmd", "particle": {"m_star": 0.1}, "material": {"mu": 0.1},
            "drive": {"amplitude": 1.0}}
    short = sd.run(sd.Scene.model_validate(base))
    long = sd.run(sd.Scene.model_validate({**base, "numerics": {
        "periods": 20060, "measure_periods": 20000}}))
    assert short.chaotic and long.chaotic
    assert short.regime == long.regime == "bouncing"
    assert math.isfinite(short.drift_ratio_se) and short.drift_ratio_se > 0.0
    combined = math.hypot(short.drift_ratio_se, long.drift_ratio_se)
    assert abs(short.drift_ratio - long.drift_ratio) <= 3.0 * combined
    assert short.settled is False  # settled keeps its meaning: fixed points and periodic orbits


def ar1(n: int, phi: float, seed: int) -> np.ndarray:
    """An AR(1) series x_i = phi x_(i-1) + e_i, unit innovations, stationary start."""
    rng = np.random.default_rng(seed)
    e = rng.standard_normal(n)
    x = np.empty(n)
    x[0] = e[0] / math.sqrt(1 - phi**2)
    for i in range(1, n):
        x[i] = phi * x[i - 1] + e[i]
    return x


def test_an_error_still_growing_with_the_batch_length_is_flagged_as_a_lower_bound():
    """2000 samples of AR(1) with a correlation time of 1000 (phi = 0.999): the blocking error
    rises with the batch length to the longest batches of the budget (a lower bound), while for
    phi = 0.5 (correlation time 2) it has reached its plateau. Over 20 seeds each: the long
    correlations are flagged in at least 15, the short ones in at most 3."""
    long = [blocking(ar1(2000, 0.999, s))[4] for s in range(20)]
    short = [blocking(ar1(2000, 0.5, s))[4] for s in range(20)]
    assert sum(long) >= 15 and sum(short) <= 3, (sum(long), sum(short))
    assert all(blocking(ar1(2000, 0.5, s))[3] for s in range(3))  # and flat


def test_a_wandering_run_counts_its_windows_in_its_long_time_mean():
    """mmd m* = 4.2e-3, A* = 1.06 keeps contact but its window means wander (a slow beat near
    the contact resonance): the default run goes on through 15 windows before giving up on a
    steady drift, and those periods are samples of its long-time mean. The mean over the
    windows and what follows must agree with an independent 16000-period mean (-0.04246 +-
    0.0016, ramp two periods longer: benchmarks/results/mean_budget.json) within 3 combined
    errors, and the twin that completes the budget runs only the periods the windows lacked.
    (A* = 1.78, -0.2737 +- 0.0009, gave up after two windows of 54 once the window ratio was
    squared as the windows doubled: it no longer goes through many windows.)"""
    from sawdrift.dynamics import batch_means as bm

    advanced = []
    original = bm.long_time_mean

    def spy(stepper, window, periods, target=0.0, series=None):
        start = stepper.step
        out = original(stepper, window, periods, target, series)
        advanced.append(((stepper.step - start) / stepper.k_per, out,
                         sum(s.shape[0] for s in series or []), window.periods))
        return out

    import sawdrift.dynamics.integrate as ig

    scene = sd.Scene(model="mmd", particle={"m_star": 0.004216965034285822},
                     drive={"amplitude": 1.0592537251772887})
    with __import__("pytest").MonkeyPatch.context() as mp:
        mp.setattr(ig, "long_time_mean", spy)
        r = sd.run(scene)
    (ran, mean, windows, window), = advanced
    assert windows > 5 * window  # the run went on through its windows first
    assert mean.periods == window + scene.numerics.mean_periods
    assert ran == scene.numerics.mean_periods - (windows - window)
    ref, ref_se = -0.04245902453402814, 0.001555793899929395
    assert abs(r.drift_ratio - ref) <= 3.0 * math.hypot(r.drift_ratio_se, ref_se)


def test_a_series_still_approaching_its_mean_is_told_from_a_stationary_one():
    """Correlated noise (AR(1), phi = 0.9, innovations 0.002) about a constant over 600 periods
    is not moving in 50 seeds; the same noise on an exponential approach (time constant 300
    periods, 0.05 to go at the start, as a heavy bouncer's mean speed) is, in every seed. (At
    5 combined errors; at 4, one stationary seed in a hundred was taken as moving.)"""
    from sawdrift.dynamics.batch_means import still_moving

    t = np.arange(600)
    moving = 0
    for seed in range(50):
        rng = np.random.default_rng(seed)
        e = rng.standard_normal(t.size) * 0.002
        x = np.empty(t.size)
        x[0] = e[0]
        for i in range(1, t.size):
            x[i] = 0.9 * x[i - 1] + e[i]
        assert not still_moving(0.8 + x)
        moving += still_moving(0.8 - 0.05 * np.exp(-t / 300.0) + x)
    assert moving == 50


def test_a_heavy_bouncer_long_in_flight_reports_the_drift_after_its_approach():
    """mmd, m* = 4.22, A* = 8.41, mu = 0.1 bounces irregularly, in flight 89 % of the time, and its
    mean speed relaxes over some 3000 periods. Its long-time mean began on the approach and
    reported 0.7929 +- 0.0006, where brute force from the same start drifts at 0.797 over periods
    3000 to 6000; a mean still moving then dropped its transient half and ran on. With the
    windows' jumps applied in flight too (a jump at a flight's closed form was lost), its windows
    now settle in 749 periods, at 0.79695: the drift must be within 1.5e-3 of brute force, by
    whichever route."""
    scene = sd.Scene(model="mmd", particle={"m_star": 4.216965}, material={"mu": 0.1},
                     drive={"amplitude": 8.413951})
    ref = sd.run(scene.with_updates(**{"numerics.settle": False, "numerics.periods": 6000,
                                       "numerics.measure_periods": 3000,
                                       "numerics.max_periods": 6000}))
    res = sd.run(scene)
    assert res.regime == ref.regime == "bouncing"
    assert abs(res.drift_ratio - ref.drift_ratio) <= 1.5e-3, (res.drift_ratio, ref.drift_ratio)
    # a settled drift, or a long-time mean with its error
    assert res.settled or math.isfinite(res.drift_ratio_se)


@pytest.mark.parametrize(("m_star", "amplitude"), [
    (0.7498942093324559, 7.079457843841379), (0.4216965034285822, 10.0)])
def test_an_error_still_growing_covers_a_sixteen_thousand_period_run_from_the_same_start(
        m_star, amplitude):
    """mmd bouncers at m* = 0.75, A* = 7.08 and m* = 0.42, A* = 10 whose windows did not settle:
    long-time means over about 500 periods whose blocking error still grows at its longest
    batches (flagged as a lower bound), followed on to the coarsest levels (about twice the
    error of the 16-batch levels). Each is within 3 combined errors of 16000 periods from the
    same start (measured: 0.7 and 0.9)."""
    base = sd.Scene(model="mmd", particle={"m_star": m_star}, material={"mu": 0.1},
                    drive={"amplitude": amplitude})
    res = sd.run(base)
    ref = sd.run(base.with_updates(**{"numerics.mean_periods": 16000,
                                      "numerics.settle_tolerance": 1e-9}))
    assert res.regime == ref.regime == "bouncing"
    assert math.isfinite(res.drift_ratio_se) and math.isfinite(ref.drift_ratio_se)
    combined = math.hypot(res.drift_ratio_se, ref.drift_ratio_se)
    assert abs(res.drift_ratio - ref.drift_ratio) <= 3.0 * combined, (
        res.drift_ratio, res.drift_ratio_se, ref.drift_ratio, ref.drift_ratio_se)
    assert any("lower bound" in w for w in res.warnings)


def test_a_rising_blocking_curve_is_followed_to_its_halves_only_for_a_reported_error():
    """A linear trend of 0.01 under white noise of 0.001 over 512 periods: the blocking curve
    rises through its 16-batch levels; the reported error (``coarse``) reaches half the
    difference of the halves' means (0.005 / 2), the test of a series keeps the finer levels."""
    rng = np.random.default_rng(3)
    x = np.linspace(0.0, 0.01, 512) + 0.001 * rng.standard_normal(512)
    fine = blocking(x)
    reported = blocking(x, coarse=True)
    assert fine[4] and reported[4]  # rising either way
    halves = abs(x[256:].mean() - x[:256].mean())
    assert reported[1] >= 0.5 * halves * 0.999
    assert fine[1] < 0.5 * reported[1]


def test_a_bouncer_gaining_energy_is_told_from_a_stationary_one():
    """heats_up: correlated noise (AR(1), phi = 0.9, standard deviation 23) about a constant
    energy of 100 over 500 periods is not heating in 50 seeds; the same noise on an energy
    rising from 100 to 250 over the run is, in every seed (a heating bouncer's tripled)."""
    from sawdrift.dynamics.batch_means import heats_up

    t = np.arange(500)
    heating = 0
    for seed in range(50):
        noise = 10.0 * ar1(t.size, 0.9, seed)
        assert heats_up(100.0 + noise) is None
        heating += heats_up(100.0 + 0.3 * t + noise) is not None
    assert heating == 50
    assert heats_up(np.linspace(0.0, 1.0, 20)) is None  # too short to tell


def test_an_undamped_bouncer_heating_up_says_so_and_a_damped_one_does_not():
    """mmd, m* = 0.1, A* = 1, mu = 0.1: the Hertz contact without normal damping gives the
    vertical motion back at every impact, and the bounces grow (their energy, as a height, from
    54 to 168 a0 between the halves of the 500-period mean; 217 to 10358 a0 over the last
    quarters of 500 to 32000 periods): the Result says its mean depends on how long it is run.
    hertz_tsuji, with normal damping, stays bounded on the same cell (within 11.2 a0)."""
    base = {"particle": {"m_star": 0.1}, "material": {"mu": 0.1}, "drive": {"amplitude": 1.0}}
    undamped = sd.run(sd.Scene(model="mmd", **base))
    assert math.isfinite(undamped.drift_ratio_se)
    heating = [w for w in undamped.warnings if "heat up" in w]
    assert len(heating) == 1 and "depends on how long it is run" in heating[0]
    damped = sd.run(sd.Scene(model="hertz_tsuji", **base))
    assert math.isfinite(damped.drift_ratio_se)  # a long-time mean too
    assert not any("heat up" in w for w in damped.warnings), damped.warnings


def test_heating_is_judged_over_the_same_periods_as_the_mean():
    """A run that went through windows before its long-time mean counts their periods in the
    mean (nine 60-period windows of mmd m* = 0.1, A* = 1: 480 periods beyond the last window
    count against the budget of 500, so only 20 are run after them). The test of heating must
    see the windows' periods too: it saw only the 20 run after them, too few to tell, and said
    nothing of a bouncer whose energy nearly quadrupled over the mean (47 to 182)."""
    from sawdrift.dynamics.batch_means import long_time_mean, period_rows
    from sawdrift.dynamics.window import measure_window
    from tests.test_separated import scene, stepper_after_ramp

    st, speed, scale = stepper_after_ramp(scene(0.1, 1.0, 0.1))
    series = []
    for _ in range(9):
        win = measure_window(st, 60, speed, scale)
        series.append(period_rows(win, st))
    alone = long_time_mean(st.twin(), win, 500)
    after = long_time_mean(st.twin(), win, 500, series=series)
    assert after.periods == 560  # the windows' 540 periods and 20 more
    assert alone.heating is not None and after.heating is not None, (alone, after)
    low, high = after.heating
    assert high > 1.2 * low > 0.0


def test_a_mean_whose_halves_differ_carries_their_difference_in_its_error():
    """material_point m* = 0.9, A* = 0.995, mu = 0.1 reaches its period-19 hop only after about
    800 periods: the default run's long-time mean, over periods 310 to 1087, still holds the
    approach (its halves 4.5 errors apart: below the 5 at which it counts as moving) and gave
    -0.0945 +- 0.011 against -0.152 from brute force (2000 of 4000 periods), 5 errors off. Its
    error must cover brute force within 3 combined errors; a stationary series of correlated
    noise keeps its plain batch-means error."""
    from sawdrift.dynamics.batch_means import blocked_error, trend_allowance

    scene = dict(model="material_point", particle={"m_star": 0.9}, drive={"amplitude": 0.994628})
    ref = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": 4000,
                                             "measure_periods": 2000}))
    res = sd.run(sd.Scene(**scene))
    assert abs(res.drift_ratio - ref.drift_ratio) <= 3.0 * res.drift_ratio_se, (
        res.drift_ratio, res.drift_ratio_se, ref.drift_ratio)
    # and no wider than the approach it covers (0.058 here) and a plain error: an error a hundred
    # times too large covered brute force too
    assert res.drift_ratio_se <= abs(res.drift_ratio - ref.drift_ratio) + 0.02
    rng = np.random.default_rng(3)
    noise = np.zeros(1000)
    for i in range(1, noise.size):
        noise[i] = 0.9 * noise[i - 1] + rng.normal(0.0, 0.002)
    assert trend_allowance(noise) == 0.0 and blocked_error(noise)[1] > 0.0
    # the same noise on a drift of 0.02 over the series: half the halves' difference, 0.005
    ramp = noise + np.linspace(0.0, 0.02, noise.size)
    assert abs(trend_allowance(ramp) - 0.005) < 0.0015


def test_a_heavy_point_in_flights_of_thousands_of_periods_averages_over_sixteen_of_them():
    """A rigid point at m* = 58.9, A* = 4.54 (a cell of the out-of-sample audit grid: m* 1.3 to 90
    and A* 0.013 to 8.7, 11 log steps each) rises to 2e4 a0 and lands about every 3500 periods.
    Its long-time mean over 500 periods lay inside one flight, whose speed does not change: the
    old code reported 0.1084 +- 0.0007 against 0.1527 from 25565 periods of brute force (62
    errors). Over at least 16 flights as long as its window's longest the mean must agree with
    brute force within 3 of its errors."""
    m_star = float(np.logspace(np.log10(1.3), np.log10(90.0), 11)[9])
    amplitude = float(np.logspace(np.log10(0.013), np.log10(8.7), 11)[9])
    scene = {"model": "material_point", "particle": {"m_star": m_star},
             "drive": {"amplitude": amplitude}}
    res = sd.run(sd.Scene(**scene))
    n = 25565  # 40 m*/mu + 2000 periods
    brute = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": n,
                                               "measure_periods": n // 2, "max_periods": n}))
    assert res.regime == brute.regime == "bouncing"
    assert math.isfinite(res.drift_ratio_se)
    assert abs(res.drift_ratio - brute.drift_ratio) <= 3.0 * res.drift_ratio_se


def test_window_means_beating_slower_than_the_last_windows_give_a_long_time_mean():
    """mmd m* = 4.2e-3, A* = 0.89 keeps contact, and its 27-period window means swing between
    0.014 and 0.062 in drift ratio over a beat of about 10 windows: the last 7 windows turn only
    once, so the run went on to its 1059-period cap and reported its last window, 0.028, not
    settled. Its window means have turned several times by then: it is a long-time mean, which
    must agree within 3 errors with brute force over periods 2000 to 4000 (0.0343) and 4000 to
    8000 (0.0337), and it costs fewer periods than the cap."""
    scene = {"model": "mmd", "particle": {"m_star": 0.004216965034285823},
             "drive": {"amplitude": 0.8912509381337456}}
    r = sd.run(sd.Scene(**scene))
    assert not r.settled and math.isfinite(r.drift_ratio_se) and r.drift_ratio_se > 0.0
    assert r.periods < 1000
    for n in (4000, 8000):
        brute = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": n,
                                                   "measure_periods": n // 2, "max_periods": n}))
        assert abs(r.drift_ratio - brute.drift_ratio) <= 3.0 * r.drift_ratio_se
    # the swing itself is far wider than the error: one window is not the answer
    assert r.drift_ratio_se < 0.25 * (0.062 - 0.014)


def test_the_regime_of_a_long_time_mean_in_contact_reads_the_mean():
    """mmd m* = 0.0042, A* = 0.89 (rounded inputs) keeps contact and is a long-time mean,
    0.0082 +- 0.0027 in drift ratio, more than 3 errors and the 1e-3 threshold above zero: it
    was called oscillating_slip, from its last window's drift."""
    from sawdrift.result.regimes import classify

    r = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.0042}, drive={"amplitude": 0.89}))
    assert not r.contact_lost and math.isfinite(r.drift_ratio_se)
    assert abs(r.drift_ratio) > 3.0 * r.drift_ratio_se
    tol = r.scene["numerics"]["drift_tolerance"]
    assert r.regime == classify(False, r.drift_ratio, tol, gross_slip_fraction=1.0)
    assert r.regime == "drift_with"
