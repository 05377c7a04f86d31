"""Periodic orbits settle on their exact period; a growing orbit is not settled.

References are closed forms or the orbit itself: the stroboscopic state repeating to round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.dynamics.synchrony import orbit_pattern


def _run(model: str, m: float, amp: float, mu: float = 0.1, **drive) -> sd.Result:
    return sd.run(sd.Scene(model=model, particle={"m_star": m}, material={"mu": mu},
                           drive={"amplitude": amp, **drive}))


def _period_two_phases(gamma: float, hops: int = 200) -> tuple[float, float]:
    """Take-off phases of the period-2 orbit of the completely inelastic bouncing ball.

    Plate u = Gamma sin(tau) (units g / omega^2), take-off where Gamma sin(tau) = 1 with the
    plate decelerating; free flight x(t) = u(t0) + u'(t0)(t - t0) - (t - t0)^2 / 2; landing at the
    first later crossing with the plate, then a take-off at once if Gamma sin(tau_land) > 1, else
    at the next phase with Gamma sin = 1. The period-2 orbit is the fixed point of the map
    iterated twice (found by iterating from the period-1 orbit's neighbourhood)."""
    def flight(t0: float) -> float:
        x0, v0 = gamma * math.sin(t0), gamma * math.cos(t0)
        t = t0 + 1e-9
        gap = lambda s: x0 + v0 * (s - t0) - 0.5 * (s - t0) ** 2 - gamma * math.sin(s)  # noqa: E731
        h = 1e-3
        while gap(t + h) > 0.0:
            t += h
        lo, hi = t, t + h
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if gap(mid) > 0.0 else (lo, mid)
        return 0.5 * (lo + hi)

    def take_off(t_land: float) -> float:
        if gamma * math.sin(t_land) >= 1.0:
            return t_land
        base = math.asin(1.0 / gamma)
        k = math.ceil((t_land - base) / (2 * math.pi))
        return base + 2 * math.pi * k

    t = math.asin(1.0 / gamma) + 0.05
    phases = []
    for _ in range(hops):  # at Gamma 3.8 the phases repeat to 5e-13 after 100 hops (4000: 8 s)
        t = take_off(flight(t))
        # the scene's surface height is -A cos(2 pi t*) = A sin(2 pi t* - pi/2): tau = 2 pi t* - pi/2
        phases.append((t / (2 * math.pi) + 0.25) % 1.0)
    # the iteration has reached the period-2 fixed point: each phase repeats two hops later
    assert abs(phases[-1] - phases[-3]) < 1e-10 and abs(phases[-2] - phases[-4]) < 1e-10
    return phases[-2], phases[-1]


def test_the_bouncing_ball_past_its_period_doubling_hops_with_period_two():
    """Gamma = 4 pi^2 m* A* = 3.8 > sqrt(4 + pi^2) = 3.724: take-offs alternate between two
    phases (0.3765 and 0.3034); the old default averaged them into one period-1 phase, 0.340."""
    m = 0.025330295910584444
    res = _run("material_point", m, 3.8, horizontal_ratio=0.0)
    assert abs(4 * math.pi**2 * m * 3.8 - 3.8) < 1e-12
    assert res.regime == "hopping" and res.hop_period == 2 and res.orbit_period == 2
    assert res.settled is True
    expected = sorted(_period_two_phases(3.8))
    got = sorted(res.liftoff_phases)
    assert len(got) == 2
    assert np.allclose(got, expected, atol=1e-4), (got, expected)


def _ball(gamma: float) -> sd.Result:
    """The completely inelastic bouncing ball (a rigid point, no horizontal motion) at Gamma."""
    return _run("material_point", 0.1, gamma / (4 * math.pi**2 * 0.1), horizontal_ratio=0.0)


def test_a_decaying_alternation_below_the_doubling_is_a_hop_of_one():
    """Gamma = 3.7 < 3.724: the period-1 orbit is stable, its multiplier 1 - sqrt(Gamma^2 - pi^2)
    = -0.955, so a transient alternates for hundreds of periods while it decays. It repeated
    after two periods to 1e-8 while its take-offs still differed by 2e-8, and was called a hop
    of period 2 with the phases 0.33858 and 0.33858; the orbit is period 1 at the take-off
    (acos(pi / Gamma) + pi/2) / (2 pi)."""
    gamma = 3.7
    res = _ball(gamma)
    assert res.hop_period == 1 and res.orbit_period == 1 and res.settled is True
    phase = (math.acos(math.pi / gamma) + math.pi / 2) / (2 * math.pi)
    assert res.liftoff_phases == pytest.approx([phase], abs=1e-6)
    # its exponent is the multiplier's log per period
    assert res.lyapunov == pytest.approx(math.log(math.sqrt(gamma**2 - math.pi**2) - 1.0),
                                         abs=0.005)


def test_past_the_doubling_a_growing_alternation_is_followed_to_its_orbit_of_two():
    """Gamma = 3.73, multiplier -1.0108: the alternation away from the unstable period-1 orbit
    grows by 1 % a period, and settles on the orbit of 2 after about 700 periods. The default
    settled on the hop of 1 (its zero drift agreed window to window) with the fixed window's
    exponent +0.010, the unstable orbit's; the 2-cycle is stable (its exponent negative)."""
    gamma = 3.73
    res = _ball(gamma)
    assert res.hop_period == 2 and res.orbit_period == 2 and res.settled is True
    expected = sorted(_period_two_phases(gamma, hops=1600))
    assert np.allclose(sorted(res.liftoff_phases), expected, atol=1e-4)
    assert res.lyapunov < 0.0


def test_a_growing_period_two_hop_is_not_settled_and_then_found():
    """hertz_tsuji, m* = 0.1, A* = 0.536: after 60 periods the alternation still grows (not
    settled, the old code said settled); run on, it reaches an exact period-2 orbit."""
    short = sd.run(sd.Scene(model="hertz_tsuji", particle={"m_star": 0.1},
                            drive={"amplitude": 0.536}, numerics={"settle": False}))
    assert short.settled is False
    res = _run("hertz_tsuji", 0.1, 0.536)
    assert res.orbit_period == 2 and res.hop_period == 2 and res.regime == "hopping"
    assert res.settled is True


def test_a_period_ten_orbit_is_a_hop_of_period_ten():
    """Material point, m* = 100, A* = 0.005, mu = 0.1: the state repeats after 10 periods (the
    old default called it bouncing, which means irregular)."""
    res = _run("material_point", 100.0, 0.005)
    assert res.orbit_period == 10
    assert res.regime == "hopping" and res.hop_period == 10 and res.settled is True
    assert res.liftoffs_per_hop == len(res.liftoff_phases) >= 1


def test_an_orbit_longer_than_the_short_windows_is_found_and_settled_on():
    """Material point, m* = 0.1755, A* = 8.7, mu = 0.1: three long flights make an orbit of 54
    periods, so windows of 27 periods alternate between drift ratios 0.21 and -0.02, and those of
    81 between 0.05 and 0.12. With orbits looked for only up to 24 periods, the run went on to
    1086 periods and settled where windows of 162 agreed, without knowing the orbit; it now
    finds it in a window of 81 and settles on it. An orbit longer than 24 periods is called
    bouncing, as a phase diagram sees it, with its period in ``orbit_period``. Reference: 40
    whole orbits of a fixed run after a transient of 840 periods."""
    from sawdrift.dynamics.window import LONGEST_HOP

    m, a = 0.17545579636386113, 8.7
    ref = sd.run(sd.Scene(model="material_point", particle={"m_star": m}, drive={"amplitude": a},
                          numerics={"settle": False, "periods": 3000, "measure_periods": 2160}))
    res = sd.run(sd.Scene(model="material_point", particle={"m_star": m}, drive={"amplitude": a}))
    assert ref.orbit_period == 54 and res.orbit_period == 54 > LONGEST_HOP
    assert res.settled is True and res.periods < 500
    assert res.regime == "bouncing" and res.hop_period == 0
    assert abs(res.drift_ratio - ref.drift_ratio) <= 1e-9 * abs(ref.drift_ratio)


def test_orbit_pattern_reads_the_last_orbit_and_checks_the_one_before():
    t = np.array([0.3, 2.25, 10.3, 12.25, 20.3, 22.25])
    sync = orbit_pattern(t, 0.0, 30, 10)
    assert sync is not None and sync.hop_period == 10 and sync.liftoffs_per_hop == 2
    assert np.allclose(sync.phases, (0.3, 0.25))
    # the orbit before does not match: no pattern claimed
    assert orbit_pattern(np.array([0.3, 2.25, 10.3, 20.3, 22.25]), 0.0, 30, 10) is None


def test_a_quasi_periodic_hop_does_not_spend_the_orbit_search():
    """mmd, m* = 0.178, A* = 2.51 hops once a period, modulated by the undamped contact
    oscillation: over 1920 periods its stroboscopic state stays about 0.02 from repeating (no
    periodic orbit to find), so the search for one stops once that distance stays flat
    (it ran its whole 300 periods before) and the drift is the long run's to 1e-5."""
    long = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.177828},
                           drive={"amplitude": 2.511886},
                           numerics={"settle": False, "periods": 1920}))
    assert long.orbit_period == 0 and long.periodicity > 1e-3  # no orbit, however long
    res = _run("mmd", 0.177828, 2.511886)
    assert res.regime == "hopping" and res.hop_period == 1
    assert res.periods <= 60 + 4 * 27  # the fixed run and at most four more windows
    assert abs(res.drift_ratio - long.drift_ratio) < 1e-5


