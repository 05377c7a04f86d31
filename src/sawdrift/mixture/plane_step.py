"""Time steps of the 2-D slow model (:mod:`.plane`): backward Euler by Newton's method.

Everything here is in SI units and written in the subset numba compiles; contacts, loads and
the cluster solves come from :mod:`.plane_kernel`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .plane_kernel import JIT, build_pairs, cluster_solve, far_gap, overlaps, pair_loads, responses


@njit(**JIT)
def _small(pi, pj, act, ddx, ddy, quarter: float, slide: float) -> bool:
    """Every bead within a quarter of the skin, every pair in contact moved by at most
    ``slide`` relative to each other."""
    for i in range(ddx.size):
        if ddx[i] * ddx[i] + ddy[i] * ddy[i] > quarter * quarter:
            return False
    for p in range(pi.size):
        if act[p]:
            rx = ddx[pj[p]] - ddx[pi[p]]
            ry = ddy[pj[p]] - ddy[pi[p]]
            if rx * rx + ry * ry > slide * slide:
                return False
    return True


@njit(**JIT)
def _guess(pi, pj, act, ux, uy, dt: float, quarter: float, slide: float) -> float:
    """A first step from the last step's velocities: every bead within a quarter of the skin,
    every pair in contact sliding by at most ``slide``."""
    for i in range(ux.size):
        sp = math.sqrt(ux[i] * ux[i] + uy[i] * uy[i])
        if sp * dt > quarter:
            dt = quarter / sp
    for p in range(pi.size):
        if act[p]:
            i, j = pi[p], pj[p]
            rel = math.sqrt((ux[j] - ux[i]) ** 2 + (uy[j] - uy[i]) ** 2)
            if rel * dt > slide:
                dt = slide / rel
    return dt


@njit(**JIT)
def _drifts(x, y, kind, rad, hgt, wgt, stiff, pi, pj, over, act, fx, fy, nl, table, v0, dv, lo,
            hi, logn, nc, hstep, vfree, u, perp, vx, vy, ax, an, mp) -> None:
    """Contacts (``act``: overlap > 0), loads and drifts at the positions (x, y)."""
    overlaps(x, y, kind, rad, hgt, pi, pj, over)
    busy = np.zeros(x.size, dtype=np.bool_)
    for p in range(pi.size):
        act[p] = over[p] > 0.0
        if act[p]:
            busy[pi[p]] = True
            busy[pj[p]] = True
    pair_loads(x, y, kind, rad, hgt, wgt, stiff, pi, pj, act, fx, fy, nl)
    responses(kind, wgt, fx, fy, nl, busy, table, v0, dv, lo, hi, logn, nc, hstep, vfree, u, perp,
              vx, vy, ax, an, mp)


@njit(**JIT)
def _parted(x, kind, rad, start, wx, wy) -> bool:
    """Can no two beads ever touch again? True when nothing touches, every bead moves straight
    along the wave at one speed per species, and every species lies wholly ahead (by more than
    a contact) of every slower one: then the rest of the run is straight lines."""
    for p in range(start.size):
        if start[p]:
            return False
    m = rad.size
    lo_x, hi_x, speed = np.full(m, math.inf), np.full(m, -math.inf), np.full(m, math.nan)
    for i in range(x.size):
        s = kind[i]
        if wy[i] != 0.0 or (speed[s] == speed[s] and wx[i] != speed[s]):
            return False
        speed[s] = wx[i]
        lo_x[s] = min(lo_x[s], x[i])
        hi_x[s] = max(hi_x[s], x[i])
    for a in range(m):
        for b in range(m):
            if speed[a] > speed[b] and lo_x[a] - hi_x[b] <= rad[a] + rad[b]:
                return False
    return True


@njit(**JIT)
def integrate(x, y, kind, rad, hgt, wgt, table, v0, dv, lo, hi, logn, nc, hstep, vfree, u: float,
              perp: float, stiff: float, tol: float, skin: float, slide: float,
              sample_t, out_x, out_y, out_u, stats, max_steps: int) -> int:
    """Move the beads (``x``, ``y`` in place) through the times ``sample_t`` (s, from 0).

    Each step is a backward Euler step, d = dt V(x + d), solved by Newton's method from the
    linearly implicit step (:func:`cluster_solve`) until no bead is off by more than 1e-3 of the
    overlap tolerance; it is accepted when :func:`_small` holds, halved otherwise. Writes the
    positions at each sample time into ``out_x``, ``out_y``, the beads' last velocities (m/s, x
    then y) into ``out_u``, and into ``stats``: steps, halvings, list builds, clusters solved,
    the largest overlap over ``tol``. Returns 0, 1 when ``max_steps`` ran out, 2 when a step
    could not be made to converge.
    """
    n = x.size
    fx, fy, nl = np.zeros(n), np.zeros(n), np.zeros(n)
    vx, vy, ax, an, mp = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    wx, wy, bx, bn, bp = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    ddx, ddy, rx, ry = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    xt, yt, ux, uy, moved = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    parent, loc = np.zeros(n, dtype=np.int64), np.zeros(n, dtype=np.int64)
    eps = 5e-2 * tol
    pi, pj, quarter, over, act, start = _pair_list(x, y, kind, rad, hgt, skin)
    t, dt_prev, first = 0.0, math.inf, True
    stats[:] = 0.0
    stats[2] = 1.0
    k = _write_samples(x, y, t, 0, sample_t, out_x, out_y)
    while k < sample_t.size:
        if stats[0] >= max_steps:
            return 1
        _drifts(x, y, kind, rad, hgt, wgt, stiff, pi, pj, over, start, fx, fy, nl, table, v0,
                dv, lo, hi, logn, nc, hstep, vfree, u, perp, wx, wy, bx, bn, bp)
        for p in range(pi.size):
            stats[4] = max(stats[4], over[p] / tol)
        if _parted(x, kind, rad, start, wx, wy):
            break  # sorted and moving apart: straight lines from here
        if first:
            ux[:] = wx
            uy[:] = wy
            first = False
        to_sample = sample_t[k] - t
        dt = _guess(pi, pj, start, ux, uy, min(to_sample, 1.3 * dt_prev), quarter, slide)
        halvings = 0
        while True:
            for i in range(n):
                ddx[i] = dt * wx[i]
                ddy[i] = dt * wy[i]
            stats[3] += cluster_solve(x, y, kind, rad, hgt, wgt, stiff, pi, pj, start, bx, bn,
                                      bp, dt, ddx, ddy, parent, loc, 1e-3 * eps)
            held = _newton(x, y, kind, rad, hgt, wgt, table, v0, dv, lo, hi, logn, nc, hstep,
                           vfree, u, perp, stiff, pi, pj, over, act, fx, fy, nl, vx, vy, ax, an,
                           mp, xt, yt, rx, ry, ddx, ddy, parent, loc, dt, eps, stats)
            if held and _small(pi, pj, act, ddx, ddy, quarter, slide) and _small(
                    pi, pj, start, ddx, ddy, quarter, slide):
                break
            dt *= 0.5
            stats[1] += 1.0
            halvings += 1
            if halvings > 80:
                return 2
        worst = 0.0
        for i in range(n):
            x[i] += ddx[i]
            y[i] += ddy[i]
            ux[i], uy[i] = ddx[i] / dt, ddy[i] / dt
            moved[i] += math.sqrt(ddx[i] * ddx[i] + ddy[i] * ddy[i])
            worst = max(worst, moved[i])
        if dt >= to_sample:
            t = sample_t[k]  # a step cut short by a sample time does not set the next one
        else:
            t += dt
            dt_prev = dt
        stats[0] += 1.0
        if worst > quarter:
            pi, pj, quarter, over, act, start = _pair_list(x, y, kind, rad, hgt, skin)
            moved[:] = 0.0
            stats[2] += 1.0
        k = _write_samples(x, y, t, k, sample_t, out_x, out_y)
    if k < sample_t.size:  # parted: every bead at its free drift from t on
        ux[:] = wx
        uy[:] = wy
        _straight_lines(x, y, wx, t, k, sample_t, out_x, out_y)
    out_u[0, :] = ux
    out_u[1, :] = uy
    return 0



@njit(**JIT)
def _pair_list(x, y, kind, rad, hgt, skin: float):
    """The pairs within the skin (:func:`~.plane_kernel.build_pairs`), a quarter of the nearest
    gap beyond it (how far a bead may move before the list is built again), and the pairs'
    overlaps and contact flags (now, at the step's start), zeroed."""
    pi, pj = build_pairs(x, y, kind, rad, hgt, skin)
    quarter = 0.25 * far_gap(x, y, kind, rad, hgt, skin)
    over = np.zeros(pi.size)
    return (pi, pj, quarter, over, np.zeros(pi.size, dtype=np.bool_),
            np.zeros(pi.size, dtype=np.bool_))


@njit(**JIT)
def _write_samples(x, y, t: float, k: int, sample_t, out_x, out_y) -> int:
    """The positions at every sample time from the ``k``-th up to ``t``; the next index."""
    while k < sample_t.size and sample_t[k] <= t:
        out_x[k, :] = x
        out_y[k, :] = y
        k += 1
    return k

@njit(**JIT)
def _newton(x, y, kind, rad, hgt, wgt, table, v0, dv, lo, hi, logn, nc, hstep, vfree, u, perp,
            stiff, pi, pj, over, act, fx, fy, nl, vx, vy, ax, an, mp, xt, yt, rx, ry, ddx, ddy,
            parent, loc, dt: float, eps: float, stats) -> bool:
    """Newton's method on the backward Euler step d = dt V(x + d) (``ddx``, ``ddy``, from the
    linearly implicit step, in place), at most 8 iterations: True once no bead is off by more
    than ``eps``, False where the residual stops halving (a smaller step is needed)."""
    n = x.size
    last = math.inf
    for it in range(8):
        for i in range(n):
            xt[i] = x[i] + ddx[i]
            yt[i] = y[i] + ddy[i]
        _drifts(xt, yt, kind, rad, hgt, wgt, stiff, pi, pj, over, act, fx, fy, nl,
                table, v0, dv, lo, hi, logn, nc, hstep, vfree, u, perp, vx, vy, ax, an, mp)
        res = 0.0
        for i in range(n):
            rx[i] = dt * vx[i] - ddx[i]
            ry[i] = dt * vy[i] - ddy[i]
            res = max(res, abs(rx[i]), abs(ry[i]))
        if res <= eps:
            return True
        if it >= 2 and res > 0.5 * last:
            return False  # not converging: a smaller step
        last = res
        stats[3] += cluster_solve(xt, yt, kind, rad, hgt, wgt, stiff, pi, pj, act, ax,
                                  an, mp, dt, rx, ry, parent, loc, 1e-3 * eps)
        for i in range(n):
            ddx[i] += rx[i]
            ddy[i] += ry[i]
    return False


@njit(**JIT)
def _straight_lines(x, y, wx, t0: float, k: int, sample_t, out_x, out_y) -> None:
    """The beads parted (:func:`_parted`): each at its free drift ``wx`` from ``t0`` on, written at
    the sample times from the ``k``-th, and moved to the last of them (``x`` in place)."""
    while k < sample_t.size:
        out_x[k, :] = x + wx * (sample_t[k] - t0)
        out_y[k, :] = y
        k += 1
    x += wx * (sample_t[-1] - t0)
