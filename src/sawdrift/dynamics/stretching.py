"""The Lyapunov estimate's twin integration in one compiled call per stretch of periods.

The estimate (:func:`~sawdrift.dynamics.window.stretching_logs`; Benettin et al. 1980) advances a
copy of the run and a twin displaced by d0 one period at a time, logs ln(d / d0) and puts the twin
back on the copy at distance d0 along the separation, every period. Done from Python that is two
loop calls and a restart of the twin per period, which cost about 30 us against 8 us for the two
periods' steps themselves (mmd, m* = 0.032, A* = 7.1: 39 us a period, measured on the benchmarks'
2-core machine), and a bouncing cell's estimate runs 72 to 264 periods, more than its own window.
:func:`stretch_body` does the same periods in one compiled call: the copy's and the twin's loop
calls, the restart (state, integrator history, counters, window statistics, and the contact
memory's live part, :meth:`~sawdrift.contact.base.ContactModel.compiled_live_floats`), the
separation and its log, bit for bit what the Python loop computes (tests/test_twin_restart.py);
the rigid scheme's loop the same way (:func:`stretch_rigid_body`). The python engine keeps the
Python loop.

The event logs of both are emptied every period (no event of the copy or of the twin is read
back); a period that fills one, or a state the loop marks bad, ends the call with its status and
the caller runs the estimate in Python instead, where the log grows and the error is raised.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from ..codegen import Generated, generate
from . import evidence as ev
from .lyapunov import LYAPUNOV_PERIODS, verdict_clear
from .records import NO_ROWS

#: what :func:`stretch_body` ended with (``status[0]``; ``status[1]`` the period it ended at)
DONE, ERASED, FALLBACK = 0, 1, 2

#: a contact memory copied whole every period at most this long (floats) where its model has no
#: compiled live size: longer ones stay with the Python loop
WHOLE_COPY_FLOATS = 4096

_N_ST, _S_FLY, _S_NEV, _S_EVCAP, _EV_W = ev.N_ST, ev.S_FLY, ev.S_NEV, ev.S_EVCAP, ev.EV_W
_S_BAD, _S_EVDROP = ev.S_BAD, ev.S_EVDROP


@njit(cache=True, _nrt=False)
def whole_floats(fs, is_):  # noqa: ARG001 - the live-size signature
    """A contact memory whose live part is all of it."""
    return fs.size


def put_back(base, twin, dy):
    """The twin's state, step counters and window statistics put on the copy's, the state
    displaced by ``dy``, the event log emptied: ``base``, ``twin`` = (y, ctr, st)."""
    by, bctr, bst = base
    ty, tctr, tst = twin
    for i in range(by.size):
        ty[i] = by[i]
    for i in range(1, 4):
        ty[i] += dy[i]
    for i in range(tctr.size):
        tctr[i] = bctr[i]
    for i in range(_N_ST):
        tst[i] = bst[i]
    tst[_S_FLY] = 0.0  # displaced off its flight's parabola: it counts afresh
    tst[_S_EVCAP] = (tst.size - _N_ST) // _EV_W


def stretched(base, twin, target, j, span, displace, out):
    """After period ``j`` of both: the separation's log into ``logs[j - align]`` and the next
    displacement into dy; False (``status`` set) where the period did not end at ``target``
    steps, a loop marked its state bad or dropped events (:data:`FALLBACK`), or the separation
    was erased (:data:`ERASED`). ``base``, ``twin`` = (y, ctr, st)."""
    by, bctr, bst = base
    ty, tctr, tst = twin
    align = span[3]
    d0, u, dy = displace
    logs, status = out
    if (bctr[0] != target or tctr[0] != target or bst[_S_BAD] > 0.0 or tst[_S_BAD] > 0.0
            or bst[_S_EVDROP] > 0.0 or tst[_S_EVDROP] > 0.0):
        status[0] = FALLBACK
        status[1] = j
        return False
    s0 = (ty[1] - by[1]) / u[0]
    s1 = (ty[2] - by[2]) / u[1]
    s2 = (ty[3] - by[3]) / u[2]
    d = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
    if not d > 0.0:
        status[0] = ERASED
        status[1] = j
        return False
    if j >= align:
        logs[j - align] = math.log(d / d0)
    dy[1] = s0 * (d0 / d) * u[0]
    dy[2] = s1 * (d0 / d) * u[1]
    dy[3] = s2 * (d0 / d) * u[2]
    return True


def stretch_body(base, twin, drive, span, displace, out):
    """Periods j0 to j1 of the stretchings on the compliant loop: before each but the first the
    twin is put on the copy (:func:`put_back`, then its integrator history and the live part of
    its contact memory, ``live`` a global bound per model), displaced by dy (scaled
    (x*', y*, y*') times d0 along the last separation); both advance one period (``wave``, the
    run's loop, a global bound per loop); :func:`stretched` logs the separation.

    ``base`` and ``twin`` are (y, fh, ctr, (fs, is_, pp), st); ``drive`` = (prm, dp, rec) of the
    loop; ``span`` = (k_per, j0, j1, align); ``displace`` = (d0, u, dy), u the state scale
    (x*', y*, y*'); ``out`` = (logs, status). ``status`` gets (:data:`DONE`, j1),
    (:data:`ERASED`, j) where the separation was erased at period j, or (:data:`FALLBACK`, j)
    where a loop filled its event log or marked its state bad."""
    prm, dp, rec = drive
    k_per, j0, j1, _align = span
    by, bfh, bctr, bcontact, bst = base
    ty, tfh, tctr, tcontact, tst = twin
    bfs, bis, _bpp = bcontact
    tfs, tis, _tpp = tcontact
    for j in range(j0, j1):
        if j:
            put_back((by, bctr, bst), (ty, tctr, tst), displace[2])
            for r in range(bfh.shape[0]):
                for c in range(bfh.shape[1]):
                    tfh[r, c] = bfh[r, c]
            for i in range(live(bfs, bis)):  # noqa: F821
                tfs[i] = bfs[i]
            for i in range(bis.size):
                tis[i] = bis[i]
        tst[_S_NEV] = 0.0
        bst[_S_NEV] = 0.0
        target = bctr[0] + k_per
        bctr[2] = 0
        wave(by, bfh, bctr, bcontact, prm, dp, k_per, rec, 0, bst)  # noqa: F821
        tctr[2] = 0
        wave(ty, tfh, tctr, tcontact, prm, dp, k_per, rec, 0, tst)  # noqa: F821
        if not stretched((by, bctr, bst), (ty, tctr, tst), target, j, span, displace, out):
            return
    out[1][0] = DONE
    out[1][1] = j1


def stretch_rigid_body(base, twin, drive, span, displace, out):
    """:func:`stretch_body` on the rigid scheme's loop (``wave``, bound per drive): ``base`` and
    ``twin`` are (y, ctr, st), ``drive`` = (prm, rec); the material point keeps no contact
    memory and no integrator history."""
    prm, rec = drive
    k_per, j0, j1, _align = span
    by, bctr, bst = base
    ty, tctr, tst = twin
    for j in range(j0, j1):
        if j:
            put_back(base, twin, displace[2])
        tst[_S_NEV] = 0.0
        bst[_S_NEV] = 0.0
        target = bctr[0] + k_per
        bctr[2] = 0
        wave(by, bctr, prm, k_per, rec, 0, bst)  # noqa: F821
        tctr[2] = 0
        wave(ty, tctr, prm, k_per, rec, 0, tst)  # noqa: F821
        if not stretched(base, twin, target, j, span, displace, out):
            return
    out[1][0] = DONE
    out[1][1] = j1


_LOOPS: dict[Any, Any] = {}


def stretch_loop(stepper: Any) -> Any | None:
    """:func:`stretch_body` (:func:`stretch_rigid_body` for the rigid scheme) bound to
    ``stepper``'s loop and its contact memory's live size, compiled once per loop and cached on
    disk (:mod:`sawdrift.codegen`); None where the Python loop runs instead: the python engine,
    or a long memory with no compiled live size."""
    if not stepper.compiled:
        return None
    live = None
    if stepper.rigid:
        body = stretch_rigid_body
    else:
        body = stretch_body
        if stepper.history is not None:
            live = stepper.history.model.compiled_live_floats()
        if live is None:
            if stepper.fs.size > WHOLE_COPY_FLOATS:
                return None
            live = whole_floats
    key = (stepper.loop, live)
    fn = _LOOPS.get(key)
    if fn is None:
        names = {"_N_ST": _N_ST, "_S_FLY": _S_FLY, "_S_NEV": _S_NEV, "_S_EVCAP": _S_EVCAP,
                 "_EV_W": _EV_W, "_S_BAD": _S_BAD, "_S_EVDROP": _S_EVDROP, "DONE": DONE,
                 "ERASED": ERASED, "FALLBACK": FALLBACK}
        bind = {"wave": stepper.loop} if live is None else {"wave": stepper.loop, "live": live}
        fn = generate(Generated(
            prefix="sawdrift_loop_", doc="the Lyapunov twin's periods bound to a run's loop",
            templates=(put_back, stretched, body), namespace={"math": math, **names, **bind},
            imports="import math\n" + "".join(f"{k} = {v!r}\n" for k, v in names.items()),
            bind=bind, decorator="njit(cache=True, _nrt=False)", memory_options={"_nrt": False},
        ))[body.__name__]
        _LOOPS[key] = fn
    return fn


def twin_pair(stepper: Any, scale: np.ndarray, d0: float, axis: int = 3
               ) -> tuple[Any, Any, np.ndarray]:
    """The estimate's start: a copy of ``stepper``, a twin of it displaced by ``d0`` along state
    ``axis`` (3: y*', 1: x*'; scaled by ``scale[axis - 1]``), and that displacement dy
    (0, x*', y*, y*')."""
    base = stepper.twin()
    dy = np.zeros(4)
    dy[axis] = d0 * scale[axis - 1]
    return base, base.twin(dy), dy


def compiled_stretchings(stepper: Any, scale: np.ndarray, periods: int, align: int,
                         d0: float, early: tuple[int, ...], axis: int = 3) -> np.ndarray | None:
    """:func:`~sawdrift.dynamics.window.stretching_logs` by :func:`stretch_body` or
    :func:`stretch_rigid_body`: the same numbers, bit for bit, or None where the Python loop
    must run (:func:`stretch_loop`, or a period that filled an event log or went bad: that loop
    grows the log or raises the error). The stretches between the ``early`` checks are one
    compiled call each."""
    fn = stretch_loop(stepper)
    if fn is None:
        return None
    base, twin, dy = twin_pair(stepper, scale, d0, axis)
    logs = np.empty(periods)
    u = np.ascontiguousarray(scale[:3], dtype=np.float64)
    status = np.zeros(2, dtype=np.int64)
    if stepper.rigid:
        b, t = (base.y, base.ctr, base.st), (twin.y, twin.ctr, twin.st)
        drive = (stepper.prm, NO_ROWS)
    else:
        b = (base.y, base.fh, base.ctr, (base.fs, base.is_, base.pp), base.st)
        t = (twin.y, twin.fh, twin.ctr, (twin.fs, twin.is_, twin.pp), twin.st)
        drive = (stepper.prm, stepper.dp, NO_ROWS)
    stops = sorted({align + n for n in early if 0 < n < periods} | {align + periods})
    j0 = 0
    for j1 in stops:
        fn(b, t, drive, (stepper.k_per, j0, j1, align), (d0, u, dy), (logs, status))
        if status[0] == FALLBACK:
            return None
        if status[0] == ERASED:
            return np.append(logs[: max(int(status[1]) - align, 0)], -math.inf)
        n = j1 - align
        if n < periods and verdict_clear(logs[:n], chaos=n >= LYAPUNOV_PERIODS):
            return logs[:n]
        j0 = j1
    return logs
