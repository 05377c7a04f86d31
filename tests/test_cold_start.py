"""Time to first answer: --help and models import neither numba, pandas nor matplotlib."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("numba", "pandas", "matplotlib", "scipy")


LIGHT = [["--help"], ["models"], ["run", "--help"]]


def test_light_commands_do_not_import_heavy_libraries():
    # one fresh process runs the light commands one after the other and prints, after each, the
    # heavy libraries imported so far (one process instead of three: 1-2 s each of start-up)
    code = (
        "import sys\n"
        "from sawdrift.cli import main\n"
        f"for argv in {LIGHT!r}:\n"
        "    sys.argv = ['sawdrift', *argv]\n"
        "    try:\n        main()\n    except SystemExit:\n        pass\n"
        f"    print('HEAVY', argv, sorted(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    after = [line for line in out.stdout.splitlines() if line.startswith("HEAVY ")]
    assert after == [f"HEAVY {argv!r} []" for argv in LIGHT], out.stdout[-400:]


_LIGHT = """
import sys, numpy as np
from numba import njit
from sawdrift._startup import load_cached_code_lightly
assert load_cached_code_lightly()

@njit(cache=True)
def ab_sum(x):
    s = 0.0
    for v in x:
        s += np.sin(v) * v
    return s

x = np.linspace(0.0, 3.0, 1001)
got = ab_sum(x)
loaded = not any(v for v in ab_sum.stats.cache_misses.values())
registries = "numba.np.arraymath" in sys.modules

@njit
def fresh(x):  # compiled after the light load: numba's compiler refreshes the full target
    return np.sum(np.cos(x)), np.argmax(x)

