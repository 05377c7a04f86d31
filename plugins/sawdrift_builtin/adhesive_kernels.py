"""Adhesive tangential steps of the built-in laws (the protocol of
:mod:`sawdrift.contact.adhesion_kernels`): the DEM spring and the memory diagram.

Both give the tangential stiffness of Mindlin's 8 G* c with c the adhesive contact radius
(normalized dT*/db* = 1.5 c*) and slide at |T*| = ``cap`` = |N* + 2 F*_pull|, as LAMMPS
``pair granular`` ``jkr``/``dmt`` with ``tangential mindlin_rescale/force`` do. Imported on
first use.
"""

from __future__ import annotations

import math

from numba import njit

from sawdrift.contact.normal import JIT_OPTIONS

from .mmd_kernel import mmd_reset, mmd_step


@njit(**JIT_OPTIONS)
def dem_adhesive_step(ts, is_, law, tp, a0, b0, a, b, c0, c1, cap):  # noqa: ARG001
    """The DEM spring on the adhesive contact: LAMMPS ``mindlin_rescale/force``'s update.

    T* <- T* c1/c0 while the contact shrinks (``tp[0]`` = rescale), T* += 1.5 c1 (b - b0), then
    clipped to [-cap, cap] (the stiffness at the step's end, as LAMMPS takes it).
    """
    t = ts[0]
    if tp[0] != 0.0 and c1 < c0:
        t *= c1 / c0
    t += 1.5 * c1 * (b - b0)
    if t > cap:
        t = cap
    elif t < -cap:
        t = -cap
    ts[0] = t
    return t


#: floats the adhesive memory diagram keeps in front of the diagram's own state
MMD_EXTRA = 2


@njit(**JIT_OPTIONS)
def mmd_adhesive_step(ts, is_, law, tp, a0, b0, a, b, c0, c1, cap):  # noqa: ARG001
    """The memory diagram of the equivalent Hertz contact (``mmd``'s adhesive assumption).

    The adhesive contact is taken to slip as the Hertz contact whose full-sliding force is its
    own, N_H(a_e) = a_e^(3/2) = cap, and whose initial stiffness is its own, 1.5 c*: the diagram
    runs in (a_e, b') with a_e = cap^(2/3) and db' = lambda db, lambda = c* / sqrt(a_e)
    (trapezoidal in the step). ``ts[0]``, ``ts[1]``: committed b', a_e; the diagram follows.
    """
    ae = cap ** (2.0 / 3.0)
    lam1 = c1 / math.sqrt(ae)
    if a0 == 0.0:
        # a new contact: the diagram starts empty (a_e0 = 0), the origin of b' anywhere
        bp0 = 0.0
        ae0 = 0.0
        lam0 = lam1
    else:
        bp0 = ts[0]
        ae0 = ts[1]
        lam0 = c0 / math.sqrt(ae0)
    bp = bp0 + 0.5 * (lam0 + lam1) * (b - b0)
    t, n = mmd_step(ts[MMD_EXTRA:], is_, law, tp, ae0, bp0, ae, bp)
    ts[0] = bp
    ts[1] = ae
    return t


@njit(**JIT_OPTIONS)
def mmd_adhesive_reset(ts, is_, law, tp):
    """Empty history: b' and a_e zero, the diagram's own reset."""
    ts[0] = 0.0
    ts[1] = 0.0
    mmd_reset(ts[MMD_EXTRA:], is_, law, tp)
