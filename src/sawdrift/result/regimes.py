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

Chaos is decided by the largest Lyapunov exponent (:func:`lyapunov_statistics`): a twin of the
run, displaced by 1e-8 (scaled state) and renormalized every period (Benettin et al. 1980), gives
one log-stretching per period; their mean is the exponent and the spread of its batch means its
uncertainty. The motion is chaotic when the exponent is positive by more than
:data:`CHAOS_SIGMAS` uncertainties and above :data:`CHAOS_EXPONENT`: a regular motion's separation
grows at most like a power of t, so its per-period stretchings decay towards 0 and their mean
stays below that floor.
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

#: Rebounds shorter than this (in wave periods) that leave the surface within this time of a
#: landing are left out of the synchrony test: the micro-rebounds of an inelastic collapse are
#: part of their landing, and their number varies with rounding. A take-off from sustained
#: contact is a hop however short its flight (just above the onset Gz = 1 the point's flight
#: lasts ~sqrt(Gz - 1) of a period).
MIN_FLIGHT = 0.01

#: Largest hop period k (in wave periods) looked for.
MAX_HOP_PERIOD = 4

#: Initial (and renormalized) separation of the twin trajectory, in scaled state units.
LYAPUNOV_D0 = 1e-8

#: Periods of the Lyapunov estimate left out at its start (the separation aligning itself with
#: the most unstable direction: its growth then is a bias, not the exponent).
ALIGN_PERIODS = 8

#: Fewest periods a Lyapunov estimate averages over (longer windows use their own length).
LYAPUNOV_PERIODS = 64

#: Most periods a Lyapunov estimate averages over: a settle window of a heavy particle can last
#: thousands of periods, and 256 stretchings already give 8 batches of 32.
LYAPUNOV_MAX_PERIODS = 256

#: Exponent (per period) below which a motion is not called chaotic, whatever the statistics
#: (the chaotic motions of the diagrams here have 0.1 to 1). A regular motion whose separation
#: grows linearly (a shear along a neutral direction) has renormalized stretchings
#: ln((1 + c (j + 1)) / (1 + c j)); after ALIGN_PERIODS their mean over LYAPUNOV_PERIODS is at
#: most ln(9) / 64 = 0.034 for every c, below this.
CHAOS_EXPONENT = 0.05

#: How many of its own uncertainties a positive exponent must stand above zero to be chaos.
CHAOS_SIGMAS = 3.0

#: Batches of the per-period stretchings whose means give the exponent's uncertainty.
LYAPUNOV_BATCHES = 8


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
        Circular standard deviation sqrt(-2 ln R) of those phases, in fractions of the block.
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
    spread = math.sqrt(-2.0 * math.log(r)) / (2 * math.pi) if r > 0 else math.inf
    return mean, r, spread


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
        p when the stroboscopic state repeats after p periods (0: not known to): k = p is tried
        first, so a period-2 orbit whose two take-off phases lie close together is a hop of
        period 2 with both phases, not a period-1 hop at their mean.
    """
    t = np.sort(np.asarray(liftoff_times, dtype=float))
    none = Synchrony(0, 0, math.nan, math.nan, 0.0)
    if t.size == 0:
        return none
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
        if coherence >= PHASE_COHERENCE:
            wave = t[inside].reshape(blocks, n) % 1.0
            phases = tuple(_circular(wave[:, j])[0] for j in range(n))
            return Synchrony(k, n, phases[0], stats[0][2], coherence, phases)
    return none


def lyapunov_statistics(logs: np.ndarray) -> tuple[float, float]:
    """Largest Lyapunov exponent per period and its uncertainty, from per-period stretchings.

    ``logs[j]`` is ln(d_j / d0), the log of the separation a twin displaced by d0 reached after
    period j (renormalized every period: Benettin, Galgani, Giorgilli and Strelcyn 1980,
    Meccanica 15, 9). The exponent is their mean. Successive stretchings are correlated, so the
    uncertainty is the standard error of :data:`LYAPUNOV_BATCHES` consecutive batch means (the
    method of batch means). -inf when a stretching is -inf (a perfectly inelastic landing or a
    sticking phase erased the separation).
    """
    x = np.asarray(logs, dtype=float)
    if x.size == 0:
        return math.nan, math.nan
    if np.isneginf(x).any():
        return -math.inf, 0.0
    lam = float(x.mean())
    nb = min(LYAPUNOV_BATCHES, x.size)
    if nb < 2:
        return lam, math.inf
    means = np.array([b.mean() for b in np.array_split(x, nb)])
    return lam, float(means.std(ddof=1)) / math.sqrt(nb)


def is_chaotic(exponent: float, uncertainty: float) -> bool:
    """A positive exponent above :data:`CHAOS_SIGMAS` of its own uncertainty and above
    :data:`CHAOS_EXPONENT` (see :func:`lyapunov_statistics`)."""
    return bool(exponent > CHAOS_EXPONENT and exponent > CHAOS_SIGMAS * uncertainty)


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
