"""Compiled kernels of the 2-D slow model (:mod:`.plane`): contacts, clusters and time steps.

Everything here is in SI units and written in the subset numba compiles; the beads' drifts under
their loads come from :mod:`.plane_curves`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .plane_curves import N_FLOOR, bead_response

JIT = {"cache": True, "nogil": True}


@njit(**JIT)
def order_of(x: np.ndarray) -> np.ndarray:
    """Indices that sort ``x`` (a bottom-up merge sort: stable, and quick to compile, unlike
    numba's own argsort)."""
    n = x.size
    a = np.arange(n)
    b = np.empty(n, dtype=np.int64)
    width = 1
    while width < n:
        for lo in range(0, n, 2 * width):
            mid, hi = min(lo + width, n), min(lo + 2 * width, n)
            i, j, k = lo, mid, lo
            while i < mid and j < hi:
                if x[a[j]] < x[a[i]]:
                    b[k] = a[j]
                    j += 1
                else:
                    b[k] = a[i]
                    i += 1
                k += 1
            while i < mid:
                b[k] = a[i]
                i += 1
                k += 1
            while j < hi:
                b[k] = a[j]
                j += 1
                k += 1
        a, b = b, a
        width *= 2
    return a


@njit(**JIT)
def build_pairs(x: np.ndarray, y: np.ndarray, kind: np.ndarray, rad: np.ndarray,
                hgt: np.ndarray, skin: float) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (i, j) whose centres are within contact distance + ``skin`` (sweep along x)."""
    n = x.size
    order = order_of(x)
    rmax = 0.0
    for s in range(rad.size):
        rmax = max(rmax, rad[s])
    reach = 2.0 * rmax + skin
    cap = 16 * n + 16
    pi = np.empty(cap, dtype=np.int64)
    pj = np.empty(cap, dtype=np.int64)
    m = 0
    for p in range(n):
        i = order[p]
        for q in range(p + 1, n):
            j = order[q]
            dx = x[j] - x[i]
            if dx > reach:
                break
            dy = y[j] - y[i]
            if abs(dy) > reach:
                continue
            dz = hgt[kind[j]] - hgt[kind[i]]
            d = math.sqrt(dx * dx + dy * dy + dz * dz)
            if d < rad[kind[i]] + rad[kind[j]] + skin:
                if m == cap:
                    cap *= 2
                    pi2 = np.empty(cap, dtype=np.int64)
                    pj2 = np.empty(cap, dtype=np.int64)
                    pi2[:m] = pi[:m]
                    pj2[:m] = pj[:m]
                    pi, pj = pi2, pj2
                pi[m] = i
                pj[m] = j
                m += 1
    return pi[:m].copy(), pj[:m].copy()


@njit(**JIT)
def far_gap(x, y, kind, rad, hgt, skin: float) -> float:
    """The smallest gap between two beads farther apart than contact + ``skin`` (not in the
    list), at least ``skin``: how far beads may move before the list must be rebuilt."""
    order = order_of(x)
    rmax = 0.0
    for s in range(rad.size):
        rmax = max(rmax, rad[s])
    gap = math.inf
    for p in range(x.size):
        i = order[p]
        for q in range(p + 1, x.size):
            j = order[q]
            if x[j] - x[i] - 2.0 * rmax > gap:
                break
            dx, dy = x[j] - x[i], y[j] - y[i]
            dz = hgt[kind[j]] - hgt[kind[i]]
            g = math.sqrt(dx * dx + dy * dy + dz * dz) - rad[kind[i]] - rad[kind[j]]
            if g >= skin:
                gap = min(gap, g)
    return max(gap, skin) if gap < math.inf else max(skin, 1.0)


@njit(**JIT)
def pair_state(x, y, kind, rad, hgt, i: int, j: int) -> tuple[float, float, float, float]:
    """(overlap, gx, gy, gz): overlap R_i + R_j - d (> 0 touching) and the unit normal i -> j."""
    dx = x[j] - x[i]
    dy = y[j] - y[i]
    dz = hgt[kind[j]] - hgt[kind[i]]
    d = math.sqrt(dx * dx + dy * dy + dz * dz)
    return rad[kind[i]] + rad[kind[j]] - d, dx / d, dy / d, dz / d


@njit(**JIT)
def find(parent: np.ndarray, i: int) -> int:
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@njit(**JIT)
def overlaps(x, y, kind, rad, hgt, pi, pj, over: np.ndarray) -> None:
    """``over[p]``: the overlap of pair p (negative: the gap)."""
    for p in range(pi.size):
        over[p] = pair_state(x, y, kind, rad, hgt, pi[p], pj[p])[0]


@njit(**JIT)
def pair_loads(x, y, kind, rad, hgt, wgt, stiff: float, pi, pj, act, fx, fy, nl) -> None:
    """Horizontal loads ``fx``, ``fy`` and normal loads ``nl`` of every bead from its contacts.

    A pair in contact (``act[p]``) pushes with P = stiff min(W_i, W_j) overlap along the 3-D
    normal: +P n on j, -P n on i; its vertical part presses the lower bead onto the plate and
    lifts the higher one. (A pair about to touch within the step is in contact with its gap
    counted as a negative overlap: the implicit step then gives its force at the end of it.)
    """
    for i in range(x.size):
        fx[i] = 0.0
        fy[i] = 0.0
        nl[i] = wgt[kind[i]]
    for p in range(pi.size):
        if not act[p]:
            continue
        i, j = pi[p], pj[p]
        ov, gx, gy, gz = pair_state(x, y, kind, rad, hgt, i, j)
        f = stiff * min(wgt[kind[i]], wgt[kind[j]]) * ov
        fx[j] += f * gx
        fy[j] += f * gy
        nl[j] -= f * gz
        fx[i] -= f * gx
        fy[i] -= f * gy
        nl[i] += f * gz


@njit(**JIT)
def responses(kind, wgt, fx, fy, nl, busy, table, v0, dv, lo, hi, logn, nc, hstep, vfree,
              u: float, perp: float, vx, vy, ax, an, mp) -> None:
    """Each bead's drift (vx, vy, m/s) under its loads and the derivatives the implicit step uses:
    ax = dVx/dLx, an = dVx/dN, mp = dVy/dLy (the transverse mobility, times ``perp``). A bead in
    no contact (``busy`` false) has the free values of its species (read once), and drifts at
    exactly ``vfree``, the free drift ratio as the curves sampled it (the 1-D model's)."""
    free = np.empty((wgt.size, 4))
    for s in range(wgt.size):
        v, slope, dvdlogn, sec = bead_response(table, v0, dv, lo, hi, logn, nc, hstep, s, 0.0,
                                               wgt[s], wgt[s])
        free[s, 0], free[s, 1], free[s, 2], free[s, 3] = v, slope, dvdlogn, sec
    for i in range(kind.size):
        s = kind[i]
        w = wgt[s]
        if busy[i]:
            floor = nl[i] < N_FLOOR * w
            n = N_FLOOR * w if floor else nl[i]
            v, slope, dvdlogn, sec = bead_response(table, v0, dv, lo, hi, logn, nc, hstep, s,
                                                   fx[i], n, w)
        else:
            floor, n = False, w
            v, slope, dvdlogn, sec = vfree[s], free[s, 1], free[s, 2], free[s, 3]
        vx[i] = u * v
        mp[i] = perp * u * sec / n
        vy[i] = mp[i] * fy[i]
        ax[i] = u * slope / n
        an[i] = 0.0 if floor else u * (-slope * fx[i] / (n * n) + dvdlogn / n)


@njit(**JIT)
def _clusters(n: int, pi, pj, act, parent, size) -> None:
    """Union-find of the beads linked by pairs in contact; ``size[root]`` members."""
    for i in range(n):
        parent[i] = i
        size[i] = 0
    for p in range(pi.size):
        if act[p]:
            a, b = find(parent, pi[p]), find(parent, pj[p])
            if a != b:
                parent[a] = b
    for i in range(n):
        size[find(parent, i)] += 1


@njit(**JIT)
def gauss(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve a x = b by Gaussian elimination with partial pivoting (in place; small systems,
    where a LAPACK call costs more than the work)."""
    m = b.size
    for c in range(m):
        piv = c
        for r in range(c + 1, m):
            if abs(a[r, c]) > abs(a[piv, c]):
                piv = r
        if piv != c:
            for q in range(c, m):
                a[c, q], a[piv, q] = a[piv, q], a[c, q]
            b[c], b[piv] = b[piv], b[c]
        inv = 1.0 / a[c, c]
        for r in range(c + 1, m):
            f = a[r, c] * inv
            if f != 0.0:
                for q in range(c + 1, m):
                    a[r, q] -= f * a[c, q]
                b[r] -= f * b[c]
    for c in range(m - 1, -1, -1):
        acc = b[c]
        for q in range(c + 1, m):
            acc -= a[c, q] * b[q]
        b[c] = acc / a[c, c]
    return b


@njit(**JIT)
def cluster_solve(x, y, kind, rad, hgt, wgt, stiff: float, pi, pj, act, ax, an, mp, dt: float,
                  rx, ry, parent, loc, quiet: float) -> int:
    """Solve (I - dt J) d = r in place of (``rx``, ``ry``) for every cluster of beads in contact
    (J: the derivative of the drifts with respect to the positions through the pair forces,
    from ``ax``, ``an``, ``mp``); beads in no contact keep d = r. A cluster none of whose
    contacts would change by more than ``quiet`` under d = r is left as it is (J r = 0 there:
    beads touching at the same velocity). Returns the number of clusters solved."""
    n = x.size
    size = np.zeros(n, dtype=np.int64)
    _clusters(n, pi, pj, act, parent, size)
    busy = np.zeros(n, dtype=np.bool_)
    for p in range(pi.size):
        if act[p]:
            i, j = pi[p], pj[p]
            _, gx, gy, _ = pair_state(x, y, kind, rad, hgt, i, j)
            if abs(gx * (rx[j] - rx[i]) + gy * (ry[j] - ry[i])) > quiet:
                busy[find(parent, i)] = True
    # members and contacts of every cluster, grouped by root (counting sort)
    first = np.zeros(n + 1, dtype=np.int64)
    for i in range(n):
        first[find(parent, i) + 1] += 1
    for r in range(n):
        first[r + 1] += first[r]
    members = np.empty(n, dtype=np.int64)
    fill = first[:n].copy()
    for i in range(n):
        r = find(parent, i)
        loc[i] = fill[r] - first[r]
        members[fill[r]] = i
        fill[r] += 1
    pfirst = np.zeros(n + 1, dtype=np.int64)
    for p in range(pi.size):
        if act[p]:
            pfirst[find(parent, pi[p]) + 1] += 1
    for r in range(n):
        pfirst[r + 1] += pfirst[r]
    plist = np.empty(pfirst[n], dtype=np.int64)
    pfill = pfirst[:n].copy()
    for p in range(pi.size):
        if act[p]:
            r = find(parent, pi[p])
            plist[pfill[r]] = p
            pfill[r] += 1
    solved = 0
    for r in range(n):
        if size[r] < 2 or not busy[r]:
            continue
        m = size[r]
        mat = np.eye(2 * m)
        rhs = np.empty(2 * m)
        for q in range(m):
            rhs[2 * q] = rx[members[first[r] + q]]
            rhs[2 * q + 1] = ry[members[first[r] + q]]
        for e in range(pfirst[r], pfirst[r + 1]):
            p = plist[e]
            i, j = pi[p], pj[p]
            _, gx, gy, gz = pair_state(x, y, kind, rad, hgt, i, j)
            k = dt * stiff * min(wgt[kind[i]], wgt[kind[j]])
            # dP = -k g.(d_j - d_i); dV_j = w_j dP, dV_i = w_i dP; A = I - dt J
            wj0, wj1 = ax[j] * gx - an[j] * gz, mp[j] * gy
            wi0, wi1 = -ax[i] * gx + an[i] * gz, -mp[i] * gy
            a, b = 2 * loc[i], 2 * loc[j]
            for row, w0, w1 in ((b, wj0, wj1), (a, wi0, wi1)):
                mat[row, b] += w0 * k * gx
                mat[row, b + 1] += w0 * k * gy
                mat[row, a] -= w0 * k * gx
                mat[row, a + 1] -= w0 * k * gy
                mat[row + 1, b] += w1 * k * gx
                mat[row + 1, b + 1] += w1 * k * gy
                mat[row + 1, a] -= w1 * k * gx
                mat[row + 1, a + 1] -= w1 * k * gy
        sol = gauss(mat, rhs)
        for q in range(m):
            rx[members[first[r] + q]] = sol[2 * q]
            ry[members[first[r] + q]] = sol[2 * q + 1]
        solved += 1
    return solved


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
    pi, pj = build_pairs(x, y, kind, rad, hgt, skin)
    quarter = 0.25 * far_gap(x, y, kind, rad, hgt, skin)
    over = np.zeros(pi.size)
    act, start = np.zeros(pi.size, dtype=np.bool_), np.zeros(pi.size, dtype=np.bool_)
    t, k, dt_prev, first = 0.0, 0, math.inf, True
    stats[:] = 0.0
    stats[2] = 1.0
    while k < sample_t.size and sample_t[k] <= t:
        out_x[k, :] = x
        out_y[k, :] = y
        k += 1
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
            held = False
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
                    held = True
                    break
                if it >= 2 and res > 0.5 * last:
                    break  # not converging: a smaller step
                last = res
                stats[3] += cluster_solve(xt, yt, kind, rad, hgt, wgt, stiff, pi, pj, act, ax,
                                          an, mp, dt, rx, ry, parent, loc, 1e-3 * eps)
                for i in range(n):
                    ddx[i] += rx[i]
                    ddy[i] += ry[i]
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
            pi, pj = build_pairs(x, y, kind, rad, hgt, skin)
            quarter = 0.25 * far_gap(x, y, kind, rad, hgt, skin)
            over = np.zeros(pi.size)
            act, start = np.zeros(pi.size, dtype=np.bool_), np.zeros(pi.size, dtype=np.bool_)
            moved[:] = 0.0
            stats[2] += 1.0
        while k < sample_t.size and sample_t[k] <= t:
            out_x[k, :] = x
            out_y[k, :] = y
            k += 1
    if k < sample_t.size:  # parted: every bead at its free drift from t on
        ux[:] = wx
        uy[:] = wy
        t0 = t
        while k < sample_t.size:
            out_x[k, :] = x + wx * (sample_t[k] - t0)
            out_y[k, :] = y
            k += 1
        x += wx * (sample_t[-1] - t0)
    out_u[0, :] = ux
    out_u[1, :] = uy
    return 0
