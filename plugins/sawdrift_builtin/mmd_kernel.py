"""Compiled kernel of the Method of Memory Diagrams (MMD): amortized O(1) per step.

Implements the normalized tangential law of ../shared/physics.md section 2 (Aleshin, Bou Matar
and Van Den Abeele 2015, "Method of memory diagrams for mechanical frictional contacts subject
to arbitrary 2D loading", Int. J. Solids Struct. 60-61; the elementary partial-slip solutions are
those of Mindlin & Deresiewicz 1953). The normal law is N*(a*) = a*^p, so
N*'(z) = p z^(p-1) for z > 0 and, by convention, N*'(0-) = 0: the flat punch (p = 1) carries a
point mass of dN*' at z = 0.

Memory diagram as a stack
-------------------------
The strip displacement v(z) on [0, a*] is piecewise linear; its kinks (the memory points) are
stored as a stack ordered by level, z = 0 at the bottom and z = a* at the top. Values are kept
relative to a global offset, v = w + offset, so a uniform shift by delta b* costs one addition.
Alongside every kink the stack keeps the prefix integral C[i] = integral_[0, z_i] w dN*'(z), so

    T* = C[top] + offset * N*'(a*)

(the total measure of [0, a*] is N*'(a*), point mass included). For a linear piece of w from
(z1, w1) to (z2, w2) the Stieltjes integral is (physics.md section 2)

    w2 N*'(z2) - w1 N*'(z1) - (w2 - w1) (N*(z2) - N*(z1)) / (z2 - z1).

All work of a step happens at the top of the stack:

* contact shrinks (a1 < a0): kinks with z >= a1 are popped and the top is re-set to the
  interpolated value at a1;
* contact grows (a1 > a0): after the shift the old top (a0, v = delta b*) and a new kink
  (a1, v = 0) bound exactly the straight-path entry profile v(z) = db (a1 - z) / (a1 - a0);
* clipping to |v| <= a1 - z: because |dv/dz| <= 1 the slack of each bound is monotone in z, so
  the violated set is a suffix ending at z = a1 and only one bound can be violated in a step.
  Violating kinks are popped, one kink is pushed where the diagram crosses the bound, and the
  top becomes (a1, 0). End-of-step clipping is exact for a straight path because each strip's
  slack is linear in the path parameter.

Every kink is pushed once and popped once, so a step costs O(1) amortized, independently of the
history length, and nothing is allocated. A drifting run makes the offset grow without bound;
when ``|offset| > REBASE_LIMIT * max(1, a*)`` the values are re-based (w += offset, offset = 0,
prefix sums recomputed). A kink that survives from one re-base to the next would have been
shifted by more than 2 a*, which the bounds forbid, so the O(kinks) re-base is also amortized
O(1) per push.

State layout (sizes from :func:`state_sizes`)
---------------------------------------------
``fs`` (float64), with ``cap = (fs.size - HEADER) // 3``:

====================  ==========================================================
``fs[0]``             committed a*
``fs[1]``             committed b*
``fs[2]``             offset (v = w + offset)
``fs[3]``, ``fs[4]``  N*, T* of the last step (diagnostics)
``fs[5:8]``           reserved
``fs[8 : 8+cap]``     z of the kinks (stack, bottom z = 0)
``fs[8+cap : ...]``   w of the kinks
``fs[8+2cap : ...]``  prefix integrals C
====================  ==========================================================

``is_`` (int64): ``is_[0]`` number of kinks (0 when out of contact), ``is_[1]`` high-water mark
of the kink count, ``is_[2]`` number of re-bases, ``is_[3]`` capacity.

``pp`` (float64): ``pp[0]`` = p.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from sawdrift.errors import SawdriftError

HEADER = 8
"""Number of scalar slots at the start of ``fs``."""
N_INT = 4
"""Size of ``is_``."""
REBASE_LIMIT = 64.0
"""Re-base the offset when it exceeds this many times max(1, a*)."""
COLLINEAR_RTOL = 4.0 * 2.220446049250313e-16
"""A pushed kink merges with the top when the top lies on the new line to this relative tolerance."""


class MemoryCapacityError(SawdriftError, RuntimeError):
    """The memory diagram needs more points than ``max_memory_points`` allows."""


def state_sizes(max_memory_points: int) -> tuple[int, int]:
    """Sizes of ``fs`` and ``is_`` for a stack of ``max_memory_points`` kinks."""
    return HEADER + 3 * max_memory_points, N_INT


@njit(cache=True, inline="always")
def _dnormal(z: float, p: float) -> float:
    """N*'(z) = p z^(p-1) for z > 0; 0 at z <= 0 (the convention N*'(0-) = 0)."""
    if z <= 0.0:
        return 0.0
    if p == 1.0:
        return 1.0
    if p == 1.5:
        return 1.5 * math.sqrt(z)
    if p == 2.0:
        return 2.0 * z
    return p * z ** (p - 1.0)


@njit(cache=True, inline="always")
def _normal(z: float, p: float) -> float:
    """N*(z) = z^p for z > 0, else 0."""
    if z <= 0.0:
        return 0.0
    if p == 1.0:
        return z
    if p == 1.5:
        return z * math.sqrt(z)
    if p == 2.0:
        return z * z
    return z**p


@njit(cache=True, inline="always")
def _segment(z1: float, w1: float, z2: float, w2: float, p: float) -> float:
    """Stieltjes integral of the linear piece (z1, w1)-(z2, w2) against dN*' (physics.md s. 2)."""
    dz = z2 - z1
    if dz <= 0.0:
        return 0.0
    return (
        w2 * _dnormal(z2, p)
        - w1 * _dnormal(z1, p)
        - (w2 - w1) * (_normal(z2, p) - _normal(z1, p)) / dz
    )


