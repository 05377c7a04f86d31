"""No steady state is an answer: ``runaway`` and ``ejected``, never a settled drift speed.

Also: validity warnings travel with the Result, and the event log of a long run stays bounded.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.contact.binding import bind, model_for
from sawdrift.dynamics import evidence as ev
from sawdrift.dynamics.assembly import assemble
from sawdrift.dynamics.stepper import Stepper


def test_a_load_above_friction_runs_away_with_its_exact_acceleration():
    """Material point, no wave, L = 0.2 > mu = 0.1: m* x'' = L - mu, 1 per period^2 at m* = 0.1.

    The old code reported a settled drift velocity of 46.5 (91.5 with --periods 120)."""
    res = sd.run(sd.Scene(model="material_point", particle={"m_star": 0.1, "load": 0.2},
                          material={"mu": 0.1}, drive={"amplitude": 0.0}))
    assert res.regime == "runaway"
    assert res.settled is False
    assert math.isnan(res.drift_velocity) and math.isnan(res.drift_ratio)
    assert abs(res.mean_acceleration - (0.2 - 0.1) / 0.1) <= 1e-9


def test_vertical_vibration_with_a_load_above_friction_runs_away():
    """A* = 0.2, r = 0, L = 0.2 > mu: the mean friction is at most mu times the weight."""
    res = sd.run(sd.Scene(model="material_point", particle={"m_star": 0.1, "load": 0.2},
                          material={"mu": 0.1},
                          drive={"amplitude": 0.2, "horizontal_ratio": 0.0}))
    assert res.regime == "runaway" and res.settled is False
    assert res.mean_acceleration > 0.5  # (L - mu <N*>) / m*, <N*> = 1 over whole periods


def test_a_runaway_reports_its_long_time_acceleration_not_its_early_stick_slip():
    """mmd m* = 100, A* = 1, L = 0.2 > mu = 0.1: the default run's window (periods 33 to 60)
    is still in stick-slip with the surface and its fitted acceleration is 0.0021 per period
    squared; once the particle outruns the surface, m* <x*''> = L - mu. Reference: a quadratic
    fit to the positions of a 2000-period run over its second half."""
    scene = {"model": "mmd", "particle": {"m_star": 100.0, "load": 0.2}}
    res = sd.run(sd.Scene(**scene))
    assert res.regime == "runaway"
    long = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": 2000}),
                  trajectory=True, record_every=64)
    t, x = long.trajectory["t"].to_numpy(), long.trajectory["x"].to_numpy()
    late = t >= 1000.0
    fitted = 2.0 * np.polyfit(t[late], x[late], 2)[0]
    assert abs(res.mean_acceleration - fitted) <= 1e-3 * fitted
    early = (t >= 33.0) & (t <= 60.0)
    assert 2.0 * np.polyfit(t[early], x[early], 2)[0] > 1.5 * fitted  # what the window saw


def test_a_chaotic_runaway_gives_no_advice_to_run_its_mean_longer():
    """mmd m* = 0.1, A* = 3, L = 0.2 > mu = 0.1 bounces irregularly while it runs away: its
    long-time mean was still moving (of course), and the run said "not settled ... numerics.
    mean_periods runs it longer" beside "runaway"."""
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1, "load": 0.2},
                          drive={"amplitude": 3.0}))
    assert res.regime == "runaway"
    assert not any("not settled" in w or "long-time mean" in w for w in res.warnings)
    assert abs(res.mean_acceleration - (0.2 - 0.1) / 0.1) <= 1e-12


def test_a_load_below_friction_settles_like_a_free_particle():
    """mmd m* = 0.3, A* = 0.5, L = -0.0139 (a point of its force-velocity curve): the default
    run stopped after its fixed 60 periods, not settled, because any load might run away;
    without the load the same cell goes on in windows and settles after 168. Reference: brute
    force over periods 1000-2000 and 2000-4000 (0.3157998)."""
    scene = {"model": "mmd", "particle": {"m_star": 0.3, "load": -0.0139},
             "drive": {"amplitude": 0.5}}
    res = sd.run(sd.Scene(**scene))
    assert res.settled and res.regime == "drift_with"
    for n in (2000, 4000):
        brute = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": n,
                                                   "measure_periods": n // 2,
                                                   "max_periods": n}))
        assert abs(res.drift_ratio - brute.drift_ratio) <= max(1e-3 * brute.drift_ratio, 2e-5)


