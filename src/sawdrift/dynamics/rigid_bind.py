"""The rigid scheme of :mod:`.rigid` bound to a drive: generated, compiled and cached per drive.

The scheme's functions (the events and the loop of :mod:`.rigid`, the closed forms of
:mod:`.rigid_closed_forms`) call ``drive_kinematics``, which is a different compiled function for
each drive (:mod:`.drives`). numba cannot cache a function whose globals are filled in later, so
this module writes, once per drive, a small module to the cache folder that imports the drive's
``kinematics`` by name and defines the scheme's functions under ``@njit(cache=True)``
(:mod:`sawdrift.codegen` keys it by the code of the scheme and of the drive).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from numba import njit

from ..codegen import Generated, generate, rebind
from . import adams_bashforth, evidence, rolling
from . import rigid as rg
from . import rigid_closed_forms as cf

#: the scheme's functions, compiled together per drive (they call ``drive_kinematics``)
_FUNCTIONS = (cf._tangential_mass, cf._tangential_load, cf._normal, cf._least_normal_inside,
              cf._contact_lost_at,
              cf._stick_margin, cf._sticks, cf._t_req, cf._slip_state, cf._slip_velocity, cf._gap,
              rg._log, rg._free_tangential, rg._flight, rg._gap_rounding, rg._slip_rounding,
              rg._impact, rg._land, rg._lift,
              cf._contact_end, rg._stick, rg._slip, rg._contact, rg._end_step, rg.rigid_loop)
_IMPORTS = (
    "from sawdrift.dynamics.adams_bashforth import *  # noqa: F403\n"
    "from sawdrift.dynamics.evidence import *  # noqa: F403\n"
    "from sawdrift.dynamics.rolling import *  # noqa: F403\n"
    "from sawdrift.dynamics.rigid_closed_forms import (  # noqa: F401\n"
    "    _BISECT, _GOLDEN, _GRAZE, N_PRM_RIGID, P_RESTITUTION, P_UY, P_VINERTIA, P_XQ,\n"
    ")\n"
    "from sawdrift.dynamics.rigid import _MAX_EVENTS, _ZENO, EV_MARGIN_RIGID  # noqa: F401\n"
)
#: the pieces of a step that numba inlines into their one caller at its IR level (``_lift``: two
#: calls): compiled as functions of their own, each ran numba's whole pipeline and LLVM's code
#: generation over everything it calls again (a material point's first compilation took 4.7 s,
#: 3.6-3.7 s before the loop was split; now 3.6 s), and the contact path of the step runs inside
#: the loop (5-10 % less time per step). ``_flight`` stays a call: inlining it too (nested, numba
#: copies the callee's IR at each level) cost 0.1-0.2 s more to compile and gained nothing. The
#: small functions called from several places stay compiled functions of their own: inlined at
#: every call, their copies cost more to compile than the calls cost to run.
_INLINED = (rg._free_tangential, rg._impact, rg._land, rg._lift, rg._contact_end, rg._stick,
            rg._slip, rg._contact, rg._end_step)
_LOOPS: dict[str, Callable[..., None]] = {}
#: the constants the generated module imports (``_IMPORTS``): of the closed forms, of the events
_CLOSED_FORM_NAMES = ("_BISECT", "_GOLDEN", "_GRAZE", "N_PRM_RIGID", "P_RESTITUTION", "P_UY",
                      "P_VINERTIA", "P_XQ")
_SCHEME_NAMES = ("_MAX_EVENTS", "_ZENO", "EV_MARGIN_RIGID")
#: numba options of the scheme's functions. The scheme allocates nothing, so it needs no reference
#: counting: without it (``_nrt``) the arrays handed from function to function cost no atomic
#: increments (the split loop ran 1.7-2.9x slower per step with them; 0.7-0.9x of the one-piece
#: loop's time without), and an allocation would fail to compile instead of slowing the loop.
_JIT = {"cache": True, "_nrt": False}


def _namespace(kinematics: Any) -> dict[str, Any]:
    ns: dict[str, Any] = {"math": math, "njit": njit}
    for module in (adams_bashforth, evidence, rolling):
        ns.update({n: v for n, v in vars(module).items() if not n.startswith("_")})
    ns.update({n: getattr(cf, n) for n in _CLOSED_FORM_NAMES})
    ns.update({n: getattr(rg, n) for n in _SCHEME_NAMES})
    ns["drive_kinematics"] = kinematics
    return ns


def rigid_loop_for(drive: Any) -> Callable[..., None]:
    """The compiled rigid scheme bound to ``drive`` (a :class:`~sawdrift.dynamics.drives.Drive`).

    Generated once per drive as a module in the cache folder (numba's disk cache then applies,
    keyed by the code of the scheme and of the drive, :mod:`sawdrift.codegen`), or compiled in memory
    if that folder cannot be written. Its ``py_func`` is the python engine (helpers compiled).
    """
    fn = _LOOPS.get(drive.module)
    if fn is not None:
        return fn
    kinematics = drive.functions()[1]
    fn = generate(Generated(
        prefix="sawdrift_rigid_", doc=f"the rigid scheme bound to {drive.module}",
        templates=_FUNCTIONS, namespace=_namespace(kinematics), imports=_IMPORTS,
        bind={"drive_kinematics": (drive.module, "kinematics")}, roots=(kinematics,),
        decorator=f"njit(**{_JIT!r})", memory_options={k: v for k, v in _JIT.items() if k != "cache"},
        options={f.__name__: {"inline": "always"} for f in _INLINED},
    ))["rigid_loop"]
    _LOOPS[drive.module] = fn
    return fn


def rigid_python_loop(drive: Any) -> Callable[..., None]:
    """The rigid scheme as plain Python bound to ``drive`` (the python engine).

    Built from the functions and globals of :mod:`.rigid_closed_forms` and :mod:`.rigid` at call
    time (:mod:`.rigid`'s win, so a patched ``rigid._MAX_EVENTS`` applies), with the drive's
    compiled ``kinematics``: the readable scheme that the compiled one is tested against.
    """
    ns = {**vars(cf), **vars(rg), "drive_kinematics": drive.functions()[1]}
    return rebind(_FUNCTIONS, ns)["rigid_loop"]
