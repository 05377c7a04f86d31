"""Start-up helpers for the command line: keep whole-process time to the first result short.

Loading a compiled numba function initialises numba's CPU target, which checks for BLAS by
importing ``scipy.linalg``; SciPy's array-API layer then runs ``from numpy import *``, and since
NumPy lists its submodules in ``__all__`` this imports ``numpy.f2py`` (with ``charset_normalizer``)
and ``numpy.testing`` (with ``unittest``), about 0.1 s that no sawdrift command uses. The
command line registers those two submodules with :class:`importlib.util.LazyLoader` before the
first compiled call: they are still importable and load in full on first attribute access, so
nothing changes but the time.

The same target initialisation then imports every registry of numba's lowering (NumPy's array
functions, typed containers, random generators, jitclass, ...: about 0.3 s) before it loads a
cached function, although a cached function is machine code that needs none of them: it needs
numba's runtime (NRT) to be initialised and the C helper symbols, which the CPU target installs
when it is created. :func:`load_cached_code_lightly` makes the on-disk cache load do just that.
Compiling anything still goes through numba's compiler, which refreshes the full target first,
so a cache miss, a new signature or a user's own ``@njit`` is compiled exactly as before.

Library users are not affected; only the command line calls these, in a process it owns.
"""

from __future__ import annotations

import importlib.util
import sys
from typing import Any

_DEFERRED = ("numpy.f2py", "numpy.testing")


def defer_unused_numpy_submodules() -> None:
    """Register ``numpy.f2py`` and ``numpy.testing`` as lazily executed modules.

    Does nothing for a module that is already imported or cannot be found.
    """
    for name in _DEFERRED:
        if name in sys.modules:
            continue
        spec = importlib.util.find_spec(name)
        if spec is None or spec.loader is None:
            continue
        loader = importlib.util.LazyLoader(spec.loader)
        spec.loader = loader
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        loader.exec_module(module)
        parent, _, child = name.rpartition(".")
        # numpy.__getattr__ would otherwise import the submodule again on `from numpy import *`
        setattr(sys.modules[parent], child, module)


def load_cached_code_lightly() -> bool:
    """Let numba load on-disk cached functions without importing its lowering registries.

    Replaces ``numba.core.caching.Cache.load_overload`` (numba 0.5x-0.6x) with a version that
    initialises the runtime instead of calling ``target_context.refresh()``. Returns False and
    changes nothing when numba's internals are not the ones this was written against.
    """
    try:
        from numba.core import caching
        from numba.core.runtime import rtsys
    except ImportError:  # pragma: no cover - numba is a dependency
        return False
    cache = caching.Cache
    needed = ("load_overload", "_load_overload", "_guard_against_spurious_io_errors")
    if not all(hasattr(cache, name) for name in needed) or not hasattr(rtsys, "initialize"):
        return False
    if getattr(cache.load_overload, "_sawdrift_light", False):
        return True

    def load_overload(self: Any, sig: Any, target_context: Any) -> Any:
        rtsys.initialize(target_context)
        with self._guard_against_spurious_io_errors():
            return self._load_overload(sig, target_context)
        return None  # pragma: no cover - the guard swallowed an I/O error: compile instead

    load_overload._sawdrift_light = True  # type: ignore[attr-defined]
    cache.load_overload = load_overload
    return True


def fast_start() -> None:
    """Everything the command line does before its first compiled call (see the module text)."""
    defer_unused_numpy_submodules()
    load_cached_code_lightly()
