"""Motion regimes of a particle on a Rayleigh-wave substrate (paper section 5, Fig. 2-3).

The classification reads only summary evidence from a run, never the runner's internals:

* ``bouncing``: contact was lost at some step after the ramp;
* otherwise by the drift ratio V = <x*'> / (2 pi r A*) against a tolerance ``tol``:
  ``stick`` (|V| <= tol: weak oscillation, no steady drift), ``drift_with`` (V > tol, the wave's
  direction, +x) or ``drift_against`` (V < -tol).
"""

from __future__ import annotations

REGIMES = ("stick", "drift_with", "drift_against", "bouncing")


def classify(contact_lost: bool, drift_ratio: float, tol: float) -> str:
    """Regime name from the evidence (see module docstring)."""
    if contact_lost:
        return "bouncing"
    if not abs(drift_ratio) > tol:
        return "stick"
    return "drift_with" if drift_ratio > 0.0 else "drift_against"
