"""Broken plugins: one that raises on import or whose hook returns something other than model
classes becomes a one-line warning naming it; the other models keep working."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import warnings
from types import SimpleNamespace

import pytest

from sawdrift.contact.registry import PluginWarning, Registry
from sawdrift.errors import ModelNotFoundError, PluginError

from .cli_call import run_main


def _write_bad_hook_dist(root) -> None:
    """A distribution ``brokenplug`` whose hook returns ``["hello", 42]`` (entry point
    ``not_a_class``), importable with ``root`` on PYTHONPATH."""
    (root / "brokenplug").mkdir()
    (root / "brokenplug" / "__init__.py").write_text(
        "def sawdrift_contact_models():\n    return ['hello', 42]\n")
    info = root / "brokenplug-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: brokenplug\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text("[sawdrift.models]\nnot_a_class = brokenplug\n")


def _entry_point(name: str, returned: object) -> SimpleNamespace:
    plugin = SimpleNamespace(sawdrift_contact_models=lambda: returned)
    return SimpleNamespace(name=name, value=name, dist=SimpleNamespace(name="badpkg"),
                           load=lambda: plugin)


@pytest.mark.parametrize("returned", [["hello", 42], None, "mmd"])
def test_hook_returning_non_models_is_skipped_with_one_warning(returned):
    from sawdrift.contact.registry import registry

    good = [ep for ep in registry.models.values()]
    entry_points = [_entry_point("not_a_class", returned)]
    entry_points += [_entry_point(e.entry_point + "_ok", [e.cls]) for e in good[:1]]
    reg = Registry(lambda: entry_points)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        names = reg.names()  # used to raise PluginError for the whole registry
    assert names == [good[0].cls.name]
    plugin_warnings = [w for w in caught if issubclass(w.category, PluginWarning)]
    assert len(plugin_warnings) == 1
    text = str(plugin_warnings[0].message)
    assert "\n" not in text and "'not_a_class'" in text and "'badpkg'" in text
    with pytest.raises(ModelNotFoundError, match="'not_a_class' is unavailable: plugin 'not_a_class'"):
        reg.get("not_a_class")


def test_hook_mixing_models_and_junk_keeps_its_models():
    from sawdrift.contact.registry import registry

    cls = registry.get("mmd")
    reg = Registry(lambda: [_entry_point("mixed", [cls, "hello"])])
    with pytest.warns(PluginWarning, match="'hello'.*those entries are skipped"):
        assert reg.get("mmd") is cls


def test_bad_hook_plugin_in_the_command_line_warns_once_and_builtins_work(tmp_path):
    _write_bad_hook_dist(tmp_path)
    env = dict(os.environ, PYTHONPATH=str(tmp_path) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-m", "sawdrift", "models", "--json"], capture_output=True,
                         text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    names = {row["name"] for row in json.loads(out.stdout)}
    assert {"material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem"} <= names
    warning = [line for line in out.stderr.splitlines() if line.startswith("warning")]
    assert len(warning) == 1 and "'not_a_class'" in warning[0] and "'brokenplug'" in warning[0]
    run = subprocess.run([sys.executable, "-m", "sawdrift", "run", "--model", "mmd", "--periods", "10",
                          "--json"], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0 and json.loads(run.stdout)["model"] == "mmd"
    ask = subprocess.run([sys.executable, "-m", "sawdrift", "run", "--model", "not_a_class",
                          "--periods", "10"], capture_output=True, text=True, env=env, timeout=300)
    errors = [line for line in ask.stderr.splitlines() if line.startswith("error")]
    assert ask.returncode == 2 and "Traceback" not in ask.stderr
    assert len(errors) == 1 and "'not_a_class' is unavailable" in errors[0]
    assert "'hello', 42" in errors[0]


def test_broken_example_plugin_warns_and_others_work(tmp_path):
    pytest.importorskip("sawdrift_tsuji")
    # shadow the installed plugin package with one whose model module raises on import
    pkg = tmp_path / "sawdrift_tsuji"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "hertz_tsuji.py").write_text("raise RuntimeError('plugin deliberately broken')\n")
    env = dict(os.environ, PYTHONPATH=str(tmp_path) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-m", "sawdrift", "models", "--json"], capture_output=True,
                         text=True, env=env, timeout=300)
    assert out.returncode == 0
    rows = json.loads(out.stdout)
    names = {row["name"] for row in rows if row["available"]}
    assert {"material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem"} <= names
    assert "hertz_tsuji" not in names  # listed as unavailable, with its reason
    assert [r["available"] for r in rows if r["name"] == "hertz_tsuji"] == [False]
    warning = [line for line in out.stderr.splitlines() if line.startswith("warning")]
    assert len(warning) == 1
    assert "'hertz_tsuji'" in warning[0] and "sawdrift-tsuji" in warning[0]
    assert "deliberately broken" in warning[0]
    run = subprocess.run([sys.executable, "-m", "sawdrift", "run", "--model", "mmd", "--periods", "10",
                          "--json"], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0 and json.loads(run.stdout)["model"] == "mmd"


def test_plugin_listed_with_parameters_when_installed():
    pytest.importorskip("sawdrift_tsuji")
    out = run_main("models", "--json", check=True)  # in this process (tests/cli_call.py)
    rows = {row["name"]: row for row in json.loads(out.stdout)}
    assert rows["hertz_tsuji"]["distribution"] == "sawdrift-tsuji"
    assert "damping" in rows["hertz_tsuji"]["parameters"]
    for name in ("material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem", "hertz_tsuji"):
        assert isinstance(rows[name]["parameters"], dict)


def _laws():
    """Tangential laws broken in the ways plugins were: a kernel that raises, one returning NaN
    above a small displacement, and classes the registry must refuse."""
    from numba import njit

    from sawdrift import Capabilities
    from sawdrift.contact.normal import law_normal, law_slope
    from sawdrift.contact.slots import TangentialLaw

    @njit
    def raise_step(ts, is_, law, tp, a0, b0, a, b):
        if b > 0.05:
            raise ValueError("boom")
        return 0.0

    @njit
    def nan_step(ts, is_, law, tp, a0, b0, a, b):
        k = law_slope(a, law, 0)
        t = ts[0] + k * (b - b0)
        n = law_normal(a, law, 0)
        ts[0] = t = min(max(t, -n), n)
        return t if abs(b) < 0.05 else math.nan

    sphere = Capabilities(profiles=("sphere",))
    laws = {}
    for name, step, caps in (("raising_law", raise_step, sphere), ("nan_law19", nan_step, sphere),
                             ("no_profiles19", nan_step, Capabilities(profiles=())),
                             ("a,b", nan_step, sphere), ("no_step19", None, sphere)):
        attrs = {"name": name, "summary": name, "capabilities": caps}
        if step is not None:
            attrs["step"] = step
        laws[name] = type(name.replace(",", "_"), (TangentialLaw,), attrs)
    return laws


@pytest.mark.parametrize(("name", "needle"), [
    ("no_profiles19", "declares no profiles"), ("a,b", "is not usable"),
    ("no_step19", "without a step function")])
def test_a_model_class_that_cannot_be_used_is_refused_when_registered(name, needle):
    """A model with no profiles passed check-model with no check run; one named "a,b" was listed
    but --model a,b chose 'a'; a tangential law without its step was listed as available and
    an internal failure when run."""
    from sawdrift.contact.registry import registry

    cls = _laws()[name]
    with pytest.raises(PluginError, match=needle):
        registry.register(cls)
    assert name not in registry.names()
    reg = Registry(lambda: [_entry_point("bad19", [cls])])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert name not in reg.names()
    assert any(needle in str(w.message) for w in caught)
    with pytest.raises(ModelNotFoundError, match=needle):
        reg.get(name)


def test_a_plugin_kernel_that_raises_is_one_line_naming_it_and_fails_check_model():
    """A law whose kernel raises: run and check-model ended in "internal failure (boom); please
    report it", exit 3, blaming sawdrift. The run raises PluginError (exit 2) naming the model
    and its distribution; check-model fails its checks with what the model raised."""
    import sawdrift as sd
    from sawdrift.contact.registry import registry

    cls = _laws()["raising_law"]
    registry.register(cls, distribution="broken-dist")
    try:
        with pytest.raises(PluginError) as err:
            sd.run(sd.Scene(model="raising_law", numerics={"periods": 10}))
        text = str(err.value)
        assert "'raising_law'" in text and "'broken-dist'" in text and "boom" in text
        assert "\n" not in text
        result = sd.check_model("raising_law")
        assert not result.passed
        assert any("the model raised ValueError: boom" in c.detail for c in result.failures)
    finally:
        registry.unregister("raising_law")


def test_a_nan_law_fails_only_finite_forces_and_shows_the_values_it_judged():
    """A law returning NaN beyond b* = 0.05: passivity failed (a NaN compares false with the
    bound) while showing a finite cycle's value that passed (-5.55e-17, which its detail called a
    pass), and the Coulomb bound passed with a null value. Each check now judges the finite
    samples, shows the value it judged, and leaves the NaN to finite_forces."""
    import sawdrift as sd
    from sawdrift.contact.registry import registry

    registry.register(_laws()["nan_law19"])
    try:
        result = sd.check_model("nan_law19")
        assert {c.name for c in result.failures} == {"finite_forces"}
        for name in ("passivity", "coulomb_bound"):
            check = result.get(name, "sphere")
            assert math.isfinite(check.value) and check.value <= check.tolerance, name
            assert "left to finite_forces" in check.detail, name
    finally:
        registry.unregister("nan_law19")


def _raising_damp(dp, law, a, adot, n_elastic):
    """A plugin's normal damping that raises (a plain Python function, not compiled)."""
    raise ValueError("kernel exploded")


