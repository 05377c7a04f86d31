"""The conformance suite: it passes the exact laws, reports known deviations, fails broken laws.

Each broken model below is wrong in one way the dynamics would show, and otherwise conformant:
the suite must fail it on exactly the check that names that way (and pass its repaired twin).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from numba import njit
from pydantic import BaseModel, ConfigDict

import sawdrift as sd
from sawdrift.codegen import refresh_stale_caches
from sawdrift.contact import Capabilities, ContactModel, KernelPair
from sawdrift.contact.base import KernelReference
from sawdrift.contact.conformance import CHECK_NAMES, check_model, cycles
from sawdrift.contact.normal import law_normal, law_slope
from sawdrift.contact.slots import NormalDamping, gives_normal
from sawdrift.errors import SceneError
from sawdrift.scene.profiles import Profile
from sawdrift_builtin.hertz_mindlin_dem import HertzMindlinDEM, HertzMindlinDEMParams
from sawdrift_builtin.mmd import MemoryDiagramModel as MMD
from sawdrift_builtin.mmd_kernel import mmd_step

ROOT = Path(__file__).resolve().parents[1]


def _cli(*args, env=None):
    return subprocess.run([sys.executable, "-m", "sawdrift", "check-model", *args],
                          capture_output=True, text=True, env=env, timeout=600)


def _failed(res) -> set[tuple[str, str]]:
    return {(c.profile, c.name) for c in res.failures}


@pytest.fixture
def register():
    names = []

    def add(cls):
        sd.registry.register(cls)
        names.append(cls.name)
        return cls.name

    yield add
    for name in names:
        sd.registry.unregister(name)


@pytest.fixture(scope="module", autouse=True)
def _kernels_match_their_code():
    """The kernels defined below are cached on disk (``cache=True``; compiling them cost about
    1 s each in every test process). numba checks only this file's time stamp, so before they
    run their caches are brought in line with the code they call in other files (``law_normal``,
    ``law_slope``, ``mmd_step``), as sawdrift does for a model's own kernels."""
    refresh_stale_caches([_anti_friction, _reset, _elastic, _unnormalized, _active_hysteresis,
                          _viscous, _stiffer_above_three, _negative_damp, _pow_normal_step,
                          _tenfold_negative_damp])


# -- the built-in models ------------------------------------------------------------------------

#: the checks each built-in model declares as deviations (every other check passes or is skipped)
DECLARED = {
    "mmd": set(),
    "mdr": {"split_invariance"},
    "jaeger": {"passivity"},
    "hertz_mindlin_dem": {"split_invariance"},
    # the DEM spring bounds its stored force by the total N*: while unloading, Tsuji's dashpot
    # lowers that bound, and the check's histories stay on it through every step (measured
    # 9e-16 on the table profile, 7e-8 declared there with the dashpot off)
    "hertz_tsuji": set(),
}


