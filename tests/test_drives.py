"""Drives as parts: any local orbit (phase), its mirror symmetry, and a drive written as one module."""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np
import pytest
from numba import njit

import sawdrift as sd
from sawdrift.dynamics import drives
from sawdrift.dynamics.drives.base import Drive
from sawdrift.dynamics.drives.ramp import TWO_PI, ramp

MODELS = ["mmd", "mdr", "jaeger", "hertz_mindlin_dem", "material_point"]


def _scene(model: str, **drive: Any) -> sd.Scene:
    return sd.Scene(model=model, particle={"m_star": 0.1},
                    drive={"amplitude": 0.5, **drive}, numerics={"periods": 30})


@pytest.mark.parametrize("model", ["mmd", "material_point"])
def test_phase_90_and_minus_90_are_the_named_orbits_bit_for_bit(model):
    for phase, orbit in ((90.0, "prograde"), (-90.0, "retrograde"), (270.0, "retrograde")):
        a = sd.run(_scene(model, phase=phase), trajectory=True)
        b = sd.run(_scene(model, orbit=orbit), trajectory=True)
        assert a.drift_velocity == b.drift_velocity and a.orbit == orbit
        np.testing.assert_array_equal(a.trajectory.to_numpy(), b.trajectory.to_numpy())


@pytest.mark.parametrize("model", MODELS)
def test_phase_plus_180_mirrors_the_motion_exactly(model):
    # x -> -x: the laws are odd in b*, so the mirrored orbit gives the mirrored motion to the bit
    a = sd.run(_scene(model, phase=30.0), trajectory=True)
    b = sd.run(_scene(model, phase=210.0), trajectory=True)
    assert a.drift_velocity != 0.0
    assert b.drift_velocity == -a.drift_velocity
    np.testing.assert_array_equal(b.trajectory["x"].to_numpy(), -a.trajectory["x"].to_numpy())
    np.testing.assert_array_equal(b.trajectory["a"].to_numpy(), a.trajectory["a"].to_numpy())


def test_a_linear_vibration_drives_and_its_ratio_is_scaled_by_the_horizontal_speed():
    # phase 0: u_x in phase with u_y (a vibratory conveyor); the drift ratio is the drift over
    # 2 pi r A*, whatever the phase
    res = sd.run(_scene("mmd", phase=0.0))
    r = sd.Scene().horizontal_ratio
    assert res.drift_ratio == pytest.approx(res.drift_velocity / (2 * math.pi * r * 0.5), rel=1e-12)
    assert res.orbit == "phase 0"


def test_vertical_vibration_has_no_drift_ratio_but_a_drift_velocity():
    res = sd.run(_scene("mmd", horizontal_ratio=0.0, amplitude=1.5))
    assert math.isnan(res.drift_ratio) and res.summary()["drift_ratio"] is None
    assert math.isfinite(res.drift_velocity) and abs(res.drift_velocity) < 1e-12


def test_phase_and_orbit_must_agree():
    with pytest.raises(sd.SceneError, match="drive.phase"):
        sd.scene.build_scene({"drive": {"phase": 45, "orbit": "retrograde"}})
    assert sd.Scene(drive={"phase": -90, "orbit": "retrograde"}).drive.phase == -90


def test_explain_names_the_orbit_from_the_drive():
    assert "u_x = A* r R(t*) cos(2 pi t* + 45 deg)" in sd.explain(_scene("mmd", phase=45.0))
    assert "retrograde orbit" in sd.explain(_scene("mmd", phase=-90.0))


# -- a new drive is one module: this one writes the travelling wave's local orbit another way --


class CosineOrbit(Drive):
    """u_x = r A* R cos(2 pi t* + phase) evaluated directly (not split into sine and cosine)."""

    kind: ClassVar[str] = "wave"
    module: ClassVar[str] = __name__
    names: ClassVar[tuple[str, ...]] = ("amplitude", "ratio", "ramp", "phase")

    def parameters(self, scene: Any) -> dict[str, float]:
        return {"amplitude": scene.drive.amplitude, "ratio": scene.horizontal_ratio,
                "ramp": scene.drive.ramp_periods, "phase": math.radians(scene.drive.phase)}

    def ramp_periods(self, scene: Any) -> float:
        return scene.drive.ramp_periods

    def horizontal_speed(self, scene: Any) -> float:
        return 2.0 * math.pi * scene.horizontal_ratio * scene.drive.amplitude

    def vertical_amplitude(self, scene: Any) -> float:
        return scene.drive.amplitude


@njit(cache=True)
def kinematics(t, x, dp):
    rr, rd, rdd = ramp(t, dp[2])
    w = TWO_PI
    ax, ay = dp[0] * dp[1], dp[0]
    cx, sx = math.cos(w * t + dp[3]), math.sin(w * t + dp[3])
    cy, sy = math.cos(w * t), math.sin(w * t)
    return (ax * rr * cx, ax * (rd * cx - rr * w * sx),
            ax * (rdd * cx - 2.0 * rd * w * sx - rr * w * w * cx),
            ay * rr * cy, ay * (rd * cy - rr * w * sy),
            ay * (rdd * cy - 2.0 * rd * w * sy - rr * w * w * cy))


