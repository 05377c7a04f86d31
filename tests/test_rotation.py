"""Rotation: a sphere free to turn (I = kappa m R^2)."""

from __future__ import annotations

import json
import math

import pytest

import sawdrift as sd
from sawdrift.analytic import heavy_sliding_v
from sawdrift.validation import MU, point_scene

from .cli_call import run_main


@pytest.mark.parametrize("kappa", [0.4, 2.0 / 3.0])
def test_rigid_sphere_rolls_without_gross_slip_below_its_bound(kappa):
    bound = (1.0 + 1.0 / kappa) * MU * math.sqrt(1.0 - 0.3**2)
    on = {"effects.rotation": True, "particle.gyration": kappa}
    below = sd.run(point_scene(0.3, 0.97 * bound).with_updates(**on))
    above = sd.run(point_scene(0.3, 1.03 * bound).with_updates(**on))
    assert below.gross_slip_fraction == 0.0 and below.regime == "stick"
    assert above.gross_slip_fraction > 0.0
    # without rotation the same forcing is 3.5 (2.5) times the point's bound: it slides
    assert sd.run(point_scene(0.3, 0.97 * bound)).gross_slip_fraction > 0.5


def _cli_json(*args: str) -> dict:
    out = run_main("run", "--model", "mmd", "--m-star", "0.1", "--amplitude", "0.316", "--json",
                   *args, check=True).stdout  # in this process (tests/cli_call.py)
    return json.loads(out)


@pytest.mark.slow
def test_mmd_rotation_cli_and_no_rotation_equals_plain_run():
    plain, off, on = _cli_json(), _cli_json("--no-rotation"), _cli_json("--rotation")
    for key in ("drift_ratio", "drift_velocity", "regime", "gross_slip_fraction", "steps",
                "min_compression", "liftoffs_per_period"):
        assert off[key] == plain[key], key
    assert plain["spin_rate"] is None
    assert math.isfinite(on["drift_ratio"]) and on["spin_rate"] is not None
    assert abs(on["drift_ratio"] - plain["drift_ratio"]) > 0.01


def test_integrated_spin_is_drift_over_kappa():
    # I phi'' = -R T and m x'' = -T give R phi' = x*' / kappa from rest. With a rolling spring of
    # negligible strength (mu_r = 1e-12) the loop integrates psi = R phi / a0 as a state of its
    # own (kappa m* psi'' = -mu T* + m_r), so its spin and the centre's drift are two independent
    # integrals of the same T*: they must agree to the step's truncation error. Both runs are
    # fixed (60 periods): the same window, which a default run of either could extend differently
    base = dict(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316},
                numerics={"settle": False})
    free = sd.run(sd.Scene(**base, effects={"rotation": True}))
    tiny = sd.run(sd.Scene(**base, effects={"rotation": True, "rolling_resistance": 1e-12}),
                  trajectory=True)
    assert tiny.spin_rate == pytest.approx(tiny.drift_velocity / 0.4, rel=1e-6)
    assert tiny.drift_ratio == pytest.approx(free.drift_ratio, rel=1e-6)
    # the trajectory carries the rolling angle and its rate
    tr = tiny.trajectory
    assert {"psi", "spin"} <= set(tr.columns)
    assert tr["psi"].iloc[-1] == pytest.approx(tr["x"].iloc[-1] / 0.4, rel=1e-6)


def test_rolling_heavy_sliding_matches_closed_form():
    # V = kappa / (1 + kappa) cos(phi0): the contact point slides like the point, the centre
    # follows at kappa / (1 + kappa) of its speed
    kappa, gz = 0.4, 0.5
    c = 1.0 + 1.0 / kappa
    scene = point_scene(gz, MU * c / 0.02, periods=40, measure_periods=10, settle=True,
                        settle_tolerance=1e-6)
    res = sd.run(scene.with_updates(**{"effects.rotation": True, "particle.gyration": kappa}))
    assert res.drift_ratio == pytest.approx(heavy_sliding_v(gz) / c, rel=0.01)


def test_explain_prints_rotation_and_kappa():
    text = sd.explain(sd.Scene(effects={"rotation": True}, particle={"gyration": 0.5}))
    assert "kappa = 0.5" in text and "I phi''" in text
    assert "rotation" not in sd.explain(sd.Scene())


def test_gyration_is_validated():
    with pytest.raises(sd.SceneError, match="particle.gyration"):
        sd.scene.build_scene({"particle": {"gyration": 1.5}})


