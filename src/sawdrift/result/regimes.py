"""Motion regimes of a particle on a Rayleigh-wave substrate (paper section 5, Fig. 2-3).

The classification reads only the evidence of a run's measurement window (after the transient;
every piece of evidence comes from that one window), never the runner's internals:

* contact lost in the window:

  - ``hopping`` - synchronous motion of period k: the window's lift-offs repeat every k wave
    periods (the same number n >= 1 of lift-offs in every block of k periods), each of the n
    lift-offs of a block at a phase that repeats (circular resultant length of its phases
    mod k at least :data:`~sawdrift.dynamics.synchrony.PHASE_COHERENCE`), and the motion is not
    chaotic;
  - ``bouncing`` - anything else: irregular, quasi-periodic or chaotic lift-offs;

* no steady state (checked first, :func:`outcome`):

  - ``runaway`` - the mean horizontal speed keeps growing: a tangential load above the largest
    mean friction mu <N*> = mu (the period-averaged normal force is the weight), or, for a
    sphere free to turn, above its rolling resistance mu_r (any load without it: the load has
    no moment about the centre, so only a rolling torque can balance the friction that would
    hold it), or, under a load, a window whose mean speed exceeds 1.5 times the largest surface
    speed and still grows in its own direction;
  - ``ejected`` - out of contact through the whole window (no lift-off and no landing in it),
    and in free flight it cannot touch the surface again within as many periods as the run has
    lasted (a default run: or within ``numerics.mean_periods``, the budget of a long-time mean):
    thrown off, or, on a real device, removed. A flight that merely spans the window is
    ``bouncing``; a default run follows a particle that lands within that budget over at least
    16 of its flights and reports the long-time mean of its bounces (a rigid point at m* = 2,
    A* = 8.7, in the air 99.97 % of the time, lands about every 190 periods);

* permanent contact, by the drift ratio V = <x*'> / (2 pi r A*) (scaled by the horizontal surface
  speed amplitude) and the fraction of the window in gross slip:

  - ``drift_with`` (V > tol, the wave's direction, +x) or ``drift_against`` (V < -tol);
  - ``oscillating_slip`` - |V| <= tol, but the contact slides as a whole part of the time
    (the material point just above its stick bound: the forward and backward slips cancel);
  - ``stick`` - |V| <= tol and no gross slip in the window (weak oscillation; a compliant contact
    may still slip partially, in its annulus).

A drift in permanent contact with no gross slip at all in the window is **creep** (:func:`creep`):
the contact never slides as a whole, and the drift comes from partial slip in its annulus alone.
It is a flag beside the regime, not a regime: the cell is still ``drift_with`` or
``drift_against``. Creep is where contact laws differ most (an incremental spring that keeps its
tangential force when the contact shrinks creeps where the exact memory law sticks), so tables and
figures mark it.

The evidence is measured by the dynamics layer, which integrates the window: the lift-off
synchrony by :mod:`sawdrift.dynamics.synchrony` (which lift-offs count, how coherent their phases
must be), chaos by the largest Lyapunov exponent of :mod:`sawdrift.dynamics.lyapunov` (a chaotic
motion has no hop period). This module only names the regime from those measurements.
"""

from __future__ import annotations

from ..errors import SceneError

REGIMES = ("stick", "oscillating_slip", "drift_with", "drift_against", "hopping", "bouncing",
           "runaway", "ejected")

#: what a table's ``regime`` column may hold: a regime; "impact" or "prescribed" for a run of
#: those drives (no drift to name, sawdrift.result.runner); "error" for a run that failed
TABLE_REGIMES = (*REGIMES, "impact", "prescribed", "error")


def check_table_regimes(values, table: str, advice: str) -> None:
    """A one-line SceneError naming the first value of a table's ``regime`` column (``values``;
    missing values are skipped) that :data:`TABLE_REGIMES` does not hold, then ``advice``: a
    table written by hand or by another program, whose cell was drawn as missing (compare
    agreed on "nan%"), or resumed and written again. The one check of the reports and of a
    resumed sweep."""
    odd = sorted({str(r) for r in values if isinstance(r, str)} - set(TABLE_REGIMES))
    if odd:
        raise SceneError(f"table {table!r} holds regime {odd[0]!r}, which no run gives (allowed: "
                         f"{', '.join(TABLE_REGIMES)}): {advice}")


