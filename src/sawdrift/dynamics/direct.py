"""The steady drift of a heavy particle solved directly, with one window of evidence for its regime.

From m* = 5 up, :func:`settle_direct` first tries to solve the drift instead of waiting for it:

* the period-one orbit at full inertia and its force-velocity curve (:mod:`.separated`), the
  drift being the first zero of the period-averaged friction <T*>(V) met from rest;
* averaged over the run's own slow vertical oscillation, which the undamped normal contact keeps
  for ever (:mod:`.torus`).

Its cost does not depend on m*: a few tens of points of the curve, three periods each, whatever
the mass. The solved drift is what the run reports (``settle_method = "solved"``). The run is
put at that speed and measures **one evidence window** for the regime, the lift-offs and the
slip: the measuring length (27 periods by default), or one slow vertical cycle where the orbits
lose contact, since the fast motion need not lift off once a period at every height of that
cycle (mmd, m* = 1e3, A* = 5 hops regularly for 27 periods, irregularly over its cycle). Its
lift-offs per period must be those of the averaged orbits (within :data:`LIFT_MATCH`), or the
run is an irregular bouncer. The window cannot check the drift itself: a heavy particle put at
a wrong speed keeps it for of order m*/mu periods. What vouches for the drift is the
validation: on the 13 solved cells of the heavy validation family (sliding and hopping, m* 30
to 1e4, three models) the solved drift is within 2.2e-4 relative of full-inertia brute force
(confirming windows were within 3.3e-4: a window of three vertical periods still carries part
of the modulation); on 222 such cells (mmd, jaeger, hertz_mindlin_dem; m* 30 to 1e4, A* 0.3 to 5,
mu 0.1 and 0.5) it is within 1.3e-3 of the confirmed drift; on the one cell where they differ
by more than 1e-3, brute force sides with the solved drift.

Between m* = 5 and :data:`~.separated.ORBIT_ALONE_MASS` (30) the drift is solved only as the
average over a slow vertical cycle of at least 10 periods (the orbit's drift alone was 1e-3 from
brute force at m* = 3 to 10); at m* = 15 to 25, 93 solved cells of three models were within
5.4e-4 of brute force, and on 216 cells at m* = 4 to 13.3 (mmd, jaeger, hertz_mindlin_dem; A*
0.3 to 5; mu 0.1 and 0.5), 135 solved drifts were within 6.6e-4 of brute force from rest of 2
(40 m*/mu + 2000) periods but one (jaeger m* = 10, A* = 3, mu = 0.5: 1.5e-3). From m* = 3 up,
where the drift is not reported as solved, the orbit (or its cycle's average) is where the
full-inertia windows start (``orbit_then_full``).

With ``numerics.confirm_solved`` the run goes on from the solved speed in full-inertia windows of
three free vertical periods each (2 pi sqrt(m*/1.5) wave periods: their cost grows as sqrt(m*))
until they settle by themselves (``settle_method = "orbit_then_full"``, the last window's drift
reported).

A model whose normal force is damped (a normal-damping slot, hertz_tsuji's) has no slow vertical
cycle to average over: it decays, and the run from rest ends on the period-one orbit itself. Its
drift is the orbit's, and the run is put on the orbit (height, speed and their histories) before
its evidence window, which then shows the orbit's own lift-offs where it is stable. Averaged
over the cycle the run had when it was solved, hertz_tsuji (c = 0.1) came out 0.4 to 1.1 % low
at m* 7 to 90, A* 1.2 and 2.4 (0.52662 against 0.52870 from brute force over 3000 periods), and
its probe, taken on that decaying cycle, sent hops at A* 4.5 and 8.7 to the irregular bouncers'
mean, 10 to 15 % low (0.7075 +- 0.0086 against 0.8113 at m* 38.6, A* 4.5); the orbit's drift is
within 1e-6 of brute force on all of them. The scene's own normal damping
(``effects.normal_damping``, ``material.restitution``) is such a damping too: the orbit's
contact law carries it (:mod:`.orbit_law`). A damped orbit need not be where the run ends (a
longer orbit nearby, or an unstable one the run leaves): the evidence window started on it must
repeat (:data:`DAMPED_REPEAT`) and must not stretch perturbations (:data:`UNSTABLE_EXPONENT`),
or the run goes back to its state from before it was put there (:func:`~.snapshot.rewind`) and
settles by windows from that state. The same holds before confirming windows.

A contact that sticks or creeps has no period-one orbit (its memory does not repeat):
:data:`~.separated.STUCK`, left to full-inertia windows. A heavy bouncer whose lift-offs are not
once a period is irregular: its long-time mean comes from :func:`~.imposed.imposed_drift`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .approach import relative_bound
from .floquet import MOST_PERIODS, reaches_orbit, vertical_decay_periods
from .full_inertia import settle_full, shift_speed
from .imposed import imposed_drift
from .orbit_law import damped_normal
from .orbit_use import approach_periods, orbit_relaxation, place_on_orbit
from .separated import (
    IRREGULAR,
    ORBIT_ALONE_MASS,
    SOLVED_MIN_MASS,
    STUCK,
    SeparatedOrbit,
    Stuck,
    applies,
    separated_orbit,
)
from .settling import SLOPE, Settling
from .snapshot import checkpoint, rewind
from .stepper import Stepper
from .torus import torus_drift
from .window import Window, lyapunov_estimate, measure_window

#: periods of the probe that checks the fast motion before the drift is solved directly
PROBE_PERIODS = 12

#: periods of the window that gives an irregular heavy bouncer's regime evidence
EVIDENCE_PERIODS = 400

#: lift-offs per period a run may differ by from those of the orbits its drift was averaged over
LIFT_MATCH = 0.05

Direct = tuple[float, float, float, float, int, bool, bool, float]


@dataclass(frozen=True)
class SentBack:
    """A run put on its damped orbit that did not stay there by its evidence window
    (:func:`_left`), sent back to its own state: its windows are trusted only where they ran
    at least ``tau`` periods, the orbit's vertical decay time (:mod:`.floquet`). hertz_tsuji
    m* 3000, A* 1, mu 0.5, L 0.2 (tau = 88500) was sent back on a stretching of +0.029 +- 0.009
    a period, though its orbit is stable and its drift right (0.61741 against 0.617399 from
    brute force over 5e5 periods); its windows then settled at 0.606004 after 16050 periods."""

    tau: float


@dataclass(frozen=True)
class Modulated:
    """A damped run that does not reach its orbit (:func:`~.floquet.reaches_orbit`): its
    long-time mean at an imposed speed, over a record of at least ``record`` periods."""

    record: int


#: the error of the slow cycle's average (:mod:`.torus`) taken as this share of its correction
#: to the orbit's drift per unit m*: under a tangential load near its holding limit the
#: correction grows (mmd m* 100, A* 3, mu 0.2: 0.06 of drift ratio unloaded, 0.25 at L = -0.19)
#: and the averaged drift missed brute force by up to 1.4 % of it (3.6e-3 there); on 26 loaded
#: cells of mmd, mdr, jaeger and hertz_mindlin_dem (m* 30 to 1000, A* 1 to 3) every one outside
#: the bound had this estimate above the bound too, though the error reached 1.8 times it (mmd
#: m* 1000, A* 1.5, L = -0.349: 6.2e-5 against 3.5e-5)
AVERAGE_ERROR = 1.0


#: the stroboscopic spread (:func:`~.window.periodicity`) of the evidence window of a run put
#: on a damped orbit of hops above which that orbit is not its motion (:func:`settle_direct`):
#: mmd m* = 5.55, A* = 0.758, mu = 0.1, normal damping 0.5 spread by 1.2e-3 there and ends on
#: an orbit of 10 periods (28 at 256 steps a period), 0.470556 against the orbit's 0.471279;
#: at m* = 90 (c = 0.5, an orbit of 33 periods) by 7.2e-5, 9.9e-4 off; at m* = 30, A* = 1,
#: mu = 0.2, c = 0.1, L = -0.1 by 6.1e-5, 3.1e-3 off. The damped hops within 2e-4 of brute force
#: spread by 1.4e-7 to 1.2e-5
DAMPED_REPEAT = 3e-5


#: the Lyapunov exponent (per period) of the evidence window of a run put on a damped orbit of
#: hops above which, at :data:`UNSTABLE_SIGMAS` of its uncertainty, the orbit is unstable and
#: not its motion (:func:`_left`): hertz_mindlin_dem m* = 1758, A* = 4.1, mu = 0.27, c = 0.53,
#: L = -0.149 stretched by +0.0325 +- 0.0088 a period and ends on a hop at -0.790 against the
#: orbit's -1.062; m* = 3000, A* = 0.5, mu = 0.5, c = 1 by +0.0326 +- 0.009 (2.4e-3 off); m* =
#: 388, A* = 1.01, mu = 0.32, e = 0.42 by +0.247 +- 0.046 (called bouncing, a hop). The solved
#: hops within 1e-3 of brute force stretched by at most +0.0161 +- 0.0018 (hertz_tsuji
#: m* = 7.08, A* = 1.24)
UNSTABLE_EXPONENT = 0.025
UNSTABLE_SIGMAS = 3.0


def _left(win: Window, scale: np.ndarray) -> bool:
    """Whether a run put on a damped orbit of hops is not on it over its evidence window ``win``:
    its period starts spread by more than :data:`DAMPED_REPEAT`, or it stretches perturbations
    faster than :data:`UNSTABLE_EXPONENT` (beyond :data:`UNSTABLE_SIGMAS` of the estimate's
    uncertainty)."""
    if win.periodicity > DAMPED_REPEAT:
        return True
    lam, err = lyapunov_estimate(win, scale)
    return lam > UNSTABLE_EXPONENT and lam > UNSTABLE_SIGMAS * err


def averaging_error(scene, orbit_drift: float, drift: float, speed: float) -> float:
    """The drift ratio's error that the slow cycle's average may carry beyond the tolerance under
    a tangential load: AVERAGE_ERROR |average - orbit| / m* where that exceeds the settle bound
    (:func:`~.approach.relative_bound`), else 0. Unloaded drifts are the validated solution
    (within 2.2e-4 of brute force on the validation family); a damped contact has no cycle."""
    if scene.particle.load == 0.0 or speed <= 0.0:
        return 0.0
    error = AVERAGE_ERROR * abs(drift - orbit_drift) / scene.particle.m_star / speed
    bound = relative_bound(drift / speed, scene.numerics.settle_tolerance)
    return error if error > bound else 0.0


def settle_direct(stepper: Stepper, scene, speed: float, scale: np.ndarray, minimum_window: int,
                  max_steps: int) -> tuple[Window, Settling] | SentBack | str | None:
    """The drift of a heavy particle solved directly (module docstring).

    Returns the evidence window and the settling where the drift was solved (or an irregular
    bouncer's long-time mean measured); :data:`~.separated.STUCK` for a contact that sticks or
    creeps (full-inertia windows from here, no reduced-inertia approach); None where nothing
    direct applies (the window approach from here); a :class:`SentBack` for a run put on its
    damped orbit and sent back (the window approach, trusted after its vertical decay time).
    """
    # a damped contact's run is put on its orbit: kept, to go back to if it does not stay there
    before = checkpoint(stepper) if damped_normal(stepper) else None
    direct = direct_start(stepper, scene, speed, scale)
    if direct == IRREGULAR:
        return irregular_mean(stepper, scene, speed, scale, minimum_window)
    if isinstance(direct, Modulated):
        return irregular_mean(stepper, scene, speed, scale, minimum_window, direct.record)
    if direct is None:
        return None
    if isinstance(direct, Stuck):
        if direct.start is not None:
            # a contact sliding over a share of its period: its mean speed is a slow variable,
            # so its windows start at the curve's zero (a sticking or creeping one from rest)
            shift_speed(stepper, direct.start - stepper.y[1])
        return STUCK
    assert isinstance(direct, tuple)
    drift, lam, lifts, t90, evidence, solved, placed, uncertain = direct
    m = scene.particle.m_star
    if not placed:
        shift_speed(stepper, drift - stepper.y[1])
    report = solved and not scene.numerics.confirm_solved
    win = None
    if report or placed:
        win = measure_window(stepper, max(minimum_window, evidence), speed, scale)
        if placed and win.contact_lost and _left(win, scale):
            assert before is not None  # placed: a damped contact's run (direct_start)
            # a run put on a damped orbit of hops that does not repeat there, or that leaves
            # it, moves on another motion, which windows started on the orbit can mistake (mmd
            # m* = 22.3, A* = 0.758, mu = 0.1, c = 0.5 settled 1.7e-3 off): windows from the
            # run's own state, as it was before it was put there; they must run as long as the
            # vertical motion takes to relax (SentBack)
            tau = vertical_decay_periods(stepper, scale)
            rewind(stepper, before)
            return SentBack(tau)
    if report:
        assert win is not None
        # the best estimate, not settled where its average may be off by more than the bound
        info = Settling(uncertain == 0.0, "solved", m, win.periods, stepper.step / stepper.k_per,
                        t90, (drift / speed, win.drift_ratio), drift=drift, uncertain=uncertain)
    else:
        win, full = settle_full(stepper, scene, speed, scale, minimum_window, max_steps, lam,
                                expected=drift / speed)
        info = Settling(full.settled, "orbit_then_full", m, full.window_periods,
                        stepper.step / stepper.k_per, t90,
                        (drift / speed, *full.history), drift=full.drift(speed))
    if abs(win.liftoffs_per_period - lifts) <= LIFT_MATCH:
        return win, info
    # the run does not lift off as the averaged orbits do: its fast motion is not a period-one
    # orbit (irregular bouncing): friction at an imposed speed along its record
    return irregular_mean(stepper, scene, speed, scale, minimum_window)


def irregular_mean(stepper: Stepper, scene, speed: float, scale: np.ndarray,
                   minimum_window: int, record: int = 0) -> tuple[Window, Settling] | None:
    """The long-time mean drift of an irregular heavy bouncer (:func:`~.imposed.imposed_drift`,
    over at least ``record`` periods) and a window at that speed for the regime's evidence; not
    settled (a mean with an error)."""
    # long enough to hold several of a bouncer's flights (a window of 60 periods can be one)
    evidence = max(minimum_window, EVIDENCE_PERIODS)
    mean, win = imposed_drift(stepper, scene, speed, scale, evidence, record)
    if mean is None:
        return None
    if win is None:
        # the record could not be its own evidence: a window at the mean's speed
        shift_speed(stepper, mean.mean - stepper.y[1])
        win = measure_window(stepper, evidence, speed, scale)
    info = Settling(False, "imposed_speed", scene.particle.m_star, win.periods,
                    stepper.step / stepper.k_per, math.nan, (mean.mean / speed,),
                    long_mean=mean)
    return win, info


def direct_start(stepper: Stepper, scene, speed: float, scale: np.ndarray
                 ) -> Direct | Stuck | Modulated | str | None:
    """(drift, relaxation rate, lift-offs per period, periods to 90 % of the drift from rest,
    periods of evidence it needs, whether it is the reported drift or only the windows' start,
    whether the run was put on the orbit: a damped contact's, :func:`~.orbit_law.damped_normal`)
    solved directly for a heavy particle, or None where that does
    not apply: the period-one orbit (:func:`~.separated.separated_orbit`) averaged over the
    run's slow vertical oscillation (:func:`~.torus.torus_drift`), the time from rest by
    :func:`~.orbit_use.approach_periods`. An orbit that keeps contact is its own start if the average
    fails; one that loses contact is not (its drift can be 8 % from the run's). A
    :class:`~.separated.Stuck` for a contact that sticks, creeps or slips over part of its period
    without a repeating memory.

    Both need the fast motion to be a period-one orbit about a slowly moving height. A probe of
    :data:`PROBE_PERIODS` periods checks it, where the orbit loses contact, before the
    force-velocity curve is sampled: a run that loses contact must lift off once a period
    (a heavy particle bouncing at A* = 6 lifts off 0.4 times a period, irregularly, and is
    left to :func:`~.imposed.imposed_drift`).
    """
    tol = scene.numerics.settle_tolerance
    if not applies(stepper, scene):
        return None
    mu, m = scene.material.mu, scene.particle.m_star

    def regular() -> bool:
        # asked before the curve is sampled, where the orbit loses contact
        probe = measure_window(stepper, PROBE_PERIODS, speed, scale)
        return not (probe.contact_lost and abs(probe.liftoffs_per_period - 1.0) > LIFT_MATCH)

    # a damped normal contact decays towards the orbit: no probe of the transient, the run is
    # put on the orbit (where a copy of it closes in on the orbit, .floquet.reaches_orbit) and
    # its evidence window judges it
    damped = damped_normal(stepper)
    orbit = separated_orbit(stepper, scene, speed, tol, keep_contact=False,
                            regular=None if damped else regular)
    if orbit == IRREGULAR:
        # an irregular bouncer: its mean at an imposed speed needs a speed that hardly changes
        # over its record, a heavy particle's
        return IRREGULAR if m >= SOLVED_MIN_MASS else None
    if orbit is None or isinstance(orbit, Stuck):
        return orbit
    assert isinstance(orbit, SeparatedOrbit)
    # a creep of partial slip is confirmed by windows started at it (orbit_then_full): near the
    # stick boundary the particle's ringing, which the orbit leaves out, sets its drift
    solved = m >= SOLVED_MIN_MASS and not orbit.partial_slip
    if damped:
        away, tau = reaches_orbit(stepper, orbit, scale)
        if away:
            # the run from its own state heads for another motion (a modulated hop): its drift is
            # that motion's long-time mean, from where the check saw it, over a record of at
            # least one decay time (its slow modulation: a record of 434 periods against a tau
            # of 4800 gave an error of 3.2e-4 for a drift 1.65e-3 off)
            stepper.advance_periods(away)
            if m < SOLVED_MIN_MASS:
                return None
            return Modulated(min(int(math.ceil(tau)), MOST_PERIODS))
        place_on_orbit(stepper, orbit)
        averaged = (orbit.drift, 1.0 if orbit.loses_contact else 0.0, 0.0)
    else:
        averaged = torus_drift(stepper, orbit, speed, tol)
    if averaged is None:
        if orbit.loses_contact:
            return None
        averaged = (orbit.drift, 0.0, 0.0)
        solved = m >= ORBIT_ALONE_MASS
    drift, lifts, cycle = averaged
    # the approach from rest is not run: its time to 90 % from the force-velocity curve
    t90 = approach_periods(orbit, drift, speed, mu, m)
    # the evidence of a hopping run spans its slow cycle: the fast motion at some heights of it
    # need not lift off once a period (mmd m* = 1e3, A* = 5: hopping in 27 periods, irregular
    # over the cycle), which a shorter window would not see
    evidence = int(math.ceil(cycle)) if lifts > 0.0 else 0
    uncertain = 0.0 if damped else averaging_error(scene, orbit.drift, drift, speed)
    return (drift, orbit_relaxation(orbit, mu, m, SLOPE), lifts, t90, evidence, solved, damped,
            uncertain)
