"""The compiled inner loops of the separated orbit (:mod:`.separated`, :mod:`.torus`).

At a fixed mean compression Y and mean speed V the heavy particle's fast parts are the periodic
solutions of

    m* eta'' = (1 - N*) - <1 - N*>          m* xi'' = -mu (T* - <T*>)

driven by the contact forces along the imposed motion they give (a contraction, iterated). Each
iteration runs the contact law over a few periods from an empty memory and integrates the
forces twice over one period in Fourier space: a period of K samples of acc has the
coefficients acc_f, and the zero-mean periodic q with q'' = acc - <acc> and its rate q' have

    q_f = -acc_f / w_f^2,     q'_f = i w_f q_f,     w_f = 2 pi f (f = 0, +-1, ..., K/2),

with q_0 = 0 and the rate's Nyquist coefficient (f = K/2) dropped (that of a real series is
not the rate of any real periodic function): the same operators as the matrices of
:func:`_operators`. Two real series a, b are transformed at once as a + i b: a real operator
(one with w_{-f} = -w_f) keeps a real series real, so the real and imaginary parts of the
result are the operator applied to a and to b.

This module holds those loops as templates, one call each, bound to a contact law's ``force``
and ``reset`` and compiled once per kernel and cached on disk (:mod:`sawdrift.codegen`, as
:func:`history_loop`): the fast-part iteration at fixed (Y, V) (:func:`fast_body`), the vertical
one at V = 0 (:func:`vertical_body`), the mean normal force on a given vertical fast part
(:func:`normal_mean_body`) and the friction force averaged over the nodes of a slow vertical
cycle (:func:`node_push_body`). The transforms are a radix-2 fast Fourier transform where K is
a power of two (the default samples per period, 128; K >= 8), else the direct sum. The python
engine runs the same loop templates as plain Python, with the transforms done by the matrices
of :func:`_operators` (numpy).
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np

from ..codegen import Generated, generate, rebind

#: rows of an orbit array (6, K): the fast parts, their rates, and N*, T* along them
ETA, ETA_D, XI, XI_D, NORMAL, TANGENTIAL = range(6)
ORBIT_ROWS = 6
#: rows of the imposed motion (5, K): the surface's u_x, u_x', u_y, u_y' and the sample times
UX, UX_D, UY, UY_D, TIME = range(5)
#: rows of the spectral tables (5, K): cos and sin of 2 pi m / K, -1 / w_f^2, w_f and the
#: bit-reversal permutation
COS, SIN, TWICE, ONCE, PERM = range(5)
#: entries of a problem's constants: m*, mu, 1 / (theta mu), periods per contact evaluation
#: and whether N* is the normal law's alone (1.0) or the contact law's (0.0)
PR_M, PR_MU, PR_SCALE_B, PR_PERIODS, PR_ALONE = range(5)
#: rows of the scratch array (10, K)
RE, IM, RE2, IM2, TRE, TIM, ACC_A, ACC_B, NEW_A, NEW_B = range(10)
WORK_ROWS = 10


@lru_cache(maxsize=8)
def _operators(k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The matrices that map K samples of one period of acc to the zero-mean periodic q with
    q'' = acc - <acc>, to q', and a periodic q to q' (Fourier, applied to the unit vectors once:
    a matrix product is cheaper than three transforms at these sizes in numpy)."""
    w = 2.0 * np.pi * np.fft.rfftfreq(k, d=1.0 / k)
    eye = np.eye(k)
    spec = np.fft.rfft(eye, axis=0)
    q_hat = np.zeros_like(spec)
    q_hat[1:] = -spec[1:] / (w[1:, None] ** 2)
    twice = np.fft.irfft(q_hat, n=k, axis=0)
    once = np.fft.irfft(1j * w[:, None] * q_hat, n=k, axis=0)
    rate = np.fft.irfft(1j * w[:, None] * spec, n=k, axis=0)
    return twice, once, rate