#: Outcomes without a steady drift: the mean speed keeps growing (``runaway``), or the particle
#: is out of contact through the whole measuring window (``ejected``). Neither has a drift speed
#: to report; see :func:`outcome`.
NO_STEADY_STATE = ("runaway", "ejected")

#: Regimes in which contact is lost in the measurement window.
CONTACT_LOST = ("hopping", "bouncing", "ejected")

#: Regimes of a steady drift in permanent contact.
DRIFTING = ("drift_with", "drift_against")


def creep(regime: str, gross_slip_fraction: float) -> bool:
    """True for a drift in permanent contact without gross slip (see the module docstring).

    Parameters
    ----------
    regime
        The regime named by :func:`classify`.
    gross_slip_fraction
        Fraction of the measuring window in gross slip; NaN (not measured) is not creep.
    """
    return bool(regime in DRIFTING and gross_slip_fraction == 0.0)


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
        k of a synchronous, non-chaotic lift-off pattern (0: none), see
        :func:`~sawdrift.dynamics.synchrony.synchrony`.
    """
    if contact_lost:
        return "hopping" if hop_period >= 1 else "bouncing"
    if abs(drift_ratio) > tol:
        return "drift_with" if drift_ratio > 0.0 else "drift_against"
    if gross_slip_fraction > 0.0:
        return "oscillating_slip"
    return "stick"


def outcome(load: float, mu: float, friction: bool, air_drag: float, flight: bool,
            return_time: float, elapsed: float, drift: float, acceleration: float,
            surface_speed: float) -> str:
    """``"runaway"``, ``"ejected"`` or ``""`` (a steady state may exist): see the module docstring.

    Parameters
    ----------
    load, mu, friction, air_drag
        The scene's tangential load (in M g), friction coefficient, whether friction is on, and
        the linear air drag (which always bounds the speed).
    flight
        The whole window was spent out of contact, with no lift-off in it, and the run did not
        follow the particle to its landing for a long-time mean of its bounces.
    return_time
        Periods until the particle, in free flight from the window's end, can touch the surface
        again (0: it can now), :func:`~sawdrift.dynamics.window.ballistic_return`.
    elapsed
        Periods run so far: a flight that outlasts it again leaves the run nothing to measure.
    drift, acceleration
        The window's mean horizontal speed and its mean acceleration (per period squared).
    surface_speed
        The largest horizontal surface speed (2 pi r A* for the wave), 0 without horizontal motion.
    """
    # the dynamics layer (numba) stays out of this module's import: it is read by light tools
    from ..dynamics.steady import load_runs_away

    if load_runs_away(load, mu, friction, air_drag):
        # the mean friction is at most mu times the weight, in flights or not: a particle
        # thrown into a flight longer than the run lands again and runs on (a rigid point at
        # m* = 10, A* = 3.16, L = 0.2 was called ejected after a 40-period run)
        return "runaway"
    if flight and return_time > elapsed:
        return "ejected"
    if air_drag > 0.0:
        return ""
    # measured: only under a load, the one source of a lasting push (a light particle pumped
    # into long flights by an undamped contact can move faster than the surface for a while,
    # its fitted acceleration is noise: measured on mmd at m* 0.01-0.1, A* 0.6-10)
    relative = abs(drift) - surface_speed
    if (load != 0.0 and surface_speed > 0.0 and relative > 0.5 * surface_speed
            and drift * acceleration > 0.0
            and abs(acceleration) * elapsed > GROWTH * surface_speed):
        return "runaway"
    return ""


#: share of the surface speed the mean speed must have gained at the window's acceleration over
#: the run's length for a fast window under a load to be a runaway: a sphere rolling steadily at
#: 1.7 times the surface speed, held by its rolling resistance, has a fitted acceleration of
#: 3e-6 per period squared (noise), and was called a runaway (`outcome`)
GROWTH = 0.1