def test_a_load_below_friction_is_not_a_runaway():
    """L = 0.05 < mu = 0.1 with a wave: a steady drift exists (the load curve's range)."""
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1, "load": 0.05},
                          material={"mu": 0.1}, drive={"amplitude": 0.316}))
    assert res.regime not in ("runaway", "ejected")
    assert math.isfinite(res.drift_ratio)


@pytest.mark.parametrize("law", ["jkr", "dmt"])
def test_adhesion_raises_the_load_friction_holds_to_mu_1_plus_2_pulloff(law):
    # friction is capped at mu |N* + 2 F*_pull|; with the weight as mean normal force a contact
    # held all the time resists mu (1 + 2 F*_pull) = 0.9 here. A load of 0.5 was a 'runaway'
    # (|L| > mu = 0.3) with a fitted acceleration of -8.7e-5 against the load, while it stuck
    def scene(load):
        return sd.Scene(model="mmd", particle={"m_star": 0.2, "load": load},
                        material={"mu": 0.3, "adhesion": 1.0}, effects={"adhesion": law},
                        drive={"amplitude": 0.0})
    held = sd.run(scene(0.5))
    assert held.regime == "stick" and held.settled
    assert held.gross_slip_fraction == 0.0
    away = sd.run(scene(0.95))
    assert away.regime == "runaway"
    # sliding on, in contact: m* x'' = L - mu (1 + 2 F*_pull)
    assert away.mean_acceleration == pytest.approx((0.95 - 0.9) / 0.2, rel=1e-6)


DEVICE = {
    "model": "mmd",
    "device": {"frequency": "20 MHz", "amplitude": "1 nm", "orbit": "retrograde",
               "friction": 0.3,
               "particle": {"radius": "5 um", "density": "2200 kg/m^3",
                            "youngs_modulus": "73 GPa", "poisson": 0.17},
               "substrate": {"youngs_modulus": "200 GPa", "poisson": 0.3}},
}


def test_a_thrown_off_micro_particle_is_ejected_without_a_speed():
    """10 um silica on 20 MHz LiNbO3 at 1 nm (A* ~ 6000): thrown off in the ramp, never lands.

    The old code gave "bouncing" at -2.82 mm/s; the a0 < 1 nm warning only with --explain."""
    res = sd.run(sd.Scene.model_validate(DEVICE))
    assert res.regime == "ejected" and res.settled is False
    assert math.isnan(res.drift_velocity) and math.isnan(res.drift_ratio)
    assert res.drift_speed_m_s != res.drift_speed_m_s  # NaN: no speed in m/s either
    assert res.out_of_contact_fraction == 1.0
    # a free flight is neither chaotic nor periodic (it reported a Lyapunov exponent and a
    # periodicity of its parabola)
    assert math.isnan(res.lyapunov) and math.isnan(res.periodicity)
    # detached during the 5-period ramp, at a phase in [0, 1)
    assert 0.0 < res.detach_time < res.ramp_periods and 0.0 <= res.detach_phase < 1.0
    assert any("a0 < 1 nm" in w for w in res.warnings)
    # and when, in seconds: t* counts wave periods, 1 / (20 MHz) each (it was in periods only)
    assert res.extra["detach_time_s"] == pytest.approx(res.detach_time / 20e6, rel=1e-12)
    # when it can land again, in periods and seconds (ballistic: the flight is gravity's alone)
    said = [w for w in res.warnings if w.startswith("ejected: ")]
    assert len(said) == 1
    land = float(said[0].split("before t* = ")[1].split(" ")[0])
    seconds = float(said[0].split("(ballistic, ")[1].split(" s)")[0])
    assert land > res.periods and seconds == pytest.approx(land / 20e6, rel=2e-3)


