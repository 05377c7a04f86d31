"""Integrate one scene and measure it: the dynamics half of a run (the Result is built above).

Compliant models go through the Adams-Bashforth loop of :mod:`sawdrift.dynamics.adams_bashforth`;
rigid ones through the unilateral-contact scheme of :mod:`sawdrift.dynamics.rigid`; a prescribed
drive feeds a*(t*), b*(t*) straight into the contact law (:mod:`sawdrift.dynamics.prescribed`).
Each scheme returns what it measured (:class:`WaveRun`,
:class:`~sawdrift.dynamics.impact.ImpactRun`, :class:`~sawdrift.dynamics.prescribed.PrescribedRun`);
:func:`sawdrift.result.runner.run` names the regime and builds the :class:`~sawdrift.result.Result`
from it. A window with contact loss goes on to its periodic orbit in
:mod:`sawdrift.dynamics.orbit_search`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from ..contact.base import ContactModel
from ..scene.schema import Numerics, Scene
from .approach import accuracy
from .assembly import Assembly
from .batch_means import BatchMeans, long_time_mean, period_rows
from .evidence import S_LASTLIFT
from .full_inertia import (
    Watch,
    held,
    longest_flight,
    on_orbit,
    settle_full,
    tapered_drift_ratio,
)
from .half_resonance import half_resonance_growth
from .orbit_search import orbit_search
from .steady import (
    Settling,
    assess_fixed,
    default_max_periods,
    horizontal_inertia,
    relaxation_periods,
    rolling_frequency,
    runs_away,
    settle,
    settles,
)
from .stepper import Stepper
from .transient import orbit_settling, orbit_window
from .window import (
    Window,
    ballistic_return,
    in_flight,
    lyapunov,
    measure_window,
)
from .window_noise import WANDER_WINDOWS, approaches, wanders

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["WaveRun", "integrate_wave"]


@dataclass
class WaveRun:
    """A periodic drive's run, integrated to its measuring window and measured.

    Attributes
    ----------
    stepper
        The integration, at the window's end.
    window
        What the measuring window saw (drift, contact, slip, lift-offs, events).
    settling
        How the drift settled (or was judged, for a fixed run).
    settle_on
        Whether the run settled (``numerics.settle``, or its default).
    speed
        Amplitude of the horizontal surface speed, 2 pi r A* for the wave.
    lyapunov, chaotic
        Largest Lyapunov exponent per period (NaN when contact was kept) and the verdict.
    hop_period
        k of the synchronous lift-off pattern; 0 if none or chaotic.
    compile_s
        Compilation or compile-cache load before the run, apart from ``wall_time_s``.
    wall_time_s
        The integration and its measurements.
    trajectory
        The time series when asked for.
    last_liftoff
        t* of the last lift-off since t* = 0 (-1: none), kept across windows.
    long_mean
        A chaotic window's long-time mean drift and its standard error (batch means), or None.
    steps
        Steps integrated since t* = 0, the long-time mean's (run on a twin after the window)
        included.
    """

    stepper: Stepper
    window: Window
    settling: Settling
    settle_on: bool
    speed: float
    lyapunov: float
    chaotic: bool
    hop_period: int
    compile_s: float
    wall_time_s: float
    trajectory: pd.DataFrame | None = field(default=None, repr=False)
    last_liftoff: float = -1.0
    long_mean: BatchMeans | None = None
    steps: int = 0


def integrate_wave(scene: Scene, model: ContactModel, plan: Assembly, trajectory: bool,
                   record_every: int | None) -> WaveRun:
    """Integrate a periodic drive to its measuring window and measure it (see :class:`WaveRun`).

    Settled windows (``numerics.settle``, by default where the drift relaxes within the period
    cap, :func:`~sawdrift.dynamics.steady.settles`) or the fixed run's last window; the Lyapunov
    estimate only for windows that lost contact.
    """
    num = scene.numerics
    n_periods = scene.measure_periods()
    stepper, compile_s = _built(scene, model, plan, trajectory, n_periods, record_every)
    t0 = time.perf_counter()
    drive = plan.drive
    speed = drive.horizontal_speed(scene)
    scale = drive.state_scale(scene)
    settle_on = settles(scene, speed, stepper.rigid)
    win, settling, before = _measure(stepper, scene, speed, scale, settle_on)
    lyap, chaotic = _exponent_of(win, scale)
    # the per-period rows of the run's windows (displacement, vertical energy), one contiguous
    # stretch of its own trajectory up to now: a long-time mean after them starts from all of it
    series = [period_rows(win, stepper)]
    fixed_end = stepper.step
    leaving = False
    if settling is None and num.settle is not False and not chaotic and win.contact_lost:
        # the run goes on to its periodic orbit (its events and trajectory with it), as a
        # settling run goes on to its steady drift
        win, before, leaving, lyap, chaotic = orbit_search(stepper, win, speed, scale, series,
                                                            before, (lyap, chaotic))
    periods_run = stepper.step / stepper.k_per
    # the long-time mean of a chaotic window runs on a twin: the run itself (its trajectory, its
    # periods) ends with its window; a run asked to be fixed (settle = false) stays as it is
    # known to the tolerance, a long-time mean stops before its budget (batch_means.CHUNK)
    target = num.settle_tolerance * speed
    chaos, twin = (_long_mean(stepper, win, _mean_budget(num, win), target)
                   if chaotic and num.settle is not False else (None, None))
    if settling is None:
        settling = _fixed_verdict(scene, win, speed, periods_run, chaotic, before)
        if num.settle is not False and stepper.step > fixed_end:  # on in windows to its orbit
            settling = replace(settling, method="fixed_then_windows")
        if leaving and num.settle is not False:
            # still leaving its old orbit for another: no steady motion to settle on yet
            settling = replace(settling, settled=False, drift=None, leaving=True)
        elif (not settling.settled and num.settle is None and num.periods == DEFAULT_PERIODS
                and not chaotic):
            # a default run that its own window could not confirm goes on to the steady drift (a
            # run given another length keeps it)
            win, settling, chaos, twin = _go_on(stepper, scene, speed, scale, win, settling,
                                                periods_run, drive.vertical_amplitude(scene),
                                                series)
            lyap, chaotic = _exponent_of(win, scale) if settling.settled else (lyap, chaotic)
    elif chaos is None and settling.long_mean is not None:
        chaos = settling.long_mean  # the settling measured the long-time mean itself
    elif chaos is None and num.settle is not False and _irregular(win, settling):
        chaos, twin = _irregular_mean(stepper, win, settling, num, target)
    elif chaos is None and num.settle is not False:
        # a settling run stopped by its cap within one flight: the mean of its bounces
        chaos, twin = _flights_mean(stepper, scene, win, settling, speed,
                                    drive.vertical_amplitude(scene), series)
    grown = _past_half_resonance(stepper, scene, win, settling, chaos, scale, speed)
    if grown is not None:
        win, settling, chaos, twin, (lyap, chaotic) = grown
    ended = orbit_window(stepper, twin, chaos, n_periods, speed, scale)
    path = stepper.trajectory() if trajectory else None
    if ended is not None:
        # the irregular motion was a transient that ended on a periodic orbit (.transient)
        win, stepper, chaos = ended, twin, None
        settling = orbit_settling(settling, twin, win)
        lyap, chaotic = _exponent_of(win, scale)
    wall = time.perf_counter() - t0
    return WaveRun(stepper=stepper, window=win, settling=settling, settle_on=settle_on,
                   speed=speed, lyapunov=lyap, chaotic=chaotic,
                   hop_period=win.sync.hop_period if not chaotic else 0, compile_s=compile_s,
                   wall_time_s=wall, trajectory=path,
                   last_liftoff=float(stepper.st[S_LASTLIFT]), long_mean=chaos,
                   steps=max(stepper.step, 0 if twin is None else twin.step))


def _fixed_verdict(scene: Scene, win: Window, speed: float, periods_run: float, chaotic: bool,
                   before: Window | None) -> Settling:
    """Whether a fixed-length run ended at its steady drift (:func:`~.steady.assess_fixed`); a
    run asked to be fixed (``settle = false``) reports its window's mean, settled on an orbit
    or in contact (no fixed point else)."""
    num = scene.numerics
    settling = assess_fixed(win, speed, num.settle_tolerance,
                            relaxation_periods(scene, scene.particle.m_star, speed), periods_run,
                            chaotic, before=None if before is None else tapered_drift_ratio(
                                before, speed))
    return settling if num.settle is not False else replace(
        settling, drift=None, settled=settling.settled and (on_orbit(win) or not win.contact_lost))


def _past_half_resonance(stepper: Stepper, scene: Scene, win: Window, settling: Settling,
                         chaos: BatchMeans | None, scale: np.ndarray, speed: float
                         ) -> tuple[Window, Settling, BatchMeans | None, Stepper | None,
                                    tuple[float, bool]] | None:
    """Where a compliant run settled in contact on a vertical orbit unstable at half the wave's
    frequency (:mod:`.half_resonance`), before its disturbance grew: not settled, and, unless
    the run is fixed (``settle = false``: it reports its window), the run goes on until the
    disturbance has grown, to the long-time mean of the motion it grows into. Returns the
    window, settling, mean, the twin the mean ran on and (Lyapunov exponent, chaos verdict)
    from there; None where the run's orbit is not such an orbit."""
    if not settling.settled or chaos is not None or stepper.rigid or win.contact_lost:
        return None
    growth = half_resonance_growth(stepper, scale, win.samples)
    if growth is None:
        return None
    settling = replace(settling, settled=False, drift=None, unstable=growth.rate)
    num = scene.numerics
    if num.settle is False:
        return win, settling, None, None, (math.nan, False)
    if growth.wait > 0:
        stepper.advance_periods(growth.wait)
    win = measure_window(stepper, scene.measure_periods(), speed, scale)
    budget = growth.mean_periods(_mean_budget(num, win), MOST_FLIGHT_BUDGETS * num.mean_periods)
    chaos, twin = _long_mean(stepper, win, budget, 0.0)  # no early stop: a beat's part can agree
    return win, settling, chaos, twin, _exponent_of(win, scale)


