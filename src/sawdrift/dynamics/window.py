"""The measurement window: drift, and all the regime evidence, from one window after the transient.

:func:`measure_window` opens the window on the stepper's evidence vector (every statistic and the
event log start from zero there), advances whole periods, and reads the drift, the stroboscopic
samples, contact loss, gross slip and lift-off synchrony. :func:`lyapunov` then estimates the
largest Lyapunov exponent from a copy of the window's start, for runs that lost contact.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..errors import NonFiniteStateError
from . import evidence as ev
from .adams_bashforth import P_KRAMP
from .lyapunov import (
    ALIGN_PERIODS,
    EARLY_CHECKS,
    LYAPUNOV_D0,
    LYAPUNOV_MAX_PERIODS,
    LYAPUNOV_PERIODS,
    is_chaotic,
    lyapunov_statistics,
    verdict_clear,
)
from .rolling import psi_from_rest
from .stepper import Stepper
from .stretching import compiled_stretchings, twin_pair
from .synchrony import MIN_FLIGHT, Synchrony, synchrony


@dataclass
class Window:
    """What one measurement window saw (see :func:`measure_window`)."""

    periods: int
    t_start: float
    drift: float
    spin_rate: float
    drift_ratio: float
    samples: np.ndarray
    contact_lost: bool
    out_of_contact_fraction: float
    min_compression: float
    gross_slip_fraction: float
    liftoffs_per_period: float
    periodicity: float
    events: np.ndarray  # rows (t*, kind code, x*, x*', y*, y*', a*), see dynamics.evidence
    events_dropped: int
    orbit_period: int  # see orbit_period(); 0: not periodic
    positions: np.ndarray = field(repr=False)  # centre x* at the start and at each period's end
    snapshot: Stepper | None = field(default=None, repr=False)
    scale: np.ndarray | None = field(default=None, repr=False)  # state_scale of the samples
    #: the window's oldest events not kept (its log holds at most Stepper's KEPT_EVENT_ROWS)
    events_shed: int = 0
    _sync: Synchrony | None = field(default=None, repr=False, compare=False)
    #: the Lyapunov estimate from the window's start and the scale it was taken at, once
    #: computed (:func:`lyapunov_estimate`: a solved damped orbit's check and the run's exponent
    #: read the same window)
    _exponent: tuple[np.ndarray, tuple[float, float]] | None = field(default=None, repr=False,
                                                                     compare=False)

    @property
    def sync(self) -> Synchrony:
        """The lift-off synchrony of the window (:func:`hop_synchrony`), read from its events
        when first asked for: the windows a run settles through are judged by their drift, and
        only the one it reports needs its hops."""
        if self._sync is None:
            t0, periods, events = self.t_start, self.periods, self.events
            if self.events_shed > 0 and events.size:
                # the log holds the window's last events only: the hops are read over the whole
                # periods they cover (blocks from the window's start would be empty)
                skip = int(math.ceil(events[0, 0] - t0))
                if 0 < skip < periods:
                    t0, periods = t0 + skip, periods - skip
                    events = events[events[:, 0] >= t0]
            orbit = self.orbit_period if self.orbit_period <= LONGEST_HOP else 0
            if self.orbit_period == 0 and self.scale is not None:
                orbit = near_orbit(self.samples, self.scale)  # the hops of an orbit approached
            self._sync = hop_synchrony(events, t0, periods, orbit)
        return self._sync


def in_flight(win: Window) -> bool:
    """The whole window was one flight: out of contact throughout, without a lift-off in it."""
    return win.out_of_contact_fraction >= 1.0 and win.liftoffs_per_period == 0.0


def ballistic_return(y: float, vy: float, m_star: float, amplitude: float) -> float:
    """Periods until a particle in free flight can touch the surface again (0: it can now).

    In flight m* y*'' = 1 (gravity and preload push y* into the substrate); contact needs
    a* = y* - u_y > 0 and |u_y| <= ``amplitude``, so not before y* reaches -amplitude:
    the positive root of y + vy t + t^2 / (2 m*) = -amplitude.
    """
    c = y + amplitude
    if c >= 0.0:
        return 0.0
    return m_star * (-vy + math.sqrt(vy * vy - 2.0 * c / m_star))


def state_scale(amp: float, r: float) -> np.ndarray:
    """Natural sizes of (x*', y*, y*'): 2 pi r A*, 1 + A*, 2 pi (1 + A*)."""
    return np.array([2 * math.pi * max(abs(r) * amp, 1e-12), 1.0 + amp, 2 * math.pi * (1.0 + amp)])


def periodicity(samples: np.ndarray, scale: np.ndarray, last: int = 10) -> float:
    """Largest scaled change of the stroboscopic state (x*', y*, y*') between consecutive periods.

    A motion of period one gives 0; reported as evidence, not used to decide the regime.
    """
    if len(samples) < 2:
        return math.inf
    s = np.asarray(samples[-last - 1 :])
    return float((np.abs(np.diff(s[:, 1:4], axis=0)) / scale).max())


#: scaled stroboscopic change below which the state counts as repeating (round-off level)
PERIODIC_TOL = 1e-8

#: scaled change by which the states of an orbit of p, d periods apart (d a divisor of p), must
#: differ: below it the motion is on its way to an orbit of d, not on one of p. The inelastic
#: bouncing ball at Gamma = 3.7, below its period doubling (multiplier 1 - sqrt(Gamma^2 - pi^2)
#: = -0.955), repeated after 2 periods to 1e-8 while its take-offs still alternated by 2e-8
#: about the period-1 phase 0.338579; an orbit of 2 just past the doubling differs by
#: sqrt(Gamma - 3.7242) in its take-offs, 1e-4 within 1e-8 of the threshold
DISTINCT = 1e-4

#: longest periodic orbit read as a hop (its period the hop period): an orbit that repeats only
#: after more periods is settled on and its drift taken over whole orbits, but its lift-offs
#: are called bouncing, as a phase diagram sees them (of the 33 x 33 material point diagram,
#: m* 1e-3..1e2, A* 1e-2..10, 116 cells are exact orbits of 28 to 4589 periods, at m* > 1,
#: amid irregular bouncing)
LONGEST_HOP = 24


def orbit_period(samples: np.ndarray, scale: np.ndarray, longest: int | None = None,
                 last: int = 8) -> int:
    """Smallest p after which the stroboscopic state (x*', y*, y*') repeats.

    The state at the ends of the last ``last`` periods must equal the state p periods earlier to
    :data:`PERIODIC_TOL` (scaled by :func:`state_scale`); 0 if no such p (not periodic, or not
    yet). p goes up to ``longest``, by default as far as the window tells (its length less
    ``last``): a window of 162 periods finds a rigid point's orbit of 54 (material_point m* =
    0.1755, A* = 8.7), whose windows of 27 periods alternate between drift ratios 0.21 and
    -0.02. A quasi-periodic or chaotic motion does not come back to 1e-8 of its state for
    ``last`` periods in a row. The equations are autonomous at the stroboscopic times, so a
    repeating state is a periodic orbit: the drift over whole multiples of p is the steady
    drift.
    """
    s, ps = _states(samples, scale, longest, last)
    # a state repeats after p periods only if the last one does: the others are compared for
    # those p alone
    near = ps[_gaps(s, ps, 1) <= PERIODIC_TOL]
    hit = near[_gaps(s, near, last) <= PERIODIC_TOL]
    if not hit.size:
        return 0
    p = int(hit[0])
    # an orbit of p has its states p / d periods apart distinct for every divisor d of p; a
    # motion still approaching an orbit of d with multiplier near -1 repeats after 2 d periods
    # long before it does after d (|lambda^2 - 1| << |lambda - 1|): it is not yet periodic
    divisors = np.array([d for d in range(1, p) if p % d == 0], dtype=np.int64)
    if divisors.size and (_gaps(s, divisors, last) <= DISTINCT).any():
        return 0
    return p


#: scaled stroboscopic change within which a state repeats after p periods while every p it
#: is no multiple of stays :data:`NEAR_APART` times further off: an orbit of p being
#: approached (:func:`near_orbit`)
NEAR_ORBIT = 1e-4
NEAR_APART = 100.0


def near_orbit(samples: np.ndarray, scale: np.ndarray, last: int = 8) -> int:
    """The period p <= :data:`LONGEST_HOP` of an orbit the window's state is approaching but
    does not yet repeat to :data:`PERIODIC_TOL` (:func:`orbit_period`), or 0: the smallest p
    whose change is within :data:`NEAR_ORBIT`, every other p (not a multiple of it) at least
    :data:`NEAR_APART` times further. The hops are read against it (a rigid point on its way to a
    period-17 hop, material_point m* 3, A* 0.3, mu 0.2, repeated after 17 periods to 7.7e-6
    and after any other to 1.1 at least; its two lift-offs a window were called bouncing)."""
    s, ps = _states(samples, scale, LONGEST_HOP, last)
    if ps.size == 0:
        return 0
    gaps = _gaps(s, ps, last)
    near = ps[gaps <= NEAR_ORBIT]
    if near.size == 0:
        return 0
    p = int(near[0])
    others = gaps[ps % p != 0]
    return p if others.size and others.min() >= NEAR_APART * gaps[p - 1] else 0


def lag_change(states: np.ndarray, lag: int, last: int = 8) -> float:
    """The largest change of the last ``last`` scaled stroboscopic states against ``lag`` periods
    earlier (:func:`_gaps`; NaN for no lag or a window too short to tell)."""
    s = np.asarray(states, dtype=float)
    if lag <= 0 or s.shape[0] < lag + last:
        return math.nan
    return float(_gaps(s, np.array([lag]), last)[0])


#: window-to-window growth of a distance from repeating, and the factor within which the logs of
#: the growths must lie, that make a steady, exponential departure (:func:`grows_steadily`)
GROWTH_RATIO = 1.02
GROWTH_SPREAD = 2.0


def grows_steadily(values: list[float], windows: int) -> bool:
    """Whether the last ``windows`` window-to-window ratios of ``values`` (one distance from
    repeating a window) all exceed :data:`GROWTH_RATIO`, their logs within :data:`GROWTH_SPREAD`
    of each other: a motion leaving an unstable orbit (as past a period doubling), not a
    quasi-periodic wobble, whose growths come and go."""
    if len(values) < windows + 1:
        return False
    g = np.asarray(values[-windows - 1:], dtype=float)
    if not (np.isfinite(g).all() and (g > 0.0).all()):
        return False
    rates = np.log(g[1:] / g[:-1])
    return bool(rates.min() > math.log(GROWTH_RATIO) and rates.max() < GROWTH_SPREAD * rates.min())


def orbit_residual(samples: np.ndarray, scale: np.ndarray, longest: int | None = None,
                   last: int = 8) -> float:
    """How far the stroboscopic state is from repeating: the smallest over p <= ``longest`` (by
    default as far as the window tells) of the largest scaled change of the last ``last``
    period-end states against p periods earlier (:func:`orbit_period` finds an orbit where it
    is at most :data:`PERIODIC_TOL`); inf where the window is too short to tell."""
    s, ps = _states(samples, scale, longest, last)
    if ps.size == 0:
        return math.inf
    return float(_gaps(s, ps, last).min())


def orbit_span(samples: np.ndarray, scale: np.ndarray, p: int) -> int:
    """The periods, a whole number of the orbit's ``p``, at the end of a window whose states
    are all on the orbit: each repeats p periods later (to :data:`PERIODIC_TOL`). The drift
    over them is the orbit's; :func:`orbit_period` checks only the last few states, and a window
    that begins on the approach to the orbit would otherwise average over that approach too (a
    rigid point on a period-7 hop, material_point m* = 0.059, A* = 8.7: -0.571062 over the
    window's last three orbits, -0.5722326 over the last two and over 2000 periods)."""
    s = np.asarray(samples)[:, 1:4] / scale
    n = s.shape[0]
    repeats = np.abs(s[p:] - s[:-p]).max(axis=1) <= PERIODIC_TOL
    off = np.flatnonzero(~repeats)
    # samples[j] is the state after period j + 1 of the window; those from `first` on repeat,
    # so the orbit holds from the end of period first + 1 (the window's start is not checked)
    first = int(off[-1]) + 1 if off.size else 0
    return max(p, ((n - first - 1) // p) * p)


def _states(samples: np.ndarray, scale: np.ndarray, longest: int | None, last: int
            ) -> tuple[np.ndarray, np.ndarray]:
    """The scaled stroboscopic states (x*', y*, y*') of a window, and the periods p = 1, 2, ...
    looked at: up to ``longest`` (None: no limit) or as far as the window tells, its length
    less ``last`` (:func:`orbit_period`, :func:`orbit_residual`)."""
    s = np.asarray(samples)[:, 1:4] / scale
    reach = s.shape[0] - last if longest is None else min(longest, s.shape[0] - last)
    return s, np.arange(1, max(0, reach) + 1)


#: most (end state, p) pairs :func:`_gaps` compares in one array operation
GAP_BLOCK = 1 << 15


def _gaps(s: np.ndarray, ps: np.ndarray, last: int) -> np.ndarray:
    """For each p of ``ps``, the largest scaled change of the last ``last`` states of ``s``
    against p periods earlier. At most :data:`GAP_BLOCK` pairs at a time, so that the memory
    stays that of the samples however long the window (a window of 1e6 periods looks for
    orbits of up to 1e6 - ``last``)."""
    n = s.shape[0]
    ends = np.arange(n - last, n)
    out = np.empty(ps.size)
    step = max(1, GAP_BLOCK // last)
    for i in range(0, ps.size, step):
        block = ps[i:i + step]
        change = np.abs(s[ends[:, None] - block[None, :]] - s[ends][:, None, :])
        out[i:i + step] = change.max(axis=(0, 2))
    return out


def hop_liftoffs(events: np.ndarray, t_start: float, t_end: float,
                 rebounds_only: bool = True) -> np.ndarray:
    """Times of the lift-offs that count as hops (see :data:`~sawdrift.dynamics.synchrony.MIN_FLIGHT`).

    A flight ends at the next landing, or at ``t_end`` (the window's end) if none follows. With
    ``rebounds_only`` a flight shorter than MIN_FLIGHT is left out only if it is a rebound: its
    lift-off follows a landing (or the window's start) within MIN_FLIGHT. Otherwise every flight
    shorter than MIN_FLIGHT is left out (the coarser filter, tried second by
    :func:`measure_window`).
    """
    t = events[:, 0]
    kind = events[:, 1]
    lifts = np.nonzero(kind == ev.EV_LIFT_OFF)[0]
    lands = np.nonzero(kind == ev.EV_LANDING)[0]
    t_lift = t[lifts]
    # the landings' times with the window's start and end around them: each lift-off's flight
    # ends at the next landing (or the end), and began from contact at the last one (or the start)
    t_lands = np.concatenate(([t_start], t[lands], [t_end]))
    after = np.searchsorted(lands, lifts, side="right")  # index of the next landing in lands
    keep = t_lands[after + 1] - t_lift >= MIN_FLIGHT
    if rebounds_only:
        # a take-off from sustained contact is a (short) hop
        keep |= t_lift - t_lands[np.searchsorted(lands, lifts, side="left")] >= MIN_FLIGHT
    return np.asarray(t_lift[keep], dtype=float)


def hop_synchrony(events: np.ndarray, t_start: float, periods: int, orbit: int) -> Synchrony:
    """The lift-off synchrony of a window, micro-rebounds left out.

    The rebounds of an inelastic collapse are left out first (:func:`hop_liftoffs`); if the
    remaining lift-offs show no synchronous pattern, every flight shorter than MIN_FLIGHT is left
    out (a compliant contact's micro-bounces touch for longer than a rigid rebound).
    """
    t_end = t_start + periods
    sync = synchrony(hop_liftoffs(events, t_start, t_end), t_start, periods, orbit)
    if sync.hop_period == 0:
        coarse = synchrony(hop_liftoffs(events, t_start, t_end, rebounds_only=False), t_start,
                           periods, orbit)
        if coarse.hop_period > 0:
            return coarse
    return sync


def measure_window(stepper: Stepper, periods: int, speed: float, scale: np.ndarray,
                   advance: Callable[[int], np.ndarray] | None = None) -> Window:
    """Advance ``periods`` whole periods as the measurement window and read its evidence.

    Parameters
    ----------
    stepper
        The integration, at the start of the window.
    periods
        Window length in wave periods.
    speed
        Horizontal surface speed amplitude 2 pi r A* (the drift ratio's scale; 0: ratio 0).
    scale
        :func:`state_scale` of the scene, for the stroboscopic evidence and the twin's distance.
    advance
        How the window's periods are run: the state (x*, x*', y*, y*') at the end of each, as
        :meth:`~.stepper.Stepper.advance_periods` (the default) gives it; one that also keeps
        every step's row (an irregular heavy bouncer's record, :mod:`.imposed`).
    """
    ev.open_window(stepper.st)
    stepper.keep_events = True
    if stepper.step + periods * stepper.k_per <= stepper.prm[P_KRAMP]:
        # a window within the drive's start-up ramp (a run shorter than it): the evidence,
        # taken from the ramp's end on, would be empty, and a particle thrown off in it was
        # reported in contact; it is the window's own steps
        stepper.prm[P_KRAMP] = stepper.step
    t_start = stepper.step * stepper.h
    snapshot = stepper.twin()
    x0, psi0 = stepper.y[0], stepper.y[4]
    samples = (stepper.advance_periods if advance is None else advance)(periods)
    positions = np.concatenate(([x0], samples[:, 0]))
    if stepper.resist:
        spin = (stepper.y[4] - psi0) / periods
    elif stepper.roll > 0.0:
        # R phi = x / kappa from rest
        spin = psi_from_rest((positions[-1] - positions[0]) / periods, stepper.roll)
    else:
        spin = math.nan
    st = stepper.st  # read after the window: the stepper may have grown its event log
    count = max(st[ev.S_COUNT], 1.0)
    events = ev.events(st)
    orbit = orbit_period(samples, scale)
    # a periodic orbit of several periods: its drift over whole orbits only, or the part of an
    # orbit left over would bias it (by up to one period's jump / periods), and only those the
    # motion was already on (the window may begin on the approach to it)
    whole = orbit_span(samples, scale, orbit) if orbit > 1 else periods
    drift = (positions[-1] - positions[periods - whole]) / whole
    return Window(
        periods=periods,
        t_start=t_start,
        drift=float(drift),
        spin_rate=float(spin),
        drift_ratio=float(drift / speed) if speed > 0.0 else 0.0,
        samples=samples,
        contact_lost=bool(st[ev.S_LOST] > 0.0),
        out_of_contact_fraction=float(st[ev.S_OUT] / count),
        min_compression=float(st[ev.S_AMIN]) if math.isfinite(st[ev.S_AMIN]) else math.nan,
        gross_slip_fraction=float(st[ev.S_SLIP] / count),
        liftoffs_per_period=float(st[ev.S_LIFTS]) / periods,
        periodicity=periodicity(samples, scale),
        events=events,
        events_dropped=int(st[ev.S_EVDROP]),
        events_shed=int(st[ev.S_EVSHED]),
        orbit_period=orbit,
        positions=positions,
        snapshot=snapshot,
        scale=scale,
    )


#: the stretchings by one compiled call per stretch (:mod:`.stretching`) where they can be
COMPILED_STRETCHINGS = True


def stretching_logs(stepper: Stepper, scale: np.ndarray, periods: int,
                    align: int = ALIGN_PERIODS, d0: float = LYAPUNOV_D0,
                    early: tuple[int, ...] = ()) -> np.ndarray:
    """ln(d / d0) of each period after ``align``, renormalized every period (Benettin et al. 1980).

    A copy of the integration and a twin displaced by ``d0`` (scaled (x*', y*, y*'), first along
    y*') are advanced one period at a time; the twin's separation d is logged and the twin is
    re-started from the copy at distance ``d0`` along the separation. The first ``align``
    periods, in which the separation turns into the most unstable direction, are left out. A
    separation erased to 0 (an inelastic landing, a sticking phase) ends the series with -inf.
    With ``early``, the series stops after any of those numbers of stretchings where they
    already decide the verdict (:func:`~sawdrift.dynamics.lyapunov.verdict_clear`).
    ``stepper`` itself is not advanced.

    A displacement along y*' that the motion erases before the series begins (a rigid contact
    holds y* to the surface at once) is tried again along x*': only if that one is erased too
    is the series -inf. A rigid point sliding through the whole period, never landing, was
    given -inf where its velocity perturbation decays at a finite rate (-0.108 a period at
    mu = 0.1, m* = 1, Gz = 0.5, Gx = 10 Gz).
    """
    logs = _stretching_logs(stepper, scale, periods, align, d0, early, 3)
    if logs.size == 1 and logs[0] == -math.inf:
        return _stretching_logs(stepper, scale, periods, align, d0, early, 1)
    return logs


def _stretching_logs(stepper: Stepper, scale: np.ndarray, periods: int, align: int, d0: float,
                     early: tuple[int, ...], axis: int) -> np.ndarray:
    """:func:`stretching_logs` from a displacement along state ``axis`` (3: y*', 1: x*')."""
    if COMPILED_STRETCHINGS:
        logs = compiled_stretchings(stepper, scale, periods, align, d0, early, axis)
        if logs is not None:
            return logs
    base, twin, dy = twin_pair(stepper, scale, d0, axis)
    logs = np.empty(periods)
    u = [float(v) for v in scale]  # (x*', y*, y*') in plain floats: three numbers a period
    for j in range(align + periods):
        if j:
            twin.restart_from(base, dy)  # in place: the same state a new twin would have
        base.advance(base.k_per)
        twin.advance(twin.k_per)
        sep = [(float(twin.y[i + 1]) - float(base.y[i + 1])) / u[i] for i in range(3)]
        d = math.sqrt(sep[0] * sep[0] + sep[1] * sep[1] + sep[2] * sep[2])
        if not d > 0.0:
            return np.append(logs[: max(j - align, 0)], -math.inf)
        if j >= align:
            logs[j - align] = math.log(d / d0)
            n = j - align + 1
            if (n in early and n < periods
                    and verdict_clear(logs[:n], chaos=n >= LYAPUNOV_PERIODS)):
                return logs[:n]
        for i in range(3):
            dy[i + 1] = sep[i] * (d0 / d) * u[i]
    return logs


def lyapunov(window: Window, scale: np.ndarray) -> tuple[float, bool]:
    """Largest Lyapunov exponent (per period) from the window's start, and whether it is chaos.

    :func:`stretching_logs` from the window's snapshot over the window's length (at least
    :data:`~sawdrift.dynamics.lyapunov.LYAPUNOV_PERIODS`, at most
    :data:`~sawdrift.dynamics.lyapunov.LYAPUNOV_MAX_PERIODS`, stopping at the first of
    :data:`~sawdrift.dynamics.lyapunov.EARLY_CHECKS` where the stretchings so far already
    decide: a long window of a heavy quasi-periodic bouncer spent three quarters of its cost on
    stretchings that changed nothing, and a hopping orbit's contraction is plain after 32),
    judged by :func:`~sawdrift.dynamics.lyapunov.lyapunov_statistics` and
    :func:`~sawdrift.dynamics.lyapunov.is_chaotic`.
    """
    lam, err = lyapunov_estimate(window, scale)
    return lam, is_chaotic(lam, err)


def lyapunov_estimate(window: Window, scale: np.ndarray) -> tuple[float, float]:
    """(exponent, its uncertainty) per period from the window's start, as :func:`lyapunov`
    estimates them; NaN without a snapshot or where the stretchings are not finite. Computed
    once per window and scale (the stretchings start from the window's own snapshot)."""
    cached = window._exponent
    if cached is not None and np.array_equal(cached[0], scale):
        return cached[1]
    if window.snapshot is None:
        return math.nan, math.nan
    try:
        periods = min(max(window.periods, LYAPUNOV_PERIODS), LYAPUNOV_MAX_PERIODS)
        logs = stretching_logs(window.snapshot, scale, periods, early=EARLY_CHECKS)
    except NonFiniteStateError:
        return math.nan, math.nan
    estimate = lyapunov_statistics(logs)
    window._exponent = (np.array(scale, copy=True), estimate)
    return estimate
