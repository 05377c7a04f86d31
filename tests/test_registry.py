"""Plugin discovery: entry points, broken plugins, duplicate names, trial/commit safety."""

from __future__ import annotations

import importlib
import types

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.contact.registry import PluginWarning, Registry

# ``sawdrift.contact.registry`` the attribute is the Registry instance; this is the module
reg = importlib.import_module("sawdrift.contact.registry")


class _FakeDist:
    def __init__(self, name: str) -> None:
        self.name = name


class _FakeEntryPoint:
    def __init__(self, name: str, dist: str, load) -> None:
        self.name = name
        self.dist = _FakeDist(dist)
        self._load = load

    def load(self):
        return self._load()


def _plugin(*classes):
    module = types.ModuleType("fake_plugin")

    @sd.hookimpl
    def sawdrift_contact_models():
        return list(classes)

    module.sawdrift_contact_models = sawdrift_contact_models
    return module


def _with_entry_points(monkeypatch, eps):
    real = reg.im.entry_points

    def fake(group=None, **kw):
        if group == reg.ENTRY_POINT_GROUP:
            return list(real(group=group)) + eps
        return real(group=group, **kw)

    monkeypatch.setattr(reg.im, "entry_points", fake)
    return Registry()


def test_builtin_models_come_from_entry_points():
    models = sd.registry.models
    for name in ("material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem"):
        assert models[name].distribution == "sawdrift"
        assert models[name].entry_point == name


def test_broken_plugin_is_a_warning_naming_it(monkeypatch):
    def boom():
        raise ImportError("deliberately broken")

    fresh = _with_entry_points(monkeypatch, [_FakeEntryPoint("broken_model", "broken-dist", boom)])
    with pytest.warns(PluginWarning, match="'broken_model' from distribution 'broken-dist'"):
        names = fresh.names()
    assert "mmd" in names and "material_point" in names
    assert "broken_model" in fresh.failed


def test_a_plugin_reusing_a_builtin_name_is_skipped_and_the_builtin_kept(monkeypatch):
    # a plugin called 'mmd' disabled sawdrift's own mmd too: the default scene, the demo and
    # the validation report failed
    class Clash(sd.ContactModel):
        name = "mmd"
        summary = "clash"

    fresh = _with_entry_points(monkeypatch, [_FakeEntryPoint("clash", "other-dist", lambda: _plugin(Clash))])
    with pytest.warns(PluginWarning, match=r"'mmd' is sawdrift's own; the one from 'other-dist'"):
        names = fresh.names()
    assert "mmd" in names and fresh.get("mmd") is not Clash
    assert fresh.models["mmd"].distribution == "sawdrift"
    assert {"mdr", "jaeger", "material_point", "hertz_mindlin_dem"} <= set(names)


def test_two_plugins_claiming_one_name_disable_only_that_name(monkeypatch):
    class First(sd.ContactModel):
        name = "twice"
        summary = "first"

    class Second(sd.ContactModel):
        name = "twice"
        summary = "second"

    fresh = _with_entry_points(monkeypatch, [
        _FakeEntryPoint("first", "dist-a", lambda: _plugin(First)),
        _FakeEntryPoint("second", "dist-b", lambda: _plugin(Second))])
    with pytest.warns(PluginWarning, match=r"'twice' is claimed by .*'dist-a'.*'dist-b'"):
        names = fresh.names()
    assert "twice" not in names
    # every other model keeps working
    assert {"mmd", "mdr", "jaeger", "material_point", "hertz_mindlin_dem"} <= set(names)
    with pytest.raises(sd.ModelNotFoundError, match="unavailable: model name 'twice' is claimed"):
        fresh.get("twice")


def test_trial_never_corrupts_the_committed_history():
    model = sd.get_model("mmd")()
    rng = np.random.default_rng(3)
    a = 1.0 + 0.3 * rng.standard_normal(200)
    b = np.cumsum(0.2 * rng.standard_normal(200))
    plain = model.new_history()
    probed = model.new_history()
    for ai, bi in zip(a, b, strict=True):
        # a trial far away (full sliding, contact loss) between commits
        probed.trial(ai + 5.0, bi - 50.0)
        probed.trial(-1.0, 0.0)
        assert probed.advance(ai, bi) == plain.advance(ai, bi)


@pytest.mark.parametrize("engine", ["compiled", "python"])
def test_reset_equals_a_fresh_history(engine):
    model = sd.get_model("mmd")()
    rng = np.random.default_rng(5)
    a = 1.0 + 0.4 * rng.standard_normal(300)
    b = np.cumsum(0.3 * rng.standard_normal(300))
    used = model.new_history(engine)
    used.drive(a[::-1], b[::-1] + 7.0)
    used.reset()
    n1, t1 = used.drive(a, b)
    n2, t2 = model.new_history(engine).drive(a, b)
    assert np.array_equal(n1, n2) and np.array_equal(t1, t2)


def test_a_model_for_another_kernel_interface_is_skipped_with_a_warning(monkeypatch):
    class Future(sd.ContactModel):
        name = "future_model"
        summary = "written for a later kernel protocol"
        kernel_interface = 99

    fresh = _with_entry_points(monkeypatch, [_FakeEntryPoint("future", "future-dist",
                                                             lambda: _plugin(Future))])
    with pytest.warns(PluginWarning, match="kernel interface 99"):
        names = fresh.names()
    assert "future_model" not in names and "mmd" in names
    with pytest.raises(sd.ModelNotFoundError, match="unavailable: model 'future_model' is written"):
        fresh.get("future_model")
