"""Compiled code follows its source: editing a plugin kernel, or a function it calls in another
file, changes what runs in the next process (issue 21, item 6).

A small plugin package is written to a temporary folder: a helper ``level()`` in one file, and in
another a slot law (tangential step ``T* = scale * level()``) and a kernel-pair model with the
same tangential force. Each of three fresh processes (own cache folder, the plugin's numba cache
beside its files) registers both models, drives the slot law's composed contact directly (the
path of ``check-model``) and runs both models in a wave scene with the compiled engine and with
the python engine, which always runs the current source. Between the processes the helper, then
the kernel file, are edited. Every compiled value must be the one the current source gives: T*
exactly, and the drift equal to the python engine's to 1e-9 (relative).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import pytest

# three fresh processes, each compiling a plugin: seconds
pytestmark = pytest.mark.slow

HELPER = """
from numba import njit


@njit(cache=True)
def level():
    return {level!r}
"""

KERNEL = """
from numba import njit

from .helper import level


@njit(cache=True)
def step(ts, is_, law, tp, a0, b0, a, b):
    return {scale!r} * level()


@njit(cache=True)
def reset(fs, is_, pp):
    fs[0] = 0.0


@njit(cache=True)
def force(fs, is_, pp, a, b, adot, bdot):
    if not a > 0.0:
        return 0.0, 0.0
    return a ** 1.5, {scale!r} * level()
"""

MODELS = """
from sawdrift.contact import Capabilities, ContactModel, KernelPair
from sawdrift.contact.slots import LazyFunction, TangentialLaw


class SlotLaw(TangentialLaw):
    name = "ck_slot"
    summary = "constant tangential force (cache-key test)"
    capabilities = Capabilities(profiles=("sphere",))
    step = LazyFunction("ckplug.kern", "step")


class PairModel(ContactModel):
    name = "ck_pair"
    summary = "constant tangential force as a kernel pair (cache-key test)"
    capabilities = Capabilities(profiles=("sphere",))
    kernel = KernelPair.lazy("ckplug.kern")

    def state_sizes(self):
        return 1, 1
"""

SCRIPT = """
import json, sys
sys.path.insert(0, sys.argv[1])
import sawdrift as sd
from sawdrift.contact.registry import registry
from ckplug.models import PairModel, SlotLaw

registry.register(SlotLaw)
registry.register(PairModel)
out = {}
for name in ("ck_pair", "ck_slot"):
    # a constant tangential force drives the particle away: compared through the runaway's
    # mean acceleration (no steady drift exists), or the drift where one does
    scene = sd.Scene(model=name, numerics={"periods": 12})
    res = [sd.run(scene, engine=e) for e in ("compiled", "python")]
    out[name] = [r.drift_velocity if r.regime != "runaway" else r.mean_acceleration for r in res]
history = SlotLaw().new_history("compiled")
history.advance(1.0, 0.0)
out["slot_t"] = history.advance(1.0, 0.01)[1]
pair = PairModel().new_history("compiled")
pair.advance(1.0, 0.0)
out["pair_t"] = pair.advance(1.0, 0.01)[1]
print(json.dumps(out))
"""


def _write(root, level: float, scale: float) -> None:
    pkg = root / "ckplug"
    pkg.mkdir(exist_ok=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "models.py").write_text(textwrap.dedent(MODELS))
    (pkg / "helper.py").write_text(HELPER.format(level=level))
    (pkg / "kern.py").write_text(KERNEL.format(scale=scale))


def test_an_edited_kernel_or_callee_runs_its_new_code_in_the_next_process(tmp_path):
    root = tmp_path / "plug"
    root.mkdir()
    script = tmp_path / "run.py"
    script.write_text(SCRIPT)
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "xdg")}
    env.pop("SAWDRIFT_CACHE_DIR", None)
    runs = []
    for level, scale in [(0.25, 1.0), (0.5, 1.0), (0.5, 0.3)]:  # start, helper edit, kernel edit
        _write(root, level, scale)
        proc = subprocess.run([sys.executable, str(script), str(root)], capture_output=True,
                              text=True, env=env, cwd=tmp_path, timeout=600)
        assert proc.returncode == 0, proc.stderr[-2000:]
        got = json.loads(proc.stdout.strip().splitlines()[-1])
        runs.append(got)
        assert got["slot_t"] == level * scale, (level, scale, got)
        assert got["pair_t"] == level * scale, (level, scale, got)  # a direct kernel call
        for name in ("ck_pair", "ck_slot"):
            compiled, python = got[name]
            assert abs(compiled - python) <= 1e-9 * abs(python), (name, level, scale, got)
    for name in ("ck_pair", "ck_slot"):  # the edits change the drift: the check can tell
        drifts = [r[name][1] for r in runs]
        assert len({round(d, 9) for d in drifts}) == 3, drifts
