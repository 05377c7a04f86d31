"""Free flights in closed form (dynamics.flight) against the scheme stepped one step at a time.

The oracle is an independent plain-Python Adams-Bashforth 4 integration of eq. 5 that calls the
contact law at every step, flights included; the wave loop takes a flight's steps in closed form
once its derivative history is a parabola's. Both must give the same trajectory to rounding and
the same window statistics (steps out of contact, deepest flight).
"""

from __future__ import annotations

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.contact.binding import bind, model_for
from sawdrift.dynamics import adams_bashforth as ig
from sawdrift.dynamics import evidence as ev
from sawdrift.dynamics.assembly import assemble
from sawdrift.dynamics.flight import flight_skip
from sawdrift.dynamics.stepper import Stepper


def _stepper(m_star: float, amplitude: float, **extra) -> Stepper:
    parts = {"particle": {"m_star": m_star}, "drive": {"amplitude": amplitude}, **extra}
    scene = bind(sd.Scene(model="mmd", numerics={"settle": False}, **parts))
    model = model_for(scene)
    st = Stepper(scene, model, assemble(scene, "compiled", model), False, event_periods=27)
    st.warm_up()
    return st


def _oracle(stepper: Stepper, n: int) -> tuple[np.ndarray, int, float]:
    """(x, x', y, y') before each of ``n`` steps, steps out of contact after the ramp, min a*
    after the ramp: AB4 with the law called every step (the module docstring's oracle)."""
    prm = stepper.prm
    m, mu, h = prm[ig.P_M], prm[ig.P_MU], prm[ig.P_H]
    scale_b = 1.0 / (prm[ig.P_THETA] * mu)
    k_ramp = int(prm[ig.P_KRAMP])
    surface = stepper.drive.functions()[0].py_func
    hist = stepper.history.copy()
    hist.reset()
    y = stepper.y[:4].copy()
    fh = np.zeros((4, 4))
    out, amin, rows = 0, np.inf, np.empty((n, 4))
    for k in range(n):
        ux, uxd, uy, uyd = surface(k * h, y[0], stepper.dp)
        a = y[2] - uy
        nf, tf = hist.advance(a, (y[0] - ux) * scale_b, y[3] - uyd, (y[1] - uxd) * scale_b)
        rows[k] = y
        if k >= k_ramp:
            out += a <= 0.0
            amin = min(amin, a)
        fh[1:] = fh[:-1].copy()
        fh[0] = (y[1], -mu * tf / m, y[3], (1.0 - nf) / m)
        q = min(k + 1, 4)
        y = y + h * (ig.AB_COEFFS[q - 1, :q] @ fh[:q])
    return rows, out, amin


@pytest.mark.parametrize("m_star, amplitude", [(0.3, 2.0), (0.1, 3.0), (1.0, 1.5)])
def test_flights_in_closed_form_follow_the_scheme_step_by_step(m_star, amplitude):
    stepper = _stepper(m_star, amplitude)
    n = 12 * stepper.k_per
    ref, out, amin = _oracle(stepper, n)
    rows: list[np.ndarray] = []
    stepper.advance(n, rows=rows)
    got = np.concatenate(rows)[:, 1:5]
    assert out > 2 * stepper.k_per  # at least two periods' worth of flight steps
    # to rounding over 12 periods (a wrong derivative history at the flight's start: 4e-8)
    assert np.max(np.abs(got - ref)) < 1e-11
    assert stepper.st[ev.S_OUT] == out
    assert stepper.st[ev.S_AMIN] == pytest.approx(amin, abs=1e-11)


def test_flights_keep_the_strobed_period_ends():
    # advance_periods records the state at each period end through the loop's rows; a period end
    # inside a flight is written by the closed form
    a, b = _stepper(0.1, 3.0), _stepper(0.1, 3.0)
    ends = a.advance_periods(10)
    rows: list[np.ndarray] = []
    b.advance(10 * b.k_per + 1, rows=rows)
    every = np.concatenate(rows)[:, 1:5]
    assert np.max(np.abs(ends - every[b.k_per :: b.k_per][:10])) < 1e-11


