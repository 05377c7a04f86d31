"""The normal slot: the normal law N*(a*) of the profile, compiled, shared by every contact law.

The law, its descriptor ``law`` (a float64 vector: ``[p]`` for a power law N*(a*) = a*^p, a
resampled monotone cubic for a table) and its tabulated form are owned by the scene layer,
:mod:`sawdrift.scene.normal_law`, as plain Python; this module compiles those same functions with
numba under the same names (:func:`law_normal`, :func:`law_slope`, :func:`power_law` and their
helpers), for the kernels to call. N* = 0 and N*' = 0 for a* <= 0 (contact lost). For a
memory-diagram law the tangential force is the Stieltjes integral of the strip displacements
against dN*' (docs/physics.md, "Contact laws"), so any profile whose N*(a*) is known is handled
exactly, up to the table's interpolation.

With friction off the integrator calls :func:`profile_normal` (or a model's own normal law, see
:meth:`sawdrift.contact.ContactModel.normal_law`) through the kernel signature
``(fs, is_, pp, a, b, adot, bdot) -> (N*, 0)``, with the descriptor at the start of ``pp``.
"""

from __future__ import annotations

import math

from numba import njit

from ..codegen import align_branches, rebind
from ..scene import normal_law
from ..scene.normal_law import TABLE_CELLS, check_table, read_table, table_descriptor

# the tabulated law is read and checked by the scene layer; its names are here for this module's users
__all__ = [
    "JIT_OPTIONS", "TABLE_CELLS", "check_table", "law_normal", "law_slope", "power_law",
    "profile_normal", "read_table", "table_descriptor",
]

align_branches()  # before anything is compiled: every kernel imports its options from here

JIT_OPTIONS = {"cache": True, "_nrt": False}
"""numba options of the kernel helpers: they never allocate, and without the runtime's reference
counting a step is several times faster."""


# The compiled law: each function of :data:`sawdrift.scene.normal_law.COMPILED` rebuilt on one
# namespace (:func:`~sawdrift.codegen.rebind`) in which the names they call each other by are the
# compiled functions (numba resolves a callee through the caller's globals and inlines it at its
# IR level), compiled with :data:`JIT_OPTIONS`, inlined into their callers. ``.py_func`` of each
# is the same Python code (the python engine's law, calling the compiled helpers).
_LAW = rebind(normal_law.COMPILED, {"__name__": __name__, "math": math})
for _func in normal_law.COMPILED:
    _LAW[_func.__name__] = njit(**JIT_OPTIONS, inline="always")(_LAW[_func.__name__])

_hermite = _LAW["_hermite"]
power_law = _LAW["power_law"]
_power_slope = _LAW["_power_slope"]
law_normal = _LAW["law_normal"]
law_slope = _LAW["law_slope"]


@njit(cache=True)
def profile_normal(fs, is_, pp, a, b, adot, bdot):  # noqa: ARG001 - the kernel signature
    """(N*(a*), 0): the profile's elastic normal force alone (descriptor at ``pp[0:]``)."""
    return law_normal(a, pp, 0), 0.0
