"""Compiled kernel of the ``jaeger`` model (Cattaneo-Mindlin/Jaeger with Masing memory).

The law and the state layout are described in :mod:`sawdrift_builtin.jaeger`; this module holds
its numba functions, imported on first use.
"""

from __future__ import annotations

import math

from numba import njit

from sawdrift.contact.normal import power_law as _nstar

from .jaeger import _DIR, _MEM, _N, _REF

# --------------------------------------------------------------------------------------------
# compiled kernel
# --------------------------------------------------------------------------------------------


@njit(cache=True)
def _extent(fs, n: int, s: int, b: float) -> float:
    """Extent c of the current branch in u: |b - o| on the virgin curve, |b - b_k| / 2 after."""
    f = 1.0 if n == 0 else 0.5
    return f * s * (b - fs[_REF])


@njit(cache=True)
def _push(fs, is_, c: float) -> None:
    """Push a breakpoint; on overflow first drop the interior adjacent pair with the least gap."""
    n = is_[_N]
    cap = fs.size - _MEM
    if n >= cap:
        best = 1
        gap = math.inf
        for j in range(1, n - 1):
            g = fs[_MEM + j] - fs[_MEM + j + 1]
            if g < gap:
                gap = g
                best = j
        for j in range(best, n - 2):
            fs[_MEM + j] = fs[_MEM + j + 2]
        n -= 2
    fs[_MEM + n] = c
    is_[_N] = n + 1


@njit(cache=True)
def _move_tangential(fs, is_, a1: float, b0: float, b1: float) -> None:
    """Advance the memory along a straight path ending at (a1, b1), b monotone from b0."""
    n = is_[_N]
    s = is_[_DIR]
    d = 0
    if b1 > b0:
        d = 1
    elif b1 < b0:
        d = -1
    if d != 0:
        if d != s:
            # reversal at b0: the current extent becomes a memory breakpoint
            _push(fs, is_, _extent(fs, n, s, b0))
            n = is_[_N]
            fs[_REF] = b0
            s = d
        while n > 0:
            top = fs[_MEM + n - 1]
            if _extent(fs, n, s, b1) < top:
                break
            # wipe-out: the branch re-joins the enclosing one where its extent equals `top`
            b_w = fs[_REF] + 2.0 * s * top
            if n >= 2:
                c_w = fs[_MEM + n - 2]
                n -= 2
            else:
                c_w = top
                n = 0
            f = 1.0 if n == 0 else 0.5
            fs[_REF] = b_w - s * c_w / f
    if _extent(fs, n, s, b1) >= a1:
        # full sliding: memory cleared, origin re-based so that the virgin extent is a1
        n = 0
        fs[_REF] = b1 - s * a1
    elif n > 0 and fs[_MEM] >= a1:
        # breakpoints beyond the (shrunken) contact collapse into one at a1
        j = 0
        while j < n and fs[_MEM + j] >= a1:
            j += 1
        fs[_MEM] = a1
        for k in range(j, n):
            fs[_MEM + k - j + 1] = fs[_MEM + k]
        n = n - j + 1
    is_[_N] = n
    is_[_DIR] = s


@njit(cache=True)
def _tangential_force(fs, is_, p: float, a: float, b: float) -> float:
    """T* as the alternating sum over the zig-zag memory profile (module docstring)."""
    n = is_[_N]
    sign = float(is_[_DIR])
    c = _extent(fs, n, is_[_DIR], b)
    t = sign * (_nstar(a, p) - _nstar(a - c, p))
    u_prev = c
    for k in range(n - 1, -1, -1):
        if u_prev >= a:
            break
        sign = -sign
        u_k = fs[_MEM + k]
        t += sign * (_nstar(a - u_prev, p) - _nstar(a - u_k, p))
        u_prev = u_k
    return t


@njit(cache=True)
def jaeger_reset(ts, is_, law, tp) -> None:
    """Empty history: no breakpoints, virgin branch loading in +b."""
    ts[:] = 0.0
    is_[_N] = 0
    is_[_DIR] = 1


@njit(cache=True)
def jaeger_step(ts, is_, law, tp, a0: float, b0: float, a: float, b: float) -> float:
    """T* at the end of the straight path (a0, b0) -> (a, b); a0 = 0 starts a virgin contact."""
    if a0 == 0.0:
        ts[_REF] = b0  # the virgin curve starts at the contact's entry point
    _move_tangential(ts, is_, a, b0, b)
    return _tangential_force(ts, is_, law[0], a, b)