@njit(cache=True)
def _set_top(fs, is_, z, w, p):
    """Overwrite the top kink with (z, w) and recompute its prefix integral."""
    cap = (fs.shape[0] - HEADER) // 3
    n = is_[0]
    iz = HEADER + n - 1
    fs[iz] = z
    fs[iz + cap] = w
    if n == 1:
        fs[iz + 2 * cap] = 0.0
    else:
        fs[iz + 2 * cap] = fs[iz - 1 + 2 * cap] + _segment(fs[iz - 1], fs[iz - 1 + cap], z, w, p)


@njit(cache=True)
def _push(fs, is_, z, w, p):
    """Push the kink (z, w); a level not above the top replaces the top (v is continuous)."""
    cap = (fs.shape[0] - HEADER) // 3
    n = is_[0]
    if n > 0 and z <= fs[HEADER + n - 1]:
        _set_top(fs, is_, fs[HEADER + n - 1], w, p)
        return
    if n >= 2:
        # a kink collinear (to rounding) with the two below it replaces the top: pure normal
        # loading and proportional loading then keep O(1) memory points
        iz = HEADER + n - 1
        z1 = fs[iz - 1]
        w1 = fs[iz - 1 + cap]
        z2 = fs[iz]
        w2 = fs[iz + cap]
        w_line = w1 + (w - w1) * ((z2 - z1) / (z - z1))
        if abs(w_line - w2) <= COLLINEAR_RTOL * (abs(w1) + abs(w)):
            fs[iz] = z
            fs[iz + cap] = w
            fs[iz + 2 * cap] = fs[iz - 1 + 2 * cap] + _segment(z1, w1, z, w, p)
            return
    if n >= cap:
        raise MemoryCapacityError(
            "mmd: the memory diagram is full; raise the model parameter max_memory_points"
        )
    iz = HEADER + n
    fs[iz] = z
    fs[iz + cap] = w
    if n == 0:
        fs[iz + 2 * cap] = 0.0
    else:
        fs[iz + 2 * cap] = fs[iz - 1 + 2 * cap] + _segment(fs[iz - 1], fs[iz - 1 + cap], z, w, p)
    is_[0] = n + 1
    if n + 1 > is_[1]:
        is_[1] = n + 1


@njit(cache=True)
def _clip(fs, is_, a, offset, s, p):
    """Clip the suffix that violates s v(z) <= a - z (s = +1 upper, -1 lower bound).

    Pops violating kinks, pushes the crossing with the bound and the end kink (a, v = 0).
    """
    cap = (fs.shape[0] - HEADER) // 3
    n = is_[0]
    zp = a
    gp = 0.0
    while n > 0:
        iz = HEADER + n - 1
        zt = fs[iz]
        g = s * (fs[iz + cap] + offset) - (a - zt)
        if g > 0.0:
            zp = zt
            gp = g
            n -= 1
        else:
            break
    is_[0] = n
    if n == 0:
        _push(fs, is_, 0.0, s * a - offset, p)
    else:
        iz = HEADER + n - 1
        zj = fs[iz]
        gj = s * (fs[iz + cap] + offset) - (a - zj)
        if gj < 0.0:
            zx = zj + (zp - zj) * (-gj / (gp - gj))
            if zx > zj:
                _push(fs, is_, zx, s * (a - zx) - offset, p)
    _push(fs, is_, a, -offset, p)