def test_a_periodic_orbit_s_drift_is_taken_only_where_the_window_is_on_it():
    """material_point m* = 0.059, A* = 8.7, mu = 0.1 hops on a period-7 orbit: the fixed window
    of 27 periods found the orbit from its last states and took the drift over its last three
    orbits (21 periods), though the first of them was still on the approach: -0.571062, 2e-3
    from the orbit's -0.5722326 (brute force over 1000 of 2000 periods, over 100 of 200 the
    same to 1e-12). Only the orbits whose states repeat count, and the drift is the orbit's."""
    from sawdrift.dynamics.window import orbit_span

    m, a = 0.05899083279439075, 8.7
    ref = sd.run(sd.Scene(model="material_point", particle={"m_star": m}, drive={"amplitude": a},
                          numerics={"settle": False, "periods": 2000, "measure_periods": 1000}))
    res = sd.run(sd.Scene(model="material_point", particle={"m_star": m}, drive={"amplitude": a}))
    assert res.settled and res.orbit_period == 7
    assert abs(res.drift_ratio - ref.drift_ratio) <= 1e-6 * abs(ref.drift_ratio)
    # states (x*', y*, y*') of an orbit of period 3 reached after 5 approaching periods
    orbit = np.array([[0.0, 1.0, 0.1, 0.2], [0.0, 1.5, 0.3, 0.1], [0.0, 0.7, 0.2, 0.4]])
    approach = np.array([[0.0, 2.0 + k, 0.5, 0.5] for k in range(5)])
    samples = np.vstack([approach] + [orbit] * 6)  # 23 states, 18 on the orbit
    assert orbit_span(samples, np.ones(3), 3) == 15  # whole orbits among the 17 checked