def _exponent_of(win: Window, scale: np.ndarray) -> tuple[float, bool]:
    """The Lyapunov exponent and chaos verdict of the window the run reports (its first, or the
    one it settled on after going on from it, :func:`_go_on`): the evidence of one motion comes
    from one window (material_point m* = 1, A* = 0.5 kept -0.061 from a window of its transient
    at period 87, where the orbit of 10 it settled on at period 195 sticks in every orbit and
    erases any perturbation, -inf, as a fixed run of 300 periods says). NaN for a window that
    did not lose contact, as for any such run."""
    return lyapunov(win, scale) if win.contact_lost else (math.nan, False)


def _built(scene: Scene, model: ContactModel, plan: Assembly, trajectory: bool,
           n_periods: int, record_every: int | None) -> tuple[Stepper, float]:
    """The run's stepper (recording every ``record_every`` steps where it keeps a trajectory)
    and the seconds its construction and warm-up took: compilation or disk-cache load, reported
    apart (the construction binds the contact history's loops: a cold cache spent 17 s there
    and reported 4.3 s when only the warm-up was timed)."""
    built = time.perf_counter()
    stepper = Stepper(scene, model, plan, trajectory, event_periods=n_periods)
    if trajectory and record_every is not None:
        stepper.rec_every = max(1, int(record_every))
    return stepper, (time.perf_counter() - built) + stepper.warm_up()


