"""Evidence gathered by the integration loops: one statistics vector and an event log.

Both schemes (compliant Adams-Bashforth and the rigid event scheme) write the same layout into
one float64 vector ``st``: a fixed block of statistics, then an event buffer of rows
``(t*, kind, x*, x*', y*, y*', a*)``. The runner clears the statistics and the buffer when the
measurement window starts (:func:`open_window`), so every piece of evidence of a result (lift-offs,
contact loss, gross slip, events) comes from the same window, after the transient.

Event kinds (:data:`EVENT_KINDS`):

* ``lift_off`` - contact is lost (a* turns <= 0); a bounce of the rigid point counts as landing
  and lift-off at the same instant;
* ``landing`` - contact is regained;
* ``slip_start`` / ``slip_end`` - gross slip (the whole contact slides, |T*| = N*) begins / ends
  while in contact; a lift-off during gross slip ends it first;
* ``stick_start`` - a phase without gross slip begins in contact (after ``slip_end``, or at a
  landing that does not slide).

Gross slip of a compliant law is |T*| >= (1 - :data:`SLIP_RTOL`) N* with N* > 0: an exact law reaches
|T*| = N* to rounding when the whole diagram slides (partial slip stays below it).
"""

from __future__ import annotations

import numpy as np
from numba import njit

# statistics block
S_LOST, S_AMIN, S_OUT, S_COUNT, S_BAD, S_BADSTEP = 0, 1, 2, 3, 4, 5
S_LIFTS, S_PREVIN = 6, 7  # lift-offs in the window; contact at the last step (1/0)
S_SLIP, S_PREVSLIP = 8, 9  # steps (fraction-weighted) in gross slip; gross slip at the last step
S_NEV, S_EVCAP = 10, 11  # events written, capacity of the buffer (rows)
S_EVDROP = 12  # events not written because the buffer was full
S_LASTLIFT = 13  # t* of the last lift-off since t* = 0 (-1: none), kept across windows
S_EVOLD = 14  # events of the transient before the window, counted and not kept
S_EVSHED = 15  # events of the window not kept: the oldest, shed where the log reached its cap
# a free flight in closed form (dynamics.flight): consecutive flight steps, and the anchor (the
# step where the derivative history became a parabola's, x*, x*', y*, y*' there); part of the
# integration's state, kept across the loop's calls, twins and snapshots
S_FLY = 16
S_ANCHOR = 17  # 17-21
N_FLIGHT = 6
N_ST = 24

#: Rows an integration step may still need in the event log: the loops return after a step that
#: leaves less room than this (compliant loop: at most 3 events a step), and the stepper grows the
#: log and goes on, so a long window never loses an event (see Stepper.advance).
EV_MARGIN = 8

#: bad-state causes written to ``st[S_BAD]``
BAD_NONFINITE, BAD_EVENTS = 1.0, 2.0

# event buffer
EV_W = 7
EVENT_KINDS = ("lift_off", "landing", "slip_start", "slip_end", "stick_start")
#: The kinds' codes are numpy integers, not Python ints: numba types a global Python int as a
#: literal and compiles a function it is passed to once per value (``event`` and the rigid
#: scheme's ``_log`` five times each, 0.1 s a compilation); an ``int64`` is one type.
EV_LIFT_OFF, EV_LANDING, EV_SLIP_START, EV_SLIP_END, EV_STICK_START = (np.int64(k) for k in range(5))
EVENT_COLUMNS = ("t", "kind", "x", "vx", "y", "vy", "a")

#: relative tolerance of the gross-slip test |T*| >= (1 - SLIP_RTOL) N*
SLIP_RTOL = 1e-6


def new_stats(event_capacity: int) -> np.ndarray:
    """A statistics vector with room for ``event_capacity`` events, in contact, window open."""
    st = np.zeros(N_ST + EV_W * max(0, int(event_capacity)))
    st[S_PREVIN] = 1.0
    st[S_LASTLIFT] = -1.0
    st[S_EVCAP] = max(0, int(event_capacity))
    open_window(st)
    return st


def grown(st: np.ndarray, minimum_free: int, most: int | None = None) -> np.ndarray:
    """A copy of ``st`` whose event log has twice the room (and at least ``minimum_free`` free rows),
    but no more than ``most`` rows where that still leaves them free.

    The statistics and the events written so far are kept.
    """
    cap = int(st[S_EVCAP])
    used = int(st[S_NEV])
    new_cap = max(2 * cap, used + int(minimum_free), 64)
    if most is not None:
        new_cap = max(min(new_cap, int(most)), used + int(minimum_free))
    out = np.zeros(N_ST + EV_W * new_cap)
    out[: st.size] = st
    out[S_EVCAP] = new_cap
    return out