@pytest.mark.slow
def test_mmd_passes_every_check_on_every_profile_through_the_cli():
    out = _cli("mmd", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["model"] == "mmd"
    assert set(data["profiles"]) == {"sphere", "cone", "flat", "power", "table"}
    assert len(data["checks"]) == len(CHECK_NAMES) * 5
    assert {c["name"] for c in data["checks"]} == set(CHECK_NAMES)
    assert {c["status"] for c in data["checks"]} == {"pass"}


@pytest.mark.parametrize("name", sorted(DECLARED))
def test_builtin_models_pass_or_declare_on_every_declared_profile(name):
    if name == "hertz_tsuji":
        pytest.importorskip("sawdrift_tsuji")
    res = check_model(name)
    cls = sd.get_model(name)
    assert res.passed, res.table()
    assert res.profiles == cls.capabilities.profiles
    assert {c.name for c in res.checks if c.status == "declared"} == DECLARED[name], res.table()
    skipped = {c.name for c in res.checks if c.status == "skipped"}
    # a model that declares velocity dependence is driven with velocities, not held to independence
    assert skipped == ({"velocity_independence"} if cls.capabilities.uses_velocity else set())


def test_rigid_model_checks_are_skipped_and_bad_input_is_one_line(sawdrift_main):
    res = check_model("material_point")
    assert {c.status for c in res.checks} == {"skipped"} and res.passed
    bad = sawdrift_main("check-model", "mmd", "--param", "max_memory_points=3")  # in this process
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1
    assert "model_params.max_memory_points" in bad.stderr


def test_jaeger_declares_its_energy_creating_cycles():
    passivity = check_model("jaeger").get("passivity")
    assert passivity.status == "declared" and passivity.value < -1e-3


def test_dem_default_is_passive_by_an_independent_cycle_and_plain_is_declared():
    # independent of the suite: drive the rectangle ten times in both orientations
    rect = [(1.0, 0.0), (1.0, 0.2), (2.0, 0.2), (2.0, 0.0), (1.0, 0.0)]
    for verts in (rect, rect[::-1]):
        h = sd.ContactHistory(HertzMindlinDEM())
        h.drive(np.linspace(0.0, 1.0, 50), np.zeros(50))
        a = np.concatenate([np.linspace(p0[0], p1[0], 201)[1:] for p0, p1 in
                            zip(verts[:-1], verts[1:], strict=True)] * 10)
        b = np.concatenate([np.linspace(p0[1], p1[1], 201)[1:] for p0, p1 in
                            zip(verts[:-1], verts[1:], strict=True)] * 10)
        _, t = h.drive(a, b)
        b_all = np.concatenate([[0.0], b])
        t_all = np.concatenate([[0.0], t])
        work = float(np.sum(0.5 * (t_all[1:] + t_all[:-1]) * np.diff(b_all)))
        assert work >= -1e-9, work
    suite = check_model("hertz_mindlin_dem", rescale=False, profile="sphere")
    plain = suite.get("passivity")
    assert plain.status == "declared" and plain.value < 0.0
    # the verdict names it (it read a bare PASS)
    assert suite.table().splitlines()[0].endswith("PASS (declared deviations: passivity)")
    assert check_model("hertz_mindlin_dem", profile="sphere").get("passivity").status == "pass"
    assert HertzMindlinDEM(params=HertzMindlinDEMParams(rescale=False)).declared_deviations()


def test_every_cycle_is_closed():
    for verts in cycles().values():
        assert verts[0] == pytest.approx(verts[-1])


# -- broken models --------------------------------------------------------------------------------


@njit(cache=True)
def _anti_friction(fs, is_, pp, a, b, adot, bdot):
    # an uncapped spring whose stiffness follows a*: T* = 2 a* b* has no potential, so closed
    # cycles with a* varying create energy in one orientation, and |T*| exceeds N* at large b*
    if a <= 0.0:
        return 0.0, 0.0
    return a**1.5, 2.0 * a * b


class _Broken(MMD):
    name = "test_broken"
    capabilities = replace(MMD.capabilities, profiles=("sphere",))
    kernel = KernelPair(reset=MMD.kernel.reset, force=_anti_friction)

    def reference(self):
        class Ref:
            def reset(self):
                pass

            def force(self, a, b, adot=0.0, bdot=0.0):
                return (a**1.5, 2.0 * a * b) if a > 0.0 else (0.0, 0.0)

        return Ref()


class _SignFlipped(MMD):
    """mmd whose python reference returns the opposite tangential force."""

    name = "test_sign_flipped"
    capabilities = replace(MMD.capabilities, profiles=("sphere",))

    def reference(self):
        inner = super().reference()

        class Ref:
            def reset(self):
                inner.reset()

            def force(self, a, b, adot=0.0, bdot=0.0):
                n, t = inner.force(a, b, adot, bdot)
                return n, -t

        return Ref()


def test_broken_tangential_laws_fail_the_checks_that_catch_them(register):
    broken = check_model(register(_Broken))
    assert broken.get("passivity").status == "fail"
    assert broken.get("coulomb_bound").status == "fail"
    assert not broken.passed
    flipped = check_model(register(_SignFlipped))
    assert _failed(flipped) == {("sphere", "kernel_vs_reference")}


# Frictionless normal laws (T* = 0) given as whole kernels; each is conformant but for one defect.


@njit(cache=True)
def _reset(fs, is_, pp):
    fs[0] = 0.0


@njit(cache=True)
def _elastic(fs, is_, pp, a, b, adot, bdot):
    # the profile's elastic law, N* = N*(a*) of the normal slot
    return law_normal(a, pp, 0), 0.0


@njit(cache=True)
def _nan_above_fifteen(fs, is_, pp, a, b, adot, bdot):
    # the elastic law, but NaN beyond a* = 15 (a plugin's overflow)
    if a > 15.0:
        return math.nan, math.nan
    return law_normal(a, pp, 0), 0.0


def _sphere_only(fs, is_, pp, a, b, adot, bdot):
    # a readable reference that hard-codes the sphere's N* = a*^1.5, whatever the profile
    return (a**1.5 if a > 0.0 else 0.0), 0.0


@njit(cache=True)
def _unnormalized(fs, is_, pp, a, b, adot, bdot):
    # 1.05 a*^p: the static compression a* = 1 carries 1.05 M g
    return 1.05 * law_normal(a, pp, 0), 0.0


@njit(cache=True)
def _active_hysteresis(fs, is_, pp, a, b, adot, bdot):
    # N* = a*^p while loading and 1.2 a*^p while unloading: a hysteresis loop run backwards
    n = law_normal(a, pp, 0)
    if a < fs[0]:
        n *= 1.2
    fs[0] = a
    return n, 0.0


@njit(cache=True)
def _viscous(fs, is_, pp, a, b, adot, bdot):
    # a dissipative normal dashpot, N* = max(a*^p + 0.1 a*', 0) in contact
    n = 0.0
    if a > 0.0:
        n = max(law_normal(a, pp, 0) + 0.1 * adot, 0.0)
    return n, 0.0


@njit(cache=True)
def _stiffer_above_three(fs, is_, pp, a, b, adot, bdot):
    # elastic, but 0.01 (a* - 3)^2 stiffer than the profile's law beyond a* = 3
    n = 0.0
    if a > 0.0:
        n = law_normal(a, pp, 0) + 0.01 * max(a - 3.0, 0.0) ** 2
    return n, 0.0


class _NormalLaw(ContactModel):
    """A frictionless contact whose kernel is ``force``; the reference is ``ref`` (default: same)."""

    summary = "test model"
    capabilities = Capabilities(profiles=("sphere",), history=False)
    ref = None

    def state_sizes(self):
        return 1, 1

    def reference(self):
        if self.ref is None:
            return super().reference()
        return KernelReference(self, _reset.py_func, self.ref)


def _law(name, force, ref=None, **caps):
    return type(name, (_NormalLaw,), {
        "name": name, "kernel": KernelPair(reset=_reset, force=force),
        "ref": staticmethod(ref) if ref is not None else None,
        "capabilities": replace(_NormalLaw.capabilities, **caps)})


Elastic = _law("test_elastic", _elastic, profiles=("sphere", "cone", "flat", "power", "table"))
Unnormalized = _law("test_unnormalized", _unnormalized)
ActiveHysteresis = _law("test_active_hysteresis", _active_hysteresis)
Viscous = _law("test_viscous", _viscous, uses_velocity=True)
ViscousUndeclared = _law("test_viscous_undeclared", _viscous, uses_velocity=False)
ViscousElasticReference = _law("test_viscous_elastic_reference", _viscous, _elastic.py_func,
                               uses_velocity=True)
StifferAboveThree = _law("test_stiffer_above_three", _stiffer_above_three, _elastic.py_func)
NanAboveFifteen = _law("test_nan_above_fifteen", _nan_above_fifteen)
SphereOnlyReference = _law("test_sphere_only_reference", _elastic, _sphere_only,
                           profiles=("sphere", "cone"))


def test_the_frictionless_elastic_and_viscous_laws_pass(register):
    # the repaired twins of the models below: what fails there is their defect alone
    assert check_model(register(Elastic)).passed
    viscous = check_model(register(Viscous))
    assert viscous.passed, viscous.table()
    assert viscous.get("passivity").value > 1e-3  # the dashpot dissipates


def test_a_law_returning_nan_fails_finite_forces(register):
    # NaN compares false with every bound: the nine other checks all passed such a law
    res = check_model(register(NanAboveFifteen))
    assert _failed(res) == {("sphere", "finite_forces")}
    assert res.get("finite_forces").value > 0


def test_normalization_fails_a_law_with_n_of_1_not_1(register):
    res = check_model(register(Unnormalized))
    assert _failed(res) == {("sphere", "normalization")}
    assert res.get("normalization").value == pytest.approx(0.05, abs=1e-12)


def test_passivity_counts_the_normal_work_of_an_active_hysteresis(register):
    res = check_model(register(ActiveHysteresis))
    assert _failed(res) == {("sphere", "passivity")}
    # worst cycle: loading 5 -> 15 at a*^1.5, unloading at 1.2 a*^1.5 (the large rectangle),
    # closed integral of N* da* = -0.2 (15^2.5 - 5^2.5) / 2.5; the trapezoidal rule and the jump
    # at the turning point stay within 1 %
    expected = -0.2 * (15.0**2.5 - 5.0**2.5) / 2.5
    assert res.get("passivity").value == pytest.approx(expected, rel=1e-2)


class _NegativeDampingParams(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")

    damping: float = 0.3


@njit(cache=True)
def _negative_damp(dp, law, a, adot, n_elastic):
    # Tsuji's dashpot with its sign reversed: the contact pushes harder while it unloads
    k1 = law_slope(1.0, law, 0)
    return max(n_elastic - dp[0] * math.sqrt(law_slope(a, law, 0) / k1) * adot, 0.0)


class _NegativeDamping(NormalDamping):
    name = "negative"
    Params = _NegativeDampingParams
    damp = _negative_damp


class _SphereDEM(HertzMindlinDEM):
    capabilities = replace(HertzMindlinDEM.capabilities, profiles=("sphere",))


NegativeDamping = _SphereDEM.with_damping(_NegativeDamping, name="test_negative_damping",
                                          summary="DEM spring with an energy-creating dashpot")


def test_negative_normal_damping_fails_passivity_and_no_damping_passes(register):
    name = register(NegativeDamping)
    assert NegativeDamping.capabilities.uses_velocity  # the damping slot declares it
    res = check_model(name)
    passivity = res.get("passivity")
    assert passivity.status == "fail" and passivity.value < -1.0, res.table()
    assert "normal -" in passivity.detail  # the normal work is the negative part
    assert check_model(name, damping=0.0).get("passivity").status == "pass"


def test_kernel_vs_reference_drives_the_velocities(register):
    # the reference forgets the dashpot: only a*' != 0 tells them apart
    res = check_model(register(ViscousElasticReference))
    assert _failed(res) == {("sphere", "kernel_vs_reference")}
    assert res.get("kernel_vs_reference").value > 1e-3


def test_uses_velocity_false_is_held_to_velocity_independence(register):
    res = check_model(register(ViscousUndeclared))
    assert _failed(res) == {("sphere", "velocity_independence")}
    assert res.get("velocity_independence").value > 1e-3


def test_kernel_vs_reference_reaches_large_compressions(register):
    res = check_model(register(StifferAboveThree))
    assert _failed(res) == {("sphere", "kernel_vs_reference")}
    # the random histories reach a* = 20: |dN*| = 0.01 * 17^2 = 2.89 against 1 + max N*, the
    # kernel's 20^1.5 + 2.89
    assert res.get("kernel_vs_reference").value == pytest.approx(2.89 / (1.0 + 20.0**1.5 + 2.89),
                                                                 rel=1e-9)


def test_every_declared_profile_is_checked_and_one_can_be_chosen(register):
    name = register(SphereOnlyReference)
    res = check_model(name)
    assert res.profiles == ("sphere", "cone")
    assert _failed(res) == {("cone", "kernel_vs_reference")}
    assert res.get("kernel_vs_reference").profile == "cone"
    assert res.get("kernel_vs_reference", profile="sphere").status == "pass"
    assert check_model(name, profile="sphere").passed
    assert _failed(check_model(name, profile="cone")) == {("cone", "kernel_vs_reference")}
    assert _failed(check_model(name, profile=Profile(shape="cone"))) == {("cone", "kernel_vs_reference")}
    with pytest.raises(SceneError, match="profile = 'flat' is not declared by model"):
        check_model(name, profile="flat")


PLUGIN = '''
from sawdrift import hookimpl
from tests.test_conformance import Unnormalized


@hookimpl
def sawdrift_contact_models():
    return [Unnormalized]
'''


def test_cli_exit_status_is_1_for_a_failing_plugin_model(tmp_path):
    # a real plugin: an entry point of a distribution found on PYTHONPATH, loaded by the registry
    (tmp_path / "conformance_broken_plugin.py").write_text(PLUGIN)
    dist = tmp_path / "sawdrift_conformance_broken-0.1.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: sawdrift-conformance-broken\n"
                                   "Version: 0.1\n")
    (dist / "entry_points.txt").write_text("[sawdrift.models]\n"
                                           "test_unnormalized = conformance_broken_plugin\n")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(tmp_path), str(ROOT), os.environ.get("PYTHONPATH", "")]))
    out = _cli("test_unnormalized", env=env)
    assert out.returncode == 1, out.stdout + out.stderr
    assert out.stdout.startswith("model 'test_unnormalized': FAIL")
    failing = [line.split() for line in out.stdout.splitlines() if " fail " in line]
    assert [row[:3] for row in failing] == [["sphere", "normalization", "fail"]]


