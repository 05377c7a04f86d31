"""The species' force-velocity curves read backwards, compiled for the 2-D slow model (:mod:`.plane`).

The curves come as padded arrays (:func:`sawdrift.mixture.plane.curve_arrays`): for species s and
curve c (normal load N / W = exp(logn[s, c])), ``table[s, k, c]`` is the load l = L / N that holds
the bead at the drift ratio v0[s] + k dv[s] (the regular speed table of
:class:`.curves.SpeciesCurves`), constant below grid index ``lo[s, c]`` and above ``hi[s, c]``
(outside the speeds that curve sampled).

Between two curves the load is interpolated linearly in log N at a fixed speed, l(v, N) =
(1 - t) l_a(v) + t l_b(v), exactly as :meth:`.curves.SpeciesCurves.load` does, so the speed under
a load, :func:`curve_speed`, is the inverse of the 1-D model's load: a chain that is steady in one
model is steady in the other.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

JIT = {"cache": True, "nogil": True}

#: a normal load never drops below this fraction of the weight (as in the chain balance)
N_FLOOR = 1e-3
#: dv/dl beyond the loads a curve sampled: a bead past its friction limit slides
SLIDE = 100.0


@njit(**JIT)
def bracket(logn: np.ndarray, nc: np.ndarray, s: int, ln: float) -> tuple[int, int, float]:
    """(a, b, t): the curves around log N = ``ln`` and the weight of b (nearest curve outside)."""
    m = nc[s]
    if m == 1:
        return 0, 0, 0.0
    if ln <= logn[s, 0]:
        return 0, 1, 0.0
    if ln >= logn[s, m - 1]:
        return m - 2, m - 1, 1.0
    a = 0
    while logn[s, a + 1] < ln:
        a += 1
    return a, a + 1, (ln - logn[s, a]) / (logn[s, a + 1] - logn[s, a])


@njit(**JIT)
def _mix(table: np.ndarray, s: int, k: int, a: int, b: int, t: float) -> float:
    return (1.0 - t) * table[s, k, a] + t * table[s, k, b]


@njit(**JIT)
def curve_speed(table: np.ndarray, v0: np.ndarray, dv: np.ndarray, lo: np.ndarray,
                hi: np.ndarray, s: int, a: int, b: int, t: float,
                ell: float) -> tuple[float, float, int, float]:
    """(v, dv/dl, k, frac): the drift ratio at which l(v) = ``ell`` between curves a and b.

    Found by bisection on the regular speed table (l is increasing in v between the curves'
    sampled speeds); ``k + frac`` is its position on the grid. Beyond the loads the curves
    sampled (near the friction limit) the bead slides: the curve goes on as a straight line of
    slope :data:`SLIDE`, so that the load stays at the end of the curve (within 1e-3 for a
    speed 0.1 beyond), as the chains of :mod:`.chains` read it (the end load at any faster
    speed).
    """
    if t <= 0.0:
        klo, khi = lo[s, a], hi[s, a]
    elif t >= 1.0:
        klo, khi = lo[s, b], hi[s, b]
    else:
        klo, khi = max(lo[s, a], lo[s, b]), min(hi[s, a], hi[s, b])
    f_lo = _mix(table, s, klo, a, b, t)
    if ell <= f_lo or khi <= klo:
        return v0[s] + dv[s] * klo + SLIDE * (ell - f_lo), SLIDE, klo, 0.0
    f_hi = _mix(table, s, khi, a, b, t)
    if ell >= f_hi:
        return v0[s] + dv[s] * khi + SLIDE * (ell - f_hi), SLIDE, khi, 0.0
    i0, i1 = klo, khi
    while i1 - i0 > 1:
        m = (i0 + i1) // 2
        if _mix(table, s, m, a, b, t) <= ell:
            i0 = m
        else:
            i1 = m
    f0 = _mix(table, s, i0, a, b, t)
    f1 = _mix(table, s, i1, a, b, t)
    frac = (ell - f0) / (f1 - f0)
    return v0[s] + dv[s] * (i0 + frac), dv[s] / (f1 - f0), i0, frac


@njit(**JIT)
def bead_response(table, v0, dv, lo, hi, logn, nc, hstep, s: int, fx: float, n_load: float,
                  weight: float) -> tuple[float, float, float, float]:
    """(v, dv/dl, dv/dlog N, M): drift ratio under the load ``fx`` and normal load ``n_load``.

    M is the transverse mobility in drift ratio per unit l (the caller multiplies it by u / N):
    the secant of the curve through its free drift, (v(l+) - v(l-)) / (l+ - l-) with l+ =
    max(l, h), l- = min(l, -h), h one sample of load (the slope at zero load for small loads).
    """
    ln = math.log(n_load / weight)
    a, b, t = bracket(logn, nc, s, ln)
    ell = fx / n_load
    v, slope, k, frac = curve_speed(table, v0, dv, lo, hi, s, a, b, t, ell)
    dvdlogn = 0.0
    if a != b and 0.0 < t < 1.0 and slope > 0.0:
        la = table[s, k, a] + frac * (table[s, k + 1, a] - table[s, k, a])
        lb = table[s, k, b] + frac * (table[s, k + 1, b] - table[s, k, b])
        dvdlogn = -(lb - la) / (logn[s, b] - logn[s, a]) * slope
    h = hstep[s]
    lp = max(ell, h)
    lm = min(ell, -h)
    vp = v if ell >= h else curve_speed(table, v0, dv, lo, hi, s, a, b, t, lp)[0]
    vm = v if ell <= -h else curve_speed(table, v0, dv, lo, hi, s, a, b, t, lm)[0]
    return v, slope, dvdlogn, (vp - vm) / (lp - lm)
