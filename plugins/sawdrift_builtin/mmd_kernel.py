"""Compiled step of the Method of Memory Diagrams (MMD): amortized O(1) per step.

Implements the normalized tangential law of docs/physics.md, "Contact laws" (Aleshin, Bou Matar
and Van Den Abeele 2015, "Method of memory diagrams for mechanical frictional contacts subject
to arbitrary 2D loading", Int. J. Solids Struct. 60-61, 84-95; the elementary partial-slip
solutions are those of Mindlin & Deresiewicz 1953) as the tangential step :func:`mmd_step` of the
contact slots (:mod:`sawdrift.contact.slots`), which keep the committed (a*, b*) and handle contact
entry and loss; the step hands N*(a*), stored with its top kink, back with T*. The composed
contact is ``MemoryDiagramModel.kernel`` (:mod:`sawdrift_builtin.mmd`).
The normal law is the profile's, given by its descriptor ``law``
(:mod:`sawdrift.contact.normal`): a power law N*(a*) = a*^p, with
N*'(z) = p z^(p-1) for z > 0 and, by convention, N*'(0-) = 0 (the flat punch, p = 1, carries a
point mass of dN*' at z = 0), or a tabulated law.

Memory diagram as a stack
-------------------------
The strip displacement v(z) on [0, a*] is piecewise linear; its kinks (the memory points) are
stored as a stack ordered by level, z = 0 at the bottom and z = a* at the top. Values are kept
relative to a global offset, v = w + offset, so the uniform shift by delta b* costs one addition.
Each kink also keeps the prefix integral C_i = integral_[0, z_i] w dN*'(z), so

    T* = C_top + offset * N*'(a*)

(the total measure of [0, a*] is N*'(a*), point mass included), and N*'(z_i) and N*(z_i), so
that a push costs one evaluation of the law at the new level only (for a power law one power:
N*(z) = z N*'(z) / p). For a linear piece of w from (z1, w1) to (z2, w2) the Stieltjes integral is

    w2 N*'(z2) - w1 N*'(z1) - (w2 - w1) (N*(z2) - N*(z1)) / (z2 - z1).

All the work of a step happens at the top of the stack:

* contact shrinks (a1 < a0): kinks with z >= a1 are popped and the top is re-set to the
  interpolated value at a1 (rule 1);
* the shift by delta b* is ``offset += db`` (rule 3);
* contact grows (a1 > a0): the old top (a0, v = db) and a new kink (a1, v = 0) bound exactly the
  straight-path entry profile v(z) = db (a1 - z) / (a1 - a0) (rule 2);
* clipping to |v| <= a1 - z (rule 4): because |dv/dz| <= 1 the slack of each bound is monotone
  in z, so the violated set is a suffix ending at z = a1 and only one bound can be violated in a
  step. Violating kinks are popped, one kink is pushed where the diagram crosses the bound, and
  the top becomes (a1, 0). End-of-step clipping is exact for a straight path because each
  strip's slack is linear in the path parameter.

A kink collinear (to rounding) with the two below it moves the top instead of being pushed, so
pure normal loading and proportional loading keep O(1) points. Every kink is pushed once and
popped once, so a step costs O(1) amortized, independently of the history length, and nothing is
allocated. A drifting run makes the offset grow without bound; when
``|offset| > REBASE_LIMIT * max(1, a*)`` the values are re-based (w += offset, offset = 0, prefix
integrals recomputed). A kink that survived from one re-base to the next would have been shifted
by more than 2 a*, which the bounds forbid, so the O(kinks) re-base is amortized O(1) per push.

State layout (sizes from :func:`state_sizes`)
---------------------------------------------
This is the law's own state in the tangential slot (:mod:`sawdrift.contact.slots`), which keeps
the committed (a*, b*) and handles contact entry and loss in front of it. ``ts`` (float64),
capacity ``cap = (ts.size - HEADER) // RECORD``:

========================  ===================================================================
``ts[0]``                 offset (v = w + offset)
``ts[1 + 5i + 0]``        z_i, level of kink i (i = 0 at the bottom, z_0 = 0)
``ts[1 + 5i + 1]``        w_i, value relative to the offset
``ts[1 + 5i + 2]``        C_i, prefix integral of w dN*' over [0, z_i]
``ts[1 + 5i + 3]``        N*'(z_i) (0 at z = 0)
``ts[1 + 5i + 4]``        N*(z_i)
========================  ===================================================================

``is_`` (int64): ``is_[0]`` number of kinks (0 when out of contact), ``is_[1]`` high-water mark
of the kink count, ``is_[2]`` number of re-bases, ``is_[3]`` capacity.

``law`` (float64): the normal-law descriptor (``[p]`` for a power law); ``tp`` is empty.

If the capacity is exceeded, :class:`MemoryCapacityError` is raised and the history is invalid.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from sawdrift.contact.normal import JIT_OPTIONS, law_normal, law_slope
from sawdrift.contact.slots import HEADER as SLOT_HEADER
from sawdrift.contact.slots import gives_normal
from sawdrift.errors import SawdriftError

HEADER = 1
"""Number of scalar slots at the start of ``ts`` (the offset)."""
RECORD = 5
"""Float64 slots per kink: z, w, C, N*'(z), N*(z)."""
N_INT = 4
"""Size of ``is_``."""
REBASE_LIMIT = 64.0
"""Re-base the offset when it exceeds this many times max(1, a*)."""
COLLINEAR_RTOL = 4.0 * 2.220446049250313e-16
"""A pushed kink moves the top along its line when the top lies on it to this tolerance."""
class MemoryCapacityError(SawdriftError, RuntimeError):
    """The memory diagram needs more points than ``max_memory_points`` allows."""


