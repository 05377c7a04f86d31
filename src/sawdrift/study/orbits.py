"""The period of a motion from its stroboscopic samples, with slow transients told apart.

:func:`sawdrift.dynamics.window.orbit_period` finds the smallest p after which the state at
integer t* repeats to round-off. Near a period doubling that test alone misleads: the period-1
orbit's multiplier lambda is close to -1, so a transient alternates and decays like |lambda|^n,
and s_(n+2) - s_n = (1 + lambda)(s_(n+1) - s_n) + ... falls below the tolerance long before the
alternation itself has gone. Such a motion is period 1 (it converges to the period-1 orbit), not
period 2.

:func:`classify` therefore also measures how the q-step differences D_n = s_(n+q) - s_n decay
(their block maxima B_j over q periods). Close to a period doubling the amplitude of the
alternation follows the normal form of the flip bifurcation (Guckenheimer and Holmes 1983,
section 3.5; Kuznetsov 2004, section 4.4): B_(j+1) / B_j - 1 = eps - g B_j^2, with
eps = |lambda| - 1. A least-squares fit of that line gives eps: eps < 0 means the alternation
dies out (the q-orbit is stable, |lambda| < 1), eps > 0 that it grows or settles at the
amplitude sqrt(eps / g) of a 2q-orbit. Far from a bifurcation the fit reduces to the geometric
decay rate of a linear transient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..dynamics.window import PERIODIC_TOL, orbit_period

#: Longest period looked for (periods of the stroboscopic map).
LONGEST = 12

#: A difference below this (scaled state) is round-off: it carries no rate.
NOISE = 1e-11

#: Smallest total decay (ln of the amplitude's fall over the blocks fitted) that counts as a real
#: decay rather than round-off in a converged orbit.
SIGNIFICANT = 1e-3


@dataclass(frozen=True)
class Decay:
    """How the q-step differences of a run of samples evolve (see :func:`decay`).

    Attributes
    ----------
    q
        The step (periods).
    rate
        eps = |lambda| - 1 per q periods from the normal-form fit (NaN without data).
    multiplier
        lambda = +-(1 + eps), negative when successive differences alternate in sign.
    last
        The last block maximum B (scaled state).
    vanishes
        True if the differences die out (eps significantly below 0, or already round-off).
    """

    q: int
    rate: float
    multiplier: float
    last: float
    vanishes: bool


@dataclass(frozen=True)
class OrbitClass:
    """The period a motion has or converges to.

    Attributes
    ----------
    period
        p >= 1 of the periodic orbit the samples repeat on or converge to; 0 if none was found
        (chaotic, quasi-periodic, or a period above :data:`LONGEST`).
    exact
        True if the samples already repeat after p periods to ``PERIODIC_TOL``.
    multiplier
        Estimated multiplier of the slowest transient mode of the p-orbit (per p periods), from
        the decay of the differences; NaN when nothing decays any more (a converged orbit).
    remaining
        Periods the transient still needs to fall below ``PERIODIC_TOL`` at that multiplier
        (0 if exact, inf if it does not converge).
    amplitude, rate
        The last block maximum B of the decaying differences and its fitted rate eps per p
        periods (NaN when exact or not periodic): a run continued by n periods should show
        B exp(eps n / p), which :func:`sawdrift.study.branch.attractor` checks.
    """

    period: int
    exact: bool
    multiplier: float
    remaining: float
    amplitude: float = math.nan
    rate: float = math.nan


def _blocks(s: np.ndarray, q: int) -> np.ndarray:
    """Block maxima B_j of the q-step differences |s_(n+q) - s_n| over blocks of q periods."""
    d = np.abs(s[q:] - s[:-q]).max(axis=1)
    n = d.size // q
    return d[: n * q].reshape(n, q).max(axis=1) if n else np.zeros(0)


def decay(s: np.ndarray, q: int, skip: float = 0.25) -> Decay:
    """Fit the normal form B_(j+1) / B_j - 1 = eps - g B_j^2 to the q-step differences.

    Parameters
    ----------
    s
        Stroboscopic samples, one row per period, scaled to order one (``state_scale``).
    q
        The period whose transient is examined.
    skip
        Fraction of the blocks left out at the start (faster modes still decaying there).
    """
    b = _blocks(s, q)
    b = b[int(skip * b.size):]
    nan = Decay(q, math.nan, math.nan, float(b[-1]) if b.size else math.nan, False)
    if b.size < 4:
        return nan
    if b[-1] <= PERIODIC_TOL:
        return Decay(q, math.nan, math.nan, float(b[-1]), True)
    use = b > NOISE
    idx = np.nonzero(use[:-1] & use[1:])[0]
    if idx.size < 3:
        return nan
    x = b[idx] ** 2
    y = np.log(b[idx + 1] / b[idx])  # ln(1 + eps - g x) ~ eps - g x
    eps = float(y.mean())
    resid = y - eps
    spread = float(x.max() - x.min())
    if spread > 0.0 and idx.size >= 6:
        # least squares on centred x: the closed form stays well conditioned when the decay
        # rates span a narrow range of x (np.polyfit warns there)
        xc = x - x.mean()
        slope = float(np.dot(xc, y - y.mean()) / np.dot(xc, xc))
        intercept = float(y.mean() - slope * x.mean())
        # the normal form has g > 0 on either side; a positive slope is another mode's decay
        if slope < 0.0:
            eps = float(intercept)
            resid = y - (intercept + slope * x)
    # a decay must stand out of the scatter of the per-block rates (chaos scatters them by O(1))
    error = float(np.std(resid)) / math.sqrt(idx.size)
    d = s[q:] - s[:-q]
    sign = float(np.sign(np.sum(d[q:] * d[:-q]))) or 1.0
    total = float(np.log(b[idx[-1] + 1] / b[idx[0]]))
    vanishes = eps < -3.0 * error and total < -SIGNIFICANT
    mult = sign * math.exp(min(eps, 50.0))  # a runaway fit is no multiplier worth printing
    return Decay(q, eps, mult, float(b[-1]), vanishes)


def classify(samples: np.ndarray, longest: int = LONGEST) -> OrbitClass:
    """The period of the motion behind ``samples`` (scaled stroboscopic states, one per period).

    A period p found by :func:`~sawdrift.dynamics.window.orbit_period` is accepted unless the
    differences of a divisor q of p still decay (:func:`decay`): then the motion converges to
    the q-orbit and only looks p-periodic (the slow alternation near a period doubling). If no
    period repeats yet, the smallest q whose differences decay gives the period the motion
    converges to; else the period is 0.
    """
    s = np.asarray(samples, dtype=float)
    unit = np.ones(s.shape[1])
    p = orbit_period(np.column_stack([np.zeros(len(s)), s]), unit, longest=longest)
    candidates = [q for q in range(1, p) if p % q == 0] if p else list(range(1, longest + 1))
    for q in candidates:
        if s.shape[0] < 4 * q + 8:
            break
        dec = decay(s, q)
        if dec.vanishes:
            return OrbitClass(q, False, dec.multiplier, _remaining(dec), dec.last, dec.rate)
    if p:
        return OrbitClass(p, True, math.nan, 0.0)
    return OrbitClass(0, False, math.nan, math.inf)


def nearest(samples: np.ndarray, longest: int = LONGEST) -> float:
    """How far the samples are from repeating: the smallest last block maximum B over q <= longest.

    A motion on its way to a periodic orbit (a damped spiral, whose differences do not fall
    steadily enough for :func:`decay`) brings this down from window to window; a chaotic or
    quasi-periodic one does not.
    """
    s = np.asarray(samples, dtype=float)
    best = math.inf
    for q in range(1, longest + 1):
        b = _blocks(s, q)
        if b.size:
            best = min(best, float(b[-1]))
    return best


def _remaining(dec: Decay) -> float:
    """Periods until the last difference B decays to ``PERIODIC_TOL`` at the fitted rate."""
    if not dec.rate < 0.0 or dec.last <= PERIODIC_TOL:
        return 0.0
    return dec.q * math.log(dec.last / PERIODIC_TOL) / -dec.rate


def alternation_side(samples: np.ndarray, q: int) -> int | None:
    """Which side of a flip (q -> 2q) a run started near the q-orbit is on.

    Returns ``q`` if the alternation dies out (|lambda| < 1), ``2 q`` if it grows or settles at
    a non-zero amplitude, None if the samples do not tell yet.
    """
    s = np.asarray(samples, dtype=float)
    unit = np.ones(s.shape[1])
    p = orbit_period(np.column_stack([np.zeros(len(s)), s]), unit, longest=2 * q)
    dec = decay(s, q, skip=0.1)
    if p == q or dec.vanishes:
        return q
    if not math.isfinite(dec.rate):
        return 2 * q if p == 2 * q else None
    b = _blocks(s, q)
    total = float(np.log(max(b[-1], NOISE) / max(b[int(0.1 * b.size)], NOISE)))
    if dec.rate > 0.0 and (total > SIGNIFICANT or p == 2 * q):
        return 2 * q
    return None