def _long_mean(stepper: Stepper, win: Window, budget: int, target: float,
               series: list[np.ndarray] | None = None) -> tuple[BatchMeans, Stepper]:
    """The long-time mean after ``win`` (:func:`~.batch_means.long_time_mean`), run on a twin
    of the run (which ends with its window), and that twin at the mean's end."""
    twin = stepper.twin()
    return long_time_mean(twin, win, budget, target, series), twin


def _measure(stepper: Stepper, scene: Scene, speed: float, scale: np.ndarray,
             settle_on: bool) -> tuple[Window, Settling | None, Window | None]:
    """Run to the measuring window and measure it: settled windows (``numerics.settle``, up to
    the period cap) or the fixed run's last window (a default one may end at its first window
    after the ramp, :func:`_held_first`). The settling is None for a fixed run. Last, the window
    measured just before the one returned (contiguous, as long), where a default fixed run
    measured it (:func:`_held_first`), else None."""
    num = scene.numerics
    n_periods = scene.measure_periods()
    k_per = stepper.k_per
    n_measure = n_periods * k_per
    n_total = max(int(round(num.periods * k_per)), n_measure)
    m_star = scene.particle.m_star
    cap = num.max_periods
    if cap is None:
        m_x = horizontal_inertia(m_star, stepper.rigid) if settle_on else m_star
        cap = default_max_periods(m_star, relaxation_periods(scene, m_x, speed), stepper.rigid,
                                  n_periods, rolling_frequency(scene, m_x))
    n_max = max(n_total, int(round(cap * k_per)))
    first = None
    if not settle_on and _default_length(scene):
        # a run recording its trajectory ends there too (the same result, table row and
        # trajectory of the run as it ran)
        first = _held_first(stepper, scene, speed, scale, n_total - n_measure)
        if first is not None and first[1] is not None:
            return first[0], first[1], None
    stepper.advance(n_total - n_measure - stepper.step)
    if settle_on:
        return *settle(stepper, scene, speed, scale, n_periods, n_max), None
    before = first[0] if first is not None else None
    return measure_window(stepper, n_periods, speed, scale), None, before