def _periodic(acc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The zero-mean periodic q and q' with q'' = acc - <acc> over one period of unit length."""
    twice, once, _ = _operators(acc.size)
    return twice @ acc, once @ acc


def _periodic_rate(q: np.ndarray) -> np.ndarray:
    """q' of a periodic q sampled over one period (Fourier)."""
    return _operators(q.size)[2] @ q


@lru_cache(maxsize=8)
def spectral_tables(k: int) -> np.ndarray:
    """The tables the compiled transforms read (rows :data:`COS`, :data:`SIN`, :data:`TWICE`,
    :data:`ONCE`, :data:`PERM`): cos and sin of 2 pi m / K, the factor -1 / w_f^2 of q'' = acc
    (0 at f = 0) and w_f of the rate (0 at f = 0 and at the Nyquist coefficient), f in FFT
    order, and for K a power of two the bit-reversed index of each sample."""
    f = np.arange(k)
    signed = np.where(f <= k // 2, f, f - k).astype(float)
    w = 2.0 * np.pi * signed
    tables = np.zeros((5, k))
    tables[COS] = np.cos(2.0 * np.pi * f / k)
    tables[SIN] = np.sin(2.0 * np.pi * f / k)
    tables[TWICE, 1:] = -1.0 / w[1:] ** 2
    tables[ONCE] = w
    if k % 2 == 0:
        tables[ONCE, k // 2] = 0.0
    bits = k.bit_length() - 1
    if k == 1 << bits:
        tables[PERM] = [int(format(i, f"0{bits}b")[::-1], 2) for i in range(k)]
    tables.setflags(write=False)
    return tables


# -- compiled templates: the transforms -------------------------------------------------------

def transform(re, im, spec, work, sign):
    """In place, the discrete Fourier transform sum_j (re_j + i im_j) exp(sign 2 pi i f j / K)
    (unnormalized; sign -1 forward, +1 inverse): radix-2 (Cooley and Tukey 1965) where K is a
    power of two, else the direct sum through the rows :data:`TRE`, :data:`TIM` of ``work``."""
    k = re.size
    if k & (k - 1) == 0:
        for i in range(k):  # into bit-reversed order
            j = int(spec[PERM, i])
            if i < j:
                re[i], re[j] = re[j], re[i]
                im[i], im[j] = im[j], im[i]
        for s in range(0, k, 4):  # the first two stages at once (twiddles 1 and sign i)
            r0 = re[s] + re[s + 1]
            i0 = im[s] + im[s + 1]
            r1 = re[s] - re[s + 1]
            i1 = im[s] - im[s + 1]
            r2 = re[s + 2] + re[s + 3]
            i2 = im[s + 2] + im[s + 3]
            r3 = -sign * (im[s + 2] - im[s + 3])
            i3 = sign * (re[s + 2] - re[s + 3])
            re[s] = r0 + r2
            im[s] = i0 + i2
            re[s + 2] = r0 - r2
            im[s + 2] = i0 - i2
            re[s + 1] = r1 + r3
            im[s + 1] = i1 + i3
            re[s + 3] = r1 - r3
            im[s + 3] = i1 - i3
        size = 8
        while size <= k:
            half = size // 2
            step = k // size
            for start in range(0, k, size):
                for m in range(half):
                    wr = spec[COS, m * step]
                    wi = sign * spec[SIN, m * step]
                    a = start + m
                    b = a + half
                    xr = re[b] * wr - im[b] * wi
                    xi = re[b] * wi + im[b] * wr
                    re[b] = re[a] - xr
                    im[b] = im[a] - xi
                    re[a] += xr
                    im[a] += xi
            size *= 2
        return
    for f in range(k):
        sr = 0.0
        si = 0.0
        for j in range(k):
            c = spec[COS, (f * j) % k]
            s = sign * spec[SIN, (f * j) % k]
            sr += re[j] * c - im[j] * s
            si += re[j] * s + im[j] * c
        work[TRE, f] = sr
        work[TIM, f] = si
    for f in range(k):
        re[f] = work[TRE, f]
        im[f] = work[TIM, f]


def periodic_pair(acc_a, acc_b, q_a, q_b, qd_a, qd_b, spec, work):
    """The zero-mean periodic q and q' with q'' = acc - <acc>, of two series at once."""
    k = acc_a.size
    re, im, re2, im2 = work[RE], work[IM], work[RE2], work[IM2]
    for j in range(k):
        re[j] = acc_a[j]
        im[j] = acc_b[j]
    transform(re, im, spec, work, -1.0)
    for f in range(k):
        qr = spec[TWICE, f] * re[f]
        qi = spec[TWICE, f] * im[f]
        re[f] = qr
        im[f] = qi
        re2[f] = -spec[ONCE, f] * qi
        im2[f] = spec[ONCE, f] * qr
    transform(re, im, spec, work, 1.0)
    transform(re2, im2, spec, work, 1.0)
    for j in range(k):
        q_a[j] = re[j] / k
        q_b[j] = im[j] / k
        qd_a[j] = re2[j] / k
        qd_b[j] = im2[j] / k


def periodic_one(acc, q, qd, spec, work):
    """:func:`periodic_pair` of one series: q and q' come out together as q + i q'."""
    k = acc.size
    re, im = work[RE], work[IM]
    for j in range(k):
        re[j] = acc[j]
        im[j] = 0.0
    transform(re, im, spec, work, -1.0)
    for f in range(k):
        qr = spec[TWICE, f] * re[f]
        qi = spec[TWICE, f] * im[f]
        re[f] = qr - spec[ONCE, f] * qr  # q + i q' = q + i (i w q)
        im[f] = qi - spec[ONCE, f] * qi
    transform(re, im, spec, work, 1.0)
    for j in range(k):
        q[j] = re[j] / k
        qd[j] = im[j] / k


def rates_pair(x_a, x_b, r_a, r_b, spec, work):
    """The rates x' of two periodic series."""
    k = x_a.size
    re, im = work[RE], work[IM]
    for j in range(k):
        re[j] = x_a[j]
        im[j] = x_b[j]
    transform(re, im, spec, work, -1.0)
    for f in range(k):
        xr = re[f]
        re[f] = -spec[ONCE, f] * im[f]
        im[f] = spec[ONCE, f] * xr
    transform(re, im, spec, work, 1.0)
    for j in range(k):
        r_a[j] = re[j] / k
        r_b[j] = im[j] / k


# -- the python engine's transforms (numpy), same signatures ----------------------------------

def _periodic_pair_numpy(acc_a, acc_b, q_a, q_b, qd_a, qd_b, spec, work):  # noqa: ARG001
    twice, once, _ = _operators(acc_a.size)
    q_a[:], qd_a[:] = twice @ acc_a, once @ acc_a
    q_b[:], qd_b[:] = twice @ acc_b, once @ acc_b


def _periodic_one_numpy(acc, q, qd, spec, work):  # noqa: ARG001
    twice, once, _ = _operators(acc.size)
    q[:], qd[:] = twice @ acc, once @ acc


def _rates_pair_numpy(x_a, x_b, r_a, r_b, spec, work):  # noqa: ARG001
    rate = _operators(x_a.size)[2]
    r_a[:], r_b[:] = rate @ x_a, rate @ x_b


# -- compiled templates: the contact law on the imposed motion, and the iterations ------------
#
# Their arguments: ``contact`` = (fs, is_, pp, npp), the contact memory's arrays and the normal
# law's parameters; ``prm`` the problem's constants (rows PR_*); ``tables`` = (motion, spec,
# work): the imposed motion (rows UX...), the spectral tables (rows COS...) and scratch rows.

def contact_periods(contact, y, v, prm, motion, orbit):
    """The contact law (``force``, ``reset``: globals bound per kernel) from an empty memory
    along ``prm[PR_PERIODS]`` periods of a* = Y + eta - u_y, b* = (V t* + xi - u_x) / (theta mu)
    and their rates (1 / (theta mu) = ``prm[PR_SCALE_B]``): N*, T* of the last period into the
    rows :data:`NORMAL`, :data:`TANGENTIAL` of ``orbit``; returns the largest change of T* from
    the period before (how far the memory is from repeating)."""
    fs, is_, pp, _npp = contact
    reset(fs, is_, pp)  # noqa: F821
    k = motion.shape[1]
    scale_b = prm[PR_SCALE_B]
    periods = int(prm[PR_PERIODS])
    db = v * scale_b
    change = 0.0
    for p in range(periods):
        for j in range(k):
            a = y + orbit[ETA, j] - motion[UY, j]
            b = (v * motion[TIME, j] + orbit[XI, j] - motion[UX, j]) * scale_b + p * db
            adot = orbit[ETA_D, j] - motion[UY_D, j]
            bdot = (v + orbit[XI_D, j] - motion[UX_D, j]) * scale_b
            n, t = force(fs, is_, pp, a, b, adot, bdot)  # noqa: F821
            if p == periods - 1:
                d = abs(t - orbit[TANGENTIAL, j])
                if d > change:
                    change = d
            orbit[NORMAL, j] = n
            orbit[TANGENTIAL, j] = t
    return change


def fast_body(contact, y, v, prm, tables, orbit, iterations, tol):
    """The fast parts at fixed (Y, V) iterated to their periodic solution from eta, xi in
    ``orbit`` (their rates are taken first): at most ``iterations`` times the contact law and
    the two integrations, until eta and xi change by at most ``tol`` max(1, |Y|), then the
    contact law once more on the result. ``orbit`` ends on eta, eta', xi, xi', N*, T*; returns
    the contact evaluations and the last one's change of T* (:func:`contact_periods`)."""
    motion, spec, work = tables
    k = motion.shape[1]
    m = prm[PR_M]
    mu = prm[PR_MU]
    rates_pair(orbit[ETA], orbit[XI], orbit[ETA_D], orbit[XI_D], spec, work)
    bound = tol * max(1.0, abs(y))
    count = 0
    for _ in range(iterations):
        contact_periods(contact, y, v, prm, motion, orbit)
        count += 1
        for j in range(k):
            work[ACC_A, j] = (1.0 - orbit[NORMAL, j]) / m
            work[ACC_B, j] = -mu * orbit[TANGENTIAL, j] / m
        periodic_pair(work[ACC_A], work[ACC_B], work[NEW_A], work[NEW_B], orbit[ETA_D],
                      orbit[XI_D], spec, work)
        change = 0.0
        for j in range(k):
            change = max(change, abs(work[NEW_A, j] - orbit[ETA, j]),
                         abs(work[NEW_B, j] - orbit[XI, j]))
            orbit[ETA, j] = work[NEW_A, j]
            orbit[XI, j] = work[NEW_B, j]
        if change <= bound:
            break
    residual = contact_periods(contact, y, v, prm, motion, orbit)
    return count + 1, residual


def row_mean(row):
    """The mean of one row of samples, summed in a plain loop: numpy's mean in a compiled loop
    makes every process that loads it from the disk cache import numba's array-math and linear
    algebra (and with them scipy.linalg): 0.45 s before a worker's first heavy cell, measured on
    the benchmarks' 2-core machine."""
    total = 0.0
    for v in row:
        total += v
    return total / row.size


def normal_mean_body(contact, y, prm, motion, orbit):
    """<N*> over the last period at rest horizontally (V = 0, xi = 0: the rows :data:`XI`,
    :data:`XI_D` of ``orbit`` are zero) on the vertical fast part eta, eta' in ``orbit``, N*
    into its row :data:`NORMAL`. Where ``prm[PR_ALONE]`` the contact law's N* is its normal
    law's (``normal``, a global bound per kernel, reading ``npp``), which keeps no memory: one
    period of it is the last period's N* (a* repeats every period); else the contact law runs."""
    if prm[PR_ALONE] == 0.0:
        contact_periods(contact, y, 0.0, prm, motion, orbit)
        return row_mean(orbit[NORMAL])
    fs, is_, _pp, npp = contact
    for j in range(motion.shape[1]):
        a = y + orbit[ETA, j] - motion[UY, j]
        adot = orbit[ETA_D, j] - motion[UY_D, j]
        n, _t = normal(fs, is_, npp, a, 0.0, adot, 0.0)  # noqa: F821
        orbit[NORMAL, j] = n
    return row_mean(orbit[NORMAL])


def vertical_body(contact, y, prm, tables, orbit, iterations):
    """``iterations`` steps of the vertical fast part at Y and rest (V = 0, xi = 0): N* on eta,
    eta' in ``orbit`` (:func:`normal_mean_body`), then eta, eta' of
    m* eta'' = (1 - N*) - <1 - N*> in their place; returns <N*> of the last step."""
    motion, spec, work = tables
    m = prm[PR_M]
    mean = 0.0
    for _ in range(iterations):
        mean = normal_mean_body(contact, y, prm, motion, orbit)
        for j in range(motion.shape[1]):
            work[ACC_A, j] = (1.0 - orbit[NORMAL, j]) / m
        periodic_one(work[ACC_A], orbit[ETA], orbit[ETA_D], spec, work)
    return mean


def node_push_body(contact, heights, weights, v, prm, tables, nodes, sweeps):
    """-sum_j w_j <T*>_j over the nodes of a slow vertical cycle at speed V: at each node j
    (mean compression ``heights[j]``, orbit array ``nodes[j]`` holding its vertical fast part)
    ``sweeps`` steps of the horizontal fast part from the xi, xi' it holds (the contact law,
    then xi, xi' of m* xi'' = -mu (T* - <T*>)), <T*> of the last contact evaluation."""
    motion, spec, work = tables
    ratio = -prm[PR_MU]
    m = prm[PR_M]
    total = 0.0
    for j in range(heights.size):
        orbit = nodes[j]
        for _ in range(sweeps):
            contact_periods(contact, heights[j], v, prm, motion, orbit)
            for i in range(motion.shape[1]):
                work[ACC_B, i] = ratio * orbit[TANGENTIAL, i] / m
            periodic_one(work[ACC_B], orbit[XI], orbit[XI_D], spec, work)
        total += weights[j] * row_mean(orbit[TANGENTIAL])
    return -total


_TEMPLATES = (contact_periods, fast_body, normal_mean_body, vertical_body, node_push_body)
_TRANSFORMS = (transform, periodic_pair, periodic_one, rates_pair, row_mean)
_NUMPY_TRANSFORMS = {"periodic_pair": _periodic_pair_numpy, "periodic_one": _periodic_one_numpy,
                     "rates_pair": _rates_pair_numpy}
_CONSTANTS = ("ETA", "ETA_D", "XI", "XI_D", "NORMAL", "TANGENTIAL", "UX", "UX_D", "UY", "UY_D",
              "TIME", "COS", "SIN", "TWICE", "ONCE", "PERM", "RE", "IM", "RE2", "IM2", "TRE", "TIM",
              "ACC_A", "ACC_B", "NEW_A", "NEW_B", "PR_M", "PR_MU", "PR_SCALE_B", "PR_PERIODS",
              "PR_ALONE")
_IMPORTS = ("import numpy as np  # noqa: F401\n"
            f"from sawdrift.dynamics.fast_parts import {', '.join(_CONSTANTS)}  # noqa: F401\n")
_LOOPS: dict[Any, dict[str, Any]] = {}


def normal_alone(history: Any, compiled: bool) -> tuple[Any, np.ndarray, bool]:
    """``(normal, npp, alone)`` for :func:`normal_mean_body`: the normal law of a contact
    history's model and its parameters, where the model is composed of slots
    (:class:`~sawdrift.contact.slots.TangentialLaw`: its N* is the normal slot's, with the
    normal-damping slot's, bit for bit, and no memory); else the contact law (not alone)."""
    from ..contact.slots import TangentialLaw

    model = history.model
    if not isinstance(model, TangentialLaw):
        force, _fs, _is, pp = history.kernel_call()
        return force, pp, False
    normal, npp = model.normal_law()
    return (normal if compiled else normal.py_func), npp, True


def fast_loops(force: Any, reset: Any, normal: Any, compiled: bool) -> dict[str, Any]:
    """The loop templates bound to a contact law's ``force`` and ``reset`` (the kernel's, with
    :meth:`~sawdrift.contact.history.ContactHistory.kernel_call`'s arrays) and its ``normal``
    law (:func:`normal_alone`), by name: compiled once per kernel and cached on disk across
    processes (:mod:`sawdrift.codegen`), or plain Python with numpy's transforms."""
    names = {name: globals()[name] for name in _CONSTANTS}
    namespace = {"np": np, "force": force, "reset": reset, "normal": normal, **names}
    if not compiled:
        return rebind(_TEMPLATES, {**namespace, **_NUMPY_TRANSFORMS, "row_mean": row_mean})
    key = (force, reset, normal)
    loops = _LOOPS.get(key)
    if loops is None:
        loops = generate(Generated(
            prefix="sawdrift_loop_", doc="the separated orbit's fast parts bound to a contact law",
            templates=_TRANSFORMS + _TEMPLATES, namespace=namespace, imports=_IMPORTS,
            bind={"force": force, "reset": reset, "normal": normal},
            decorator="njit(cache=True, _nrt=False)", memory_options={"_nrt": False},
        ))
        _LOOPS[key] = loops
    return loops
