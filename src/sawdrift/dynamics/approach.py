"""How the full-inertia windows approach the steady drift: the bookkeeping after each window of
:func:`~sawdrift.dynamics.full_inertia.settle_full` (settle, jump, longer windows, next).

From two consecutive window means the distance still to go is extrapolated as a geometric series
(Aitken, :func:`remaining_distance`) with the window ratio q = exp(-lambda W) of the mean speed's
relaxation: predicted, corrected by the secant across a jump (:func:`secant_ratio`), or measured
on a partly stuck contact whose mean speed still relaxes (:func:`creep_ratio`). The module
docstring of :mod:`.full_inertia` gives the physics.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from .window import Window, in_flight
from .window_noise import JUMP_Z, chases_noise

#: fraction of a window in gross slip from which its mean speed is a slow variable (a contact
#: that is partly stuck most of the time relaxes with its tangential oscillation instead)
SLIDING_FRACTION = 0.05

#: the stage aims at this fraction of ``settle_tolerance`` (relative to the drift): a slow second
#: mode (the undamped free vertical oscillation trading energy with the horizontal motion) can
#: hide under window changes of this size, so the aim is well inside the tolerance
ACCURACY = 0.5

#: a drift ratio below which the tolerance is absolute (tol * ABS_FLOOR)
ABS_FLOOR = 0.02

#: consecutive window changes within the accuracy that a settled drift needs (a hopping particle
#: can drift on a slow mode whose changes grow before they decay)
STEADY_CHANGES = 3

#: the largest jump, in window changes: q / (1 - q) at most this, so a ratio q measured near one
#: (a secant across a jump on a noisy, hopping window) cannot throw the speed far past its fixed
#: point; a slower approach takes several jumps
LONGEST_JUMP = 20.0

#: the window ratio at which an extrapolation reaches :data:`LONGEST_JUMP` changes
LONGEST_Q = LONGEST_JUMP / (1.0 + LONGEST_JUMP)

#: windows may grow to this many times their first length (changes that alternate in sign)
LONGEST_WINDOW = 16


def relative_bound(drift_ratio: float, tol: float) -> float:
    """The tolerance relative to the drift ratio, with the floor :data:`ABS_FLOOR` (below it the
    bound is absolute)."""
    return tol * max(abs(drift_ratio), ABS_FLOOR)


def accuracy(drift_ratio: float, tol: float) -> float:
    """:data:`ACCURACY` times :func:`relative_bound`: what successive windows must agree to."""
    return ACCURACY * relative_bound(drift_ratio, tol)


def remaining_distance(c1: float | None, c2: float, q_pred: float) -> float:
    """Distance still to go after two consecutive window changes ``c1``, ``c2`` (Aitken).

    Changes of one sign are a monotone approach, extrapolated as a geometric series with the
    ratio q = min(c2/c1, q_pred): the measured ratio, but never slower than the predicted
    relaxation ``q_pred`` = exp(-lambda W), so window noise near a ratio of one cannot make a jump
    of many times the change; a ratio of one or more (noise on a slow approach) takes ``q_pred``.
    A single change (``c1`` None) is extrapolated with ``q_pred`` too. Alternating signs (the
    windows are at their noise): the last change itself. ``q_pred`` = 0 turns extrapolation off
    (a partly stuck contact, whose mean speed is not a slow variable).
    """
    if q_pred <= 0.0 or c2 == 0.0:
        return c2
    q_pred = min(q_pred, LONGEST_Q)
    if c1 is None:
        return c2 * q_pred / (1.0 - q_pred)
    if c1 == 0.0 or c2 / c1 <= 0.0:
        return c2
    q = min(c2 / c1, q_pred)
    return c2 * q / (1.0 - q)


#: the largest jump, in window changes, along a secant that stood out of the noise
#: (:meth:`_Approach._learn`): near the holding limit a load's force-velocity curve is flat and
#: its speed relaxes with a ratio of 0.98 a window, 50 changes still to go, which jumps of 20
#: did not close within the stage's windows (mmd m* = 47, A* = 0.71, L = -0.1499)
TRUSTED_JUMP = 100.0

#: a partly stuck contact's windows are extrapolated with their measured ratio
#: (:func:`creep_ratio`), and a sliding one's with the secant across a jump past the jumps' bound
#: (:meth:`_Approach._learn`), only where the mean speed is predicted to relax over a window or
#: more, q = exp(-lambda W) at least this: a lighter particle's window means scatter with its
#: flights, and secants of that scatter (mmd m* = 1, A* = 10) near one kept it from settling
SLOW_Q = 0.5

#: the largest factor between the 1 - q of two consecutive window ratios that still make one
#: geometric approach (:func:`creep_ratio`)
GEOMETRIC_SPREAD = 1.5


def creep_ratio(c0: float | None, c1: float | None, c2: float) -> float | None:
    """The window ratio q of a partly stuck contact whose mean speed still relaxes: three
    consecutive window changes of one sign falling geometrically, c1 / c0 and c2 / c1 in (0, 1)
    with their 1 - q within :data:`GEOMETRIC_SPREAD` of each other; None otherwise.

    Its tangential stiffness does not always tie the mean speed to the surface within a window:
    mmd m* = 3300, A* = 0.16, mu = 0.1, gross slip in 1.6 % of its periods, crept up by 9.4e-6,
    8.7e-6, ... a window of 885 periods (ratio 0.927 throughout), changes within the accuracy
    whose sum still to go was 1.0e-4: it stopped at 8.43e-4, where brute force reaches 9.447e-4
    after 8e4 periods (Aitken's extrapolation with the measured ratio gives 9.45e-4).
    """
    if c0 is None or c1 is None or c0 == 0.0 or c1 == 0.0:
        return None
    r1, r2 = c1 / c0, c2 / c1
    if not (0.0 < r1 < 1.0 and 0.0 < r2 < 1.0):
        return None
    g1, g2 = 1.0 - r1, 1.0 - r2
    return r2 if max(g1, g2) <= GEOMETRIC_SPREAD * min(g1, g2) else None


#: window changes whose mean :func:`trend_remaining` extrapolates
TREND_CHANGES = 4


def trend_remaining(changes: list[float], q: float) -> float:
    """The distance still to go of a slow approach from the mean of its last
    :data:`TREND_CHANGES` window changes (at least :data:`STEADY_CHANGES`), extrapolated with
    the window ratio ``q`` (at most :data:`LONGEST_JUMP` changes); 0 with fewer changes.

    A beat of about two windows makes consecutive changes alternate between large and small
    (mmd m* = 75, A* = 1.3, mu = 0.2 under a load of -0.18: -7.9e-5, -1.1e-5, -8.6e-5, -1.3e-6),
    and the ratio of the last two, 0.015, said nothing was left to go: it settled at -0.20156
    where brute force reaches -0.203186. Their mean, -4.4e-5 a window, says it is still moving;
    the mean of changes about a steady drift is their noise over two.
    """
    recent = changes[-TREND_CHANGES:]
    if len(recent) < STEADY_CHANGES:
        return 0.0
    q = min(q, LONGEST_Q)
    return abs(sum(recent) / len(recent)) * q / (1.0 - q)


def accelerates(last: float | None, change: float, noise: Callable[[], float]) -> bool:
    """Whether the window means still speed up: the last two changes of one sign, the later the
    larger, both standing out of the windows' noise (:data:`~.window_noise.JUMP_Z` times it).

    After a jump the mean speed of a heavy hop can hold still for a window or two and then move
    on, slowly at first (the fast motion's slow part re-adapts with it): hertz_mindlin_dem
    m* = 100, A* = 1.2, mu = 0.2, normal damping 0.1, L = -0.05 changed by 9.5e-6 and then
    2.3e-5 a window after its last jump, their extrapolation said 1.2e-4 was left, and it
    settled at 0.321082 where brute force reaches 0.322146."""
    return (last is not None and change * last > 0.0 and abs(change) > abs(last)
            and abs(last) > JUMP_Z * noise())


def secant_ratio(before: tuple[float, float], after: tuple[float, float]) -> float | None:
    """The window ratio q measured across a jump: a secant of the change per window against the
    window mean, c = -(1 - q) (D - v*), through the (mean, change) pair before and the pair
    after the jump; None where it gives no ratio in (0, 1).

    The first stage's relaxation rate, scaled to full inertia, is only an estimate (a jump on it
    overshot by a factor of two on jaeger, m* = 3000); the secant corrects it
    (:meth:`_Approach._learn`).
    """
    (d0, c0), (d1, c1) = before, after
    if d1 == d0:
        return None
    k = (c1 - c0) / (d1 - d0)
    return 1.0 + k if -1.0 < k < 0.0 else None


#: lift-offs a window that lost contact must hold for its mean to move the speed by a jump,
#: where its flights are long (:data:`LONG_FLIGHT`)
JUMP_FLIGHTS = 8

#: periods a window's flights last on average, at least, for :data:`JUMP_FLIGHTS` to apply: a
#: light bouncer's windows of 27 to 32 periods hold 6 or 7 flights of about 4 periods, whose
#: scatter the noise of a change sees (mmd m* 2.4 to 4.2, A* 10 settle within the bound with
#: their jumps and took 1.1 to 2 times as long, further from brute force in three of four,
#: without them)
LONG_FLIGHT = 16.0


def few_flights(win: Window) -> bool:
    """Whether a window that lost contact is a few long flights: fewer than
    :data:`JUMP_FLIGHTS` lift-offs, out of contact :data:`LONG_FLIGHT` periods or more a flight
    on average. Its mean is a sample of those flights, the drift constant in each, and the
    scatter of its periods says nothing of how it differs from the next window's (a rigid point
    at m* = 100, A* = 0.548, flights of about 860 periods: its windows of 2592 periods jumped the
    speed 15 times by 0.3 to 0.4, and the long-time mean after them was 0.236 +- 0.016 where
    brute force over the second half of 400000 periods gives 0.0478; without the jumps 0.021 +-
    0.016). A heavy sliding window with a stray lift-off is not one."""
    if not win.contact_lost:
        return False
    lifts = win.liftoffs_per_period * win.periods
    return lifts < JUMP_FLIGHTS and win.out_of_contact_fraction * win.periods >= (
        LONG_FLIGHT * max(lifts, 1.0))


@dataclass
class _Approach:
    """The window-to-window bookkeeping of :func:`settle_full`: what to do after each window."""

    w: int
    q: float
    tol: float
    w0: int = 0
    prev: float | None = None
    #: the window changes since the last restart (the last two are what Aitken's extrapolation
    #: and :func:`creep_ratio` read; the last four, :func:`trend_remaining`)
    changes: list[float] = field(default_factory=list)
    before: tuple[float, float] | None = None  # (window mean, change) where the last jump began
    steady_run: int = 0  # consecutive window changes within the accuracy
    flips: int = 0  # consecutive changes of alternating sign
    jumps: int = 0
    #: the drift ratio solved directly that the windows confirm (None: windows alone decide)
    expected: float | None = None
    #: the relaxation rate predicted before any jump (per period)
    rate: float = 0.0
    #: the window ratio of the last secant across a jump that stood out of the noise (None:
    #: none yet; :meth:`_learn`)
    seen: float | None = None
    #: the distance still to go estimated after the last window (drift ratio); after a jump,
    #: until the next change is measured, the jump's own distance
    to_go: float = 0.0

    def restart(self, longer: bool) -> None:
        """Compare afresh from the next window (after a jump, or in windows twice as long)."""
        if longer:
            # the ratio per window of a mode relaxing as exp(-lambda t) squares as it doubles
            self.w, self.q, self.flips = 2 * self.w, self.q * self.q, 0
            self.seen = None if self.seen is None else self.seen * self.seen
        self.prev, self.changes, self.steady_run = None, [], 0

    def _learn(self, d: float, change: float, noise: Callable[[], float], lost: bool) -> None:
        """After a jump: the secant across it (:func:`secant_ratio`) corrects the predicted
        rate by up to a factor of four either way (a noisy secant of an irregular bouncer's
        windows is no rate), and where both its changes stand out of the windows' noise
        (:data:`~.window_noise.JUMP_Z` times it) its own ratio is kept as :attr:`seen`, the
        distance still to go of a slower approach: mmd m* = 47, A* = 0.71, mu = 0.15 under a
        load of -0.1495, near the holding limit where the force-velocity curve is flat, relaxes
        with a ratio of about 0.98 a window against 0.96 predicted, and settled 1.35e-3 short
        (-0.985942 against -0.987330 from brute force) on changes of 2e-5 that jumps of 20
        changes had not yet closed. Not where the window lost contact (``lost``): a bouncer's
        mean speed moves back by about the same change a window from either side of its drift
        (mmd m* = 4.63, A* = 8.7: 0.02 from 2.25 and from -0.74 alike), no geometric approach,
        and a secant across its jump threw it by 2 back and forth."""
        q0 = math.exp(-self.rate * self.w)
        before, self.before = self.before, None
        secant = secant_ratio(before, (d, change))
        if secant is None:
            return
        self.q = min(max(secant, q0 ** 4.0), q0 ** 0.25)
        if (not lost and q0 >= SLOW_Q
                and min(abs(before[1]), abs(change)) > JUMP_Z * noise()):
            self.seen = secant

    def judge(self, d: float, win: Window, noise: Callable[[], float] = lambda: 0.0
              ) -> tuple[str, float]:
        """("settled" | "jump" | "longer" | "next", the jump in drift ratio) after a window;
        ``noise``: the standard error of a change between two window means
        (:func:`change_noise`, :func:`chases_noise`), asked for only where a jump is in view."""
        if in_flight(win):
            return "longer", 0.0  # one flight spans the window: its constant drift says nothing
        if self.prev is None:
            self.prev = d
            return "next", 0.0
        change = d - self.prev
        if self.before is not None:
            self._learn(d, change, noise, win.contact_lost)
        slow = win.contact_lost or win.gross_slip_fraction >= SLIDING_FRACTION
        last = self.changes[-1] if self.changes else None
        older = self.changes[-2] if len(self.changes) > 1 else None
        creep = None if slow or self.q < SLOW_Q else creep_ratio(older, last, change)
        remaining = remaining_distance(last, change, self.q if slow else (creep or 0.0))
        if slow and self.seen is not None and last is not None and change * last > 0.0:
            # an approach slower than the jumps may go (the secant's ratio past LONGEST_JUMP):
            # its distance to go is the secant's, and the jump the most a jump may be
            remaining = math.copysign(max(abs(remaining), abs(change) * self.seen
                                          / (1.0 - self.seen)), change)
        eps = accuracy(d, self.tol)
        self.steady_run = self.steady_run + 1 if abs(change) <= eps else 0
        # the trend's ratio: the secant's where one was measured (faster or slower than the
        # bounded prediction: the larger of the two overshot a ratio of 0.88 by a factor 2.4,
        # and its jumps alternated in sign), else the prediction
        q_trend = self.q if self.seen is None else self.seen
        trend = (trend_remaining([*self.changes, change], q_trend)
                 if slow and self.q >= SLOW_Q else 0.0)
        self.to_go = max(abs(remaining), trend)
        if (self.steady_run >= STEADY_CHANGES and self.to_go <= eps
                and not (slow and accelerates(last, change, noise))):
            return "settled", 0.0
        if (self.expected is not None and self.steady_run >= 1 and abs(remaining) <= eps
                and abs(d - self.expected) <= eps and abs(self.prev - self.expected) <= eps):
            # two windows in a row on the drift solved directly, their change within the
            # accuracy: an independent estimate agrees, so one change suffices
            return "settled", 0.0
        # no jump where nothing relaxes slowly (q = 0: the speed of a light particle settles
        # within a window, and changes of one sign are a beat of its contact, not an approach)
        q_jump = self.q if slow else (creep or 0.0)
        if (q_jump > 0.0 and last is not None and change * last > 0.0 and abs(remaining) > eps
                and not few_flights(win) and not chases_noise(change, last, q_jump, noise(), eps)):
            self.jumps += 1
            self.before = (d, change)
            # the next window re-adapts; compare the two after it
            longest = LONGEST_JUMP if self.seen is None else TRUSTED_JUMP
            return "jump", math.copysign(min(abs(remaining), longest * abs(change)), change)
        self.flips = self.flips + 1 if (last is not None and change * last < 0.0) else 0
        if self.flips >= 2 and abs(change) > eps and self.w < LONGEST_WINDOW * self.w0:
            # changes that alternate in sign are a slow oscillation beating against the window
            # (a quasi-periodic motion), not an approach: longer windows average it out; below
            # the accuracy the alternation is the windows' noise (a sticking contact's drift of
            # 1e-8 changing sign), which the steady count above settles without longer windows
            return "longer", 0.0
        self.prev = d
        self.changes.append(change)
        return "next", 0.0