def _default_length(scene: Scene) -> bool:
    """Whether a run's length and window are the defaults, left to the run to use (a run given
    ``periods``, ``measure_periods`` or ``settle`` is run as asked), with no load (whose
    accelerating window the Result judges over the whole run)."""
    num = scene.numerics
    return (num.settle is None and num.periods == DEFAULT_PERIODS and num.measure_periods is None
            and scene.particle.load == 0.0)


def _held_first(stepper: Stepper, scene: Scene, speed: float, scale: np.ndarray,
                window_start: int) -> tuple[Window, Settling | None] | None:
    """A default fixed run whose first window after the ramp shows a held contact ends there.

    The window before the measuring one (the same length, ending where that one starts) is
    measured if it starts after the ramp; where it neither slid as a whole nor lost contact and
    its tapered mean is at the accuracy's floor (:func:`~.full_inertia.held`, the rule that
    settles a sticking contact at full inertia), the run has settled: the drive is periodic from
    there, and a contact that held through a window of all its phases holds on (its speed tied
    to the substrate by the tangential stiffness). The drift is that tapered mean (a box mean of
    a held contact is its ringing over the window: up to 1e-4 in drift ratio at m* = 0.02,
    against a zero long-time mean). Half the fixed run's cost for it. Otherwise the window with
    no settling (the stepper is then at ``window_start`` (steps), where the fixed run's window
    begins), or None where the window would start within the ramp (not measured).
    """
    n = scene.measure_periods()
    k_per = stepper.k_per
    first = window_start - n * k_per
    ramp = float(getattr(scene.drive, "ramp_periods", 0.0))
    if first < math.ceil(ramp) * k_per:
        return None
    stepper.advance(first - stepper.step)
    win = measure_window(stepper, n, speed, scale)
    d = tapered_drift_ratio(win, speed)
    if not held(win, d, scene.numerics.settle_tolerance):
        return win, None
    periods = stepper.step / k_per
    return win, Settling(True, "fixed", math.nan, n, periods, math.nan, (d,), drift=d * speed)


def _go_on(stepper: Stepper, scene: Scene, speed: float, scale: np.ndarray, win: Window,
           settling: Settling, periods_run: float, vertical: float, series: list[np.ndarray]
           ) -> tuple[Window, Settling, BatchMeans | None, Stepper | None]:
    """Where a default fixed run's window could not confirm its drift: full-inertia windows
    (:func:`_settle_on`) and, for an irregular motion, its long-time mean; for a window spent in
    one flight by a particle that lands again within the time run so far or within the mean's
    budget, ``numerics.mean_periods`` (thrown higher than a window lasts,
    :func:`~.window.ballistic_return`, ``vertical`` the drive's vertical amplitude), the
    long-time mean of its bounces, whose flights a window cannot average over, over at least
    :data:`FLIGHTS_PER_MEAN` flights as long as this one (a rigid point at m* = 1.986, A* = 8.7
    lands about every 190 periods: over the budget's 527 periods, 0.066 +- 0.074 against 0.347
    from brute force; over 16 flights, 0.280 +- 0.061). A load, or a flight that outlasts both
    (an ejection), is left to the Result's outcome. The long-time mean counts the windows
    already run (``series``, their per-period rows since the last jump of the speed) against
    its budget. Last, the twin the mean ran on (None without a mean)."""
    num = scene.numerics
    if not _leaving(scene, win, speed):
        win, settling = _settle_on(stepper, scene, speed, scale, win, periods_run, series)
    elif not in_flight(win):  # leaving under a load that runs away: the Result says so
        return win, settling, None, None
    if _irregular(win, settling):
        return win, settling, *_irregular_mean(stepper, win, settling, num,
                                               num.settle_tolerance * speed, series)
    return win, settling, *_flights_mean(stepper, scene, win, settling, speed, vertical, series)