def test_rolling_resistance_spans_free_rolling_and_locked_rotation():
    # mu_r -> 0: the rolling spring vanishes and the sphere rolls freely; mu_r -> infinity: the
    # spring locks the rotation and the drift tends to the run without rotation (all over the
    # same fixed 60-period window)
    base = dict(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316},
                numerics={"settle": False})
    plain = sd.run(sd.Scene(**base))
    free = sd.run(sd.Scene(**base, effects={"rotation": True}))
    weak = sd.run(sd.Scene(**base, effects={"rotation": True, "rolling_resistance": 1e-6}))
    stiff = sd.run(sd.Scene(**base, effects={"rotation": True, "rolling_resistance": 30.0}))
    assert weak.drift_ratio == pytest.approx(free.drift_ratio, abs=1e-4)
    assert stiff.drift_ratio == pytest.approx(plain.drift_ratio, abs=2e-3)
    assert abs(stiff.spin_rate) < 1e-5 < abs(free.spin_rate)


def test_rolling_resistance_needs_rotation_and_a_compliant_model():
    with pytest.raises(sd.SceneError, match="rolling_resistance"):
        sd.bind(sd.scene.build_scene({"effects": {"rolling_resistance": 0.1}}))
    with pytest.raises(sd.SceneError, match="rigid"):
        sd.bind(sd.scene.build_scene({"model": "material_point",
                                      "effects": {"rotation": True, "rolling_resistance": 0.1}}))


def _rolling(model: str, amplitude: float, load: float, mu_r: float = 0.0, m: float = 0.1,
             mu: float = 0.1, **drive) -> sd.Scene:
    return sd.Scene(model=model, particle={"m_star": m, "load": load},
                    drive={"amplitude": amplitude, **drive}, material={"mu": mu},
                    effects={"rotation": True, "rolling_resistance": mu_r})


