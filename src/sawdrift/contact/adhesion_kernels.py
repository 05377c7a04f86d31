"""The adhesive contact compiled: its normal slot and its composition with a tangential law.

The law is :mod:`sawdrift.contact.adhesion_law` (plain Python); this module compiles the same
functions under the same names (as :mod:`sawdrift.contact.normal` does for the elastic laws) and
composes an adhesive contact from them and a law's adhesive tangential step, in the manner of
:mod:`sawdrift.contact.slots` (imported only when an adhesive contact is compiled).

State (``fs``)::

    fs[0], fs[1]   committed a*, b*
    fs[2]          1.0 while in contact (the JKR hysteresis: made at a* > 0, broken at a*_detach)
    fs[3]          committed contact radius c*
    fs[4:]         the tangential law's own state

Parameters (``pp``): ``[start of tp, start of ad, law descriptor..., tp..., ad...]``.

Adhesive tangential step protocol (numba functions)::

    step(ts, is_, law, tp, a0, b0, a, b, c0, c1, cap) -> T*    # commit; a0 = 0: a new contact
    reset(ts, is_, law, tp) -> None

with c0, c1 the contact radii at both ends of the straight path and ``cap`` the sliding limit
|N* + 2 F*_pull| at its end (LAMMPS ``pair granular`` with ``jkr``/``dmt``: mu |F_ne + 2 F_pulloff|).
"""

from __future__ import annotations

import math
from typing import Any

from numba import njit

from ..codegen import Generated, generate, rebind
from . import adhesion_law
from .normal import JIT_OPTIONS

#: floats the composition keeps in front of the law's state
ADH_HEADER = 4
#: where the normal-law descriptor starts in ``pp``
LAW = 2

_LAW = rebind(adhesion_law.COMPILED, {"__name__": __name__, "math": math, "DMT": adhesion_law.DMT,
                                       "NEWTON_MAX": adhesion_law.NEWTON_MAX})
for _func in adhesion_law.COMPILED:
    _LAW[_func.__name__] = njit(**JIT_OPTIONS, inline="always")(_LAW[_func.__name__])

jkr_root = _LAW["jkr_root"]
adhesive_normal = _LAW["adhesive_normal"]
entry_radius = _LAW["entry_radius"]


# -- the composition's templates (compiled for the kernel, run plainly for the python engine) --


def adhesive_reset(fs, is_, pp):
    """Empty history, out of contact at (a*, b*) = (0, 0); the law's reset on a zeroed ``is_``."""
    for i in range(ADH_HEADER):
        fs[i] = 0.0
    for i in range(is_.shape[0]):
        is_[i] = 0
    adhesive_tangential_reset(fs[ADH_HEADER:], is_, pp[LAW:], pp[int(pp[0]):int(pp[1])])  # noqa: F821


def adhesive_force(fs, is_, pp, a, b, adot, bdot):
    """Advance along the straight path to (a, b), commit, (N*, T*): contact made at a* > 0,
    kept down to the detach overlap ``ad[2]`` (the hysteresis), the sliding limit N* + 2 F*_pull."""
    ad = pp[int(pp[1]):]
    a0 = fs[0]
    b0 = fs[1]
    fs[0] = a
    fs[1] = b
    if fs[2] != 0.0:
        if not a > ad[2]:
            # contact broken: the tangential history is forgotten, once
            adhesive_tangential_reset(fs[ADH_HEADER:], is_, pp[LAW:],  # noqa: F821
                                      pp[int(pp[0]):int(pp[1])])
            fs[2] = 0.0
            fs[3] = 0.0
            return 0.0, 0.0
        c0 = fs[3]
    else:
        if not a > 0.0:
            return 0.0, 0.0
        # a contact is made where the straight path crosses a* = 0
        if a0 < 0.0:
            b0 = b0 + (b - b0) * (-a0 / (a - a0))
        a0 = 0.0
        c0 = entry_radius(ad)
        fs[2] = 1.0
    n, c1 = adhesive_normal(a, ad)
    fs[3] = c1
    cap = abs(n + 2.0 * ad[3])
    t = adhesive_tangential_step(fs[ADH_HEADER:], is_, pp[LAW:], pp[int(pp[0]):int(pp[1])],  # noqa: F821
                                 a0, b0, a, b, c0, c1, cap)
    return n, t