def test_an_ejection_says_when_the_particle_can_land_again():
    """A rigid point at m* = 4.13, A* = 2170 is thrown off in the ramp and ejected; the run said
    "a longer run would not settle it", but under gravity it lands at t* = 16321 and bounces on.
    Its warning now gives the earliest landing of its free flight, which a fixed run brackets:
    still in the air over periods 16200 to 16300, down again within 16300 to 16400."""
    cell = {"model": "material_point", "particle": {"m_star": 4.13}, "drive": {"amplitude": 2170}}
    res = sd.run(sd.Scene(**cell))
    assert res.regime == "ejected"
    said = [w for w in res.warnings if w.startswith("ejected: ")]
    assert len(said) == 1
    land = float(said[0].split("before t* = ")[1].split(" ")[0])
    assert 16300.0 < land < 16400.0

    def window_to(end: int) -> sd.Result:
        return sd.run(sd.Scene(**cell, numerics={"settle": False, "periods": end,
                                                 "measure_periods": 100}))

    # (a rigid point's landing is an impact of no duration: it shows as the lift-off after it)
    assert window_to(16300).liftoffs_per_period == 0.0
    assert window_to(16400).liftoffs_per_period > 0.0


def test_a_point_thrown_into_long_flights_bounces_and_is_not_ejected():
    """A rigid point at m* = 1.986, A* = 8.7 (a cell of the out-of-sample audit grid, m* 1.3 to
    90 in 11 log steps) is in the air 99.97 % of the time, one landing about every 190 periods.
    Its default run spent its window in one such flight and, the flight outlasting the 114
    periods run so far, was reported ``ejected`` without a drift; brute force (8000 periods,
    the last 4000 measured) shows it bouncing on. The default run follows the bounces over at
    least 16 flights and reports their long-time mean, which must agree with brute force within
    3 of its errors."""
    m_star = 1.3 * (90.0 / 1.3) ** 0.1
    scene = {"model": "material_point", "particle": {"m_star": m_star},
             "drive": {"amplitude": 8.7}}
    res = sd.run(sd.Scene(**scene))
    brute = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": 8000,
                                               "measure_periods": 4000, "max_periods": 8000}))
    assert brute.regime == "bouncing"
    assert res.regime == "bouncing" and res.settled is False
    assert math.isfinite(res.drift_ratio_se) and res.drift_ratio_se > 0.0
    assert abs(res.drift_ratio - brute.drift_ratio) <= 3.0 * res.drift_ratio_se
    # an error that tells the sign (brute force drifts at 0.35): below a third of the drift, not
    # any error wide enough to cover it (0.061 over its 3400 periods)
    assert res.drift_ratio_se < brute.drift_ratio / 3.0


def test_the_event_log_of_a_long_run_is_bounded():
    """mmd, m* = 1e4, A* = 0.5, mu = 0.5 slips every period: 20000 periods before the window
    leave the log at its first size, the transient's events counted, not kept."""
    scene = bind(sd.Scene(model="mmd", particle={"m_star": 1e4}, material={"mu": 0.5},
                          drive={"amplitude": 0.5}))
    model = model_for(scene)
    stepper = Stepper(scene, model, assemble(scene, "compiled", model), False, event_periods=1)
    size = stepper.st.size
    stepper.advance(20000 * stepper.k_per)
    assert stepper.st.size == size
    assert stepper.st[ev.S_EVOLD] > 20000  # at least one event a period was seen and counted
    assert int(stepper.st[ev.S_NEV]) <= int(stepper.st[ev.S_EVCAP])
    assert np.all(np.isfinite(stepper.y))