@njit(**JIT_OPTIONS)
def live_floats(fs, is_):  # noqa: ARG001 - the live-size signature
    """The floats of ``fs`` that hold the memory (the slots' header, this law's header and its
    stored points): :meth:`MemoryDiagramModel.live_sizes`, compiled."""
    return SLOT_HEADER + HEADER + RECORD * is_[0]


def state_sizes(max_memory_points: int) -> tuple[int, int]:
    """Sizes of ``ts`` and ``is_`` for a stack of ``max_memory_points`` kinks."""
    return HEADER + RECORD * max_memory_points, N_INT


@njit(**JIT_OPTIONS, inline="always")
def _segment(z1, w1, d1, n1, z2, w2, d2, n2) -> float:
    """Stieltjes integral of the linear piece (z1, w1)-(z2, w2) against dN*' (docs/physics.md).

    ``d1``, ``d2`` are N*'(z1), N*'(z2) and ``n1``, ``n2`` are N*(z1), N*(z2): by parts,
    [w N*'] - (dw/dz) [N*]. A zero-length piece contributes 0.
    """
    dz = z2 - z1
    out = 0.0
    if dz > 0.0:
        out = w2 * d2 - w1 * d1 - (w2 - w1) * ((n2 - n1) / dz)
    return out


@njit(**JIT_OPTIONS, inline="always")
def _normal_at(z, d, pp):
    """N*(z) given N*'(z) = d: z d / p for a power law (no power taken), else the table.

    The same rounding as :func:`~sawdrift.contact.normal.law_normal`, the normal slot's N*.
    """
    p = pp[0]
    out = 0.0
    if p > 0.0:
        out = z * d / p
    else:
        out = law_normal(z, pp, 0)
    return out


@njit(**JIT_OPTIONS, inline="always")
def _write(fs, k, z, w, d, pp):
    """Store kink (z, w, N*'(z) = d, N*(z)) in record slot k and its prefix integral."""
    r = HEADER + RECORD * k
    nz = _normal_at(z, d, pp)
    fs[r] = z
    fs[r + 1] = w
    fs[r + 3] = d
    fs[r + 4] = nz
    if k == 0:
        fs[r + 2] = 0.0
    else:
        q = r - RECORD
        fs[r + 2] = fs[q + 2] + _segment(fs[q], fs[q + 1], fs[q + 3], fs[q + 4], z, w, d, nz)


@njit(**JIT_OPTIONS, inline="always")
def _push(fs, n, cap, z, w, pp):
    """Push the kink (z, w) on the stack of ``n`` kinks (capacity ``cap``); the new count.

    A level not above the top only replaces the top's value (v is continuous, so the two agree
    to rounding); a kink collinear with the two below it moves the top instead of stacking.
    Two writes, not one per case: numba's inlining copies an inlined body once per call site,
    and the step is itself inlined into the contact slots. The count lives in a register for
    the whole step (the step stores it once).
    """
    r = HEADER + RECORD * (n - 1)  # top record
    if n > 0 and z <= fs[r]:
        _write(fs, n - 1, fs[r], w, fs[r + 3], pp)
    else:
        k = n  # push, or n - 1: move the top along its line
        if n >= 2:
            z1 = fs[r - RECORD]
            w1 = fs[r - RECORD + 1]
            # |w_line(z_top) - w_top| <= tol (|w1| + |w|), multiplied through by z - z1 > 0
            # (no division on the hot path)
            dev = (w1 - fs[r + 1]) * (z - z1) + (w - w1) * (fs[r] - z1)
            if abs(dev) <= COLLINEAR_RTOL * (abs(w1) + abs(w)) * (z - z1):
                k = n - 1
        if k == n:
            if n >= cap:
                raise MemoryCapacityError(
                    "mmd: the memory diagram is full; raise the model parameter max_memory_points"
                )
            n += 1
        _write(fs, k, z, w, law_slope(z, pp, 0), pp)
    return n


