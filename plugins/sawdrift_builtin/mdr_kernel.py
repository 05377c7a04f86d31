"""Compiled kernel of the ``mdr`` model: Popov's Method of Dimensionality Reduction on N strips.

The same rule set as the memory diagram (docs/physics.md) applied strip by strip on a fixed
grid: Popov & Hess (2015), "Method of Dimensionality Reduction in Contact Mechanics and
Friction", Springer (tangential contact with the springs' local Coulomb limits); the continuous
limit is the Method of Memory Diagrams of Aleshin et al. (2015), Int. J. Solids Struct. 60-61.

Discretization
--------------
The level axis [0, z_max] is cut into N cells of width dz = z_max / N. Cell j,
[j dz, (j+1) dz], is one strip (one MDR spring) of weight m_j = N*'((j+1) dz) - N*'(j dz)
(the measure dN*' of the cell, with N*'(0-) = 0, so the flat punch's point mass sits in cell 0),
placed at the centroid of that measure, c_j = integral z dN*' / m_j over the cell. With that
placement the quadrature of integral v dN*' is exact for v linear on a cell, so the only errors
are the cells holding a kink of v and the cell holding z = a*, each bounded by dz m_j since
|dv/dz| <= 1: the error falls like dz^p near z = 0 and dz^2 elsewhere. (In the coordinate
x = z^(p-1) the measure dN*' = p dx is uniform and z = x^(1/(p-1)) is Popov's equivalent 1-D
profile, the parabola for a sphere: these are his equally stiff springs, on a grid regular in z
instead of x, which keeps the flat punch non-degenerate.)

Strip j is in contact when c_j < a*. Each strip follows the rules of the memory diagram
pointwise, so its value v_j equals the exact v(c_j) of the continuous model:

* a strip that leaves (c_j >= a1) is forgotten (v_j = 0);
* a strip in contact before and after shifts by db;
* a strip entering along the straight path (a0 <= c_j < a1) gets db (a1 - c_j) / (a1 - a0);
* then v_j is clipped to [-(a1 - c_j), a1 - c_j].

Forces: T* = min(N*(a*) / Q, 1.05) sum_j m_j v_j, Q = sum_j m_j (a* - c_j)^+ the strips'
quadrature of N*(a*), which falls short of it by O(dz^2) through the partial cell at z = a*
(the cap only within the first cell, where Q -> 0): on that scale
full sliding gives T* = N*(a*) to rounding (the gross-slip test |T*| >= (1 - 1e-6) N* sees it
as for an exact law) and |T*| <= N* holds. The normal force is the profile's N*(a*) of the
normal slot (:mod:`sawdrift.contact.slots`, which also handles contact entry and loss).

Adaptive growth: when a* exceeds the grid end N dz, the grid is coarsened (cells merged in
pairs, dz doubled) until it covers a*; the values on the new centroids are interpolated
linearly on the old diagram closed by v(a0) = 0. This costs some accuracy once, and is undone
(back to the initial dz) when contact is lost and the memory is empty anyway.

Cost O(strips in contact) per step, no allocation.

State layout (sizes from :func:`state_sizes`)
---------------------------------------------
This is the law's own state in the tangential slot. ``ts`` (float64), N = ``strips``: ``ts[0]``
current dz; then the blocks ``c`` = ``ts[1 : 1+N]`` (centroids), ``m`` = ``ts[1+N : 1+2N]``
(weights), ``v`` = ``ts[1+2N : 1+3N]`` (strip displacements) and ``ts[1+3N : 1+4N]`` scratch.

``is_`` (int64): ``is_[0]`` number of coarsenings of the current grid, ``is_[1]`` N (0 before the
first reset), ``is_[2]`` number of strips in contact (c_j < a*), ``is_[3]`` reserved.

``law`` (float64): the profile's normal-law descriptor (:mod:`sawdrift.contact.normal`; ``[p]``
for a power law); ``tp`` = ``[N, z_max]``.
"""

from __future__ import annotations

from numba import njit

from sawdrift.contact.normal import JIT_OPTIONS, law_normal, law_slope

from .mdr_quadrature import SCALE_CAP

HEADER = 1
"""Number of scalar slots at the start of ``ts`` (the current dz)."""
N_INT = 4
"""Size of ``is_``."""


def state_sizes(strips: int) -> tuple[int, int]:
    """Sizes of ``ts`` and ``is_`` for ``strips`` strips."""
    return HEADER + 4 * strips, N_INT


@njit(**JIT_OPTIONS, inline="always")
def _cell(j, dz, law):
    """Centroid c and weight m = dN*' of the cell [j dz, (j+1) dz]."""
    e0 = j * dz
    e1 = (j + 1) * dz
    d0 = law_slope(e0, law, 0)
    d1 = law_slope(e1, law, 0)
    m = d1 - d0
    if m > 0.0:
        # integral z dN*' over the cell, by parts: [z N*'] - [N*]
        c = (e1 * d1 - e0 * d0 - (law_normal(e1, law, 0) - law_normal(e0, law, 0))) / m
    else:
        c = 0.5 * (e0 + e1)
    return c, m