def _flights_mean(stepper: Stepper, scene: Scene, win: Window, settling: Settling,
                  speed: float, vertical: float, series: list[np.ndarray] | None
                  ) -> tuple[BatchMeans | None, Stepper | None]:
    """For an unsettled window spent in one flight by a particle that lands again within the
    time run so far or within ``numerics.mean_periods``, the long-time mean of its bounces over
    at least :data:`FLIGHTS_PER_MEAN` flights as long as this one (:func:`_go_on`), and the twin
    it ran on; else (None, None): settled, in contact, or an ejection the Result names. A
    settling run stopped by its cap mid-flight is one too (material_point m* 60, A* 10, mu 0.5
    reported +0.400, the speed of one 6900-period flight, where its orbit of 7540 periods
    drifts at -0.421)."""
    if settling.settled or not in_flight(win):
        return None, None
    num = scene.numerics
    now = stepper.step / stepper.k_per
    ret = ballistic_return(float(stepper.y[2]), float(stepper.y[3]), scene.particle.m_star,
                           vertical)
    if ret > max(now, num.mean_periods):
        return None, None
    # the flight the window was spent in, from its lift-off to its landing; the whole budget
    # runs (no early stop at the tolerance: within one flight the per-period drift is constant,
    # an error of 0 that says nothing about the bounces)
    lift = float(stepper.st[S_LASTLIFT])
    flight = ret + (now - lift if lift >= 0.0 else now)
    budget = _mean_budget(num, win, flight)
    mean, twin = _long_mean(stepper, win, budget, 0.0, series)
    longest = max(longest_flight(win), flight)
    if budget < FLIGHTS_PER_MEAN * longest:  # capped: fewer flights than a mean of bounces asks
        mean = replace(mean, few_flights=mean.periods / longest)
    return mean, twin


#: flights (as long as the longest of the run's window) a long-time mean of bounces runs at
#: least
FLIGHTS_PER_MEAN = 16

#: the flights' budget is at most this many times ``numerics.mean_periods``
MOST_FLIGHT_BUDGETS = 100


def _mean_budget(num: Numerics, win: Window, flight: float = 0.0) -> int:
    """The budget of a long-time mean after ``win``: ``numerics.mean_periods``, or
    :data:`FLIGHTS_PER_MEAN` flights as long as the window's longest (or ``flight``, where
    longer) where that is more, up to :data:`MOST_FLIGHT_BUDGETS` times ``mean_periods``: a
    mean of bounces needs many flights."""
    periods = num.mean_periods
    flights = FLIGHTS_PER_MEAN * max(longest_flight(win), flight)
    return max(periods, min(int(math.ceil(flights)), MOST_FLIGHT_BUDGETS * periods))


def _irregular(win: Window, settling: Settling) -> bool:
    """An unsettled run whose drift is a long-time mean with an error, like a chaotic one: no
    positive exponent, but irregular lift-offs (quasi-periodic, intermittent; heavy bouncing), or
    in contact with window means that wander (their last changes turn at least twice: a slow
    beat of the undamped vertical mode against the wave, near the contact resonances). A
    monotone approach cut off by its cap stays unsettled: its mean would not be the steady one
    (in contact; one that lost contact gets its mean, marked still moving where it was
    approaching, :func:`_irregular_mean`)."""
    if settling.settled or settling.uncertain > 0.0 or in_flight(win):
        return False  # (a loaded drift solved directly, its average uncertain, is no mean)
    if win.contact_lost:
        return True
    return wanders(settling.history)


