"""A contact that stopped sliding may slide again: the slow beat of the free vertical oscillation.

The normal equation of a compliant contact without normal damping has an undamped free
oscillation of frequency f = sqrt(N*'(1) / m*) / (2 pi) per wave period (N*'(1) = 1.5 for
Hertz), which the start-up leaves behind and nothing removes. Against the wave's harmonic k
nearest to f it beats with the period 1 / |f - k|: the normal force's modulation grows and
shrinks over that many periods, and with it the friction limit. Near a harmonic the beat is long
(mmd m* = 0.00237: f = 4.0028, a beat of 355 periods), so a light particle can slide while the
modulation is strong, hold its contact for a window or several while it is weak, and slide again
a beat later: one window that held, or windows that agreed while they held, are then no steady
state (mmd m* = 0.00237, A* = 1.26 held from period 87 and was settled as sticking at period
114; brute force over 4000 periods slides again after about 450 and drifts at -6e-4 in
oscillating slip).

:class:`SlipReturn` follows a run's windows: where the contact slid in an earlier window and
the beat outlasts a window, the run may settle only once its contact has held for
:data:`HELD_BEATS` beats since it last slid. A contact that never slid, a beat shorter than a
window, or a run still sliding (whose windows judge a drift) are not held back.
"""

from __future__ import annotations

import math

from .window import Window, in_flight

#: beats of the free vertical oscillation a contact that slid before must hold through before
#: it may settle
HELD_BEATS = 2.0

#: N*'(1) of the Hertz law: the free vertical oscillation's stiffness (the convention of the
#: settle windows, :func:`~.full_inertia.full_window_length`, :func:`~.steady.window_length`)
NORMAL_STIFFNESS = 1.5


def free_vertical_period(m_star: float) -> float:
    """The period, in wave periods, of the undamped free vertical oscillation of a compliant
    contact: 2 pi sqrt(m* / N*'(1)), N*'(1) = :data:`NORMAL_STIFFNESS`."""
    return 2.0 * math.pi * math.sqrt(m_star / NORMAL_STIFFNESS)


def vertical_beat(m_star: float, rigid: bool = False) -> float:
    """Periods of the beat of the free vertical oscillation against the wave's nearest harmonic,
    1 / |f - k| with f = 1 / :func:`free_vertical_period` and k >= 1 (module docstring); inf on
    a harmonic, 0 for a rigid point (no free oscillation)."""
    if rigid or m_star <= 0.0:
        return 0.0
    f = 1.0 / free_vertical_period(m_star)
    gap = abs(f - max(1, round(f)))
    return math.inf if gap == 0.0 else 1.0 / gap


class SlipReturn:
    """Whether a run whose windows would settle must wait for a slip to come back (module
    docstring). ``beat``: :func:`vertical_beat`; ``last``: the window before the first one
    seen, if any (a default run's fixed window)."""

    def __init__(self, beat: float, last: Window | None = None):
        self.beat = beat
        self.slid = last is not None and _slides(last)
        self.held_for = 0  # periods since the last window that slid
        self.returned = False
        #: the slip came back after a hold at least once: the drift is modulated over the beat
        self.came_back = False

    def see(self, win: Window) -> None:
        """Take the next window into account."""
        slides = _slides(win)
        # the slip came back in this window after a hold that was being waited on
        self.returned = slides and self.slid and self.beat > win.periods and self.held_for > 0
        if slides:
            self.slid, self.held_for = True, 0
        else:
            self.held_for += win.periods

    def overrule(self, action: str, win: Window) -> str:
        """Take the next window ``win`` into account (:meth:`see`) and return the
        window-to-window verdict ``action`` after it (``"settled"``, ``"next"``, ...), held
        back: ``"wait"`` for a settled verdict while :meth:`waits`, ``"again"`` (compare afresh)
        where the slip has just come back, so that the agreement of the windows that held does
        not settle the sliding that follows."""
        self.see(win)
        if self.returned and action in ("settled", "next"):
            self.came_back = True
            return "again"
        if action == "settled" and self.waits(win):
            return "wait"
        return action

    def waits(self, win: Window) -> bool:
        """Whether a run whose last window is ``win`` may not settle yet: it holds its contact
        now, slid before, and has held for fewer than :data:`HELD_BEATS` beats longer than the
        window."""
        return (self.slid and not _slides(win) and self.beat > win.periods
                and self.held_for < HELD_BEATS * self.beat)


def _slides(win: Window) -> bool:
    """The window slid as a whole at some step, or lost contact."""
    return win.gross_slip_fraction > 0.0 or (win.contact_lost and not in_flight(win))
