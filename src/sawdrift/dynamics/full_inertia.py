"""The steady drift at full inertia: the last stage of ``numerics.settle``.

The reduced-inertia approach (:func:`~sawdrift.dynamics.steady.settle`, first stage) reaches the
fixed point of the period-averaged friction force <T*>(v) quickly, but its fast motion is not the
particle's: with the horizontal inertia reduced to m*_x, the small horizontal oscillation of the
particle about its mean speed, whose amplitude scales as 1/m*, is m*/m*_x times too large. Where
the contact slides as a whole that biases the drift by up to 1 %; where it is partly stuck (creep
near the stick boundary) the oscillation *is* the mechanism of the drift, and the reduced-inertia
value can be 10-70 times too large.

This stage therefore puts the full m* back and measures windows of W periods until the drift has
settled at full inertia. W spans at least three periods of the free vertical oscillation
(2 pi sqrt(m*/1.5), undamped, it modulates the friction) and two of the tangential contact
oscillation (2 pi sqrt(theta m*/1.5), the particle on its tangential contact stiffness 1.5/theta),
so a window mean is not a sample of either.

Two kinds of approach remain, told apart by the window's gross slip:

* **A sliding or hopping contact** (gross slip or contact loss in at least half the window). The
  mean velocity is a slow variable: it relaxes as v* + c exp(-lambda t) with lambda = mu F'/m*
  (F' the slope of the force-velocity curve at its zero). lambda is known from the first stage
  (its relaxation rate there, times m*_x / m*), and corrected after each jump by the secant of
  the change per window against the window mean (:func:`~.approach.secant_ratio`), within a factor of
  four of the predicted rate either way (the secant of an irregular bouncer's scattered window
  means is noise: a ratio near one from it threw mmd m* = 1, A* = 10 by 0.65 in drift ratio).
  From two consecutive window means D1, D2 the distance still to go is (D2 - D1) q / (1 - q)
  with q = exp(-lambda W) (Aitken's extrapolation with a known ratio); when it exceeds the
  tolerance the particle's velocity is moved by it (projective integration: only the mean speed
  jumps; the vertical motion and the contact memory are kept, and re-adapt within a few
  periods, far less than W).
* **A partly stuck contact** (creep). The mean velocity is mostly held by the tangential
  contact stiffness; the relaxation is then the damped contact oscillation, a few of its
  periods, and the windows converge by themselves. Where the mean speed is predicted to relax
  over a window or more and three window changes of one sign fall geometrically
  (:func:`~.approach.creep_ratio`), it still relaxes as a slow variable: the distance to go and the jump
  use the measured ratio.

The run stops when :data:`~.approach.STEADY_CHANGES` consecutive changes of the window mean and the
estimated remaining distance (for a heavy particle also that of the mean of its last four
changes, :func:`~.approach.trend_remaining`: a beat of two windows alternates its changes
between large and small) are all within half the tolerance (relative to the drift, with an
absolute floor of 2 % of the tolerance in drift-ratio units) and the tapered mean over the last
two windows agrees with the last one's (a beat as long as a window makes every window agree on
a biased mean, :func:`beats`; the windows then double), or at the first window whose
contact held (neither slid as a whole nor lost contact, its mean at that floor: :func:`held`;
a contact that slid before, whose free vertical oscillation beats against the wave more slowly
than a window lasts, must hold for two beats first: :mod:`.slip_return`);
the reported drift is the last window's tapered mean (:func:`tapered_drift_ratio`), measured at
full inertia.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

from .adams_bashforth import P_FRICTION, P_LOAD, P_M, P_ROLL
from .approach import LONGEST_WINDOW, _Approach, accuracy
from .batch_means import period_rows
from .evidence import EV_LANDING, EV_LIFT_OFF
from .rolling import contact_point, integrates_psi
from .slip_return import NORMAL_STIFFNESS, SlipReturn, free_vertical_period, vertical_beat
from .stepper import Stepper
from .window import Window, in_flight, measure_window
from .window_noise import beats, change_noise, hann_mean

#: free vertical periods per window
VERTICALS = 3.0

#: windows the full-inertia stage may take at most
MAX_WINDOWS = 60

#: decay times of the free vertical oscillation's amplitude a hop under air drag waits before
#: its windows may settle (:func:`drag_settle_periods`)
DRAG_DECAYS = 2.0

#: windows the full-inertia stage may always take, even past the settle cap
MIN_WINDOWS = 12


@dataclass(frozen=True)
class Watch:
    """What a caller of :func:`settle_full` follows window by window.

    ``give_up`` is called with the window drift ratios so far after each window: True ends the
    stage unsettled (a run whose window means wander has no drift to settle on). ``series``
    collects the per-period rows of the run (displacement, vertical energy:
    :func:`~.batch_means.period_rows`), one array per window: each window's are appended, and a
    jump of the speed empties it (what follows is another trajectory).
    """

    give_up: Callable[[list[float]], bool] | None = None
    series: list[np.ndarray] | None = None


@dataclass(frozen=True)
class FullInertia:
    """How the full-inertia stage ended."""

    settled: bool
    window_periods: int
    windows: int
    jumps: int
    periods: float
    history: tuple[float, ...]
    ratio: float = math.nan
    #: the beat (periods) of the free vertical oscillation after which a contact that had held
    #: slid again (:mod:`.slip_return`), 0 where none did
    slip_beat: float = 0.0
    #: the distance still to go after the last window (:attr:`~.approach._Approach.to_go`)
    to_go: float = 0.0

    def drift(self, speed: float) -> float | None:
        """The settled drift (x* per period) to report: the last window's tapered mean
        (:func:`tapered_drift_ratio`, what the windows settled on) times ``speed``; None where
        the stage did not settle (the last window's own mean is then reported as a sample).
        A box mean carries the slow oscillations' leak: up to 3e-5 in drift ratio on a sticking
        mmd contact at m* 5.6 to 100 whose brute-force drift is below 1e-7."""
        return self.history[-1] * speed if self.settled and self.history else None


def full_window_length(m_star: float, theta: float, minimum: int, rigid: bool = False) -> int:
    """W: three free vertical periods 2 pi sqrt(m*/1.5) and two tangential contact periods
    2 pi sqrt(theta m*/1.5), at least ``minimum`` (see the module docstring); a rigid point has
    neither oscillation: ``minimum``."""
    if rigid:
        return int(minimum)
    vertical = free_vertical_period(m_star)
    tangential = 2.0 * math.pi * math.sqrt(theta * m_star / NORMAL_STIFFNESS)
    return max(int(minimum), int(math.ceil(VERTICALS * vertical)), int(math.ceil(2.0 * tangential)))


def held(win: Window, d: float, tol: float) -> bool:
    """Whether a window shows a sticking contact: it neither slid as a whole nor lost contact,
    and its (tapered) mean is at the accuracy's floor (:func:`accuracy` of a zero drift).

    One such window settles the drift. It spans three free vertical periods and two tangential
    contact ones (:func:`full_window_length`), the slowest modulations of the contact forces:
    the motion after it is quasi-periodic and passes the same states again, so a contact that
    held through it holds on, and has no slow mode of its mean speed to wait for (its speed is
    tied to the substrate by the tangential stiffness). A creeping contact, which slides in
    part of its periods, is not held and settles by window changes.
    """
    return (win.gross_slip_fraction == 0.0 and not win.contact_lost
            and abs(d) <= accuracy(0.0, tol) and not in_flight(win))


def on_orbit(win: Window) -> bool:
    """Whether a window ends on an exact periodic orbit (its stroboscopic state repeats to
    round-off, :func:`~.window.orbit_period`), not spent in one flight: its drift over whole
    orbits is the steady one, as a fixed run's is (:func:`~.steady.assess_fixed`). Windows that
    are not a whole number of orbits have means that differ by part of an orbit: a rigid point
    on an orbit of 20 (m* 0.1, A* 8) went on in windows of 62 periods whose tapered means
    changed by 3e-4, gave up and reported a long-time mean, 0.0269 +- 0.012, of its 0.030393."""
    return win.orbit_period > 0 and not in_flight(win)


def relaxation_rate(history: tuple[float, ...], window: int, m_x: float, m_star: float,
                    mu: float) -> float:
    """lambda at full inertia (per period) from the first stage's window means.

    Three window means v1, v2, v3 of a relaxation give q = (v3 - v2) / (v2 - v1) = exp(-lambda_x W)
    at the inertia m*_x; lambda = lambda_x m*_x / m*. Without a usable ratio, mu / m* (a slope F'
    of one).
    """
    lam = mu / m_star
    if len(history) >= 3:
        d1 = history[-2] - history[-3]
        d2 = history[-1] - history[-2]
        if d1 != 0.0 and 0.0 < d2 / d1 < 1.0:
            lam = -math.log(d2 / d1) / window * m_x / m_star
    return lam


def tapered_drift_ratio(win: Window, speed: float) -> float:
    """The window's drift ratio as a Hann-weighted mean of its per-period displacements.

    A box mean of x* over W periods leaks a slow oscillation (the free vertical one, or the
    particle ringing on its tangential contact stiffness, periods 2 pi sqrt(m*/1.5) and
    2 pi sqrt(theta m*/1.5)) into the drift in proportion to P / W; with the weights
    sin^2(pi (k + 1/2) / W) the leak falls as (P / W)^3 (the Hann window's sidelobes), while a
    constant or linearly changing speed gives the same mean as the box. A periodic orbit of
    several periods keeps the box mean over whole orbits (its displacements repeat exactly).
    """
    if speed <= 0.0:
        return 0.0
    if win.orbit_period > 1:
        return win.drift_ratio
    return hann_mean(np.diff(win.positions)) / speed


def shift_speed(stepper: Stepper, dv: float) -> None:
    """Move the particle's horizontal velocity by ``dv`` (and its Adams-Bashforth history of x*').

    A flight taken in closed form (:mod:`.flight`) goes on from its anchor, a state taken before
    the move: its count starts afresh (the scheme's next steps, exact on a parabola, then anchor
    it on the moved state), or the move would be lost until the landing and past it (mmd m* =
    31.6, A* = 0.891 moved by 2 in flight: x*' 0.0383 a period later, not 2.0383).
    """
    stepper.y[1] += dv
    if stepper.rigid:
        _slip_after_move(stepper)
    else:
        stepper.fh[:, 0] += dv
        stepper.moved()


def _slip_after_move(stepper: Stepper) -> None:
    """The rigid scheme's contact mode after a move of the speed: a point on the surface with
    friction slips in the direction of its new velocity relative to the surface. Its stick, or
    its slip's search for the zero of that velocity (which the move may have crossed), would
    otherwise take the move back within the step: material_point m* = 1, A* = 0.02 moved by -1
    while slipping forward was back at -0.054 a period later, not at -0.95 (mu / m* = 0.1 a
    period)."""
    ctr, prm, y = stepper.ctr, stepper.prm, stepper.y
    if ctr[1] == 1 or not prm[P_FRICTION] > 0.0:
        return  # in flight, or no friction: nothing to stick or slip
    # what slips is the contact point: the centre's speed, c x*' for a sphere rolling from rest,
    # or x*' + psi' where psi is integrated (as the rigid loop takes its step)
    roll = float(prm[P_ROLL])
    turning = integrates_psi.py_func(roll, 0.0, prm[P_LOAD] / prm[P_M], y)
    s = float(contact_point.py_func(y, roll, turning)[1] - stepper.surface()[1])
    if s != 0.0:
        ctr[3] = 0  # slipping, with sgn(s)
        ctr[4] = 1 if s > 0.0 else -1


def drag_settle_periods(scene) -> float:
    """Periods before which a hopping run under air drag is not settled: :data:`DRAG_DECAYS`
    decay times 2 m*/c of the free vertical oscillation's amplitude (c = ``effects.air_drag``;
    m* y*'' = ... - c y*'), 0 without drag.

    The undamped contact keeps the vertical oscillation a run's start leaves, and where contact
    is lost it moves the drift (:mod:`.torus`). Air drag damps it, slowly for a heavy particle,
    so the windows settle on the drift of the oscillation they see, which keeps moving long
    after: mmd m* = 22.3, A* = 1.71, c = 0.05 settled at 0.23216 after 1420 periods, and brute
    force from rest reaches 0.23262 (0.23245 at 3000 periods, 0.23262 at 4000 and 6000); at
    m* = 90, A* = 1.71 0.23121 against 0.23253. A contact kept (no flight) is not held back: the
    oscillation moves its drift by less than the tolerance."""
    c = float(scene.effects.air_drag)
    return DRAG_DECAYS * 2.0 * scene.particle.m_star / c if c > 0.0 else 0.0


def longest_flight(win: Window) -> float:
    """The longest flight of a window, in periods: lift-off to the next landing (or the window's
    end); the whole window if it was spent in one flight."""
    if win.out_of_contact_fraction >= 1.0:
        return float(win.periods)
    ev = win.events
    if ev.size == 0:
        return 0.0
    t, kind = ev[:, 0], ev[:, 1]
    end = win.t_start + win.periods
    longest = 0.0
    lift = None
    for ti, ki in zip(t, kind, strict=True):
        if ki == EV_LIFT_OFF:
            lift = ti
        elif ki == EV_LANDING and lift is not None:
            longest = max(longest, ti - lift)
            lift = None
    if lift is not None:
        longest = max(longest, end - lift)
    return float(longest)


def settle_full(stepper: Stepper, scene, speed: float, scale: np.ndarray, minimum_window: int,
                max_steps: int, lam: float, last: Window | None = None,
                expected: float | None = None, watch: Watch | None = None
                ) -> tuple[Window, FullInertia]:
    """Measure full-inertia windows until the drift has settled (module docstring).

    Windows span at least three of the longest flight of ``last`` (the first stage's final
    window); a window spent in one flight is not compared, and the next ones are twice as long.

    Parameters
    ----------
    stepper
        The integration, with the full m* restored.
    speed
        2 pi r A*, the drift ratio's scale.
    lam
        Relaxation rate of the mean speed at full inertia, per period (:func:`relaxation_rate`).
    max_steps
        The settle cap: no window starts that would end past it.
    expected
        A drift ratio solved directly (:mod:`.separated`, :mod:`.torus`): two consecutive windows
        within the accuracy of it and of each other settle the drift (else the usual
        :data:`~.approach.STEADY_CHANGES` consecutive changes do).
    watch
        What the caller follows window by window (:class:`Watch`).
    """
    watch = watch if watch is not None else Watch()
    give_up = watch.give_up
    w = full_window_length(scene.particle.m_star, scene.theta, minimum_window, stepper.rigid)
    if last is not None:
        # flights of many periods (a heavy point thrown by one impact): windows of three of them
        w = max(w, int(math.ceil(3.0 * longest_flight(last))))
    state = _Approach(w=w, q=math.exp(-lam * w), tol=scene.numerics.settle_tolerance, w0=w,
                      expected=expected, rate=lam)
    start = stepper.step
    # the stage may outlast the first stage's cap by MIN_WINDOWS windows, and a hop under air
    # drag goes on until its slow vertical oscillation has died out (drag_settle_periods)
    not_before = int(round(drag_settle_periods(scene) * stepper.k_per))
    max_steps = max(max_steps, start + MIN_WINDOWS * w * stepper.k_per,
                    not_before + 2 * w * stepper.k_per)
    log = watch.series if watch.series is not None else []
    win = measure_window(stepper, w, speed, scale)
    log.append(period_rows(win, stepper))
    values = [tapered_drift_ratio(win, speed)]
    state.prev = values[-1]
    # a contact that slid before may slide again a slow beat later (.slip_return)
    slips = SlipReturn(vertical_beat(scene.particle.m_star, stepper.rigid), last)
    slips.see(win)
    settled = held(win, values[-1], state.tol) and not slips.waits(win)
    while (not settled and len(values) < MAX_WINDOWS
           and stepper.step + state.w * stepper.k_per <= max_steps):
        win = measure_window(stepper, state.w, speed, scale)
        log.append(period_rows(win, stepper))
        values.append(tapered_drift_ratio(win, speed))
        action, jump = state.judge(values[-1], win, partial(change_noise, log[-1], speed))
        action = slips.overrule(action, win)
        if on_orbit(win) or (not slips.waits(win) and held(win, values[-1], state.tol)):
            settled = True  # an exact orbit (its drift over whole orbits), or a held contact
            break
        if action == "settled" and beats(log, win, values[-1], speed,
                                         accuracy(values[-1], state.tol)):
            # longer windows average the beat out; at the longest, compare afresh from here
            action = "longer" if state.w < LONGEST_WINDOW * state.w0 else "again"
        if action == "settled" and win.contact_lost and stepper.step < not_before:
            action = "again"  # a quasi-steady drift on a vertical oscillation still decaying
        if action == "settled":
            settled = True
            break
        if give_up is not None and give_up(values):
            break
        if action == "jump" and speed > 0.0:
            shift_speed(stepper, jump * speed)
            log.clear()
        if action not in ("next", "wait"):
            state.restart(longer=action == "longer")
    info = FullInertia(settled, state.w, len(values), state.jumps,
                       (stepper.step - start) / stepper.k_per, tuple(values), state.q,
                       slips.beat if slips.came_back else 0.0, 0.0 if settled else state.to_go)
    return win, info
