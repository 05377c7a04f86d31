"""Motion regimes of a particle on a Rayleigh-wave substrate (paper section 5, Fig. 2-3).

The classification reads only the evidence of a run's measurement window (after the transient;
every piece of evidence comes from that one window), never the runner's internals:

* contact lost in the window:

  - ``hopping`` - synchronous motion of period k: the window's lift-offs repeat every k wave
    periods (the same number n >= 1 of lift-offs in every block of k periods), each of the n
    lift-offs of a block at a phase that repeats (circular resultant length of its phases
    mod k at least :data:`PHASE_COHERENCE`), and the motion is not chaotic;
  - ``bouncing`` - anything else: irregular, quasi-periodic or chaotic lift-offs;

* permanent contact, by the drift ratio V = <x*'> / (2 pi r A*) (scaled by the horizontal surface
  speed amplitude) and the fraction of the window in gross slip:

  - ``drift_with`` (V > tol, the wave's direction, +x) or ``drift_against`` (V < -tol);
  - ``oscillating_slip`` - |V| <= tol, but the contact slides as a whole part of the time
    (the material point just above its stick bound: the forward and backward slips cancel);
  - ``stick`` - |V| <= tol and no gross slip in the window (weak oscillation; a compliant contact
    may still slip partially, in its annulus).

Chaos is decided by a finite-time Lyapunov estimate (:func:`lyapunov_estimate`): two trajectories
started 1e-10 apart (scaled state) separate by a factor of at least :data:`CHAOS_GROWTH` within
the window only if they diverge exponentially; a regular (periodic or quasi-periodic) motion
separates at most polynomially, by far less than that over the windows used.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

REGIMES = ("stick", "oscillating_slip", "drift_with", "drift_against", "hopping", "bouncing")

#: Regimes in which contact is lost in the measurement window.
CONTACT_LOST = ("hopping", "bouncing")

#: Minimum circular resultant length of the lift-off phases of a synchronous (hopping) motion.
#: 0.9 is a circular standard deviation sqrt(-2 ln 0.9) = 0.46 rad = 0.073 of the period.
PHASE_COHERENCE = 0.9

#: Flights shorter than this (in wave periods) are left out of the synchrony test: the micro-
#: rebounds of an inelastic collapse after a landing are part of that landing, and their number
#: varies with rounding.
MIN_FLIGHT = 0.01

#: Largest hop period k (in wave periods) looked for.
MAX_HOP_PERIOD = 4

#: Initial separation of the twin trajectory (scaled state units) and the growth factor within
#: the window that counts as exponential divergence (chaos).
LYAPUNOV_D0 = 1e-10
CHAOS_GROWTH = 1e7


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
        Wave phase t* mod 1 of the block's first lift-off (circular mean, in [0, 1)); NaN if none.
    spread
        Circular standard deviation sqrt(-2 ln R) of those phases, in fractions of the block.
    coherence
        The smallest circular resultant length R over the n lift-off slots.
    """

    hop_period: int
    liftoffs_per_hop: int
    phase: float
    spread: float
    coherence: float


def _circular(phases: np.ndarray) -> tuple[float, float, float]:
    """(mean phase in [0, 1), resultant length R, circular std in fractions) of phases in [0, 1)."""
    z = np.exp(2j * math.pi * phases).mean()
    r = min(float(abs(z)), 1.0)
    mean = (math.atan2(z.imag, z.real) / (2 * math.pi)) % 1.0
    spread = math.sqrt(-2.0 * math.log(r)) / (2 * math.pi) if r > 0 else math.inf
    return mean, r, spread


def synchrony(liftoff_times: np.ndarray, t_start: float, periods: int) -> Synchrony:
    """Look for a lift-off pattern that repeats every k whole periods of the window.

    Parameters
    ----------
    liftoff_times
        t* of every lift-off in the window [t_start, t_start + periods).
    t_start
        Start of the window, at a whole period.
    periods
        Length of the window in wave periods.
    """
    t = np.sort(np.asarray(liftoff_times, dtype=float))
    none = Synchrony(0, 0, math.nan, math.nan, 0.0)
    if t.size == 0:
        return none
    rel = t - t_start
    for k in range(1, MAX_HOP_PERIOD + 1):
        # blocks of k periods start in the middle of the widest gap between lift-off phases,
        # so a lift-off that jitters about a block boundary is not split between two blocks
        ps = np.unique((rel / k) % 1.0)
        gaps = np.diff(np.concatenate([ps, [ps[0] + 1.0]]))
        g = int(np.argmax(gaps))
        origin = ((ps[g] + 0.5 * gaps[g]) % 1.0) * k
        blocks = int(math.floor((periods - origin) / k))
        if blocks < 3:
            break
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
        if coherence >= PHASE_COHERENCE:
            wave_phase = _circular(t[inside].reshape(blocks, n)[:, 0] % 1.0)[0]
            return Synchrony(k, n, wave_phase, stats[0][2], coherence)
    return none


def lyapunov_estimate(distances: np.ndarray, d0: float = LYAPUNOV_D0) -> tuple[float, bool]:
    """Finite-time Lyapunov exponent per wave period from a twin trajectory's separation.

    ``distances[j]`` is the scaled separation after j + 1 periods. The exponent is
    ln(d/d0)/t at the first period where d/d0 >= :data:`CHAOS_GROWTH` (then the motion is
    chaotic), else ln(d_end/d0)/t_end. Returns (exponent, chaotic).
    """
    d = np.asarray(distances, dtype=float)
    if d.size == 0:
        return math.nan, False
    growth = d / d0
    over = np.nonzero(growth >= CHAOS_GROWTH)[0]
    j = int(over[0]) if over.size else d.size - 1
    if growth[j] <= 0.0:
        return -math.inf, False  # a perfectly inelastic landing erased the perturbation
    return math.log(growth[j]) / (j + 1), bool(over.size)


def classify(
    contact_lost: bool,
    drift_ratio: float,
    tol: float,
    *,
    gross_slip_fraction: float = 0.0,
    hop_period: int = 0,
) -> str:
    """Regime name from the window's evidence (see module docstring).

    Parameters
    ----------
    contact_lost
        True if a* <= 0 at some step of the measurement window.
    drift_ratio
        Mean x*' over the window divided by 2 pi r A*.
    tol
        |drift_ratio| at or below this is no steady drift.
    gross_slip_fraction
        Fraction of the window in gross slip.
    hop_period
        k of a synchronous, non-chaotic lift-off pattern (0: none), see :func:`synchrony`.
    """
    if contact_lost:
        return "hopping" if hop_period >= 1 else "bouncing"
    if abs(drift_ratio) > tol:
        return "drift_with" if drift_ratio > 0.0 else "drift_against"
    if gross_slip_fraction > 0.0:
        return "oscillating_slip"
    return "stick"