@njit(cache=True)
def log_full(st, margin):
    """True when the event log has fewer than ``margin`` free rows (the loop then returns)."""
    return st[S_NEV] + margin > st[S_EVCAP]


def forget_transient(st: np.ndarray) -> None:
    """Empty the event log before the measuring window opens, counting what it held
    (``st[S_EVOLD]``): the log of a run of any length stays bounded."""
    st[S_EVOLD] += st[S_NEV]
    st[S_NEV] = 0.0


def shed_oldest(st: np.ndarray, keep: int) -> None:
    """Keep only the newest ``keep`` events of the log, counting the others (``st[S_EVSHED]``):
    a measuring window of any length holds at most a log's cap of events, its last ones, while
    its statistics (lift-offs, contact loss, gross slip) still count every step."""
    n = int(st[S_NEV])
    keep = max(0, min(int(keep), n))
    if keep == n:
        return
    rows = st[N_ST : N_ST + EV_W * n].reshape(n, EV_W)
    rows[:keep] = rows[n - keep :].copy()
    st[S_EVSHED] += n - keep
    st[S_NEV] = float(keep)


def open_window(st: np.ndarray) -> None:
    """Start the measurement window: clear every statistic and the event log (not the state)."""
    for i in (S_LOST, S_OUT, S_COUNT, S_LIFTS, S_SLIP, S_NEV, S_EVDROP, S_EVSHED):
        st[i] = 0.0
    st[S_AMIN] = np.inf


@njit(cache=True)
def event(st, kind, t, y, a):
    """Append one event row (see :data:`EVENT_COLUMNS`), or count it as dropped when full."""
    if kind == EV_LIFT_OFF:
        st[S_LASTLIFT] = t
    i = int(st[S_NEV])
    if i >= st[S_EVCAP]:
        st[S_EVDROP] += 1.0
        return
    j = N_ST + EV_W * i
    st[j] = t
    st[j + 1] = kind
    st[j + 2] = y[0]
    st[j + 3] = y[1]
    st[j + 4] = y[2]
    st[j + 5] = y[3]
    st[j + 6] = a
    st[S_NEV] = i + 1.0


@njit(cache=True)
def observe_contact(st, t, y, a, inside, slipping):
    """Log the events of a step sampled at ``t``: contact (``inside``) and gross slip against the
    last step's (the compliant loop; the rigid scheme locates its events itself)."""
    was_in = st[S_PREVIN] > 0.0
    was_slip = st[S_PREVSLIP] > 0.0
    if inside and not was_in:
        event(st, EV_LANDING, t, y, a)
        event(st, EV_SLIP_START if slipping else EV_STICK_START, t, y, a)
    elif was_in and not inside:
        if was_slip:
            event(st, EV_SLIP_END, t, y, a)
        event(st, EV_LIFT_OFF, t, y, a)
        st[S_LIFTS] += 1.0
    elif inside:
        if slipping and not was_slip:
            event(st, EV_SLIP_START, t, y, a)
        elif was_slip and not slipping:
            event(st, EV_SLIP_END, t, y, a)
            event(st, EV_STICK_START, t, y, a)
    st[S_PREVIN] = 1.0 if inside else 0.0
    st[S_PREVSLIP] = 1.0 if slipping else 0.0


@njit(cache=True)
def observe_step(st, out, slip, a):
    """Add one step to the window's statistics (both schemes, after the ramp): ``out`` and
    ``slip`` are the fractions of the step out of contact and in gross slip, ``a`` is a*."""
    if out > 0.0:
        st[S_LOST] = 1.0
        st[S_OUT] += out
    st[S_SLIP] += slip
    if a < st[S_AMIN]:
        st[S_AMIN] = a
    st[S_COUNT] += 1.0


@njit(cache=True)
def observe_flight_steps(st, n):
    """:func:`observe_step` of ``n`` whole flight steps at once (``n`` > 0), none of which
    deepens a* (:func:`~sawdrift.dynamics.flight.flight_skip`): out of contact, no slip. The
    counts are whole numbers, so the sums are those of ``n`` single steps to the bit."""
    st[S_LOST] = 1.0
    st[S_OUT] += n
    st[S_COUNT] += n


def events(st: np.ndarray) -> np.ndarray:
    """The events written since the window opened, as an (n, EV_W) array."""
    n = int(st[S_NEV])
    return st[N_ST : N_ST + EV_W * n].reshape(n, EV_W).copy()
