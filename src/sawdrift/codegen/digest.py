"""The key of compiled code: the code of every compiled function reachable from some roots.

numba's own cache of a function is keyed by the function's bytecode and its file's time stamp,
not by the functions it calls: a kernel whose helper in *another* file changed would load its old
machine code. :func:`code_digest` hashes the code of a function and of every compiled function it
calls, across modules, with the constants they read (it keys generated modules,
:mod:`sawdrift.codegen.modules`), and :func:`refresh_stale_caches` brings numba's on-disk caches
in line with it.
"""

from __future__ import annotations

import hashlib
import os
import types
from collections.abc import Iterable
from pathlib import Path
from typing import Any

#: Prefixes of the generated modules: their names already carry the digest of their code.
GENERATED = ("sawdrift_loop_", "sawdrift_contact_", "sawdrift_rigid_")
#: Modules whose functions are not walked (their code is not the project's or a plugin's).
_FOREIGN = ("numba", "numpy", "llvmlite", "math", "cmath", "builtins")

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