def test_a_plugin_damping_that_raises_where_the_step_is_chosen_names_the_plugin():
    """The step per period asks a velocity-dependent law for its dashpot before any run (a run's
    size estimate too): there a plugin's damping that raised was an internal failure, exit 3
    ("KeyError: '__builtins__'"), on both engines. It is the plugin's one-line PluginError."""
    from typing import ClassVar

    from pydantic import BaseModel, ConfigDict, Field

    import sawdrift as sd
    from sawdrift.contact.base import LazyFunction
    from sawdrift.contact.registry import registry
    from sawdrift.contact.slots import NormalDamping
    from sawdrift.dynamics.assembly import steps_per_period
    from sawdrift_builtin.hertz_mindlin_dem import HertzMindlinDEM

    class DampParams(BaseModel):
        model_config = ConfigDict(frozen=True, extra="forbid")
        damping: float = Field(0.1, ge=0.0, description="x")

    class Damp(NormalDamping):
        name: ClassVar[str] = "raising_damp20"
        Params: ClassVar[type[BaseModel]] = DampParams
        damp: ClassVar[LazyFunction] = LazyFunction(__name__, "_raising_damp")

    model = HertzMindlinDEM.with_damping(Damp, name="raising_damp_model20", summary="raises")
    registry.register(model, distribution="broken-dist")
    try:
        scene = sd.Scene(model="raising_damp_model20", numerics={"periods": 5})
        with pytest.raises(PluginError, match=r"'raising_damp_model20' from 'broken-dist'"):
            steps_per_period(scene)
    finally:
        registry.unregister("raising_damp_model20")
