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
when it is created. :func:`~sawdrift.codegen.loading.load_cached_code_lightly` makes the on-disk
cache load do just that (the study executor's worker processes call it too).
Compiling anything still goes through numba's compiler, which refreshes the full target first,
so a cache miss, a new signature or a user's own ``@njit`` is compiled exactly as before.

Before its first cached load numba scans every distribution's entry points for numba extensions,
pydantic for its plugins before its first validator, the model registry for models: all three
are answered from one stored scan (:func:`skip_plugin_scans`; numba and pydantic only when
nothing is installed for them).

Three answers are stored on disk instead of recomputed by every process: those scans, the
top-level ``--help`` text (:func:`replay_help`, :func:`stored_help`) and the rows of ``sawdrift
models`` (:func:`stored_models`); the comment above their helpers says what their keys hold.

Library users are not affected; only the command line calls these, in a process it owns (and
the executor's worker processes the light cache load, in processes it owns).
"""

from __future__ import annotations

import importlib.util
import io
import sys
from pathlib import Path
from typing import Any

from .codegen.loading import load_cached_code_lightly

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


# --- answers stored on disk: plugin scans, the top-level --help text, the model listing ---------
#
# Numba, pydantic and the model registry each scan every distribution's entry points for their
# plugins. ``sawdrift --help`` spends most of its time importing Typer's rich help renderer (with
# the Markdown and traceback support it loads and this program never uses) and building all the
# commands to print their one-line summaries; ``sawdrift models`` imports every model plugin
# (numpy, the scene schema) to describe its parameters. These answers are the same every time
# for the same code and installation, so each is stored once, in ``<cache folder>/cli`` (the
# folder of :func:`sawdrift.codegen.modules.cache_dir`), under a key that hashes everything it
# depends on: the interpreter, ``sys.path`` and the installed distributions (their ``.dist-info``
# folders, which hold the entry points), for the help and the models also the modification time
# and size of every Python file of the packages that produce them, and for the help where it is
# printed (program name, terminals, width, encoding, and the environment variables Typer and
# Rich read). A cache that cannot be read or written only means the answer is computed as
# before, and an answer computed with a warning or a failed plugin is not stored.

#: environment variables that change how Typer and Rich print help (widths, colours, terminals)
_HELP_ENV = ("COLUMNS", "LINES", "JUPYTER_COLUMNS", "JUPYTER_LINES", "TERM", "COLORTERM",
             "NO_COLOR", "FORCE_COLOR", "PY_COLORS", "TTY_COMPATIBLE", "TTY_INTERACTIVE",
             "GITHUB_ACTIONS", "TERMINAL_WIDTH", "DATABRICKS_RUNTIME_VERSION", "LANG", "LANGUAGE")
_HELP_ENV_PREFIXES = ("TYPER", "_TYPER", "LC_")
#: stored answers kept per kind (terminal sizes make new help keys); the oldest go first
_KEEP = 16


def _tree_stamp(root: str) -> list[tuple[str, int, int]]:
    """(path, mtime_ns, size) of every Python file at or below ``root`` (a file or a folder)."""
    import os

    if os.path.isfile(root):
        st = os.stat(root)
        return [(root, st.st_mtime_ns, st.st_size)]
    out: list[tuple[str, int, int]] = []
    folders = [root]
    while folders:
        try:
            entries = list(os.scandir(folders.pop()))
        except OSError:
            continue
        for entry in entries:
            if entry.is_dir(follow_symlinks=False):
                if entry.name != "__pycache__" and not entry.name.startswith("."):
                    folders.append(entry.path)
            elif entry.name.endswith(".py"):
                st = entry.stat()
                out.append((entry.path, st.st_mtime_ns, st.st_size))
    return sorted(out)


def _package_stamp(name: str) -> list[Any]:
    """:func:`_tree_stamp` of the installed top-level package or module ``name`` (not imported)."""
    spec = importlib.util.find_spec(name)
    if spec is None:
        return [name, None]
    roots = list(spec.submodule_search_locations or []) or [spec.origin or ""]
    return [name, [_tree_stamp(root) for root in roots if root]]


def _installed() -> list[Any]:
    """The interpreter, ``sys.path`` and every distribution's metadata folder on it, with the times
    of the folder and of its ``entry_points.txt`` (a new or reinstalled distribution changes them)."""
    import os

    def mtime(path: str) -> int | None:
        try:
            return os.stat(path).st_mtime_ns
        except OSError:
            return None

    found: list[Any] = [sys.version, sys.platform, sys.path]
    for entry in sys.path:
        folder = entry or "."
        try:
            names = sorted(n for n in os.listdir(folder) if n.endswith((".dist-info", ".egg-info")))
        except OSError:  # not a folder (a zip file: its time), or missing
            found.append([entry, mtime(folder)])
            continue
        found.append([entry, [(n, mtime(os.path.join(folder, n)),
                               mtime(os.path.join(folder, n, "entry_points.txt"))) for n in names]])
    return found


def _digest(facts: Any) -> str:
    import hashlib
    import json

    return hashlib.sha1(json.dumps(facts, sort_keys=True, default=str).encode()).hexdigest()[:20]


def cache_root() -> Path:
    """The folder of :func:`sawdrift.codegen.modules.cache_dir`, by the same rule.

    Repeated here because importing :mod:`sawdrift.codegen` reads the package metadata (its
    version): about 0.06 s, as long as the rest of a stored help's start (tests/test_cold_start.py
    checks that the two agree).
    """
    import os

    env = os.environ.get("SAWDRIFT_CACHE_DIR")
    if env:
        return Path(env)
    return Path(os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")) / "sawdrift"


def _stored(kind: str, key: str) -> Path:
    return cache_root() / "cli" / f"{kind}-{key}"


def _store(kind: str, key: str, data: bytes) -> None:
    """Write one stored answer atomically; keep the newest :data:`_KEEP` of its kind."""
    import os
    import tempfile

    path = _stored(kind, key)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{kind}-")
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
        old = sorted(path.parent.glob(f"{kind}-*"), key=lambda p: p.stat().st_mtime_ns)
        for stale in old[:-_KEEP]:
            stale.unlink(missing_ok=True)
    except OSError:
        pass


#: entry-point groups read once per process: numba runs the ``init`` entry points of
#: ``numba_extensions`` before its first compilation or cached load, pydantic loads the
#: ``pydantic`` group's plugins before its first validator, the model registry loads
#: ``sawdrift.models``
_SCANNED_GROUPS = ("numba_extensions", "pydantic", "sawdrift.models")


def _scanned() -> dict[str, list[list[Any]]]:
    """``[name, value, distribution]`` of every entry point of :data:`_SCANNED_GROUPS`.

    Reading them scans every installed distribution (about 0.02 s each time a library does it);
    the result is stored under the key of the installed distributions (:func:`_installed`).
    """
    import json

    key = _digest({"installed": _installed(), "groups": _SCANNED_GROUPS})
    try:
        return json.loads(_stored("entry-points", key).read_bytes())
    except (OSError, ValueError):
        pass
    from importlib.metadata import entry_points

    found = {group: sorted([ep.name, ep.value, ep.dist.name if ep.dist is not None else None]
                           for ep in entry_points(group=group))
             for group in _SCANNED_GROUPS}
    _store("entry-points", key, json.dumps(found).encode())
    return found


class _StoredEntryPoint:
    """An entry point of the stored scan, with what the model registry uses of importlib's."""

    def __init__(self, name: str, value: str, dist: str | None, group: str) -> None:
        import types

        self.name, self.value, self.group = name, value, group
        self.dist = types.SimpleNamespace(name=dist) if dist is not None else None

    def load(self) -> Any:
        from importlib.metadata import EntryPoint

        return EntryPoint(self.name, self.value, self.group).load()


def skip_plugin_scans() -> list[str]:
    """Spare numba, pydantic and the model registry their scans of every distribution.

    Each reads the entry points of every installed distribution once per process to find its
    plugins (:data:`_SCANNED_GROUPS`; about 0.015-0.03 s each). They are told the stored ones
    instead (:func:`_scanned`): numba and pydantic only when their group has none (their plugins
    are then loaded, and there are none, which is what their scans would conclude; pydantic only
    if it is imported, as every command's options import it, and has not scanned yet), the
    registry always, when it has not discovered its models yet (it loads the same entry points).
    Returns the groups whose scan was spared.
    """
    found = _scanned()
    skipped = []
    if not any(name == "init" for name, _, _ in found.get("numba_extensions", [["init", 0, 0]])):
        try:
            from numba.core import entrypoints
        except ImportError:  # pragma: no cover - numba is a dependency
            entrypoints = None
        if entrypoints is not None and getattr(entrypoints, "_already_initialized", True) is False:
            entrypoints._already_initialized = True
            skipped.append("numba_extensions")
    if found.get("pydantic", [None]) == [] and "pydantic" in sys.modules:
        from pydantic.plugin import _loader

        if getattr(_loader, "_plugins", 0) is None:
            _loader._plugins = {}
            skipped.append("pydantic")
    from .contact.registry import ENTRY_POINT_GROUP, registry

    if registry._models is None and registry.entry_points is None and ENTRY_POINT_GROUP in found:
        rows = found[ENTRY_POINT_GROUP]
        registry.entry_points = lambda: [_StoredEntryPoint(*row, ENTRY_POINT_GROUP) for row in rows]
        skipped.append(ENTRY_POINT_GROUP)
    return skipped


def skip_teardown(code: Any) -> bool:
    """End the process, once it exits with ``code``, without the interpreter's teardown.

    After the exit handlers have run, the interpreter frees every module and object one by one
    before the process ends: about 0.2 s once numba, pydantic and the scene are loaded, a sixth
    of ``sawdrift run``. This registers an exit handler that runs first, runs every other exit
    handler in their usual order (logging, temporary folders, worker pools, ...; the interpreter
    has already waited for non-daemon threads), flushes standard output and error, and ends the
    process with ``code``. The skipped teardown only frees memory the operating system reclaims
    anyway. A code that is not an exit status (a message), or standard streams that cannot be
    flushed (a closed pipe), leave the usual exit in place. Only ``python -m sawdrift`` calls this,
    as the owner of its process. Returns whether the handler was registered.
    """
    import atexit
    import os

    if code is None:
        code = 0
    if not isinstance(code, int) or not hasattr(atexit, "_run_exitfuncs"):
        return False

    def end_now() -> None:
        atexit.unregister(end_now)
        atexit._run_exitfuncs()
        try:
            for stream in (sys.stdout, sys.stderr):
                if stream is not None:
                    stream.flush()
        except (OSError, ValueError):
            return  # the usual exit reports it
        os._exit(code)

    atexit.register(end_now)
    return True


def fast_start() -> None:
    """Everything the command line does before its first compiled call (see the module text)."""
    defer_unused_numpy_submodules()
    load_cached_code_lightly()
    skip_plugin_scans()


def _help_key() -> str:
    """The key of the top-level help as this process would print it."""
    import os

    main = sys.modules.get("__main__")
    size = None
    for fd in (0, 1, 2):  # where Rich looks for the terminal's size
        try:
            size = tuple(os.get_terminal_size(fd))
            break
        except (OSError, ValueError):
            continue
    streams = (sys.stdin, sys.stdout, sys.stderr)
    here = os.path.dirname(os.path.abspath(__file__))
    return _digest({
        "installed": _installed(),
        "code": [_tree_stamp(os.path.join(here, "cli")), _tree_stamp(os.path.join(here, "_scene_options.py")),
                 _package_stamp("typer"), _package_stamp("rich")],
        "program": [sys.argv[0], getattr(getattr(main, "__spec__", None), "name", None),
                    getattr(main, "__package__", None)],
        "terminal": [[s is not None and s.isatty() for s in streams], size,
                     getattr(sys.stdout, "encoding", None), getattr(sys.stdout, "errors", None)],
        "env": {k: v for k, v in os.environ.items() if k in _HELP_ENV or k.startswith(_HELP_ENV_PREFIXES)},
    })


def _real_stdout() -> bool:
    """Whether ``sys.stdout`` is the process's own (not a test's or a caller's replacement)."""
    return sys.stdout is sys.__stdout__ and hasattr(sys.stdout, "buffer")


def replay_help() -> None:
    """Print the stored top-level help and exit with status 0, if this process's help is stored."""
    if not _real_stdout():
        return
    try:
        data = _stored("help", _help_key()).read_bytes()
    except OSError:
        return
    sys.stdout.flush()
    sys.stdout.buffer.write(data)
    sys.stdout.flush()
    raise SystemExit(0)


def stored_help(produce: Any) -> None:
    """Print the stored top-level help and exit, or run ``produce`` and store what it printed.

    ``produce`` is the command line itself (it ends in ``SystemExit``); its standard output is
    stored only when it exits with status 0.
    """
    replay_help()
    if not _real_stdout():
        produce()
        return
    key = _help_key()
    real = sys.stdout
    real.flush()
    tee = _Tee(real.buffer)
    sys.stdout = io.TextIOWrapper(tee, encoding=real.encoding, errors=real.errors,
                                  line_buffering=real.line_buffering, write_through=True)
    try:
        produce()
    except SystemExit as done:
        sys.stdout.flush()
        if done.code in (0, None) and tee.recorded:
            _store("help", key, b"".join(tee.recorded))
        raise
    finally:
        sys.stdout.flush()
        sys.stdout = real


class _Tee(io.RawIOBase):
    """A binary stream that writes through to another and records what it wrote."""

    def __init__(self, target: Any) -> None:
        super().__init__()
        self.target = target
        self.recorded: list[bytes] = []

    def writable(self) -> bool:
        return True

    def write(self, data: Any) -> int:
        data = bytes(data)
        self.target.write(data)
        self.target.flush()
        self.recorded.append(data)
        return len(data)

    def isatty(self) -> bool:
        return self.target.isatty()

    def fileno(self) -> int:
        return self.target.fileno()


def stored_models(describe: Any) -> tuple[list[dict[str, Any]], dict[str, str]]:
    """The rows of ``sawdrift models`` (one dict per model) and the plugins that failed to load.

    ``describe()`` computes them from the registry and returns ``(rows, failed, packages,
    clean)``: ``packages`` the top-level packages of the model classes outside sawdrift (their
    code is checked on every use of the stored rows), ``clean`` False if a warning was shown. Used
    only in a process whose registry has not been loaded yet, so models registered at run time
    (tests, notebooks) are never stored nor hidden.
    """
    import json
    import os

    if "sawdrift.contact.registry" in sys.modules:
        rows, failed, _packages, _clean = describe()
        return rows, failed
    here = os.path.dirname(os.path.abspath(__file__))
    key = _digest({"installed": _installed(), "code": _tree_stamp(here)})
    try:
        record = json.loads(_stored("models", key).read_bytes())
        if _digest([_package_stamp(n) for n in record["packages"]]) == record["packages_code"]:
            return record["rows"], {}
    except (OSError, ValueError, KeyError, TypeError):
        pass
    rows, failed, packages, clean = describe()
    if clean and not failed:
        _store("models", key, json.dumps({
            "packages": packages, "packages_code": _digest([_package_stamp(n) for n in packages]),
            "rows": rows}).encode())
    return rows, failed
