"""Lift-off synchrony: does a window's pattern of lift-offs repeat every k wave periods?

A motion that loses contact is *hopping* when its lift-offs repeat every k whole periods (the same
number n >= 1 of lift-offs in every block of k periods, each of them at a time in the block that
repeats within a circular standard deviation of 0.073 of a period: :data:`PHASE_COHERENCE`) and
it is not chaotic (:mod:`sawdrift.dynamics.lyapunov`); anything else that loses contact is *bouncing*
(:func:`sawdrift.result.regimes.classify` reads the hop period measured here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Minimum circular resultant length of the lift-off phases of a synchronous (hopping) motion
#: of period 1: 0.9 is a circular standard deviation sqrt(-2 ln 0.9) = 0.46 rad = 0.073 of the
#: period. In blocks of k periods the same spread in periods is 1/k of the block: the
#: resultant of the phases in the block must reach 0.9^(1/k^2).
PHASE_COHERENCE = 0.9

#: Rebounds shorter than this (in wave periods) that leave the surface within this time of a
#: landing are left out of the synchrony test: the micro-rebounds of an inelastic collapse are
#: part of their landing, and their number varies with rounding. A take-off from sustained
#: contact is a hop however short its flight (just above the onset Gz = 1 the point's flight
#: lasts ~sqrt(Gz - 1) of a period).
MIN_FLIGHT = 0.01

#: Largest hop period k (in wave periods) looked for.
MAX_HOP_PERIOD = 4


@dataclass(frozen=True)
class Synchrony:
    """Lift-off synchrony of a window (see :func:`synchrony`).

    Attributes
    ----------
    hop_period
        k, the number of wave periods after which the lift-off pattern repeats; 0 if none
        (k <= :data:`MAX_HOP_PERIOD`).
    liftoffs_per_hop
        n, lift-offs in each block of k periods.
    phase
        Wave phase t* mod 1 of the block's first lift-off (circular mean over the blocks, in
        [0, 1)); NaN if none.
    spread
        Circular standard deviation sqrt(-2 ln R) of those phases, in fractions of a period.
    coherence
        The smallest circular resultant length R over the n lift-off slots.
    phases
        Wave phase t* mod 1 of each of the n lift-offs of a block, in the order they occur
        (each a circular mean over the blocks): the take-off phases of the orbit.
    """

    hop_period: int
    liftoffs_per_hop: int
    phase: float
    spread: float
    coherence: float
    phases: tuple[float, ...] = ()


def _circular(phases: np.ndarray) -> tuple[float, float, float]:
    """(mean phase in [0, 1), resultant length R, circular std in fractions) of phases in [0, 1)."""
    z = np.exp(2j * math.pi * phases).mean()
    r = min(float(abs(z)), 1.0)
    mean = (math.atan2(z.imag, z.real) / (2 * math.pi)) % 1.0
    if r >= 1.0:
        spread = 0.0  # phases all equal: not the -0.0 of sqrt(-2 ln 1) = sqrt(-0.0)
    elif r > 0.0:
        spread = math.sqrt(-2.0 * math.log(r)) / (2 * math.pi)
    else:
        spread = math.inf
    return mean, r, spread


def orbit_pattern(t: np.ndarray, t_start: float, periods: int, p: int) -> Synchrony | None:
    """The hop of an exact periodic orbit of ``p`` periods, read from its last whole orbit.

    The stroboscopic state repeats after p periods (to round-off), so the lift-offs repeat too:
    hop period p, the lift-offs of the window's last p periods, their phases t* mod 1. The
    block before must hold as many lift-offs (a check against a lift-off that grazes a block
    boundary); None if it does not, if the window is shorter than p, or if no lift-off falls in
    the last orbit (an orbit that keeps contact).
    """
    end = t_start + periods
    if periods < p:
        return None
    last = t[(t >= end - p) & (t < end)]
    if last.size == 0:
        return None
    if periods >= 2 * p:
        before = t[(t >= end - 2 * p) & (t < end - p)]
        if before.size != last.size or np.max(np.abs((last - before) - p)) > 1e-6 * p:
            return None
    phases = tuple(float(v) for v in (last % 1.0))
    return Synchrony(p, int(last.size), phases[0], 0.0, 1.0, phases)


def synchrony(liftoff_times: np.ndarray, t_start: float, periods: int,
              orbit_period: int = 0) -> Synchrony:
    """Look for a lift-off pattern that repeats every k whole periods of the window.

    Parameters
    ----------
    liftoff_times
        t* of every lift-off in the window [t_start, t_start + periods).
    t_start
        Start of the window, at a whole period.
    periods
        Length of the window in wave periods.
    orbit_period
        p when the stroboscopic state repeats after p periods (0: not known to): the hop is
        then read from the orbit itself (:func:`orbit_pattern`), for any p, so a period-2 orbit
        whose two take-off phases lie close together is a hop of period 2 with both phases, not
        a period-1 hop at their mean; otherwise k = 1 .. :data:`MAX_HOP_PERIOD` are tried.
    """
    t = np.sort(np.asarray(liftoff_times, dtype=float))
    none = Synchrony(0, 0, math.nan, math.nan, 0.0)
    if t.size == 0:
        return none
    if orbit_period >= 1:
        exact = orbit_pattern(t, t_start, periods, orbit_period)
        if exact is not None:
            return exact
    rel = t - t_start
    first = [orbit_period] if 1 <= orbit_period <= MAX_HOP_PERIOD else []
    for k in first + [k for k in range(1, MAX_HOP_PERIOD + 1) if k not in first]:
        # blocks of k periods start in the middle of the widest gap between lift-off phases,
        # so a lift-off that jitters about a block boundary is not split between two blocks
        ps = np.unique((rel / k) % 1.0)
        gaps = np.diff(np.concatenate([ps, [ps[0] + 1.0]]))
        g = int(np.argmax(gaps))
        origin = ((ps[g] + 0.5 * gaps[g]) % 1.0) * k
        blocks = int(math.floor((periods - origin) / k))
        if blocks < 3:
            continue
        block = np.floor((rel - origin) / k).astype(int)
        inside = (block >= 0) & (block < blocks)
        counts = np.bincount(block[inside], minlength=blocks)
        n = int(counts[0])
        if n == 0 or not np.all(counts == n):
            continue
        phases = ((rel[inside] - origin) / k) % 1.0
        slots = phases.reshape(blocks, n)
        stats = [_circular(slots[:, j]) for j in range(n)]
        coherence = min(s[1] for s in stats)
        # the slots' spread is judged in periods, not in fractions of the block: in blocks of k
        # periods a jitter counts k times less, and a period-1 hop whose take-offs wandered
        # between phases 0.53 and 0.76 (resultant 0.890) passed as a hop of 2 with two equal
        # phases (mmd m* = 1.15, A* = 4.7, mu = 0.3): the resultant must reach 0.9^(1/k^2)
        if coherence >= PHASE_COHERENCE ** (1.0 / (k * k)):
            wave = t[inside].reshape(blocks, n) % 1.0
            phases = tuple(_circular(wave[:, j])[0] for j in range(n))
            return Synchrony(k, n, phases[0], k * stats[0][2], coherence, phases)
    return none