def _slipping_stepper() -> tuple[Stepper, np.ndarray, float]:
    """mmd, m* = 1e4, A* = 0.5, mu = 0.5 (slips in most periods: events all through a window)."""
    scene = bind(sd.Scene(model="mmd", particle={"m_star": 1e4}, material={"mu": 0.5},
                          drive={"amplitude": 0.5}))
    model = model_for(scene)
    plan = assemble(scene, "compiled", model)
    stepper = Stepper(scene, model, plan, False, event_periods=1)
    stepper.advance(20 * stepper.k_per)
    return stepper, plan.drive.state_scale(scene), plan.drive.horizontal_speed(scene)


def test_a_long_measuring_window_starts_with_a_bounded_event_log():
    """A fixed run's window is half of it: 64 event rows a period reserved up front made a
    2e6-period run allocate 3.3 GiB before its first step (and fail); the log now starts at
    most 65536 rows (3.7 MB) and grows as the events come."""
    scene = bind(sd.Scene(model="mmd", particle={"m_star": 1e4}, drive={"amplitude": 0.5}))
    model = model_for(scene)
    stepper = Stepper(scene, model, assemble(scene, "compiled", model), False,
                      event_periods=1_000_000)
    assert stepper.st.nbytes <= 4_000_000


def test_a_window_with_more_events_than_its_log_keeps_its_newest_and_counts_all(monkeypatch):
    """With the log's cap at 128 rows, a 600-period window of a contact slipping in most periods
    (over 300 events) keeps its newest events, the same rows as an uncapped window of the same
    run, sheds the rest (counted), and its statistics still cover every step."""
    from sawdrift.dynamics import stepper as stepper_module
    from sawdrift.dynamics.window import measure_window

    full_stepper, scale, speed = _slipping_stepper()
    full = measure_window(full_stepper, 600, speed, scale)
    monkeypatch.setattr(stepper_module, "KEPT_EVENT_ROWS", 128)
    capped_stepper, _, _ = _slipping_stepper()
    capped = measure_window(capped_stepper, 600, speed, scale)
    n_full, n_kept = full.events.shape[0], capped.events.shape[0]
    assert n_full > 300 and full.events_shed == 0
    assert capped_stepper.st[ev.S_EVCAP] <= 128 and 64 <= n_kept <= 128
    assert capped.events_shed == n_full - n_kept
    np.testing.assert_array_equal(capped.events, full.events[-n_kept:])
    assert capped.gross_slip_fraction == full.gross_slip_fraction
    assert capped.drift == full.drift
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 1e4}, material={"mu": 0.5},
                          drive={"amplitude": 0.5}, numerics={"settle": False, "periods": 600}))
    assert any("events" in w and "not kept" in w for w in res.warnings)


def test_a_bouncer_last_seen_in_one_flight_reports_its_long_time_mean():
    """mmd, m* = 0.178, A* = 8.41: thrown for longer than a window, the default run's windows
    ended inside one flight, and its drift was reported unsettled without an error. It lands again
    within the time run, so its drift is the long-time mean of its bounces, with an error that
    covers an independent run of 8000 periods (started on another trajectory) within 3
    combined errors."""
    base = {"model": "mmd", "particle": {"m_star": 0.177828}, "drive": {"amplitude": 8.413951}}
    res = sd.run(sd.Scene.model_validate(base))
    assert res.regime == "bouncing" and not res.settled
    assert math.isfinite(res.drift_ratio_se) and res.drift_ratio_se > 0.0
    ref = sd.run(sd.Scene.model_validate({**base, "drive": {**base["drive"], "ramp_periods": 7.0},
                                          "numerics": {"mean_periods": 8000, "settle_tolerance": 1e-9}}))
    assert math.isfinite(ref.drift_ratio_se)
    assert abs(res.drift_ratio - ref.drift_ratio) <= 3.0 * math.hypot(res.drift_ratio_se,
                                                                      ref.drift_ratio_se)
    # the error of a mean over its periods, as the reference's over its own: within twice the
    # reference's error scaled by sqrt(their lengths' ratio) (not any error that covers it)
    scaled = ref.drift_ratio_se * math.sqrt(ref.periods / res.periods)
    assert res.drift_ratio_se <= 2.0 * scaled, (res.drift_ratio_se, scaled)


