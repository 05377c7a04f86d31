"""Loading numba's on-disk cached functions without its lowering registries.

Loading a cached function makes numba's CPU target import every registry of its lowering
(NumPy's array functions, typed containers, random generators, jitclass, ...: about 0.35 s on
the 2-core machine of the benchmarks) before it loads machine code that needs none of them: it
needs numba's runtime (NRT) initialised and the C helper symbols, which the CPU target installs
when it is created. :func:`load_cached_code_lightly` makes the cache load do just that. Compiling
anything still goes through numba's compiler, which refreshes the full target first, so a cache
miss, a new signature or a user's own ``@njit`` is compiled exactly as before.

Called by the processes sawdrift owns: the command line (:mod:`sawdrift._startup`) and the
worker processes of a study's executor (:mod:`sawdrift.study.executor`), never in a library
user's own process. Importing this module imports neither numba nor numpy.
"""

from __future__ import annotations

from typing import Any


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