@njit(cache=True)
def _rebase(fs, is_, p):
    """Fold the offset into the stored values and recompute the prefix integrals."""
    cap = (fs.shape[0] - HEADER) // 3
    n = is_[0]
    offset = fs[2]
    for i in range(n):
        fs[HEADER + cap + i] += offset
    fs[2] = 0.0
    if n > 0:
        fs[HEADER + 2 * cap] = 0.0
    for i in range(1, n):
        iz = HEADER + i
        fs[iz + 2 * cap] = fs[iz - 1 + 2 * cap] + _segment(
            fs[iz - 1], fs[iz - 1 + cap], fs[iz], fs[iz + cap], p
        )
    is_[2] += 1


@njit(cache=True)
def reset(fs, is_, pp):
    """Empty history: out of contact at (a*, b*) = (0, 0)."""
    fs[:HEADER] = 0.0
    is_[0] = 0
    is_[1] = 0
    is_[2] = 0
    is_[3] = (fs.shape[0] - HEADER) // 3


@njit(cache=True)
def force(fs, is_, pp, a, b, adot, bdot):
    """Advance along the straight path to (a*, b*), commit, return (N*, T*).

    ``adot`` and ``bdot`` are ignored (the law is rate independent).
    """
    p = pp[0]
    cap = (fs.shape[0] - HEADER) // 3
    a0 = fs[0]
    b0 = fs[1]
    fs[0] = a
    fs[1] = b
    if not a > 0.0:
        # contact lost: the memory is erased, the next contact starts clean
        is_[0] = 0
        fs[2] = 0.0
        fs[3] = 0.0
        fs[4] = 0.0
        return 0.0, 0.0
    if a0 <= 0.0:
        # the straight path enters contact where a* crosses 0; start there from a point diagram
        if a0 < 0.0:
            b0 = b0 + (b - b0) * (-a0 / (a - a0))
        a0 = 0.0
        is_[0] = 0
        fs[2] = 0.0
        _push(fs, is_, 0.0, 0.0, p)
    offset = fs[2] + (b - b0)
    fs[2] = offset
    n = is_[0]
    if a < a0:
        # strips z >= a leave contact: pop them, re-set the top at z = a by interpolation
        while n >= 2 and fs[HEADER + n - 2] >= a:
            n -= 1
        is_[0] = n
        iz = HEADER + n - 1
        z1 = fs[iz - 1]
        w1 = fs[iz - 1 + cap]
        z2 = fs[iz]
        w2 = fs[iz + cap]
        _set_top(fs, is_, a, w1 + (w2 - w1) * ((a - z1) / (z2 - z1)), p)
    iz = HEADER + n - 1
    zt = fs[iz]
    vt = fs[iz + cap] + offset
    slack = a - zt if zt < a else 0.0
    if vt > slack:
        _clip(fs, is_, a, offset, 1.0, p)
    elif -vt > slack:
        _clip(fs, is_, a, offset, -1.0, p)
    else:
        _push(fs, is_, a, -offset, p)
    if abs(offset) > REBASE_LIMIT * max(1.0, a):
        _rebase(fs, is_, p)
        offset = 0.0
    n = is_[0]
    nf = _normal(a, p)
    t = fs[HEADER + n - 1 + 2 * cap] + offset * _dnormal(a, p)
    fs[3] = nf
    fs[4] = t
    return nf, t


def memory_points(fs: np.ndarray, is_: np.ndarray) -> np.ndarray:
    """The stored kinks as a (k, 2) array of (z, v), bottom (z = 0) first."""
    cap = (fs.shape[0] - HEADER) // 3
    n = int(is_[0])
    z = fs[HEADER : HEADER + n]
    v = fs[HEADER + cap : HEADER + cap + n] + fs[2]
    return np.column_stack([z, v])
