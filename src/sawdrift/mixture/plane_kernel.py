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
