"""The one generator of compiled modules, below the contact and dynamics layers.

Everything that turns Python source into numba machine code cached across processes goes through
this package:

* :mod:`.layout` - the code layout setting of every compiled kernel (``align_branches``);
* :mod:`.digest` - the key of compiled code: the code of every compiled function reachable from
  some roots (``code_digest``), and numba's own caches brought in line with it
  (``refresh_stale_caches``);
* :mod:`.modules` - a generated module: its source (:class:`Generated`), its file in the cache
  folder (``cache_dir``), its name (the key), its import, and the in-memory compilation when it
  cannot be cached (:func:`generate`);
* :mod:`.loading` - loading cached machine code without numba's lowering registries, in the
  processes sawdrift owns (the command line, the executor's workers).

Its users: the contact composition of :mod:`sawdrift.contact.slots`, the wave loop of
:mod:`sawdrift.dynamics.adams_bashforth` and the rigid scheme of :mod:`sawdrift.dynamics.rigid_bind`.
Importing it imports neither numba nor numpy.
"""

from __future__ import annotations

from .digest import GENERATED, code_digest, refresh_stale_caches, walk_code
from .layout import OPTION, align_branches
from .modules import (
    Generated,
    cache_dir,
    generate,
    importable_origin,
    load_generated,
    rebind,
    template_source,
)

__all__ = [
    "GENERATED",
    "OPTION",
    "Generated",
    "align_branches",
    "cache_dir",
    "code_digest",
    "generate",
    "importable_origin",
    "load_generated",
    "rebind",
    "refresh_stale_caches",
    "template_source",
    "walk_code",
]