s, i = fresh(x)
print(repr(got), loaded, registries, repr(s), i)
"""


def test_light_cache_load_gives_the_compiled_result_and_leaves_compiling_intact(tmp_path):
    """A cached function loads without numba's lowering registries and returns the same value.

    Run twice in fresh processes sharing one cache folder: the first compiles and writes the
    cache, the second loads it through ``load_cached_code_lightly``. Both values must agree with
    numpy to 1e-12, the second load must be a cache hit that did not import
    ``numba.np.arraymath``, and a function compiled afterwards must still be right.
    """
    import os

    import numpy as np

    script = tmp_path / "light.py"
    script.write_text(_LIGHT)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    runs = [
        subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env,
                       check=True, cwd=tmp_path).stdout.split()
        for _ in range(2)
    ]
    x = np.linspace(0.0, 3.0, 1001)
    expect = float(np.sum(np.sin(x) * x))
    for got, _, _, s, i in runs:
        assert abs(float(got) - expect) <= 1e-12 * abs(expect)
        assert abs(float(s) - float(np.sum(np.cos(x)))) <= 1e-12
        assert int(i) == 1000
    assert runs[1][1] == "True", "second process should load from the disk cache"
    assert runs[1][2] == "False", "a light cache load imported numba's lowering registries"


def _sawdrift(args: list[str], cache, extra_env: dict[str, str] | None = None,
              importtime: bool = False) -> subprocess.CompletedProcess:
    """``python -m sawdrift ARGS`` in a fresh process whose stored answers live in ``cache``."""
    import os

    env = {**os.environ, "SAWDRIFT_CACHE_DIR": str(cache), **(extra_env or {})}
    flags = ["-X", "importtime"] if importtime else []
    return subprocess.run([sys.executable, *flags, "-m", "sawdrift", *args], capture_output=True,
                          text=True, env=env, check=True, timeout=300)


def _imported(run: subprocess.CompletedProcess, name: str) -> bool:
    """Whether ``-X importtime`` of a process lists the module ``name``."""
    return any(line.rsplit("|", 1)[-1].strip() == name for line in run.stderr.splitlines())


def test_stored_help_is_the_printed_help_and_follows_the_width(tmp_path):
    # the first process prints the help and stores it; the second prints the stored copy
    # without importing Typer, byte for byte the same; another width is another key, and its
    # help is the one a process without any stored help prints at that width
    first = _sawdrift(["--help"], tmp_path / "a", {"COLUMNS": "80"})
    second = _sawdrift(["--help"], tmp_path / "a", {"COLUMNS": "80"}, importtime=True)
    assert second.stdout == first.stdout
    assert not _imported(second, "typer") and _imported(second, "sawdrift._startup")
    wide = _sawdrift(["--help"], tmp_path / "a", {"COLUMNS": "120"})
    fresh = _sawdrift(["--help"], tmp_path / "b", {"COLUMNS": "120"})
    assert wide.stdout == fresh.stdout != first.stdout
    assert max(map(len, wide.stdout.splitlines())) == 120
    assert max(map(len, first.stdout.splitlines())) == 80


def test_stored_models_are_the_listed_models(tmp_path):
    # the second process lists the stored rows without importing numpy (no plugin is loaded),
    # the same text and JSON as the first, which computed them
    first = _sawdrift(["models", "--json"], tmp_path)
    second = _sawdrift(["models", "--json"], tmp_path, importtime=True)
    assert second.stdout == first.stdout
    assert not _imported(second, "numpy") and _imported(second, "sawdrift._startup")
    rows = json.loads(second.stdout)
    assert {"material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem"} <= {r["name"] for r in rows}


def test_a_broken_plugin_is_listed_as_computed_and_never_stored(tmp_path):
    # a plugin shadowed by one that raises on import: its warning is shown by every process
    # (nothing stored), and shadowing changes the key, so the good listing is not used either
    pytest.importorskip("sawdrift_tsuji")
    import os

    pkg = tmp_path / "shadow" / "sawdrift_tsuji"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "hertz_tsuji.py").write_text("raise RuntimeError('plugin deliberately broken')\n")
    _sawdrift(["models"], tmp_path / "cache")  # stores the good listing
    path = str(pkg.parent) + os.pathsep + os.environ.get("PYTHONPATH", "")
    runs = [_sawdrift(["models"], tmp_path / "cache", {"PYTHONPATH": path}) for _ in range(2)]
    for run in runs:
        assert "deliberately broken" in run.stderr
        listed = [line for line in run.stdout.splitlines() if line.startswith("hertz_tsuji ")]
        assert len(listed) == 1 and "unavailable: RuntimeError" in listed[0]
    assert len(list((tmp_path / "cache" / "cli").glob("models-*"))) == 1
    # the JSON lists it too, unavailable with its reason (it was left out)
    rows = json.loads(_sawdrift(["models", "--json"], tmp_path / "cache",
                                {"PYTHONPATH": path}).stdout)
    broken = [r for r in rows if r["name"] == "hertz_tsuji"]
    assert len(broken) == 1 and broken[0]["available"] is False
    assert "RuntimeError" in broken[0]["reason"]
    assert all(r["available"] for r in rows if r["name"] == "mmd")


def test_cache_root_is_the_generated_modules_folder(monkeypatch, tmp_path):
    from sawdrift._startup import cache_root
    from sawdrift.codegen.modules import cache_dir

    for env in ({"SAWDRIFT_CACHE_DIR": str(tmp_path / "s")}, {"XDG_CACHE_HOME": str(tmp_path)}, {}):
        for name in ("SAWDRIFT_CACHE_DIR", "XDG_CACHE_HOME"):
            monkeypatch.delenv(name, raising=False)
        for name, value in env.items():
            monkeypatch.setenv(name, value)
        assert cache_root() == cache_dir()


_PLUGINS = """
import os, sys
import pydantic
from sawdrift._startup import fast_start
fast_start()
from numba.core import entrypoints
from pydantic.plugin import _loader
skipped = [entrypoints._already_initialized, _loader._plugins == {}]
from numba import njit

@njit
def plus_one(x):
    return x + 1

class Point(pydantic.BaseModel):
    x: float

