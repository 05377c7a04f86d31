"""Start-up helpers for the command line: keep whole-process time to the first result short.

Loading a compiled numba function initialises numba's CPU target, which checks for BLAS by
importing ``scipy.linalg``; SciPy's array-API layer then runs ``from numpy import *``, and since
NumPy lists its submodules in ``__all__`` this imports ``numpy.f2py`` (with ``charset_normalizer``)
and ``numpy.testing`` (with ``unittest``), about 0.1 s that no sawdrift command uses. The
command line registers those two submodules with :class:`importlib.util.LazyLoader` before the
first compiled call: they are still importable and load in full on first attribute access, so
nothing changes but the time. Library users are not affected; only the CLI calls this.
"""

from __future__ import annotations

import importlib.util
import sys

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
