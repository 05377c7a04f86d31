"""The drift of an irregular heavy bouncer from the weighted mean of its friction (:mod:`.imposed`).

An irregular heavy bouncer's vertical motion is quasi-periodic (its largest Lyapunov exponent
within 1e-2 of zero: the wave and its own undamped free oscillation) and does not depend on the
horizontal one, so the friction along it at an imposed speed is a quasi-periodic signal. Its
weighted Birkhoff average (:mod:`.birkhoff`) converges far faster than the plain mean whose
batch-means error the drift otherwise carries (5e-3 to 1e-2 in drift ratio over a 500-period
record). Two steps, where the record is quasi-periodic:

1. the zero of the weighted mean force at the imposed speed alone, by secants from the plain
   mean's zero;
2. the same with the horizontal fast motion the friction at that zero gives the particle at full
   inertia (:meth:`~.imposed._Record.add_fast_motion`), the next order of the separation of
   motions: the imposed speed alone put the drift 2e-4 to 5e-4 (relative) from converged brute
   force on 9 such cells at m* = 5.5 to 22 (mmd, jaeger, hertz_mindlin_dem; a cone, a
   retrograde orbit, mu = 0.5), where its error said 1e-6 to 3e-5.

The error reported is the weighted mean's own (:func:`~.birkhoff.quasi_periodic_error`) plus
the size of the second step's correction, which bounds what the next order leaves, and at
least :data:`RELATIVE_FLOOR` of the drift: on the 11 cells of the stored audit that take this
route and whose brute force converged, the drift is within 1.9e-6 to 2.6e-4 (relative) of it,
at most 0.41 of the error; on 177 cells of a review, within 2.4e-4, at most 1.6 errors.
Iterating the second step does not converge where mu / m* is large (jaeger, mu = 0.5,
m* = 5.5 moved by 1.6e-3 on its second pass, away from brute force).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .birkhoff import weighted_estimate

if TYPE_CHECKING:
    from .imposed import _Pushes

#: secant steps at most on the weighted mean force
WEIGHTED_STEPS = 6

#: the least error of the drift (relative): what the route leaves beyond its own estimate.
#: On 177 irregular heavy bouncers (mmd, jaeger, hertz_mindlin_dem; m* 5.7 to 71, A* 2.7 to 9.4,
#: mu 0.1 to 0.5; loads, a cone, a retrograde orbit) against converged brute force, the drift
#: was within 2.4e-4 (relative; median 3.3e-5, below it in 85 % of them), growing with mu/m*;
#: two had errors of 3e-6 and 9e-6 for differences of 5e-5 (17 and 6 errors). With this floor
#: every one is within 1.6 errors
RELATIVE_FLOOR = 1e-4

#: the weighted zero is found to this share of itself (a hundredth of :data:`RELATIVE_FLOOR`,
#: the least error it is reported with), or to :data:`WEIGHTED_XTOL` in drift ratio where that
#: is looser: on the 79 irregular heavy bouncers of the default 41 x 41 mmd sweep the drifts
#: moved by at most 2.6e-9 (relative) from a tolerance of 1e-7 in drift ratio, with one secant
#: step fewer on most
WEIGHTED_RTOL = 1e-6

#: the weighted zero's tolerance in drift ratio for drifts near zero (:data:`WEIGHTED_RTOL`)
WEIGHTED_XTOL = 1e-8


def weighted_zero(push: _Pushes, root: float, slope: float, se_force: float
                  ) -> tuple[float, float] | None:
    """(drift ratio, its error) of an irregular heavy bouncer from the weighted mean of its
    friction (module docstring), where its record is quasi-periodic at the plain mean's zero
    ``root`` (``se_force``: the batch-means error of the plain mean force there; ``slope``:
    d(-<T*>)/d(drift ratio) there); None for a chaotic record, or where the secants do not
    converge (the plain mean and its batch-means error stand)."""
    rec, speed = push.rec, push.speed
    if not slope < 0.0:
        return None
    rec.clear_fast_motion()
    bare = _secants(push, root, slope, se_force)
    if bare is None:
        return None
    rec.add_fast_motion(bare[0] * speed)
    full = _secants(push, bare[0], slope, se_force)
    # the record as it was: its other means (push, _Pushes.known) are at the imposed speed alone
    rec.clear_fast_motion()
    if full is None:
        return None
    return full[0], max(full[1] + abs(full[0] - bare[0]), RELATIVE_FLOOR * abs(full[0]))


def _secants(push: _Pushes, root: float, slope: float, se_force: float
             ) -> tuple[float, float] | None:
    """The zero of the weighted mean force along the record as it is driven now, by secants from
    ``root``, and the weighted mean's error there in drift ratio; None where the record is not
    quasi-periodic or the secants do not converge within :data:`WEIGHTED_STEPS`."""
    rec, speed = push.rec, push.speed

    def force(d: float) -> tuple[float, float | None]:
        mean, error = weighted_estimate(rec.friction(d * speed), se_force)
        return -mean + rec.offset, error

    f0, error = force(root)
    if error is None:
        return None
    r0, r1 = root, root - f0 / slope
    for _ in range(WEIGHTED_STEPS):
        f1, error = force(r1)
        if error is None:
            return None
        if abs(r1 - r0) <= max(WEIGHTED_RTOL * abs(r1), WEIGHTED_XTOL):
            return r1, error / abs(slope)
        if f1 == f0:
            return None
        r0, f0, r1 = r1, f1, r1 - f1 * (r1 - r0) / (f1 - f0)
    return None