def test_a_run_that_does_not_settle_says_why():
    # mmd, m* = 0.00237, A* = 1.50: in contact next to the contact resonance, its window means
    # still move one way after the default run's 1000 further periods (-0.0049 there; -0.0074
    # over periods 2000-4000 of a fixed run, -0.0086 over 4000-8000). (m* = 0.0042, A* = 0.89,
    # the example before, has window means that turn over a long beat: a long-time mean now.)
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.002371},
                          drive={"amplitude": 1.496236}))
    assert not res.settled and math.isnan(res.drift_ratio_se)
    assert any(w.startswith("not settled: the drift") for w in res.warnings)


def test_a_window_that_shed_events_still_reads_its_hops(monkeypatch):
    """mmd m* = 1, A* = 1 hops once a period. With the log's cap at 128 rows a 400-period window
    keeps only its last events: its hops were read in blocks from the window's start (empty,
    so no hop period: "bouncing"); they are read over the periods the kept events cover."""
    from sawdrift.dynamics import stepper as stepper_module

    scene = sd.Scene(model="mmd", particle={"m_star": 1.0}, drive={"amplitude": 1.0},
                     numerics={"settle": False, "periods": 400})
    full = sd.run(scene)
    monkeypatch.setattr(stepper_module, "KEPT_EVENT_ROWS", 128)
    capped = sd.run(scene)
    assert any("not kept" in w for w in capped.warnings)
    assert full.regime == capped.regime == "hopping"
    assert capped.hop_period == full.hop_period == 1
    # the kept lift-offs are the window's last ones: their mean phase lies within the spread of
    # the whole window's phases (0.019), and the spreads agree
    assert abs(capped.liftoff_phase - full.liftoff_phase) <= full.liftoff_phase_spread
    assert capped.liftoff_phase_spread == pytest.approx(full.liftoff_phase_spread, rel=0.1)


def test_the_periods_and_steps_of_a_result_count_its_long_time_mean():
    """mmd m* = 0.1, A* = 1, mu = 0.1 is chaotic: its long-time mean runs 500 periods after the
    fixed 60-period run, on a copy of the run. The Result said periods 60, steps 7680,
    settle_periods 60 although its mean (and the drift reported) came from 560 periods."""
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 1.0},
                          material={"mu": 0.1}))
    assert math.isfinite(res.drift_ratio_se)
    budget = res.scene["numerics"]["mean_periods"]
    assert res.periods >= 60 + budget
    assert res.steps == round(res.periods * res.steps_per_period)
    assert res.settle_periods == res.periods


@pytest.mark.parametrize(("m_star", "amplitude", "method"), [
    (50.0, 1.0, "solved"), (4.216965034285822, 8.413951416451951, "windows_full")])
def test_a_settling_run_counts_its_periods_from_its_start(m_star, amplitude, method):
    """A settling run's ``settle_periods`` are its own periods when it settled, the 33 periods it
    ran before its settling began included, as ``periods`` and a fixed run count them: mmd m* = 50,
    A* = 1 (solved) said settle_periods 53 with periods 86, and m* = 4.2, A* = 8.4 (windows) 716
    with periods 749."""
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": m_star},
                          drive={"amplitude": amplitude}))
    assert res.settle_method == method and res.settled is True
    assert res.settle_periods == res.periods
    assert res.steps == round(res.periods * res.steps_per_period)


def test_a_run_gone_on_to_its_orbit_is_not_called_fixed():
    """mmd m* = 0.3, A* = 1.5 loses contact and its fixed window found no orbit: the run goes on
    in windows until it is on one (114 periods), and said settle_method "fixed"."""
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.3}, drive={"amplitude": 1.5}))
    assert res.settled and res.periods > 60
    assert res.settle_method == "fixed_then_windows"