results = [plus_one(1), Point(x=1).x]
marker = os.environ["FAKEEXT_MARKER"]
loaded = [os.path.exists(marker + ".numba"), os.path.exists(marker + ".pydantic")]
print(*skipped, *results, *loaded)
"""


def test_plugin_scans_are_skipped_only_when_nothing_is_installed(tmp_path):
    # without numba extensions or pydantic plugins the libraries' scans are answered from the
    # stored one (flags set before any compilation or validator); a distribution with a
    # numba_extensions 'init' and a pydantic plugin entry point makes a new key, and both
    # plugins still load when numba first compiles and pydantic first builds a validator
    import os

    script = tmp_path / "plugins.py"
    script.write_text(_PLUGINS)
    site = tmp_path / "site"
    info = site / "fakeext-0.1.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: fakeext\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text("[numba_extensions]\ninit = fakeext:init\n\n"
                                           "[pydantic]\nfake = fakeext:plugin\n")
    marker = tmp_path / "loaded"
    (site / "fakeext.py").write_text(
        f"open({str(marker)!r} + '.pydantic', 'w').close()\n"
        "class _Plugin:\n"
        "    def new_schema_validator(self, *args, **kwargs):\n"
        "        return None, None, None\n"
        "plugin = _Plugin()\n"
        f"def init():\n    open({str(marker)!r} + '.numba', 'w').close()\n")
    base = {**os.environ, "SAWDRIFT_CACHE_DIR": str(tmp_path / "cache"), "FAKEEXT_MARKER": str(marker)}
    base.pop("PYDANTIC_DISABLE_PLUGINS", None)
    with_ext = {**base, "PYTHONPATH": str(site) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    outs = [subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env,
                           check=True, cwd=tmp_path, timeout=300).stdout.split()
            for env in (base, base, with_ext)]
    assert outs[0] == outs[1] == ["True", "True", "2", "1.0", "False", "False"]
    assert outs[2] == ["False", "False", "2", "1.0", "True", "True"]
    stored = sorted((tmp_path / "cache" / "cli").glob("entry-points-*"))
    pydantic_plugins = sorted(json.loads(p.read_text())["pydantic"] for p in stored)
    assert pydantic_plugins == [[], [["fake", "fakeext:plugin", "fakeext"]]]


def test_the_start_up_map_names_the_module_of_every_command():
    # `sawdrift NAME` imports only COMMAND_MODULES[NAME]: each command (and the bench group's
    # commands) must be registered by that module, and every command must be in the map, which
    # also fixes the order of --help
    from sawdrift.cli import app
    from sawdrift.cli.app import COMMAND_MODULES

    found = {info.name: info.callback.__module__ for info in app.registered_commands}
    for group in app.registered_groups:
        modules = {info.callback.__module__ for info in group.typer_instance.registered_commands}
        assert len(modules) == 1, (group.name, modules)
        found[group.name] = modules.pop()
    assert found == {name: f"sawdrift.cli.{module}" for name, module in COMMAND_MODULES.items()}
    commands = [info.name for info in app.registered_commands]
    assert commands == [name for name in COMMAND_MODULES if name in commands]


def test_registry_from_the_stored_entry_points_is_the_scanned_registry(monkeypatch, tmp_path):
    # the model registry fed the stored entry points finds the same models, from the same
    # distributions and entry points, as one that scans the installed distributions; the second
    # read comes from the stored file
    from sawdrift._startup import _scanned, _StoredEntryPoint
    from sawdrift.contact.registry import ENTRY_POINT_GROUP, Registry

    monkeypatch.setenv("SAWDRIFT_CACHE_DIR", str(tmp_path))
    first = _scanned()
    assert len(list((tmp_path / "cli").glob("entry-points-*"))) == 1
    assert _scanned() == first

    def stored():
        return [_StoredEntryPoint(*row, ENTRY_POINT_GROUP) for row in _scanned()[ENTRY_POINT_GROUP]]

    scanned, from_store = Registry(), Registry(entry_points=stored)
    assert {"material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem"} <= set(scanned.models)
    assert {n: (e.cls, e.distribution, e.entry_point) for n, e in from_store.models.items()} == \
        {n: (e.cls, e.distribution, e.entry_point) for n, e in scanned.models.items()}
    assert from_store.failed == scanned.failed


_TEARDOWN = """
import atexit, sys, tempfile
from sawdrift._startup import skip_teardown

marker, code, skip = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "skip"
atexit.register(lambda: open(marker + ".atexit", "w").close())
folder = tempfile.TemporaryDirectory()  # removed by its finalizer, an exit handler
open(marker + ".folder", "w").write(folder.name)


class Freed:
    def __del__(self, path=marker + ".freed", open=open):
        open(path, "w").close()


kept = Freed()  # a module global: freed by the interpreter's teardown only
sys.stdout.write("y" * 100000)  # still buffered when the process ends
try:
    raise SystemExit(code)
except SystemExit as done:
    if skip:
        skip_teardown(done.code)
    raise
"""


@pytest.mark.parametrize("code", [0, 3])
def test_skip_teardown_keeps_exit_status_handlers_and_output(tmp_path, code):
    # with and without skipping the teardown: the same exit status, the whole buffered output,
    # the exit handlers run (one of them removes a temporary folder); only the teardown's freeing
    # of a module global is gone
    script = tmp_path / "teardown.py"
    script.write_text(_TEARDOWN)
    seen = {}
    for mode in ("usual", "skip"):
        marker = tmp_path / mode
        out = subprocess.run([sys.executable, str(script), str(marker), str(code), mode],
                             capture_output=True, text=True, timeout=120)
        folder = (tmp_path / f"{mode}.folder").read_text()
        seen[mode] = (out.returncode, len(out.stdout), (tmp_path / f"{mode}.atexit").exists(),
                      __import__("os").path.exists(folder), (tmp_path / f"{mode}.freed").exists())
    assert seen["usual"] == (code, 100000, True, False, True)
    assert seen["skip"] == (code, 100000, True, False, False)
