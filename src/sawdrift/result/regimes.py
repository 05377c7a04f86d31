"""Motion regimes of a particle on a Rayleigh-wave substrate (paper section 5, Fig. 2-3).

The classification reads only summary evidence from a run, never the runner's internals:

* contact lost at some step after the ramp: ``hopping`` when the motion is periodic hopping
  (one lift-off per period, stroboscopic map converged: ``periodicity <= periodic_tol``), which
  can carry a drift (see the drift ratio), else irregular ``bouncing``;
* otherwise by the drift ratio V = <x*'> / (2 pi r A*) against a tolerance ``tol``:
  ``stick`` (|V| <= tol: weak oscillation, no steady drift), ``drift_with`` (V > tol, the wave's
  direction, +x) or ``drift_against`` (V < -tol).
"""

from __future__ import annotations

import math

REGIMES = ("stick", "drift_with", "drift_against", "hopping", "bouncing")

#: Regimes in which contact is lost after the ramp.
CONTACT_LOST = ("hopping", "bouncing")


def classify(
    contact_lost: bool,
    drift_ratio: float,
    tol: float,
    liftoffs_per_period: float = math.nan,
    periodicity: float = math.inf,
    periodic_tol: float = 1e-3,
) -> str:
    """Regime name from the evidence (see module docstring).

    Parameters
    ----------
    contact_lost
        True if a* <= 0 at some step after the ramp.
    drift_ratio
        Mean x*' over the measurement window divided by 2 pi r A*.
    tol
        |drift_ratio| at or below this is ``stick``.
    liftoffs_per_period
        Lift-offs per period in the measurement window.
    periodicity
        Largest change of the stroboscopic state (x*', y*, y*' sampled once per period, scaled)
        between consecutive periods of the measurement window.
    periodic_tol
        ``periodicity`` at or below this (with one lift-off per period) is periodic hopping.
    """
    if contact_lost:
        if abs(liftoffs_per_period - 1.0) < 1e-9 and periodicity <= periodic_tol:
            return "hopping"
        return "bouncing"
    if not abs(drift_ratio) > tol:
        return "stick"
    return "drift_with" if drift_ratio > 0.0 else "drift_against"