def _fitted_acceleration(scene: sd.Scene, periods: int) -> float:
    """Twice the quadratic coefficient of x*(t*) over the last half of a fixed run of
    ``periods``: the brute-force mean acceleration the Result's closed form must match."""
    import numpy as np

    fixed = scene.with_updates(**{"numerics.settle": False, "numerics.periods": periods,
                                  "numerics.measure_periods": periods // 2})
    tr = sd.run(fixed, trajectory=True).trajectory
    late = tr[tr["t"] >= periods / 2]
    return 2.0 * float(np.polyfit(late["t"], late["x"], 2)[0])


@pytest.mark.parametrize(("model", "amplitude", "drive"), [
    ("material_point", 0.0, {}), ("mmd", 0.2, {"horizontal_ratio": 0.0}), ("mmd", 0.5, {})])
def test_a_sphere_free_to_turn_rolls_away_under_a_load_below_mu(model, amplitude, drive):
    """The load acts on the centre, friction alone turns the sphere, so no load is held: with
    L = 0.05 < mu = 0.1 the sphere rolls away at L / (m* (1 + kappa)) = 0.357 per period^2 (a
    fit over periods 100-200 of the run agrees to 1e-6). A still substrate said stick, settled,
    with a drift of 16.6; a vertical vibration, or the wave, said a settled drift."""
    scene = _rolling(model, amplitude, 0.05, **drive)
    res = sd.run(scene)
    assert res.regime == "runaway" and res.settled is False and math.isnan(res.drift_velocity)
    expected = 0.05 / (0.1 * 1.4)
    assert res.mean_acceleration == pytest.approx(expected, rel=1e-12)
    assert _fitted_acceleration(scene, 200) == pytest.approx(expected, rel=1e-5)


def test_a_turning_sphere_rolls_without_slip_up_to_mu_times_one_plus_one_over_kappa():
    """L = 0.15 between mu = 0.1 and mu (1 + 1/kappa) = 0.35: the sphere rolls without gross
    slip at L / (m* (1 + kappa)) = 1.0714 per period^2, as its own trajectory shows; the Result
    said (L - mu) / m* = 0.5, the acceleration of a particle that does not turn. Beyond 0.35
    (L = 0.5) it slides at (L - mu) / m* = 4."""
    rolls, slides = _rolling("mmd", 0.1, 0.15), _rolling("mmd", 0.5, 0.5)
    assert sd.run(rolls).mean_acceleration == pytest.approx(0.15 / 0.14, rel=1e-12)
    assert _fitted_acceleration(rolls, 200) == pytest.approx(0.15 / 0.14, rel=1e-5)
    assert sd.run(slides).mean_acceleration == pytest.approx(4.0, rel=1e-12)
    assert _fitted_acceleration(slides, 200) == pytest.approx(4.0, rel=1e-5)


@pytest.mark.parametrize("amplitude", [0.0, 0.5])
def test_rolling_resistance_holds_at_most_mu_r_and_brakes_a_runaway_by_it(amplitude):
    """EPSD rolling spring, mu_r = 0.01: a load of 2 mu_r rolls the sphere away at
    (L - mu_r) / (m* (1 + kappa)) = 0.0714 per period^2 over periods 400-800 of its run, on a
    still substrate and under the wave. The viscous term had acted at full mobilization (a
    strict comparison with the cap), and uncapped on a vibrating contact: the sphere reached a
    terminal speed (its fitted acceleration 8e-6 on the still substrate, 8e-5 under the wave)."""
    scene = _rolling("mmd", amplitude, 0.02, mu_r=0.01)
    res = sd.run(scene)
    assert res.regime == "runaway"
    assert res.mean_acceleration == pytest.approx(0.01 / 0.14, rel=1e-12)
    assert _fitted_acceleration(scene, 800) == pytest.approx(0.01 / 0.14, rel=1e-4)


def test_a_load_curve_of_a_sphere_free_to_turn_is_refused_in_one_line():
    """No load is held without rolling resistance: the load curve crashed on the runaway of its
    first loaded run (internal failure, exit 3)."""
    proc = run_main("load-curve", "--model", "mmd", "--rotation", "--loads", "3",
                    "--no-progress")
    assert proc.returncode == 2
    assert proc.stderr.strip().count("\n") == 0
    assert "effects.rolling_resistance" in proc.stderr and "Traceback" not in proc.stderr


def test_a_rolling_resistance_the_step_cannot_resolve_is_named(sawdrift_main):
    """mu_r = 1e6 makes a rolling spring whose stable step needs 1.7e8 steps a period: the run
    failed on a non-finite state that blamed particle.m_star and drive.amplitude."""
    proc = sawdrift_main("run", "--model", "mmd", "--rotation", "--rolling-resistance", "1e6",
                         "--periods", "10")
    assert proc.returncode == 2 and "effects.rolling_resistance = 1e+06" in proc.stderr
    assert "m_star = 0.1 with" not in proc.stderr and proc.stderr.strip().count("\n") == 0


def test_a_sphere_free_to_turn_under_air_drag_alone_holds_no_drift():
    """Air drag acts on the centre and has no moment about it, as a load: the contact point no
    longer stays at (1 + 1/kappa) x*, and psi must be integrated. The from-rest shortcut gave a
    settled drift ratio of 0.134; without a load the drift is zero (brute force with loads of
    +-1e-12 gives +-2e-11 a0 f, L/c)."""
    res = sd.run(sd.Scene(model="mmd", effects={"rotation": True, "air_drag": 0.05}))
    assert abs(res.drift_ratio) < 2e-5 and res.regime in ("stick", "oscillating_slip")


@pytest.mark.parametrize("load", [0.03, -0.035])
def test_a_load_held_by_rolling_resistance_is_a_steady_drift_not_a_runaway(load):
    """mu_r = 0.04 holds |L| < 0.04: the sphere rolls steadily at 1.3-1.8 times the surface
    speed, and a window that fast with a fitted acceleration of 3e-6 per period squared (noise)
    was called a runaway. The default run agrees with a fixed run of 4000 periods (last 2000)
    within 1e-4."""
    scene = _rolling("mmd", 0.316, load, mu_r=0.04)
    res = sd.run(scene)
    brute = sd.run(scene.with_updates(**{"numerics.settle": False, "numerics.periods": 4000,
                                         "numerics.measure_periods": 2000}))
    assert res.regime == brute.regime == ("drift_with" if load > 0 else "drift_against")
    assert res.settled and res.drift_ratio == pytest.approx(brute.drift_ratio, rel=1e-4)


def test_adhesion_raises_the_load_rolling_resistance_holds_to_mu_r_one_plus_two_f_pull():
    """The rolling spring is capped at mu_r (N* + 2 F*_pull), as friction is: with F*_pull = 0.5
    and mu_r = 0.01 it holds 0.02. L = 0.015 was a runaway (acceleration -0.02, of the wrong
    sign), and L = -0.01 was warned as at the bound mu_r, the load nothing restores."""
    from sawdrift.dynamics.steady import holding_bound

    def scene(load: float) -> sd.Scene:
        return _rolling("mmd", 0.316, load, mu_r=0.01).with_updates(
            **{"effects.adhesion": "jkr", "material.adhesion": 0.5})

    assert holding_bound(scene(0.015)) == pytest.approx(0.02, rel=1e-12)
    held = sd.run(scene(0.015))
    assert held.regime != "runaway" and held.drift_ratio > 0.0
    neutral = sd.run(scene(-0.01))
    assert not any("nothing restores" in w or "neutral" in w for w in neutral.warnings)
    assert sd.run(scene(0.025)).regime == "runaway"


def test_force_velocity_of_a_turning_sphere_spans_its_rolling_resistance():
    """A sphere free to turn holds at most mu_r: the curve's loads were spread over (-mu, mu),
    three of five runaways. Without rolling resistance it holds nothing: one line."""
    from sawdrift.errors import SceneError
    from sawdrift.study.force_velocity import force_velocity

    curve = force_velocity(_rolling("mmd", 0.316, 0.0, mu_r=0.04), points=3, workers=1)
    assert max(abs(curve.forces)) < 0.04 and curve.friction_bound == 0.04
    assert "runaway" not in curve.regimes
    with pytest.raises(SceneError, match="effects.rolling_resistance"):
        force_velocity(_rolling("mmd", 0.316, 0.0), points=3, workers=1)
