"""Brent's bracketed root finder, without importing :mod:`scipy.optimize`.

The steady-drift routes (:mod:`.separated`, :mod:`.torus`,
:mod:`.imposed`) find zeros of period-averaged forces with Brent's method.
Importing ``scipy.optimize`` for it costs 0.4 s per process (measured on the 2-core machine
of the benchmarks), paid by every worker of a sweep and by every single ``sawdrift run`` of a
heavy particle. :func:`brentq` is the same algorithm as ``scipy.optimize.brentq`` (Brent 1973,
"Algorithms for Minimization without Derivatives", ch. 4, in the form of SciPy's ``brentq.c``:
inverse quadratic interpolation or secant steps, bisection when they do not shrink the bracket
fast enough), step for step, so it returns the same root to the last bit
(``tests/test_roots.py`` checks that against SciPy).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

__all__ = ["brentq", "first_passed"]

#: SciPy's lower bound on the relative tolerance: 4 machine epsilons
_RTOL_MIN = 4.0 * 2.220446049250313e-16


def brentq(f: Callable[[float], float], a: float, b: float, xtol: float = 2e-12,
           rtol: float = _RTOL_MIN, maxiter: int = 100, fa: float | None = None,
           fb: float | None = None) -> float:
    """A root of ``f`` in [a, b], where f(a) and f(b) have opposite signs (Brent's method).

    Parameters and errors as ``scipy.optimize.brentq``: converged when half the bracket is
    below (xtol + rtol |x|) / 2; ValueError for a bracket without a sign change, a
    non-positive ``xtol``, an ``rtol`` below 4 machine epsilons or a NaN value of ``f``;
    RuntimeError after ``maxiter`` iterations. ``fa``, ``fb``: f(a) and f(b) where the caller
    has them already (the bracket search computed them), so that they are not evaluated again:
    each evaluation of a period-averaged force integrates the fast motion.
    """
    if not xtol > 0.0:
        raise ValueError(f"xtol too small ({xtol:g} <= 0)")
    if rtol < _RTOL_MIN:
        raise ValueError(f"rtol too small ({rtol:g} < {_RTOL_MIN:g})")

    def value(x: float) -> float:
        fx = float(f(x))
        if math.isnan(fx):
            raise ValueError(f"The function value at x={x:f} is NaN; solver cannot continue.")
        return fx

    xpre, xcur = float(a), float(b)
    fpre = value(xpre) if fa is None else float(fa)
    fcur = value(xcur) if fb is None else float(fb)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise ValueError("f(a) and f(b) must have different signs")
    return _iterate(value, xpre, fpre, xcur, fcur, xtol, rtol, maxiter)


def _iterate(value: Callable[[float], float], xpre: float, fpre: float, xcur: float,
             fcur: float, xtol: float, rtol: float, maxiter: int) -> float:
    """Brent's iterations from a sign-changing pair (SciPy's ``brentq.c``, line for line)."""
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre != 0.0 and fcur != 0.0 and (math.copysign(1.0, fpre)
                                            != math.copysign(1.0, fcur)):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2.0
        sbis = (xblk - xcur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:  # interpolate (secant)
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:  # extrapolate (inverse quadratic)
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre, scur = scur, stry  # a good short step
            else:
                spre = scur = sbis  # bisect
        else:
            spre = scur = sbis  # bisect
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0.0 else -delta)
        fcur = value(xcur)
    raise RuntimeError(f"Brent's method did not converge in {maxiter} iterations")


def first_passed(f: Callable[[float], float], points: Sequence[float], start: float,
                 passed: Callable[[float], bool]) -> tuple[float, float] | None:
    """The first of ``points`` (in order, from ``start``) at which ``passed(f(point))`` holds,
    with the point before it (``start`` for the first): (last point not passed, first passed),
    or None where none is.

    The points are visited two at a time: f is evaluated at every second point, and at the
    point skipped only where the pair's far point is passed. The result is that of a
    point-by-point search except where the skipped point is passed and the far one is not (f
    passes and comes back within two steps of the grid, which a point-by-point search also
    misses unless a point falls between); it costs about half the evaluations, each of which
    integrates a fast motion where the force-velocity curves are searched.
    """
    prev = start
    j = 0
    while j < len(points):
        far = min(j + 1, len(points) - 1)
        if passed(f(points[far])):
            if far > j:  # the point skipped: is it passed already?
                if passed(f(points[j])):
                    return prev, points[j]
                return points[j], points[far]
            return prev, points[far]
        prev = points[far]
        j = far + 1
    return None