def test_a_window_on_an_exact_orbit_settles_the_full_inertia_windows():
    """A rigid point hopping on an orbit of 20 periods (m* 0.1, A* 8): its full-inertia windows
    of 62 periods (not whole orbits) had means changing by 3e-4, gave up, and it was reported
    'NOT settled: irregular', 0.0269 +- 0.012, with orbit_period 20 in the same Result. Its
    drift over whole orbits is exact: brute force over periods 1100-1500, measured on the orbit,
    gives the same to 1e-9."""
    res = _run("material_point", 0.1, 8.0)
    assert res.orbit_period == 20 and res.hop_period == 20 and res.settled is True
    assert res.drift_ratio_se is None or math.isnan(res.drift_ratio_se)
    brute = sd.run(sd.Scene(model="material_point", particle={"m_star": 0.1},
                            drive={"amplitude": 8.0},
                            numerics={"settle": False, "periods": 1500, "measure_periods": 400}))
    assert brute.orbit_period == 20
    assert res.drift_ratio == pytest.approx(brute.drift_ratio, abs=1e-9)


def test_a_window_approaching_an_orbit_reads_its_hops_against_it():
    """material_point m* 3, A* 0.3, mu 0.2 settles by its windows (its changes within the
    tolerance) before its state repeats after 17 periods to round-off: its two lift-offs a
    window were called 'bouncing' (the docs' irregular motion) with no hop period. Brute force
    over 2600 periods: hopping, hop period 17 on an orbit of 17, the same two take-off phases."""
    import sawdrift as sd

    scene = dict(model="material_point", particle={"m_star": 3.0}, drive={"amplitude": 0.3},
                 material={"mu": 0.2})
    res = sd.run(sd.Scene(**scene))
    brute = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": 2600,
                                               "measure_periods": 1300}))
    assert brute.orbit_period == 17 and brute.hop_period == 17
    assert res.settled and res.regime == brute.regime == "hopping" and res.hop_period == 17
    assert sorted(res.liftoff_phases) == pytest.approx(sorted(brute.liftoff_phases), abs=1e-6)