@njit(cache=True)
def surface(t, x, dp):
    k = kinematics(t, x, dp)
    return k[0], k[1], k[3], k[4]


@pytest.mark.parametrize("model", ["mmd", "material_point"])
def test_a_drive_module_plugs_into_both_schemes(model, monkeypatch):
    scene = _scene(model, phase=40.0)
    builtin = sd.run(scene)
    monkeypatch.setitem(drives.DRIVES, "wave", CosineOrbit())
    other = sd.run(scene)
    # the same orbit written another way: the drift agrees to rounding
    assert other.drift_velocity == pytest.approx(builtin.drift_velocity, rel=1e-8, abs=1e-12)
    assert other.regime == builtin.regime


def test_the_loop_runs_with_the_parameters_the_assembly_prints():
    # --explain prints Assembly.params; the stepper packs exactly those, in the loops' order
    from sawdrift.dynamics import adams_bashforth as ig
    from sawdrift.dynamics import rigid as rg
    from sawdrift.dynamics.assembly import assemble, explain
    from sawdrift.dynamics.stepper import Stepper

    for data in ({"particle": {"load": 0.02}, "effects": {"rotation": True}},
                 {"model": "material_point", "effects": {"rotation": True}}):
        scene = sd.Scene(**data)
        model = sd.model_for(scene)
        plan = assemble(scene, "compiled", model)
        st = Stepper(scene, model, plan, record=False)
        names = ig.PRM_NAMES + (rg.RIGID_PRM_NAMES if st.rigid else ())
        assert st.prm[: len(names)].tolist() == [plan.param(n) for n in names]
        text = explain(scene)
        assert f"load = {scene.particle.load:.6g}" in text and "roll = 3.5" in text


def test_the_phase_table_gives_the_sine_and_cosine_of_the_wave_at_the_steps():
    """The wave's phase read from its one-period table (the loops' parameter vector) equals sin and
    cos of 2 pi t* at the steps to 1e-15 at t* < 1, and to 1e-11 at t* ~ 1e4, where sin(2 pi t*)
    itself has lost digits to t*'s integer part (the table is the exact phase); off the step
    grid it is sin and cos themselves."""
    import math

    import numpy as np

    from sawdrift.dynamics.drives.ramp import phase, with_phase_table

    k = 128
    dp = with_phase_table(np.zeros(7), k)
    h = 1.0 / k
    for step in (0, 1, 37, 127, 128, 129, 1_280_005):
        t = step * h
        s, c = phase(t, dp, 7)
        tol = 1e-15 if t < 1.0 else 1e-11
        assert abs(s - math.sin(2 * math.pi * t)) <= tol and abs(c - math.cos(2 * math.pi * t)) <= tol
        j = step % k
        assert (s, c) == (math.sin(2 * math.pi * (j * h)), math.cos(2 * math.pi * (j * h)))
    s, c = phase(0.3 * h, dp, 7)  # off the grid
    assert (s, c) == (math.sin(2 * math.pi * 0.3 * h), math.cos(2 * math.pi * 0.3 * h))


@pytest.mark.parametrize("data", [
    {"drive": {"amplitude": 2.5}},
    {"drive": {"amplitude": 0.7, "orbit": "retrograde"}},
    {"drive": {"amplitude": 1.3, "phase": 30.0, "ramp_periods": 3.0}},
    {"drive": {"amplitude": 1.0, "backward": 0.5, "wavelength": 40.0}},
    {"drive": {"amplitude": 1.0, "backward": 0.8, "position": 0.2}},
    {"drive": {"amplitude": 1.0, "backward": 0.6, "backward_phase_rate": 3.0}},
    {"drive": {"kind": "biharmonic", "amplitude": 0.8, "second": 0.3, "second_phase": 40.0}},
    {"drive": {"amplitude": 2.0}, "effects": {"vertical_wave": False}},
])
def test_a_drives_surface_bound_holds_everywhere_and_is_tight(data):
    """The bound U of |u_y| that lets a high flight go at once (dynamics.flight) holds at every
    t* (ramp included) and x* the drive's compiled surface is sampled at, and is reached within
    3 % (a bound too loose would skip nothing; one too tight would let a landing through). The
    biharmonic bound |Y1| + |Y2| is reached only where the harmonics peak together: 1.0709 of
    1.1 at a second phase of 40 degrees."""
    scene = sd.Scene(model="mmd", **data)
    drive = drives.drive_of(scene)
    bound = drive.surface_bound(scene)
    surface = drive.functions()[0]
    dp = drive.for_steps(drive.pack(scene), 128)
    t = np.linspace(0.0, 12.0, 12 * 128 * 4 + 1)
    peak = 0.0
    for x in np.linspace(-60.0, 60.0, 241):
        peak = max(peak, max(abs(surface(ti, x, dp)[2]) for ti in t[::7]))
    assert peak <= bound * (1.0 + 1e-12)
    assert peak >= 0.97 * bound