def test_a_flight_does_not_depend_on_where_the_loop_is_cut():
    # the loop runs in segments (windows, periods, trajectory rows, a full event log): every state
    # of a flight is the parabola through its anchor, so any cutting gives the same bits
    one, cut = _stepper(0.1, 3.0), _stepper(0.1, 3.0)
    n = 20 * one.k_per
    one.advance(n)
    while cut.step < n:
        cut.advance(min(7, n - cut.step))
    assert one.y.tobytes() == cut.y.tobytes()
    assert one.st[ev.S_OUT] == cut.st[ev.S_OUT] and one.st[ev.S_AMIN] == cut.st[ev.S_AMIN]


def test_a_snapshot_taken_in_flight_goes_on_bit_for_bit():
    a = _stepper(0.1, 3.0)
    a.advance(10 * a.k_per)
    while a.st[ev.S_FLY] < 20:  # well inside a flight, past its anchor
        a.advance(1)
    snap = a.save()
    b = _stepper(0.1, 3.0)
    b.restore(snap)
    a.advance(5 * a.k_per)
    b.advance(5 * b.k_per)
    assert a.y.tobytes() == b.y.tobytes()


def test_a_speed_moved_in_flight_holds():
    """mmd m* = 31.6, A* = 0.891 is in a flight taken in closed form at the end of period 20.
    Moving its horizontal speed there by 2 (a full-inertia jump, the speed of a drift solved
    directly, an irregular bouncer's mean) must move the flight's parabola too: its anchor was
    taken before the move, and the closed form went on at the old speed (x*' 0.0383 a period
    later instead of 2.0383). A period later the speed is the moved one within what friction
    can change in a period (mu / m* = 0.003), the position moved by it, and both are the same
    as for a twin moved in the same way (whose flight counts afresh, as any displaced twin's)."""
    from sawdrift.dynamics.full_inertia import shift_speed

    st = _stepper(31.6, 0.891)
    st.advance(20 * st.k_per)
    assert st.st[ev.S_FLY] >= 8  # in a closed-form flight
    x0, v0 = float(st.y[0]), float(st.y[1])
    twin = st.twin(np.zeros(1))  # displaced by nothing: counts its flight afresh
    shift_speed(st, 2.0)
    shift_speed(twin, 2.0)
    end = st.advance_periods(1)[0]
    assert abs(end[1] - (v0 + 2.0)) < 0.01, (v0, end[1])
    assert abs(end[0] - (x0 + v0 + 2.0)) < 0.01, (x0, v0, end[0])
    np.testing.assert_allclose(twin.advance_periods(1)[0], end, rtol=1e-12, atol=1e-12)


def test_an_inertia_changed_in_flight_changes_the_flight_from_then_on():
    """mmd m* = 0.1, A* = 3 under a load of 0.3 (x*'' = L / m*_x in flight), in a flight taken
    in closed form: the reduced horizontal inertia of the first settle stage is changed there
    (to 10). The closed form applied the new x*'' over the whole flight since its anchor, so x*'
    jumped from 18.03 to 16.83 in one step; it must go on as the scheme stepped from the same
    state does (a twin whose flight counts afresh), to rounding over a period."""
    scene = bind(sd.Scene(model="mmd", particle={"m_star": 0.1, "load": 0.3},
                          drive={"amplitude": 3.0}, numerics={"settle": False}))
    model = model_for(scene)
    st = Stepper(scene, model, assemble(scene, "compiled", model), False, event_periods=27)
    st.warm_up()
    st.advance(10 * st.k_per)
    while st.st[ev.S_FLY] < 20:  # well inside a flight taken in closed form
        st.advance(1)
    twin = st.twin(np.zeros(1))  # displaced by nothing: counts its flight afresh
    v0 = float(st.y[1])
    st.set_horizontal_inertia(10.0)
    twin.set_horizontal_inertia(10.0)
    st.advance(1)
    assert abs(st.y[1] - v0) < 0.1, (v0, st.y[1])  # 0.3 / 10 per period, one step of it
    st.advance(st.k_per)
    twin.advance(st.k_per + 1)
    np.testing.assert_allclose(st.y[:4], twin.y[:4], rtol=1e-12, atol=1e-12)


# -- flights gone over at once (flight.flight_skip) ------------------------------------------------


def _without_skips(stepper: Stepper) -> Stepper:
    """A twin of ``stepper`` whose flights are stepped one step at a time (no surface bound)."""
    twin = stepper.twin()
    twin.prm = stepper.prm.copy()
    twin.prm[ig.P_SURF] = -1.0
    return twin