# A step that hands N* back (gives_normal) must hand the normal slot's N*(a*) to the last bit.


@njit(cache=True)
def _pow_normal_step(ts, is_, law, tp, a0, b0, a, b):
    # mmd's step, but N* = a*^1.5 by a power: the sphere's law, rounded otherwise than the slot's
    # z N*'(z) / p (many a* differ in the last bit)
    t, _n = mmd_step(ts, is_, law, tp, a0, b0, a, b)
    return t, a**1.5


class _PowNormal(MMD):
    name = "test_pow_normal"
    capabilities = replace(MMD.capabilities, profiles=("sphere",))
    step = gives_normal(_pow_normal_step)


@pytest.mark.slow
def test_a_step_handing_back_another_normal_force_fails_normal_slot(register):
    res = check_model(register(_PowNormal))
    assert _failed(res) == {("sphere", "normal_slot")}
    assert 0.0 < res.get("normal_slot").value < 1e-12
    assert check_model("mmd", "sphere").get("normal_slot").status == "pass"


@njit(cache=True)
def _tenfold_negative_damp(dp, law, a, adot, n_elastic):
    return n_elastic - 10.0 * dp[0] * adot


def test_replacing_a_damping_function_recomposes_the_kernel(monkeypatch):
    # the kernel is cached per class: a new damp function must not leave the old one running
    law = _SphereDEM.with_damping(_NegativeDamping, name="test_swapped_damping", summary="test")
    model = law(law.Params(), Profile())
    fs, is_ = (np.zeros(n, dtype=d) for n, d in zip(model.state_sizes(), (float, np.int64),
                                                     strict=True))
    pp = model.packed_params()
    c = float(model.damping_params()[0])
    n_before, _ = law.kernel.force(fs.copy(), is_.copy(), pp, 1.0, 0.0, 1.0, 0.0)
    monkeypatch.setattr(_NegativeDamping, "damp", _tenfold_negative_damp)
    n_after, _ = law.kernel.force(fs.copy(), is_.copy(), pp, 1.0, 0.0, 1.0, 0.0)
    # N*(1) = 1 elastic, a*' = 1: the dashpot's share is -c, then -10 c (this damp has no clamp)
    assert n_before == pytest.approx(1.0 - c, abs=1e-12)
    assert n_after == pytest.approx(1.0 - 10.0 * c, abs=1e-12)
    assert n_after != n_before
