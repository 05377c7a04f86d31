"""Generated modules: their source, their file in the cache folder, their key, their import.

numba's ``cache=True`` cannot cache a function built at run time (a closure, or a function whose
globals are filled in later), yet the integration loops and the contact composition are built
per kernel and per drive. So, once per binding, :func:`generate` writes a small Python module to
the cache folder that imports the bound compiled functions by name and defines the template
functions from their source under ``@njit``; numba then stores the machine code next to it and
the next process loads it instead of compiling (about 1 s saved per process and loop).

The folder is ``$SAWDRIFT_CACHE_DIR``, else ``$XDG_CACHE_HOME/sawdrift``, else
``~/.cache/sawdrift``. The generated file's name hashes the sawdrift version, the code layout
setting (:mod:`.layout`), the generated source and the *code* of every compiled function that goes
into it (:func:`~sawdrift.codegen.digest.code_digest`), so editing a plugin kernel or any function
it calls generates a new module instead of running the old machine code. A function that cannot
be imported by name (defined in ``__main__`` or a notebook), or a folder that cannot be written,
makes :func:`generate` compile the same templates in memory instead (same globals, no disk cache).
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import inspect
import os
import sys
import textwrap
import types
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._version import __version__
from .digest import GENERATED, refresh_stale_caches, walk_code
from .layout import align_branches


def cache_dir() -> Path:
    """Where generated modules (and numba's cache of them) live."""
    env = os.environ.get("SAWDRIFT_CACHE_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "sawdrift"


def importable_origin(func: Any) -> tuple[str, str] | None:
    """``(module, name)`` under which a compiled function can be imported again, or None.

    A generated module can only bind functions it can import by name.
    """
    py = getattr(func, "py_func", None)
    if py is None:
        return None
    module, name = py.__module__, py.__name__
    if module in (None, "__main__") or "<" in name:
        return None
    try:
        if getattr(importlib.import_module(module), name, None) is not func:
            return None
    except Exception:  # noqa: BLE001 - not importable by name: no disk cache
        return None
    return module, name


def load_generated(prefix: str, source: str, code: str = "") -> types.ModuleType | None:
    """Write ``source`` to the cache folder as a module and import it (numba then caches it).

    The name is ``prefix`` (one of :data:`~sawdrift.codegen.digest.GENERATED`) plus a hash of the
    sawdrift version, the code layout setting (:mod:`.layout`), the source and ``code`` (the
    :func:`~sawdrift.codegen.digest.code_digest` of the compiled functions the module binds), so a
    change of any generates a new module; a module already imported is returned as it is. None if
    the folder cannot be written or the module does not load (the caller compiles in memory).
    """
    if not prefix.startswith(GENERATED):
        raise ValueError(f"generated module prefix {prefix!r} is not one of {GENERATED}")
    tag = align_branches()  # the code layout setting is part of what the cache holds
    digest = hashlib.sha1(f"{__version__}\n{tag}\n{code}\n{source}".encode()).hexdigest()[:16]
    modname = f"{prefix}{digest}"
    if modname in sys.modules:
        return sys.modules[modname]
    folder = cache_dir()
    path = folder / f"{modname}.py"
    try:
        folder.mkdir(parents=True, exist_ok=True)
        if not path.exists() or path.read_text() != source:
            tmp = path.with_suffix(f".{os.getpid()}.tmp")
            tmp.write_text(source)
            os.replace(tmp, path)
    except OSError:
        return None
    spec = importlib.util.spec_from_file_location(modname, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[modname] = module  # numba's cache records the module by name
    try:
        spec.loader.exec_module(module)
    except Exception:  # noqa: BLE001 - a broken cache file must not break a run
        sys.modules.pop(modname, None)
        return None
    return module


def rebind(templates: tuple[Callable[..., Any], ...], namespace: Mapping[str, Any]) -> dict[str, Any]:
    """``namespace`` with every template rebuilt as a plain function whose globals it is.

    The templates then call each other and read their global names in that namespace (the
    python engine runs them as they are; :func:`generate`'s in-memory fallback compiles them).
    """
    ns = dict(namespace)
    for func in templates:
        new = types.FunctionType(func.__code__, ns, func.__name__, func.__defaults__)
        new.__kwdefaults__ = func.__kwdefaults__
        ns[func.__name__] = new
    return ns


def _with_options(decorator: str, options: Mapping[str, Any] | None) -> str:
    """``decorator`` (a call such as ``njit(cache=True)`` or a bare ``njit``) given ``options`` too."""
    if not options:
        return decorator
    if decorator.endswith(")"):
        return f"{decorator[:-1]}, **{dict(options)!r})"
    return f"{decorator}(**{dict(options)!r})"


def template_source(templates: tuple[Callable[..., Any], ...], decorator: str,
                    options: Mapping[str, Mapping[str, Any]] | None = None) -> str:
    """The source of ``templates``, each under ``@decorator``, as a generated module holds them.

    ``options`` adds numba options to some templates, by name (e.g. ``{"f": {"inline": "always"}}``).
    """
    options = options or {}
    return "\n\n".join(f"@{_with_options(decorator, options.get(f.__name__))}\n"
                       + textwrap.dedent(inspect.getsource(f)) for f in templates)


@dataclass(frozen=True)
class Generated:
    """What one generated module is made of (see :func:`generate`).

    Attributes
    ----------
    prefix
        The module name's prefix, one of :data:`~sawdrift.codegen.digest.GENERATED`.
    doc
        What the module is, for its docstring ("the rigid scheme bound to ...").
    templates
        Plain functions compiled from their source, in this order, under ``@decorator``.
    namespace
        The templates' global names as values: they key the module (their code, for compiled
        ones) and are the in-memory compilation's globals.
    imports
        Import lines that give the templates those global names in the generated file.
    bind
        Alias -> compiled function (or its ``(module, name)``) that the file imports by name;
        a function that cannot be imported by name makes the module compile in memory.
    roots
        Further compiled functions whose code goes in (calls made through ``bind``).
    preamble
        Lines after the imports (module constants, re-decorated bound functions).
    decorator
        The decorator of each template in the file (numba's on-disk cache on).
    memory_options
        The numba options of the in-memory compilation (its source has no file: no cache).
    memory_namespace
        Globals of the in-memory compilation if not ``namespace`` (e.g. inlined slot functions).
    options
        Further numba options of some templates, by name, in the file and in memory: e.g.
        ``{"helper": {"inline": "always"}}`` inlines ``helper`` into its callers at numba's IR
        level, so it is not compiled (nor cached) as a function of its own.
    """

    prefix: str
    doc: str
    templates: tuple[Callable[..., Any], ...]
    namespace: Mapping[str, Any]
    imports: str = ""
    bind: Mapping[str, Any] = field(default_factory=dict)
    roots: tuple[Any, ...] = ()
    preamble: str = ""
    decorator: str = "njit(cache=True)"
    memory_options: Mapping[str, Any] = field(default_factory=dict)
    memory_namespace: Mapping[str, Any] | None = None
    options: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)

    def source(self, origins: Mapping[str, tuple[str, str]]) -> str:
        """The generated module's text, the bound functions imported from ``origins``."""
        binds = "".join(f"from {mod} import {name} as {alias}  # noqa: F401\n"
                        for alias, (mod, name) in origins.items())
        return (f'"""Generated by sawdrift: {self.doc}. Do not edit."""\n'
                "import math  # noqa: F401\n\n"
                "from numba import njit\n\n"
                f"{self.imports}{binds}\n"
                + (f"{self.preamble}\n" if self.preamble else "")
                + "\n" + template_source(self.templates, self.decorator, self.options))


def _origin(value: Any) -> tuple[str, str] | None:
    return tuple(value) if isinstance(value, tuple) else importable_origin(value)


def generate(spec: Generated) -> dict[str, Any]:
    """The compiled templates of ``spec`` (and the rest of their module's names), by name.

    Every compiled function that goes in (``roots``, the ``bind`` functions, and what the
    templates read from ``namespace``) keys the module and is first brought in line with its code
    (:func:`~sawdrift.codegen.digest.refresh_stale_caches`), also when the module is then compiled
    in memory. The module is written to :func:`cache_dir` and imported (:func:`load_generated`);
    if a bound function cannot be imported by name or the module cannot be written or loaded, the
    templates are compiled in memory with the same globals (:func:`rebind`).
    """
    bound = [v for v in spec.bind.values() if not isinstance(v, tuple)]
    walk, code = walk_code([*spec.roots, *bound], dict(spec.namespace), spec.templates)
    refresh_stale_caches(walk)
    origins = {alias: _origin(value) for alias, value in spec.bind.items()}
    if all(o is not None for o in origins.values()):
        module = load_generated(spec.prefix, spec.source(origins), code)
        if module is not None:
            return vars(module)
    from numba import njit

    ns = rebind(spec.templates, spec.memory_namespace or spec.namespace)
    for func in spec.templates:
        opts = {**spec.memory_options, **spec.options.get(func.__name__, {})}
        ns[func.__name__] = njit(**opts)(ns[func.__name__])
    return ns
