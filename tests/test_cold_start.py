"""Time to first answer: --help and models import neither numba, pandas nor matplotlib."""

from __future__ import annotations

import subprocess
import sys

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