@njit(**JIT_OPTIONS, inline="always")
def _clip(fs, n, cap, a, offset, s, pp):
    """Clip the suffix that violates s v(z) <= a - z (s = +1 upper, -1 lower bound).

    Pops the violating kinks and pushes the crossing of the diagram with the bound; the caller
    then pushes the end kink (a, v = 0). Returns the new count of kinks.
    """
    zp = a
    gp = 0.0
    while n > 0:
        r = HEADER + RECORD * (n - 1)
        g = s * (fs[r + 1] + offset) - (a - fs[r])
        if g > 0.0:
            zp = fs[r]
            gp = g
            n -= 1
        else:
            break
    # n = 0: the whole diagram slides, v = s (a - z) from z = 0
    cross = n == 0
    zx = 0.0
    wx = s * a - offset
    if n > 0:
        r = HEADER + RECORD * (n - 1)
        zj = fs[r]
        gj = s * (fs[r + 1] + offset) - (a - zj)
        if gj < 0.0:
            zx = zj + (zp - zj) * (-gj / (gp - gj))
            if zx > zj:
                cross = True
                wx = s * (a - zx) - offset
    if cross:
        n = _push(fs, n, cap, zx, wx, pp)
    return n


@njit(**JIT_OPTIONS)
def _rebase(fs, is_, pp):
    """Fold the offset into the stored values and recompute the prefix integrals."""
    offset = fs[0]
    for k in range(is_[0]):
        r = HEADER + RECORD * k
        fs[r + 1] += offset
        _write(fs, k, fs[r], fs[r + 1], fs[r + 3], pp)
    fs[0] = 0.0
    is_[2] += 1


@njit(**JIT_OPTIONS)
def mmd_reset(ts, is_, law, tp):  # noqa: ARG001 - the slot signature
    """Empty diagram: no memory points, zero offset.

    The slots call it on a zeroed ``is_`` for a new history and on the live state when contact
    is lost; the high-water mark and the re-base count then carry over.
    """
    ts[0] = 0.0
    is_[0] = 0
    is_[3] = (ts.shape[0] - HEADER) // RECORD


@gives_normal
@njit(**JIT_OPTIONS)
def mmd_step(ts, is_, law, tp, a0, b0, a, b):  # noqa: ARG001 - the slot signature
    """Advance the diagram along the straight path (a0, b0) -> (a, b), commit, return (T*, N*).

    The tangential slot of :mod:`sawdrift.contact.slots` (which handles contact entry and
    loss): ``a0 = 0`` is a new contact, which starts from the point diagram at z = 0 on an empty
    stack. N* = N*(a*) is the top kink's (z = a*), which the step has just written: the normal
    slot's N*(a*) bit for bit (:func:`_normal_at`), so the slots take it from here
    (:func:`~sawdrift.contact.slots.gives_normal`) instead of evaluating the law again.
    """
    n = is_[0]
    if a0 == 0.0:
        # a new contact (the stack is empty): the point diagram, one kink (z, w) = (0, 0) with
        # C = N*' = N* = 0
        for i in range(HEADER, HEADER + RECORD):
            ts[i] = 0.0
        n = 1
    cap = is_[3]
    offset = ts[0] + (b - b0)
    ts[0] = offset
    if a < a0:
        # strips z >= a leave contact: pop them, re-set the top at z = a by interpolation
        while n >= 2 and ts[HEADER + RECORD * (n - 2)] >= a:
            n -= 1
        r = HEADER + RECORD * (n - 1)
        z1 = ts[r - RECORD]
        w1 = ts[r - RECORD + 1]
        wa = w1 + (ts[r + 1] - w1) * ((a - z1) / (ts[r] - z1))
        # the top's level, value and N*'; its prefix integral and N* are written by the push at
        # z = a below, which replaces the top's value (or the clip pops it first)
        ts[r] = a
        ts[r + 1] = wa
        ts[r + 3] = law_slope(a, law, 0)
    r = HEADER + RECORD * (n - 1)
    vt = ts[r + 1] + offset
    slack = a - ts[r] if ts[r] < a else 0.0
    s = 0.0  # the bound the top violates (rule 4): +1 upper, -1 lower, 0 none
    if vt > slack:
        s = 1.0
    elif -vt > slack:
        s = -1.0
    if s != 0.0:
        n = _clip(ts, n, cap, a, offset, s, law)
    n = _push(ts, n, cap, a, -offset, law)
    # pops come before pushes in a step, so its last count is its largest
    is_[0] = n
    if n > is_[1]:
        is_[1] = n
    if abs(offset) > REBASE_LIMIT * max(1.0, a):
        _rebase(ts, is_, law)
        offset = 0.0
    r = HEADER + RECORD * (n - 1)
    return ts[r + 2] + offset * ts[r + 3], ts[r + 4]


def memory_points(ts: np.ndarray, is_: np.ndarray) -> np.ndarray:
    """The stored kinks of the law's state ``ts`` as a (k, 2) array of (z, v), bottom first."""
    n = int(is_[0])
    rec = ts[HEADER : HEADER + RECORD * n].reshape(n, RECORD)
    return np.column_stack([rec[:, 0], rec[:, 1] + ts[0]])