def test_near_orbit_needs_one_period_clearly_nearer_than_every_other():
    import numpy as np

    from sawdrift.dynamics.window import near_orbit

    n, p = 60, 5
    k = np.arange(n)
    base = np.stack([np.sin(2 * np.pi * k / p), np.cos(2 * np.pi * k / p),
                     np.sin(4 * np.pi * k / p)], axis=1)
    scale = np.ones(3)

    def samples(states):
        return np.column_stack([k, states])  # x*, then the scaled (x*', y*, y*')

    approaching = base + 1e-3 * 0.8 ** k[:, None]  # 0.8^52 ~ 1e-5 at the end
    assert near_orbit(samples(approaching), scale) == p
    assert near_orbit(samples(base + 1e-2), scale) == p  # a constant offset repeats too
    quasi = np.stack([np.sin(2 * np.pi * k * 0.3819), np.cos(2 * np.pi * k * 0.3819),
                      np.sin(2 * np.pi * k * 0.7234)], axis=1)
    assert near_orbit(samples(quasi), scale) == 0


def test_a_settled_orbit_s_exponent_is_measured_on_that_orbit():
    """material_point m* = 1, A* = 0.5 settles on an orbit of 10 periods in which the point
    sticks after its landings: a perturbation is erased, the exponent is -inf, as a 300-period
    fixed run measures on the orbit. The default run reported -0.061, the exponent of a window of
    its transient (at period 87), before going on to settle at period 195."""
    settled = _run("material_point", 1.0, 0.5)
    fixed = sd.run(sd.Scene(model="material_point", particle={"m_star": 1.0},
                            drive={"amplitude": 0.5}, numerics={"settle": False, "periods": 300}))
    assert settled.settled and settled.orbit_period == 10 and fixed.orbit_period == 10
    assert fixed.lyapunov == -math.inf
    assert settled.lyapunov == -math.inf


def test_a_fixed_run_off_any_orbit_is_not_called_settled():
    """hertz_mindlin_dem m* = 0.05, A* = 0.4: irregular bouncing, no periodic orbit. Its fixed
    run of 2000 periods said settled (the thirds of its window agreed), which means a fixed point
    or a periodic orbit; the default run says irregular, a long-time mean."""
    res = sd.run(sd.Scene(model="hertz_mindlin_dem", particle={"m_star": 0.05},
                          drive={"amplitude": 0.4},
                          numerics={"settle": False, "periods": 2000, "measure_periods": 1000}))
    assert res.contact_lost and res.orbit_period == 0
    assert res.settled is False
    default = _run("hertz_mindlin_dem", 0.05, 0.4)
    assert default.settled is False and math.isfinite(default.drift_ratio_se)