@pytest.mark.parametrize("m_star, amplitude, extra", [
    (0.1, 1.0, {}),  # thrown high: 98.5 % of its steps in flight, a* down to -47
    (0.03, 4.0, {"drive": {"amplitude": 4.0, "orbit": "retrograde"}}),
    (1.0, 3.0, {"particle": {"m_star": 1.0, "load": 0.2}}),
])
def test_high_flights_gone_over_at_once_give_the_same_bits(m_star, amplitude, extra):
    """A run whose flights skip the steps that can neither land nor deepen a* (the drive's bound
    of |u_y|) against the same run stepping every flight step: the same state, window counts,
    deepest a* and events, to the last bit, over 200 periods cut into windows and periods."""
    skip = _stepper(m_star, amplitude, **extra)
    step = _without_skips(skip)
    assert skip.prm[ig.P_SURF] == pytest.approx(abs(amplitude))
    for stepper in (skip, step):
        stepper.advance(50 * stepper.k_per)
        stepper.advance_periods(100)
        stepper.advance(50 * stepper.k_per + 17)
    assert skip.y.tobytes() == step.y.tobytes()
    assert skip.fh.tobytes() == step.fh.tobytes()
    for index in (ev.S_OUT, ev.S_AMIN, ev.S_COUNT, ev.S_LOST, ev.S_SLIP, ev.S_NEV):
        assert skip.st[index] == step.st[index], index
    assert np.array_equal(ev.events(skip.st), ev.events(step.st))
    assert skip.st[ev.S_OUT] > 50 * skip.k_per  # it did fly


def test_a_high_flight_is_gone_over_in_a_few_evaluations():
    """The skip is the point: mid-flight at m* 0.1, A* 1 (a flight of many periods) the steps
    ahead that cannot land or deepen a* number in the hundreds."""
    st = _stepper(0.1, 1.0)
    st.advance(40 * st.k_per)
    while not (st.st[ev.S_FLY] > 40 and st.y[3] < 0.0):  # rising, well inside a flight
        st.advance(1)
    ka = st.st[ev.S_ANCHOR]
    parab = (float(st.prm[ig.P_H]), st.st[ev.S_ANCHOR + 3], st.st[ev.S_ANCHOR + 4],
             1.0 / float(st.prm[ig.P_M]))
    n = flight_skip(st.step - ka, 10 ** 6, parab, float(st.prm[ig.P_SURF]), st.st[ev.S_AMIN])
    assert n > 100


def test_flight_skip_never_goes_over_a_landing_or_a_deeper_flight():
    """Random parabolas, bounds and deepest a*: every step the skip goes over is below -U (it
    cannot land) and every step it counts is not below deepest + U (it cannot deepen a*), checked
    step by step; and it does skip where a whole flight stays far from the surface."""
    rng = np.random.default_rng(7)
    skipped = 0
    for _ in range(3000):
        h = 1.0 / rng.choice([64, 128, 512])
        ay = 10.0 ** rng.uniform(-2, 3)
        bound = rng.uniform(0.0, 10.0)
        apex = -bound - 10.0 ** rng.uniform(-6, 3)
        t_apex = rng.uniform(-5.0, 5.0)
        vy0 = -ay * t_apex
        y0 = apex + 0.5 * ay * t_apex * t_apex
        deepest = apex - bound + rng.uniform(-3.0, 3.0)
        s = int(rng.integers(-2000, 2000))
        n_max = int(rng.integers(0, 5000))
        n = flight_skip(s, n_max, (h, y0, vy0, ay), bound, deepest)
        assert 0 <= n <= n_max
        if n == 0:
            continue
        skipped += 1
        t = (s + np.arange(1, n + 1)) * h
        height = y0 + vy0 * t + 0.5 * ay * t * t
        assert np.all(height < -bound), "a skipped step could land"
        assert np.all(height[:-1] - bound >= deepest), "a counted step could deepen a*"
    assert skipped > 200  # 386 of the 3000 (the others: near the surface, or n_max < 4)
    # no bound from the drive: every step is stepped
    assert flight_skip(0, 1000, (0.01, -100.0, 0.0, 1.0), -1.0, -200.0) == 0