@njit(**JIT_OPTIONS)
def _grid(fs, nst, dz, law):
    """Fill centroids c_j and weights m_j of the cells [j dz, (j+1) dz]."""
    for j in range(nst):
        c, m = _cell(j, dz, law)
        fs[HEADER + j] = c
        fs[HEADER + nst + j] = m


@njit(**JIT_OPTIONS)
def _coarsen(fs, is_, a0, law):
    """Merge cells in pairs (dz doubled); interpolate the diagram onto the new centroids."""
    nst = is_[1]
    n_in = is_[2]
    ic = HEADER
    iv = HEADER + 2 * nst
    isc = HEADER + 3 * nst
    dz = 2.0 * fs[0]
    # new centroids into scratch first, to interpolate against the old ones
    for j in range(nst):
        fs[isc + j] = _cell(j, dz, law)[0]
    k = 0
    n_new = 0
    for j in range(nst):
        x = fs[isc + j]
        if n_in == 0 or x >= a0:
            fs[isc + j] = 0.0
            continue
        while k + 1 < n_in and fs[ic + k + 1] <= x:
            k += 1
        zl = fs[ic + k]
        vl = fs[iv + k]
        if k + 1 < n_in:
            zr = fs[ic + k + 1]
            vr = fs[iv + k + 1]
        else:
            zr = a0
            vr = 0.0
        if x <= zl or zr <= zl:
            val = vl
        else:
            val = vl + (vr - vl) * ((x - zl) / (zr - zl))
        fs[isc + j] = val
        n_new = j + 1
    for j in range(nst):
        fs[iv + j] = fs[isc + j]
    fs[0] = dz
    _grid(fs, nst, dz, law)
    is_[0] += 1
    is_[2] = n_new


@njit(**JIT_OPTIONS)
def mdr_reset(ts, is_, law, tp):
    """Every strip at rest on the initial grid (dz = z_max / N).

    The slots call it on a zeroed ``is_`` for a new history (everything is set up) and on the
    live state when contact is lost: then only the strips that were in contact are zeroed, and
    the grid is rebuilt only if it was coarsened.
    """
    nst = int(tp[0])
    iv = HEADER + 2 * nst
    regrid = True
    if is_[1] == nst:
        # contact lost: forget every strip in contact (the others are at rest)
        for j in range(is_[2]):
            ts[iv + j] = 0.0
        regrid = is_[0] > 0
    else:
        ts[:] = 0.0
        is_[1] = nst
        is_[3] = 0
    is_[2] = 0
    if regrid:
        ts[0] = tp[1] / nst
        _grid(ts, nst, ts[0], law)
        is_[0] = 0


@njit(**JIT_OPTIONS)
def mdr_step(ts, is_, law, tp, a0, b0, a, b):  # noqa: ARG001 - the slot signature
    """Advance all strips along the straight path (a0, b0) -> (a, b), commit, return T*.

    The tangential slot of :mod:`sawdrift.contact.slots` (which gives N* and handles contact
    entry and loss); ``a0 = 0`` is a new contact, every strip entering.
    """
    nst = is_[1]
    ic = HEADER
    im = HEADER + nst
    iv = HEADER + 2 * nst
    while a > nst * ts[0]:
        _coarsen(ts, is_, a0, law)
    db = b - b0
    n_old = is_[2]
    n_in = 0
    t = 0.0
    q = 0.0  # the strips' quadrature of N*(a*), sum m_j (a* - c_j)
    for j in range(nst):
        c = ts[ic + j]
        if c >= a:
            if j >= n_old:
                break
            ts[iv + j] = 0.0  # rule 1: the strip leaves contact and is forgotten
        else:
            if c < a0:
                v = ts[iv + j] + db  # rule 3: shift
            else:
                v = db * ((a - c) / (a - a0))  # rule 2: straight-path entry
            lim = a - c
            if v > lim:  # rule 4: local slip
                v = lim
            elif v < -lim:
                v = -lim
            ts[iv + j] = v
            t += ts[im + j] * v
            q += ts[im + j] * lim
            n_in = j + 1
    is_[2] = n_in
    if q > 0.0:
        # the quadrature falls short of N*(a*) by O(dz^2) (the partial cell at z = a*): T* on
        # the scale of N*, so that full sliding gives |T*| = N* to rounding (256 strips stopped
        # 1e-4 short, and gross slip was seen a third as often as by mmd); at most SCALE_CAP,
        # as N*/Q grows without bound just after the first strip enters (Q -> 0: an entry 67
        # times stiffer than the step is sized for, at a* = 1.01 c_0)
        t *= min(law_normal(a, law, 0) / q, SCALE_CAP)
    return t
