"""A prescribed history's compiled loop is cached on disk: a second process loads it.

``ContactHistory.drive`` runs a kernel over a sampled history in one compiled loop bound to the
kernel (generated through :mod:`sawdrift.codegen`, as the wave loop). A small plugin kernel is
written to a temporary folder; two fresh processes sharing one cache folder drive the same
history through it, quasi-statically and with rates. The first compiles the two loops, the second
must load both from the disk cache (numba's dispatcher statistics: hits, no misses). Both must give
N*, T* equal bit for bit to the closed form of the kernel and to the python engine.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

# two fresh processes, the first compiling a kernel and its loops: several seconds
pytestmark = pytest.mark.slow

KERNEL = """
from numba import njit


@njit(cache=True)
def reset(fs, is_, pp):
    fs[0] = 0.0


@njit(cache=True)
def force(fs, is_, pp, a, b, adot, bdot):
    # N* = a*^2 in contact; T* = b* since the last separation (its b* in fs[0]) plus bdot/4
    if not a > 0.0:
        fs[0] = b
        return 0.0, 0.0
    return a * a, (b - fs[0]) + 0.25 * bdot
"""

MODELS = """
from sawdrift.contact import Capabilities, ContactModel, KernelPair


class DriveModel(ContactModel):
    name = "dc_pair"
    summary = "a kernel pair for the drive-loop cache test"
    capabilities = Capabilities(profiles=("sphere",))
    kernel = KernelPair.lazy("dcplug.kern")

    def state_sizes(self):
        return 1, 1
"""

SCRIPT = """
import json, sys
sys.path.insert(0, sys.argv[1])
import numpy as np
from sawdrift.contact import history as H
from dcplug.models import DriveModel

a = np.array([0.5, 1.0, -0.25, 0.75, 1.5, 0.0, 2.0])
b = np.array([0.0, 0.125, 0.5, 0.25, -0.5, 1.0, 1.25])
bdot = np.array([1.0, -2.0, 0.5, 4.0, 0.0, 3.0, -1.0])
out = {}
for engine in ("compiled", "python"):
    h = DriveModel().new_history(engine)
    qs = h.drive(a, b)
    rate = h.drive(a, b, None, bdot)
    out[engine] = [x.tolist() for x in (*qs, *rate)]
model = DriveModel()
loops = H._DRIVERS[model.kernel.force]
out["stats"] = {n: [sum(loops[n].stats.cache_hits.values()), sum(loops[n].stats.cache_misses.values()),
                    loops[n].py_func.__module__]
                for n in ("drive_body", "drive_body_quasi_static")}
print(json.dumps(out))
"""


def _closed_form(a, b, bdot, last_b):
    """N*, T* of the kernel in KERNEL along a, b (rates bdot), from separation at b* = last_b."""
    n_out, t_out = [], []
    for ak, bk, dk in zip(a, b, bdot, strict=True):
        if not ak > 0.0:
            last_b = bk
            n_out.append(0.0)
            t_out.append(0.0)
        else:
            n_out.append(ak * ak)
            t_out.append((bk - last_b) + 0.25 * dk)
    return n_out, t_out, last_b


def test_a_second_process_loads_the_drive_loops_from_the_disk_cache(tmp_path):
    pkg = tmp_path / "plug" / "dcplug"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "kern.py").write_text(KERNEL)
    (pkg / "models.py").write_text(MODELS)
    script = tmp_path / "run.py"
    script.write_text(SCRIPT)
    env = {**os.environ, "SAWDRIFT_CACHE_DIR": str(tmp_path / "cache")}
    runs = []
    for _ in range(2):
        proc = subprocess.run([sys.executable, str(script), str(tmp_path / "plug")],
                              capture_output=True, text=True, env=env, cwd=tmp_path, timeout=600)
        assert proc.returncode == 0, proc.stderr[-2000:]
        runs.append(json.loads(proc.stdout.strip().splitlines()[-1]))
    a = [0.5, 1.0, -0.25, 0.75, 1.5, 0.0, 2.0]
    b = [0.0, 0.125, 0.5, 0.25, -0.5, 1.0, 1.25]
    bdot = [1.0, -2.0, 0.5, 4.0, 0.0, 3.0, -1.0]
    n_qs, t_qs, last = _closed_form(a, b, [0.0] * len(a), 0.0)
    n_rate, t_rate, _ = _closed_form(a, b, bdot, last)  # the second drive continues the history
    expect = [n_qs, t_qs, n_rate, t_rate]
    for run in runs:
        assert run["compiled"] == expect, run
        assert run["python"] == expect, run
    for name in ("drive_body", "drive_body_quasi_static"):
        first_hits, first_misses, module = runs[0]["stats"][name]
        hits, misses, module2 = runs[1]["stats"][name]
        assert module.startswith("sawdrift_loop_") and module2 == module, (name, runs)
        assert first_misses >= 1, (name, runs[0]["stats"])  # the first process compiled it
        assert hits >= 1 and misses == 0, (name, runs[1]["stats"])  # the second loaded it