def test_a_load_above_friction_is_a_runaway_even_in_a_long_flight():
    """A rigid point at m* = 10, A* = 3.16 under L = 0.2 > mu = 0.1, run for 40 periods, ends in
    a flight longer than the run and was called ejected; without the load the same cell lands
    and bounces on (a horizontal load does not change a rigid point's vertical motion), so under
    it the particle runs away at (L - mu)/m*."""
    scene = {"model": "material_point", "particle": {"m_star": 10.0, "load": 0.2},
             "drive": {"amplitude": 3.1622776601683795}, "numerics": {"periods": 40}}
    res = sd.run(sd.Scene(**scene))
    assert res.regime == "runaway"
    assert abs(res.mean_acceleration - 0.01) <= 1e-12
    free = sd.run(sd.Scene(**{**scene, "particle": {"m_star": 10.0}}))
    assert free.regime != "ejected"


def test_a_sweep_row_keeps_an_ejection_s_detach_time():
    """The table row of an ejected cell holds its detach time (the explorer shows it): the
    column was not kept, so a table said only that the cell had no drift."""
    from sawdrift.study.sweep import run_cell

    scene = sd.Scene(**DEVICE)
    res = sd.run(scene)
    row = run_cell(scene.model_dump_json())
    assert res.regime == row["regime"] == "ejected" and row["resolved_as"] == "ejected"
    assert row["detach_time"] == res.detach_time and math.isfinite(row["detach_time"])


def _brute(periods: float, window: float, **scene) -> sd.Result:
    return sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": periods,
                                              "measure_periods": window}))


def test_a_slow_approach_of_a_damped_heavy_hopper_is_no_long_time_mean():
    """mmd m* 30, A* 2, mu 0.2, e = 0.6 hops once a period while its speed still rises after
    the 60 windows of its cap: the default reported 0.7928 +- 0.0052 as a long-time mean, 16
    errors from the drift it reaches (0.8779 over the last 20000 of 1e5 periods, an orbit of
    one period); then not settled, its windows still rising one way. With the restitution
    damping in the contact law its orbit is solved directly: settled, within 1e-4 of brute
    force (0.8779294 against 0.8779269), no long-time mean."""
    scene = dict(model="mmd", particle={"m_star": 30.0}, drive={"amplitude": 2.0},
                 material={"mu": 0.2, "restitution": 0.6})
    truth = _brute(1e5, 2e4, **scene)
    assert truth.orbit_period == 1
    res = sd.run(sd.Scene(**scene))
    assert res.settled and not math.isfinite(res.drift_ratio_se)
    assert abs(res.drift_ratio - truth.drift_ratio) <= 1e-4 * abs(truth.drift_ratio), (
        res.drift_ratio, truth.drift_ratio)
    assert res.regime == truth.regime == "hopping"


def test_a_settling_run_stopped_within_a_flight_means_its_bounces():
    """material_point m* 60, A* 10, mu 0.5: its settling windows hit their cap inside a flight
    of 6900 periods and reported that flight's speed, +0.400, with no error, where its orbit of
    7540 periods drifts at -0.4207. The mean of its bounces is within 3 of its errors of it."""
    scene = dict(model="material_point", particle={"m_star": 60.0}, drive={"amplitude": 10.0},
                 material={"mu": 0.5})
    truth = _brute(5e4, 30160, **scene)
    assert truth.orbit_period == 7540
    res = sd.run(sd.Scene(**scene))
    assert math.isfinite(res.drift_ratio_se) and res.drift_ratio_se > 1e-6
    assert abs(res.drift_ratio - truth.drift_ratio) <= 3.0 * res.drift_ratio_se
    # a budget capped below 16 flights says so: at mean_periods 100 its 11728 periods hold 1.7
    # flights and gave +0.457 +- 0.12 (7 errors off) with only the generic lower-bound warning
    short = sd.run(sd.Scene(**scene, numerics={"mean_periods": 100}))
    assert any("of its longest flights only" in w for w in short.warnings), short.warnings


