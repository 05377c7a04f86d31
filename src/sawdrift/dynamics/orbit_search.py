"""The periodic orbit a regular motion with contact loss settles on: the windows a default run
goes on with until it repeats (the hop period and take-off phases are the orbit's), and the
signs that it never will (a distance from repeating that stays flat or falls too slowly) or that
it is leaving its hop for another orbit (a distance that grows steadily, as past a period
doubling). :mod:`sawdrift.dynamics.integrate` calls :func:`orbit_search` after a fixed window.
"""

from __future__ import annotations

import math

import numpy as np

from .batch_means import period_rows
from .stepper import Stepper
from .window import (
    GROWTH_RATIO,
    PERIODIC_TOL,
    Window,
    grows_steadily,
    lag_change,
    lyapunov,
    measure_window,
    orbit_residual,
)

__all__ = ["LEAVING_PERIODS", "ORBIT_PERIODS", "find_orbit", "orbit_search"]


def orbit_search(stepper: Stepper, win: Window, speed: float, scale: np.ndarray,
                  series: list[np.ndarray], before: Window | None,
                  exponent: tuple[float, bool]) -> tuple[Window, Window | None, bool, float, bool]:
    """:func:`find_orbit` from the fixed window ``win``, and the Lyapunov exponent and verdict
    of the window it ends on (``exponent``, the fixed window's, where it ran none): the evidence
    comes from one window (a stable orbit of 2 reached after its doubling kept the fixed window's
    +0.029, the unstable orbit of 1's)."""
    found, before, leaving = find_orbit(stepper, win, speed, scale, series, before)
    lyap, chaotic = lyapunov(found, scale) if found is not win else exponent
    return found, before, leaving, lyap, chaotic


#: periods a regular (not chaotic) window that lost contact may run on to reach its periodic orbit
ORBIT_PERIODS = 300

#: periods the orbit search goes on while the motion leaves its hop (:func:`_still_leaving`):
#: the new orbit it heads for may lie that far
LEAVING_PERIODS = 1000


def find_orbit(stepper: Stepper, win: Window, speed: float, scale: np.ndarray,
                series: list[np.ndarray] | None = None, before: Window | None = None
                ) -> tuple[Window, Window | None, bool]:
    """Run on, window after window, until a regular window that lost contact is on its orbit.

    A motion with contact loss that is not chaotic settles on a periodic orbit (or is still on
    its way, or is quasi-periodic): its hop period and take-off phases are the orbit's
    (:func:`~sawdrift.dynamics.synchrony.orbit_pattern`), and a window before the orbit is reached
    can show a slowly decaying or growing alternation that looks like a hop of another period
    (the inelastic bouncing ball just past its period doubling: lift-offs at 0.3765 and 0.3034
    alternately, which 60 periods averaged into one phase). At most :data:`ORBIT_PERIODS` more,
    and no more once the distance from repeating (:func:`~.window.orbit_residual`) shows that
    they would not reach an orbit (:func:`_no_orbit_ahead`). Each window's per-period rows
    (:func:`~.batch_means.period_rows`) are appended to ``series``. Returns the last window,
    the one before it (``before`` where no window was run), and whether the motion was still
    leaving its orbit when the periods ran out (:func:`_still_leaving`: the bouncing ball just
    past its period doubling, Gamma = 3.73, multiplier -1.0108, whose alternation grows for
    about a thousand periods before it settles on the orbit of 2, was called a settled hop of 1).
    """
    spent = 0
    residuals = [orbit_residual(win.samples, scale)]
    gaps = [_hop_gap(win, scale)]
    cap = ORBIT_PERIODS
    while win.contact_lost and win.orbit_period == 0 and spent < cap:
        before = win
        win = measure_window(stepper, win.periods, speed, scale)
        if series is not None:
            series.append(period_rows(win, stepper))
        spent += win.periods
        residuals.append(orbit_residual(win.samples, scale))
        gaps.append(_hop_gap(win, scale))
        if _still_leaving(win, gaps):
            cap = LEAVING_PERIODS  # leaving its hop for another orbit: follow it there
            continue
        if _no_orbit_ahead(residuals, (cap - spent) / win.periods) and not _rising(gaps):
            break
    return win, before, _still_leaving(win, gaps)


#: windows of steady growth (:func:`~.window.grows_steadily`) that tell a hop leaving its orbit
#: from a quasi-periodic wobble
LEAVING_WINDOWS = 4


def _hop_gap(win: Window, scale: np.ndarray) -> float:
    """The distance of ``win`` from repeating after its hop period (:func:`~.window.lag_change`
    of its scaled states; NaN without a synchronous hop)."""
    return lag_change(np.asarray(win.samples)[:, 1:4] / scale, win.sync.hop_period)


def _rising(gaps: list[float]) -> bool:
    """Whether every window so far, fewer than :func:`_still_leaving` needs, moved further from
    repeating after the hop period than the one before (by :data:`~.window.GROWTH_RATIO`): the
    orbit search waits for the windows that tell."""
    g = np.asarray(gaps)
    return bool(1 < g.size <= LEAVING_WINDOWS and np.isfinite(g).all() and (g > 0.0).all()
                and (g[1:] > GROWTH_RATIO * g[:-1]).all())


def _still_leaving(win: Window, gaps: list[float]) -> bool:
    """Whether a window with contact loss and no orbit ends the orbit search leaving its hop: its
    distance from repeating after the hop period (:func:`_hop_gap`, one per window) grew steadily
    over the last :data:`LEAVING_WINDOWS` windows (:func:`~.window.grows_steadily`: an orbit
    losing its stability, as at a period doubling)."""
    return (win.contact_lost and win.orbit_period == 0
            and grows_steadily(gaps, LEAVING_WINDOWS))


#: window-to-window ratios of the distance from repeating within this factor of 1 (twice in a
#: row): the motion neither approaches an orbit nor leaves one (a quasi-periodic hop, the undamped
#: contact oscillation beating against it: mmd m* 0.178, A* 2.51 stays 0.02 from repeating over
#: 1900 periods)
FLAT_RATIO = 1.25


def _no_orbit_ahead(residuals: list[float], windows_left: float) -> bool:
    """Whether the windows left cannot reach a periodic orbit: the distance from repeating stays
    flat (within :data:`FLAT_RATIO` over the last two windows), or falls so slowly that at its
    last rate it would reach :data:`~.window.PERIODIC_TOL` only after more than three times the
    windows left. A growing distance goes on (an alternation still unfolding can settle on an
    orbit of another period)."""
    if len(residuals) < 3 or not all(math.isfinite(r) and r > 0.0 for r in residuals[-3:]):
        return False
    q1, q2 = residuals[-2] / residuals[-3], residuals[-1] / residuals[-2]
    if all(1.0 / FLAT_RATIO <= q <= FLAT_RATIO for q in (q1, q2)):
        return True
    if q2 >= 1.0:
        return False
    needed = math.log(PERIODIC_TOL / residuals[-1]) / math.log(q2)
    return needed > 3.0 * windows_left