def adhesive_normal_only(fs, is_, pp, a, b, adot, bdot):
    """(N*, 0): the adhesive normal law alone (friction off), ``pp`` = ``ad``, ``fs[0]`` the
    contact flag of the hysteresis."""
    if fs[0] != 0.0:
        if not a > pp[2]:
            fs[0] = 0.0
            return 0.0, 0.0
    elif not a > 0.0:
        return 0.0, 0.0
    fs[0] = 1.0
    n, c = adhesive_normal(a, pp)
    return n, 0.0


_TEMPLATES = (adhesive_reset, adhesive_force, adhesive_normal_only)
_INLINE = {"inline": "always", "_nrt": False}
_COMPOSED: dict[tuple[Any, Any], dict[str, Any]] = {}


def compiled(step: Any, reset: Any, law: Any = None) -> dict[str, Any]:
    """The adhesive composition with ``step`` and ``reset`` (numba functions), disk-cached.

    ``law`` replaces the normal law :func:`adhesive_normal` (same signature, ``(N*, c*)``);
    the conformance suite's tests use it to show that a wrong law fails.
    """
    law = adhesive_normal if law is None else law
    key = (step, reset, law)
    ns = _COMPOSED.get(key)
    if ns is not None:
        return ns
    consts = {"ADH_HEADER": ADH_HEADER, "LAW": LAW}
    ns = generate(Generated(
        prefix="sawdrift_contact_",
        doc="an adhesive contact composed of its normal law and a tangential step",
        templates=_TEMPLATES,
        namespace={"adhesive_normal": law, "entry_radius": entry_radius,
                   "adhesive_tangential_step": step, "adhesive_tangential_reset": reset, **consts},
        imports=("from sawdrift.contact.normal import JIT_OPTIONS  # noqa: F401\n"
                 "from sawdrift.contact.adhesion_kernels import ADH_HEADER, LAW  # noqa: F401\n"
                 "from sawdrift.contact.adhesion_kernels import entry_radius  # noqa: F401\n"),
        bind={"_step": step, "adhesive_tangential_reset": reset, "_law": law},
        preamble=(f"adhesive_tangential_step = njit(**{_INLINE!r})(_step.py_func)\n"
                  f"adhesive_normal = njit(**{_INLINE!r})(_law.py_func)\n"),
        decorator="njit(**JIT_OPTIONS)",
        memory_options={k: v for k, v in JIT_OPTIONS.items() if k != "cache"},
        memory_namespace={"adhesive_normal": law, "entry_radius": entry_radius,
                          "adhesive_tangential_step": njit(**_INLINE)(step.py_func),
                          "adhesive_tangential_reset": reset, **consts},
    ))
    _COMPOSED[key] = ns
    return ns


def python(step: Any, reset: Any, law: Any = None) -> dict[str, Any]:
    """The same composition as plain Python: the readable law of :mod:`.adhesion_law` (or
    ``law``'s Python code) and the step's own Python code (the python engine)."""
    law = adhesion_law.adhesive_normal if law is None else getattr(law, "py_func", law)
    return rebind(_TEMPLATES, {
        "adhesive_normal": law, "entry_radius": adhesion_law.entry_radius,
        "jkr_root": adhesion_law.jkr_root, "DMT": adhesion_law.DMT,
        "NEWTON_MAX": adhesion_law.NEWTON_MAX, "math": math,
        "adhesive_tangential_step": getattr(step, "py_func", step),
        "adhesive_tangential_reset": getattr(reset, "py_func", reset),
        "ADH_HEADER": ADH_HEADER, "LAW": LAW})


#: :func:`adhesive_normal_only` compiled on its own: the friction-off slot (``.py_func`` runs it
#: as Python)
normal_only = njit(cache=True)(adhesive_normal_only)