def _irregular_mean(stepper: Stepper, win: Window, settling: Settling, num: Numerics,
                    target: float, series: list[np.ndarray] | None = None
                    ) -> tuple[BatchMeans, Stepper]:
    """The long-time mean of an :func:`_irregular` run and its twin; marked still moving (no
    error: the mean of a stretch, not a long-time mean) where the run hops in step with the wave
    and its window means still moved one way (:func:`~.window_noise.approaches`): a monotone
    approach its windows stopped on (their cap, or their most windows), whose halves a mean of a
    few hundred periods cannot tell apart
    (mmd m* 30, A* 2, mu 0.2, e = 0.6 reported 0.793 +- 0.005, brute force reaches 0.878)."""
    mean, twin = _long_mean(stepper, win, _mean_budget(num, win), target, series)
    history = settling.history
    if win.sync.hop_period > 0 and len(history) > 0:
        eps = accuracy(history[-1], num.settle_tolerance)
        if approaches(history, eps) or settling.to_go > eps:
            mean = replace(mean, moving=True, approaching=True)
    return mean, twin


def _gives_up(values: list[float]) -> bool:
    """A default run going on from its fixed window stops its windows once their means wander
    (:func:`wanders`) over :data:`WANDER_WINDOWS` windows past the first three: its long-time
    mean runs from there, not after :data:`SETTLE_ON_PERIODS`."""
    return len(values) >= WANDER_WINDOWS + 3 and wanders(values)


def _leaving(scene: Scene, win: Window, speed: float) -> bool:
    """A window that may have no steady drift to settle on: one flight (a particle thrown off),
    or a load that friction cannot hold (:func:`~.steady.runs_away`); the Result judges both.
    A load below that goes on in windows as a free particle does: a point of a force-velocity
    or load curve is a steady drift (mmd m* = 0.3, A* = 0.5, L = -0.0139 stopped after its
    fixed 60 periods, not settled, where without the load it settles in 168)."""
    return in_flight(win) or runs_away(scene)


#: the default ``numerics.periods``: a fixed run of another length was asked for as it is
DEFAULT_PERIODS = Numerics.model_fields["periods"].default

#: periods a default fixed run its window did not confirm may run on (:func:`_settle_on`)
SETTLE_ON_PERIODS = 1000


def _settle_on(stepper: Stepper, scene: Scene, speed: float, scale: np.ndarray, win: Window,
               periods_run: float, series: list[np.ndarray] | None = None
               ) -> tuple[Window, Settling]:
    """Full-inertia windows from where a default fixed run ended unconfirmed
    (:func:`~sawdrift.dynamics.full_inertia.settle_full`; ``settle_method``
    "fixed_then_windows"), for :data:`SETTLE_ON_PERIODS` more periods at most, or the
    :data:`~sawdrift.dynamics.full_inertia.MIN_WINDOWS` windows that stage always may take where
    those are longer (the run was
    fixed because its drift relaxes fast: what has not settled by then drifts on a slow mode of
    its own, and says so) and within ``numerics.max_periods`` if given."""
    m_star = scene.particle.m_star
    mu = scene.material.mu
    n_periods = scene.measure_periods()
    omega = rolling_frequency(scene, m_star)
    if omega > 0.0:
        # windows span the rolling spring's slow mode, as a settling run's do: shorter ones
        # see it as a steady drift (mmd m* = 1.38, A* = 0.029, mu_r = 0.01, a period of 253:
        # three 27-period windows agreed on -4.8e-5 against 1e-10 from brute force)
        n_periods = max(n_periods, int(math.ceil(2.0 * math.pi / omega)))
    cap = scene.numerics.max_periods
    n_max = stepper.step + int(round(SETTLE_ON_PERIODS * stepper.k_per))
    if cap is not None:
        n_max = min(n_max, int(round(cap * stepper.k_per)))
    lam = mu / m_star if mu > 0.0 else 0.0
    start = stepper.step
    win, full = settle_full(stepper, scene, speed, scale, n_periods, n_max, lam, last=win,
                            watch=Watch(give_up=_gives_up, series=series))
    info = Settling(full.settled, "fixed_then_windows", m_star, full.window_periods,
                    periods_run + (stepper.step - start) / stepper.k_per, math.nan, full.history,
                    drift=full.drift(speed), slip_beat=full.slip_beat)
    return win, info
