"""The compiled wave loop, cached on disk across processes, and the key of that cache.

numba's ``cache=True`` cannot cache a function built per kernel at run time (a closure, or a
function whose globals are filled in later). So, once per kernel, this module writes a small
Python module to the cache folder that imports the kernel's ``force`` by name and defines the loop
body of :func:`sawdrift.dynamics.adams_bashforth.wave_loop_body` under ``@njit(cache=True)``;
numba then stores the machine code next to it and the next process loads it instead of compiling
(about 1 s saved per process).

The folder is ``$SAWDRIFT_CACHE_DIR``, else ``$XDG_CACHE_HOME/sawdrift``, else
``~/.cache/sawdrift``. The generated file's name hashes the sawdrift version, the code layout
setting, the generated source and the *code* of every compiled function that goes into it
(:func:`code_digest`: the kernel, every compiled function it calls, across modules, and the
constants they read), so editing a plugin kernel or any function it calls generates a new module
instead of running the old machine code. A kernel that cannot be imported by name, or a folder
that cannot be written, makes :func:`cached_loop` return None (the caller then compiles in memory).

numba's own cache of a function is keyed by the function's bytecode and its file's time stamp,
not by the functions it calls: a kernel whose helper in *another* file changed would load its old
machine code. :func:`refresh_stale_caches` closes that gap (see there).
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
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

#: Prefixes of the generated modules: their names already carry the digest of their code.
GENERATED = ("sawdrift_loop_", "sawdrift_contact_")
#: Modules whose functions are not walked (their code is not the project's or a plugin's).
_FOREIGN = ("numba", "numpy", "llvmlite", "math", "cmath", "builtins")


def cache_dir() -> Path:
    """Where generated loop modules (and numba's cache of them) live."""
    env = os.environ.get("SAWDRIFT_CACHE_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "sawdrift"


def importable_origin(force: Any) -> tuple[str, str] | None:
    """``(module, name)`` under which a compiled function can be imported again, or None.

    A generated module can only bind functions it can import by name.
    """
    func = getattr(force, "py_func", None)
    if func is None:
        return None
    module, name = func.__module__, func.__name__
    if module in (None, "__main__") or "<" in name:
        return None
    try:
        if getattr(importlib.import_module(module), name, None) is not force:
            return None
    except Exception:  # noqa: BLE001 - not importable by name: no disk cache
        return None
    return module, name


# -- the code that goes into a compiled function ----------------------------------------------

_FILES: dict[str, tuple[int, int, str]] = {}


def _file_digest(path: str) -> str | None:
    """sha1 of a source file's bytes, cached per process by (mtime, size); None if unreadable."""
    try:
        st = os.stat(path)
    except OSError:
        return None
    hit = _FILES.get(path)
    if hit is not None and hit[:2] == (st.st_mtime_ns, st.st_size):
        return hit[2]
    try:
        digest = hashlib.sha1(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None
    _FILES[path] = (st.st_mtime_ns, st.st_size, digest)
    return digest


def _is_dispatcher(value: Any) -> bool:
    return hasattr(value, "py_func") and hasattr(value, "overloads")


def _names(code: types.CodeType) -> set[str]:
    """Global and attribute names a code object (and the code nested in it) refers to."""
    names = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _names(const)
    return names


def _constant(value: Any) -> str | None:
    """A stable text of a value numba freezes into machine code (None: not such a value)."""
    if value is None or isinstance(value, bool | int | float | complex | str | bytes):
        return repr(value)
    if isinstance(value, tuple) and all(_constant(v) is not None for v in value):
        return repr(value)
    try:
        import numpy as np
    except ImportError:  # pragma: no cover - numpy is a dependency
        return None
    if isinstance(value, np.generic):
        return repr(value)
    if isinstance(value, np.ndarray):
        return f"{value.dtype}{value.shape}:" + hashlib.sha1(value.tobytes()).hexdigest()
    return None


class _Walk:
    """The compiled functions reachable from some roots, each with the digest of its code.

    A function's *own* text is the sha1 of its source file (the file is what numba's cache
    stamps) or, for code without a file, of its bytecode and constants, plus the values of the
    constants it reads from its globals; its digest adds the digests of every compiled function
    it calls (through its globals, a module attribute or a closure cell), recursively.
    """

    def __init__(self) -> None:
        self.digests: dict[int, str] = {}
        self.dispatchers: dict[int, Any] = {}  # reachable numba dispatchers, callees first
        self.files: dict[int, set[str]] = {}  # source files a function's compiled code spans

    def function(self, func: Any) -> str:
        """Digest of a plain Python function (or a dispatcher's ``py_func``)."""
        key = id(func)
        done = self.digests.get(key)
        if done is not None:
            return done
        self.digests[key] = "cycle"  # a recursive call refers back by this mark
        code: types.CodeType = func.__code__
        own = _file_digest(code.co_filename)
        files = {code.co_filename}
        if own is None:
            own = hashlib.sha1(code.co_code + repr(code.co_consts).encode()).hexdigest()
        parts = [f"{func.__module__}.{func.__qualname__}:{own}"]
        names = sorted(_names(code))
        scopes = [func.__globals__]
        cells = dict(zip(code.co_freevars, func.__closure__ or (), strict=False))
        for name, cell in cells.items():
            parts.append(self._value(f"cell {name}", cell.cell_contents, names, files))
        for name in names:
            for scope in scopes:
                if name in scope:
                    parts.append(self._value(name, scope[name], names, files))
        digest = hashlib.sha1("\n".join(parts).encode()).hexdigest()
        self.digests[key] = digest
        self.files[key] = files
        return digest

    def _value(self, name: str, value: Any, names: list[str], files: set[str]) -> str:
        if _is_dispatcher(value):
            return f"{name}=" + self.dispatcher(value, files)
        if isinstance(value, types.ModuleType):
            if value.__name__.split(".")[0] in _FOREIGN:
                return ""
            attrs = [f"{name}.{a}" + self._value("", getattr(value, a), [], files)
                     for a in names if a in vars(value) and _is_dispatcher(getattr(value, a))
                     or a in vars(value) and _constant(getattr(value, a)) is not None]
            return ";".join(attrs)
        if isinstance(value, types.FunctionType) and (value.__module__ or "").split(".")[0] not in _FOREIGN:
            return f"{name}=" + self.function(value)  # e.g. a function numba inlines or overloads
        text = _constant(value)
        return "" if text is None else f"{name}={text}"

    def dispatcher(self, disp: Any, files: set[str] | None = None) -> str:
        """Digest of a numba dispatcher (the code of its ``py_func`` and all it calls)."""
        func = disp.py_func
        if (func.__module__ or "").split(".")[0] in _FOREIGN:
            return f"{func.__module__}.{func.__qualname__}"
        digest = self.function(func)
        self.dispatchers.setdefault(id(func), disp)
        if files is not None:
            files |= self.files.get(id(func), {func.__code__.co_filename})
        return digest


def _load(func: Any) -> Any:
    load = getattr(func, "load", None)  # a LazyFunction: the function it names
    return load() if callable(load) and not _is_dispatcher(func) else func


def walk_code(roots: Iterable[Any], namespace: dict[str, Any] | None = None,
              templates: Iterable[Any] = ()) -> tuple[_Walk, str]:
    """The compiled functions reachable from ``roots``, and the sha1 of all their code.

    ``roots`` are numba dispatchers, plain functions or :class:`~sawdrift.contact.base.LazyFunction`
    objects; ``templates`` are plain functions whose global names are looked up in ``namespace``
    (the namespace a generated module gives them).
    """
    walk = _Walk()
    parts = [walk.dispatcher(f) if _is_dispatcher(f) else walk.function(f)
             for f in map(_load, roots)]
    files: set[str] = set()
    for template in templates:
        parts += [walk._value(n, (namespace or {})[n], [], files)
                  for n in sorted(_names(template.__code__)) if n in (namespace or {})]
    return walk, hashlib.sha1("\n".join(parts).encode()).hexdigest()


def code_digest(roots: Iterable[Any], namespace: dict[str, Any] | None = None,
                templates: Iterable[Any] = ()) -> str:
    """sha1 of the code of every compiled function reachable from ``roots`` (:func:`walk_code`)."""
    return walk_code(roots, namespace, templates)[1]


def refresh_stale_caches(roots: Iterable[Any] | _Walk) -> list[str]:
    """Make numba's on-disk cache of every function reachable from ``roots`` match its code.

    numba keys a cached function by its own bytecode and its file's time stamp; the machine code
    it stores also holds the functions it calls, so after an edit of a callee in another file the
    old code would load. For every reachable dispatcher whose compiled code spans more than its
    own file, the digest of all that code is recorded beside numba's index
    (``<index>.sawdrift-code``); when the record is missing (a cache from before the record) or
    differs, numba's index is emptied, and a function this process already compiled or loaded
    is compiled again (callees first). Generated modules are skipped (their name is their key).
    Returns the names of the refreshed functions.
    """
    walk = roots if isinstance(roots, _Walk) else walk_code(roots)[0]
    refreshed: list[str] = []
    for key, disp in walk.dispatchers.items():
        func = disp.py_func
        cache = getattr(disp, "_cache", None)
        index = getattr(getattr(cache, "_cache_file", None), "_index_path", None)
        if (index is None or (func.__module__ or "").startswith(GENERATED)
                or len(walk.files.get(key, ())) < 2):
            continue
        record = Path(index + ".sawdrift-code")
        digest = walk.digests[key]
        try:
            old = record.read_text() if record.exists() else None
        except OSError:
            old = None
        if old == digest:
            continue
        if old is not None or os.path.exists(index):
            if disp.overloads:
                disp.recompile()  # flushes numba's index too
            else:
                cache.flush()
            refreshed.append(f"{func.__module__}.{func.__qualname__}")
        try:
            record.parent.mkdir(parents=True, exist_ok=True)
            record.write_text(digest)
        except OSError:
            pass  # an unwritable cache folder: numba will not write its index either
    return refreshed


# -- generated modules ---------------------------------------------------------------------------


def load_generated(prefix: str, source: str, code: str = "") -> types.ModuleType | None:
    """Write ``source`` to the cache folder as a module and import it (numba then caches it).

    The name is ``prefix`` plus a hash of the sawdrift version, the code layout setting
    (:mod:`sawdrift._codegen`), the source and ``code`` (the :func:`code_digest` of the compiled
    functions the module binds), so a change of any generates a new module; a module already
    imported is returned as it is. None if the folder cannot be written or the module does not
    load (the caller compiles in memory).
    """
    from .. import __version__
    from .._codegen import align_branches

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


def _public(module: types.ModuleType) -> dict[str, Any]:
    """What ``from module import *`` binds."""
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n in vars(module) if not n.startswith("_")]
    return {n: getattr(module, n) for n in names}


def _source(module: str, name: str, body: Callable[..., Any], imports: str) -> str:
    """A module that binds ``module.name`` as ``force`` and defines ``body`` under ``@njit``."""
    text = textwrap.dedent(inspect.getsource(body))
    return (
        f'"""Generated by sawdrift: {body.__name__} bound to {module}.{name}. Do not edit."""\n'
        "import math  # noqa: F401\n\n"
        "from numba import njit\n\n"
        f"{imports}"
        f"from {module} import {name} as force  # noqa: F401\n\n\n"
        "@njit(cache=True)\n" + text
    )


def cached_loop(force: Any, body: Callable[..., Any], imports: str,
                namespace: dict[str, Any]) -> Callable[..., None] | None:
    """The disk-cached compiled ``body`` with the kernel ``force`` bound in, or None.

    ``imports`` are the generated module's import lines that give ``body`` its global names,
    ``namespace`` the same names as values (they key the cache). Every compiled function that
    goes in (the kernel, what it calls, the loop's helpers) is first brought in line with its
    code (:func:`refresh_stale_caches`), also when the loop is then compiled in memory; the
    generated module is keyed by all that code (:func:`code_digest`). None if the kernel cannot
    be imported by name (the caller compiles in memory).
    """
    walk, code = walk_code([force], namespace, [body])
    refresh_stale_caches(walk)
    origin = importable_origin(force)
    if origin is None:
        return None
    module = load_generated("sawdrift_loop_", _source(*origin, body, imports), code)
    return None if module is None else getattr(module, body.__name__)