def test_a_load_equal_to_the_friction_bound_has_no_steady_drift():
    """At L = mu the sliding particle's mean force vanishes at every speed: mmd m* 1, A* 0.5,
    mu = L = 0.1 settled at 1.0088 while brute force went on rising (1.0143 at 2400 periods,
    1.0170 at 40000). Below the bound the same scene settles."""
    scene = dict(model="mmd", particle={"m_star": 1.0, "load": 0.1}, drive={"amplitude": 0.5},
                 material={"mu": 0.1})
    res = sd.run(sd.Scene(**scene))
    assert not res.settled and any("(neutral)" in w for w in res.warnings)
    below = sd.run(sd.Scene(**{**scene, "particle": {"m_star": 1.0, "load": 0.05}}))
    assert below.settled and not any("(neutral)" in w for w in below.warnings)


def test_a_run_recording_its_trajectory_reports_what_a_plain_one_does():
    """A default run whose contact held through its first window ends there; one recording its
    trajectory went on to its whole length and reported its last window instead (mmd m* 1.3335,
    A* 0.13335: 5.79e-6 became -2.69e-6, and a table swept with --traces differed in 50 of 162
    rows from the same sweep without)."""
    scene = sd.Scene(model="mmd", particle={"m_star": 1.3335}, drive={"amplitude": 0.13335})
    plain, traced = sd.run(scene), sd.run(scene, trajectory=True)
    assert plain.regime == traced.regime == "stick"
    assert traced.drift_ratio == plain.drift_ratio and traced.periods == plain.periods
    assert traced.trajectory is not None and len(traced.trajectory) > 0


def test_a_recorded_trajectory_is_bounded_and_thinned_evenly(monkeypatch):
    """A 2e5-period run with -o asked one buffer of 2.1 GiB (every step of the advance) and lost
    the run. A recorded advance goes in segments, and past the most rows a run keeps its record
    is thinned to every other row: bounded, evenly spaced, to the end, the run itself unchanged
    (here with the bound at 4096 rows: 60 periods of 128 steps record 7680)."""
    import sawdrift.dynamics.records as records
    import sawdrift.dynamics.stepper as stepper_module

    monkeypatch.setattr(stepper_module, "MAX_TRAJECTORY_ROWS", 4096)
    monkeypatch.setattr(stepper_module, "SEGMENT_ROWS", 512)
    scene = sd.Scene(model="mmd", numerics={"settle": False, "steps_per_period": 128})
    plain = sd.run(scene)
    recorded = sd.run(scene, trajectory=True)
    tr = recorded.trajectory
    assert len(tr) <= 4096 + 512 and tr["t"].iloc[-1] > 59.9
    gaps = np.diff(tr["t"].to_numpy())
    assert np.allclose(gaps, gaps[0], rtol=1e-9) and gaps[0] == pytest.approx(2 / 128)
    assert recorded.drift_velocity == plain.drift_velocity  # recording changes no arithmetic
    assert records.MAX_TRAJECTORY_ROWS == 1 << 20  # the bound itself: 92 MB of rows


def test_recording_a_trajectory_does_not_change_an_irregular_heavy_bouncers_evidence():
    """mmd m* = 10, A* = 5, 40 periods: an irregular heavy bouncer whose long-time mean comes
    from the friction at an imposed speed along its record. With a trajectory (``run -o``) it
    ran a separate 400-period evidence window: 935 periods, Lyapunov +0.0077 against 535 and
    -0.0001 without. The trajectory holds every step of the run, evenly spaced."""
    import numpy as np

    scene = sd.Scene(model="mmd", particle={"m_star": 10.0}, drive={"amplitude": 5.0},
                     numerics={"periods": 40})
    plain, traced = sd.run(scene), sd.run(scene, trajectory=True)
    assert plain.settle_method == traced.settle_method == "imposed_speed"
    for key in ("periods", "steps", "drift_ratio", "drift_ratio_se", "lyapunov",
                "gross_slip_fraction", "liftoffs_per_period", "periodicity", "regime"):
        assert getattr(plain, key) == getattr(traced, key), key
    t = traced.trajectory["t"].to_numpy()
    assert t[0] == 0.0 and t[-1] == pytest.approx(traced.periods, abs=0.01)
    assert np.ptp(np.diff(t)) < 1e-9
