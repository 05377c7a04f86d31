"""The long-time mean drift of an irregular (chaotic) motion, with an honest standard error.

A chaotic window has no steady drift to settle on: its drift over a few tens of periods is one
sample of a fluctuating quantity (mmd, m* = 0.1, A* = 1, mu = 0.1: a 27-period window gave
-0.255, the mean over 4e5 periods is -0.014 +- 0.016). What is reported instead is the mean
over ``numerics.mean_periods`` further periods (the budget, 500 by default) with its standard
error by the method of batch means
(Flyvbjerg and Petersen 1989): the run is cut into batches, the batch means are averaged, and
their spread over sqrt(n) is the error, valid when the batches are long enough to be nearly
uncorrelated. Batches are merged pairwise (Flyvbjerg-Petersen blocking) down to
:data:`MIN_BATCHES`, and the largest error over those levels is reported (the plateau of the
blocking curve). Correlations longer than the longest batch are not seen: for the cell above a
budget of 2000 periods gives +- 0.085 in drift ratio, while a 22000-period run gives +- 0.107, which
scaled back to 2000 periods would be about 0.35; the two means still agree within their errors.
Where the blocking curve is still rising at the end (:attr:`BatchMeans.rising`) the reported
error follows it on to its coarsest levels, down to two batches (half the difference of the
series' halves): noisy, but the only levels that see correlations that long. It is still a lower
bound, and the Result says so in its warnings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .adams_bashforth import P_M
from .stepper import Stepper
from .window import orbit_period

#: fewest batches an error is computed from
MIN_BATCHES = 16

#: fewest batches of the levels a blocking curve still rising at :data:`MIN_BATCHES` is followed
#: on to (:func:`blocking`)
COARSEST_BATCHES = 2

#: periods per step of a long-time mean that may stop early (``target``), and its fewest periods
CHUNK = 250
MIN_PERIODS = 500

#: combined blocked errors by which the means of a series' two halves may differ before it is
#: taken to be still approaching its mean (:func:`still_moving`)
HALVES_Z = 5.0

#: combined blocked errors of the two halves past which a long-time mean's error is at least
#: half their difference (:func:`trend_allowance`)
TREND_Z = 3.0

#: times a long-time mean still approaching drops its first half and runs another budget
MAX_EXTENSIONS = 3

#: the last two blocking levels' errors within this fraction of each other: a plateau
PLATEAU = 0.25

#: the last blocking level's error above the one before by this factor (and that one above its
#: predecessor): still rising. On 60 chaotic and irregular cells of a 41 x 41 mmd sweep, 11 rose
#: at 2000 periods; of the two whose mean was more than 3 errors from a 16000-period run's, one
#: rose (both sit at the tangential contact resonance, m* = 0.03, where the motion switches
#: between drifting states over more than 16000 periods)
RISE = 1.15


@dataclass(frozen=True)
class BatchMeans:
    """Mean drift velocity (x* per period), its standard error, batches and periods used.

    ``rising``: the blocking curve still grew over its last three levels (:func:`blocking`), so
    correlations at least as long as the longest batches remain and ``se`` is a lower bound.
    """

    mean: float
    se: float
    batches: int
    periods: int
    rising: bool = False
    #: the two halves of the series still differed by more than :data:`HALVES_Z` combined errors
    #: after :data:`MAX_EXTENSIONS` extensions: a slow approach, not a long-time mean
    moving: bool = False
    #: the mean vertical energy of the two halves of the run (:func:`heats_up`) where the second
    #: is higher by more than :data:`HALVES_Z` combined errors: the bounces heat up, else None
    heating: tuple[float, float] | None = None
    #: the two halves differed by more than :data:`TREND_Z` combined errors (but not
    #: :data:`HALVES_Z` after the extensions): ``se`` is at least half their difference
    #: (:func:`trend_allowance`)
    trend: bool = False
    #: the motion was on a periodic orbit of this many periods at the end of the mean (0: not):
    #: an irregular transient that has ended (:func:`long_time_mean`)
    orbit: int = 0
    #: the windows before the mean still moved one way (``moving`` is then set too): a monotone
    #: approach cut off by its cap, whatever the mean's own halves say
    approaching: bool = False
    #: a mean of bounces whose budget was capped below the flights it asks for: how many of its
    #: longest flights it covers (0: not such a mean, or not capped)
    few_flights: float = 0.0


def blocked_error(per_period: np.ndarray, coarse: bool = False) -> tuple[float, float, int]:
    """(mean, standard error, batches) of a series of per-period drifts by blocking (above;
    ``coarse`` as for :func:`blocking`)."""
    mean, se, n, _, _ = blocking(per_period, coarse)
    return mean, se, n


def blocking(per_period: np.ndarray, coarse: bool = False
             ) -> tuple[float, float, int, bool, bool]:
    """:func:`blocked_error`, whether the blocking curve has reached its plateau (the errors of
    the two levels of longest batches within :data:`PLATEAU` of each other), and whether it is
    still rising (each of its last three levels above the one before, the last by more than
    :data:`RISE`): an error still growing with the batch length has not seen the longest
    correlations yet.

    With ``coarse`` (an error to report), a curve still rising is followed on to its coarsest
    levels, down to :data:`COARSEST_BATCHES` batches (whose error is half the difference of the
    series' halves): noisy, but the only levels that see correlations that long, and the largest
    error is kept. An irregular bouncer whose windows did not settle (mmd m* = 1.78, A* = 5.96)
    gives 0.7909 over 527 periods, its speed still approaching the 0.8010 of 16000 periods from
    the same start: +- 0.0041 from the 16-batch levels (2.5 errors off), +- 0.0099 from the
    coarsest (1.0). The tests of a series (:func:`still_moving`, the early stop) keep the levels
    of at least :data:`MIN_BATCHES`."""
    x = np.asarray(per_period, dtype=float)
    mean = float(x.mean())
    levels = _levels(x, COARSEST_BATCHES if coarse else MIN_BATCHES)
    errors = [se for n, se in levels if n >= MIN_BATCHES]
    flat = len(errors) >= 2 and abs(errors[-1] - errors[-2]) <= PLATEAU * max(errors[-2], 1e-300)
    rising = (len(errors) >= 3 and errors[-1] > RISE * errors[-2] and errors[-2] > errors[-3])
    # a curve still rising has correlations as long as its longest batches left: the levels
    # beyond (coarse), noisy but the only ones that see them, count then
    kept = levels if rising else [lv for lv in levels if lv[0] >= MIN_BATCHES]
    best_n, best_se = x.size, 0.0
    for n, se in kept:
        if se >= best_se:
            best_n, best_se = n, se
    return mean, best_se, best_n, flat, rising


def _levels(x: np.ndarray, fewest: int) -> list[tuple[int, float]]:
    """(batches, standard error of the mean) of each blocking level of ``x``, batches merged
    pairwise, down to ``fewest`` batches."""
    out = []
    level = x
    while level.size >= fewest:
        n = level.size
        out.append((n, float(level.std(ddof=1) / math.sqrt(n))))
        level = 0.5 * (level[: n // 2 * 2 : 2] + level[1 : n // 2 * 2 : 2])
    return out


def long_time_mean(stepper: Stepper, window, periods: int,
                   target: float = 0.0, series: list[np.ndarray] | None = None) -> BatchMeans:
    """Advance up to ``periods`` more periods and return the batch-mean drift over them and the
    window.

    With ``series`` (the rows of the windows run before, :func:`period_rows`, contiguous and
    ending with ``window``'s), the mean is over all of them and what follows, and the periods
    they hold beyond the window count against ``periods``: windows that a run went through
    looking for a steady drift are already samples of its long-time mean.

    ``stepper`` is at the end of the measuring ``window`` (a
    :class:`~sawdrift.dynamics.window.Window`, whose per-period positions start the series). With
    a ``target`` error (x* per period), the run stops early, after :data:`MIN_PERIODS` in all and
    at a whole chunk of :data:`CHUNK` periods, once the blocked error is at most the target and
    its blocking curve has reached its plateau (and is not rising): a quasi-periodic motion whose
    mean is known to the tolerance is not run on for the error bars of a chaotic one.

    A series whose two halves still differ, by more than ``target`` too (:func:`still_moving`),
    is approaching its mean, not fluctuating about it: its first half is dropped and it runs
    another ``periods``, at most :data:`MAX_EXTENSIONS` times (mmd m* = 4.2, A* = 10, in flight
    91 % of the time: 0.7867 +- 0.0018 over a series that began on the approach, 0.8010 from
    brute force after 4000 periods). One still moving after that is reported with ``moving``
    set.

    A motion whose last chunk of periods shows its stroboscopic state repeating
    (:func:`~.window.orbit_period`, at the scale of ``window``) has ended its irregular transient
    on a periodic orbit, which it keeps for ever: ``orbit`` holds its period, and the caller
    reports the orbit rather than the mean of its transient (:mod:`.transient`; a rigid point at
    m* = 0.9, A* = 1.7105: 0.0635 +- 0.0061 over about a thousand irregular periods, then an orbit
    of 26 periods drifting at 0.046173).
    """
    parts = [period_rows(window, stepper)]
    done = 0
    if series and np.array_equal(series[-1], parts[0]):
        parts = [np.concatenate(series)]
        done = min(periods, parts[0].shape[0] - window.periods)
        if target > 0.0 and done < periods and parts[0].shape[0] >= MIN_PERIODS:
            _mean, se, _n, flat, rising = blocking(parts[0][:, 0])
            if flat and not rising and se <= target:
                done = periods  # known to the target already
    tail: list[np.ndarray] = []
    rows = _advance_mean(stepper, parts, done, periods, target, tail)
    extensions = 0
    while extensions < MAX_EXTENSIONS and still_moving(rows[:, 0], target):
        # still approaching: the first half is a transient, the mean goes on from the second
        rows = _advance_mean(stepper, [rows[rows.shape[0] // 2:]], 0, periods, target, tail)
        extensions += 1
    per_period = rows[:, 0]
    mean, se, n, _, rising = blocking(per_period, coarse=True)
    allowance = trend_allowance(per_period)
    scale = getattr(window, "scale", None)
    orbit = orbit_period(tail[-1], scale) if tail and scale is not None else 0
    return BatchMeans(mean, max(se, allowance), n, int(per_period.size), rising,
                      moving=extensions == MAX_EXTENSIONS and still_moving(per_period, target),
                      heating=heats_up(rows[:, 1]), trend=allowance > se, orbit=orbit)


def period_rows(window, stepper: Stepper) -> np.ndarray:
    """The rows a long-time mean is taken over, one a period of ``window`` (measured on
    ``stepper`` or a twin of it): its displacement and the vertical energy at its end
    (:func:`heats_up`). The windows a run goes through before its long-time mean keep theirs
    (``series``), so that the mean and the test of heating cover the same periods."""
    return np.column_stack((np.diff(window.positions),
                            _energy(window.samples, float(stepper.prm[P_M]))))


def _energy(states: np.ndarray, m_star: float) -> np.ndarray:
    """E = m* y*'^2 / 2 - y* of period-end states (x*, x*', y*, y*') (:func:`heats_up`)."""
    return 0.5 * m_star * states[:, 3] ** 2 - states[:, 2]


def heats_up(energy: np.ndarray) -> tuple[float, float] | None:
    """(mean of the first half, mean of the second) of a run's vertical energy per period where
    the second is higher by more than :data:`HALVES_Z` standard errors of the difference, else
    None (also for a series too short to tell).

    The energy at each period's end is E = m* y*'^2 / 2 - y* (y* positive into the substrate,
    gravity 1: in flight E is constant, the height the particle would rise to). A contact with
    no normal damping (mmd's) gives the vertical motion back to the wave at every impact, and
    the tangential friction takes none of it: the bounces can grow without end, as a ball on a
    vibrating table with elastic impacts does (Fermi acceleration). In the default 41 x 41 mmd
    sweep (m* 1e-3..1e2, A* 1e-2..10), 86 of the 342 long-time means gain more than 5 errors
    within their 500 periods (m* = 0.1, A* = 1: 54 to 168), all at m* <= 0.24; no irregular
    heavy bouncer does. Such a run has no steady drift yet: its mean depends on how long it is
    run. The error of the difference comes from the fluctuations about the series' linear
    trend: of 300 series of correlated noise (AR(1), phi = 0.9) about a constant, none is
    taken as heating (3 at phi = 0.95, 11 at 0.98, whose correlations span a tenth to a fifth
    of the run)."""
    half = energy.size // 2
    if half < MIN_BATCHES:
        return None
    m1, m2 = float(energy[:half].mean()), float(energy[half:].mean())
    # the error of the difference from the fluctuations about the series' linear trend (a rise
    # left in would widen the batches' spread and hide itself): each half's mean carries twice
    # the variance of the whole's, so the difference has twice its standard error
    t = np.arange(energy.size, dtype=float)
    residual = energy - np.polyval(np.polyfit(t, energy, 1), t)
    _mean, se, _n = blocked_error(residual)
    if m2 - m1 > HALVES_Z * 2.0 * se:
        return m1, m2
    return None


def still_moving(per_period: np.ndarray, floor: float = 0.0) -> bool:
    """Whether the means of the series' two halves differ by more than :data:`HALVES_Z` of
    their combined blocked errors, and by more than ``floor`` (the tolerance, x* per period): a
    mean still approaching its value (a heavy bouncer in flight 90 % of the time relaxes over
    thousands of periods), whose long-time mean would carry its transient."""
    halves = _halves(per_period)
    return halves is not None and halves[0] > max(HALVES_Z * halves[1], floor)


def trend_allowance(per_period: np.ndarray) -> float:
    """Half the difference of the series' two halves' means where it exceeds :data:`TREND_Z`
    of their combined blocked errors, else 0: the least by which a mean still drifting is off
    its asymptote (an approach goes on past the second half's mean, which is this far from the
    mean of the whole).

    :func:`still_moving` takes a series to be still approaching only past :data:`HALVES_Z`
    errors, so that correlated noise is not taken for an approach; between the two a mean kept
    an error that said nothing of its drift. A rigid point hopping on a period-19 orbit it
    reaches after about 800 periods (material_point m* = 0.9, A* = 0.99) was -0.0945 +- 0.011
    over periods 310 to 1087 (halves 4.5 errors apart), against -0.152 from brute force; with
    the allowance its error is 0.045. For a series that only fluctuates the halves pass 3
    errors in a few percent of runs, whose error then grows to half their difference.
    """
    halves = _halves(per_period)
    if halves is None or not halves[0] > TREND_Z * halves[1]:
        return 0.0
    return 0.5 * halves[0]


def _halves(per_period: np.ndarray) -> tuple[float, float] | None:
    """(|difference of the means of the series' two halves|, its standard error from their
    blocked errors), for :func:`still_moving` and :func:`trend_allowance`; None for a series
    too short to tell."""
    half = per_period.size // 2
    if half < MIN_BATCHES:
        return None
    m1, s1, _ = blocked_error(per_period[:half])
    m2, s2, _ = blocked_error(per_period[half:])
    return abs(m2 - m1), math.hypot(s1, s2)


def _advance_mean(stepper: Stepper, parts: list[np.ndarray], done: int, periods: int,
                  target: float, tail: list[np.ndarray] | None = None) -> np.ndarray:
    """Run on from ``parts`` (the rows so far, :func:`period_rows`, ``done`` of the ``periods``
    counted) to the budget, stopping early at the ``target`` error (:func:`long_time_mean`);
    returns the rows of the whole series. ``tail`` gets the period-end states (x*, x*', y*,
    y*') of the last chunk run, if any."""
    x_last = stepper.y[0]
    m_star = float(stepper.prm[P_M])
    while done < periods:
        chunk = min(CHUNK, periods - done)
        state = stepper.advance_periods(chunk)
        if tail is not None:
            tail[:] = [state]
        x = state[:, 0]
        parts.append(np.column_stack((np.diff(np.concatenate(([x_last], x))),
                                      _energy(state, m_star))))
        x_last = x[-1]
        done += chunk
        if (target > 0.0 and done < periods
                and sum(p.shape[0] for p in parts) >= MIN_PERIODS):
            _mean, se, _n, flat, rising = blocking(np.concatenate(parts)[:, 0])
            if flat and not rising and se <= target:
                break
    return np.concatenate(parts)
