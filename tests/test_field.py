"""Two waves: the local orbit, the drift field and its traps, direct runs, moving traps, sorting."""

from __future__ import annotations

import json
import math
import sys
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import sawdrift as sd
from sawdrift.dynamics import drives
from sawdrift.dynamics.drives.two_wave import local_orbit
from sawdrift.study.field import (
    PERIOD,
    device_wavelength,
    drift_field,
    find_zeros,
    rayleigh_wavelength,
)
from sawdrift.study.field_direct import direct_run, nearest_zero

SETTLED = dict(model="mmd", particle={"m_star": 0.1}, numerics={"settle": True})


def _speed(amplitude: float) -> float:
    """The forward wave's horizontal surface speed 2 pi r A* (the drift tolerances' scale)."""
    return 2.0 * math.pi * sd.Scene().horizontal_ratio * amplitude


def test_the_default_wave_still_runs_the_travelling_drive():
    assert drives.drive_of(sd.Scene()) is drives.DRIVES["wave"]
    assert drives.drive_of(sd.Scene(drive={"backward": 0.2})) is drives.TWO_WAVES
    assert drives.drive_of(sd.Scene(drive={"wavelength": 300.0})) is drives.TWO_WAVES


@pytest.mark.parametrize("model", ["mmd", "material_point"])
def test_two_waves_with_s_0_at_xi_0_are_the_travelling_wave(model, monkeypatch):
    scene = sd.Scene(model=model, particle={"m_star": 0.1}, drive={"amplitude": 0.5, "phase": 30},
                     numerics={"periods": 30})
    single = sd.run(scene)
    monkeypatch.setitem(drives.DRIVES, "wave", drives.TWO_WAVES)
    both = sd.run(scene)
    assert single.drift_velocity != 0.0
    assert both.drift_velocity == pytest.approx(single.drift_velocity, rel=1e-12, abs=1e-14)
    assert both.regime == single.regime


def test_the_standing_wave_is_vertical_at_0_and_horizontal_at_a_quarter():
    r = 0.7
    u_x, u_y = local_orbit(1.0, r, 90.0, 1.0, 0.0, 0.0)
    assert abs(u_x) == 0.0 and abs(u_y) == pytest.approx(2.0, rel=1e-15)
    u_x, u_y = local_orbit(1.0, r, 90.0, 1.0, 0.0, 0.25)
    assert abs(u_y) < 1e-15 and abs(u_x) == pytest.approx(2.0 * r, rel=1e-15)
    # in between a linear vibration: U_x / U_y real (phase 0 or 180 degrees)
    u_x, u_y = local_orbit(1.0, r, 90.0, 1.0, 0.0, 0.1)
    assert abs((u_x / u_y).imag) < 1e-14


def test_s_0_field_is_flat_and_equals_the_single_wave_drift():
    single = sd.run(sd.Scene(**SETTLED))
    fld = drift_field(sd.Scene(**SETTLED, drive={"backward": 0.0}), 8, workers=1).fields[0]
    tol = sd.Scene().numerics.settle_tolerance * _speed(0.316)
    assert np.max(np.abs(fld.drift_velocity - single.drift_velocity)) <= tol
    assert fld.zeros == [] and fld.summary.startswith("goes to +x")


def test_s_1_field_is_antisymmetric_about_a_quarter_wavelength():
    fld = drift_field(sd.Scene(**SETTLED, drive={"backward": 1.0, "amplitude": 0.2}), 16,
                      workers=2).fields[0]
    v = fld.drift_velocity
    assert fld.positions[8] == 0.25
    tol = 2.0 * sd.Scene().numerics.settle_tolerance * _speed(0.2)
    pairs = np.array([v[8 - k] + v[8 + k] for k in range(1, 8)])
    assert np.max(np.abs(pairs)) <= tol
    assert abs(v[0]) <= tol  # V(0) = -V(1/2) = -V(0): the period is 1/2
    assert np.max(np.abs(v)) > 100 * tol  # not trivially zero
    kinds = {round(z["position"], 9): z["kind"] for z in fld.zeros}
    assert kinds == {0.0: "trap", 0.25: "repeller"}


def test_a_phase_shift_moves_every_zero_by_minus_psi_over_4_pi():
    base = sd.Scene(**SETTLED, drive={"backward": 0.5})
    psi = 50.0
    a = drift_field(base, 16, workers=2).fields[0]
    b = drift_field(base.with_updates(**{"drive.backward_phase": psi}), 16, workers=2).fields[0]
    assert len(a.zeros) == len(b.zeros) == 2
    shift = -math.radians(psi) / (4.0 * math.pi)
    for za in a.zeros:
        moved = za["position"] + shift
        zb = min(b.zeros, key=lambda z: abs(math.remainder(z["position"] - moved, PERIOD)))
        assert zb["kind"] == za["kind"]
        assert abs(math.remainder(zb["position"] - moved, PERIOD)) < 1e-3


def test_a_light_particle_direct_run_ends_at_the_trap_the_field_predicts():
    scene = sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"backward": 0.5})
    fld = drift_field(scene, 16, workers=2).fields[0]
    start = 0.12  # between the trap (~0.042) and the repeller (~0.186)
    run = direct_run(scene, start, 1500, fld, wavelength=200.0)
    trap = nearest_zero(fld, start)
    assert run["predicted"]["trap"] == pytest.approx(trap, abs=1e-12)
    assert abs(run["final_position"] - trap) < 1e-3
    assert abs(run["predicted"]["final_position"] - trap) < 1e-3
    assert abs(start - trap) > 0.05  # it really moved


def test_a_phase_ramp_carries_the_trapped_particle_along():
    scene = sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"backward": 0.5})
    fld = drift_field(scene, 16, workers=2).fields[0]
    trap = nearest_zero(fld, 0.0)
    rate, periods = 0.5, 3000.0
    run = direct_run(scene.with_updates(**{"drive.backward_phase_rate": rate}), trap, periods, fld,
                     wavelength=200.0)
    moved = trap - rate * periods / 720.0  # -2.08 wavelengths: the trap's own path
    assert run["final_position"] < trap - 1.5
    assert abs(run["final_position"] - moved) < 0.05
    assert abs(run["final_position"] - run["predicted"]["final_position"]) < 0.02
    # the end is the run's end: the last row was up to a row interval short of it (2992.5 of
    # 3000, 5e-3 wavelengths of the carried particle's path), and the trap was taken there
    assert run["trajectory"]["t"][-1] == pytest.approx(periods, abs=1e-9)
    assert run["predicted"]["trap"] == pytest.approx(
        nearest_zero(fld, run["predicted"]["final_position"] + rate * periods / 720.0)
        - rate * periods / 720.0, abs=1e-12)


def test_species_of_an_axis_are_the_fields_of_each_scene_alone():
    scene = sd.Scene(model="mmd", drive={"backward": 0.5}, numerics={"periods": 30})
    study = drift_field(scene, 4, axis=("particle.m_star", [0.1, 3.0]), workers=2, refine=0)
    assert [f.label for f in study.fields] == ["particle.m_star=0.1", "particle.m_star=3.0"]
    for fld, m in zip(study.fields, (0.1, 3.0), strict=True):
        alone = drift_field(scene.with_updates(**{"particle.m_star": m}), 4, workers=1,
                            refine=0).fields[0]
        np.testing.assert_array_equal(fld.drift_velocity, alone.drift_velocity)
    assert study.to_json()["species"][1]["label"] == "particle.m_star=3.0"


def test_zeros_of_a_sampled_field_are_located_and_classified():
    x = np.arange(32) * (PERIOD / 32)
    v = np.sin(4.0 * np.pi * (x - 0.1))  # rises through 0.1, falls through 0.35
    zeros = find_zeros(x, v)
    assert [z["kind"] for z in zeros] == ["repeller", "trap"]
    assert zeros[0]["position"] == pytest.approx(0.1, abs=2e-3)
    assert zeros[1]["position"] == pytest.approx(0.35, abs=2e-3)
    # a band of zero drift between + and - is a trap at its centre
    band = np.array([1.0, 0.5, 0.0, 0.0, 0.0, -0.5, -1.0, -0.2])
    xb = np.arange(8) * (PERIOD / 8)
    assert find_zeros(xb, band)[0]["kind"] == "trap"
    assert find_zeros(xb, band)[0]["position"] == pytest.approx(xb[3])


def test_the_rayleigh_wavelength_solves_the_rayleigh_equation():
    from scipy.optimize import brentq

    e, nu, rho, f = 210e9, 0.3, 7850.0, 1e6
    k2 = (1 - 2 * nu) / (2 * (1 - nu))
    eta = brentq(lambda q: (2 - q) ** 2 - 4 * math.sqrt(1 - q) * math.sqrt(1 - k2 * q), 0.5, 0.99)
    c_s = math.sqrt(e / (2 * (1 + nu)) / rho)
    assert rayleigh_wavelength(e, nu, rho, f) == pytest.approx(math.sqrt(eta) * c_s / f, rel=1e-9)
    sub = SimpleNamespace(youngs_modulus=e, poisson=nu, density=rho)
    assert device_wavelength(SimpleNamespace(substrate=sub, frequency=f)) == pytest.approx(
        rayleigh_wavelength(e, nu, rho, f), rel=1e-15)
    given = SimpleNamespace(substrate=sub, frequency=f, wavelength=3.99e-4)
    assert device_wavelength(given) == 3.99e-4


def test_bad_input_is_one_line():
    with pytest.raises(sd.SceneError, match="points = 3"):
        drift_field(sd.Scene(drive={"backward": 0.5}), 3)
    with pytest.raises(sd.SceneError, match="wavelength"):
        direct_run(sd.Scene(drive={"backward": 0.5}), 0.1, 100)
    with pytest.raises(sd.SceneError, match="drive.backward"):
        sd.scene.build_scene({"drive": {"backward": 1.5}})


@pytest.mark.parametrize("line", ["run --backward 1.5", "run --backward -0.1",
                                  "field --points 3 --backward 0.5", "field --backward 2",
                                  "field --backward 0.5 --direct --start 0.1",
                                  # --periods 0 ran the default 2000 periods
                                  "field --backward 0.5 --direct --wavelength 200 --periods 0",
                                  "field --backward 0.5 --direct --wavelength 200 --periods 0.5"])
def test_the_command_line_answers_bad_input_with_one_line_and_exit_2(line, monkeypatch, capsys):
    from sawdrift.cli import main
    monkeypatch.setattr(sys, "argv", ["sawdrift", *line.split()])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(err) == 1 and err[0].startswith("error: "), err


def test_a_long_time_mean_in_a_field_carries_its_error():
    """A 0.2 mm steel bead of examples/sorting.toml bounces irregularly at xi = 0, where the two
    waves' vertical motions add, and drifts steadily at xi = 0.25: the first position's drift
    is a long-time mean whose error (its run's drift_ratio_se scaled to x*') the field keeps and
    writes; a steady drift has none."""
    from pathlib import Path

    scene = sd.Scene.from_toml(Path(__file__).resolve().parents[1] / "examples" / "sorting.toml")
    scene = scene.with_updates(**{"device.particle.radius": "0.2 mm"})
    fld = drift_field(scene, 4, workers=1, progress=False).fields[0]
    at0 = sd.run(scene.with_updates(**{"drive.position": 0.0}))
    assert at0.regime == "bouncing" and at0.drift_ratio_se > 0.0
    want = at0.drift_ratio_se * abs(at0.drift_velocity / at0.drift_ratio)
    assert fld.drift_velocity_se[0] == pytest.approx(want, rel=1e-9)
    steady = [i for i, ok in enumerate(fld.settled) if ok]
    assert steady and all(math.isnan(fld.drift_velocity_se[i]) for i in steady)
    data = fld.to_json()
    assert data["drift_velocity_se"][0] == pytest.approx(want, rel=1e-9)
    assert all(data["drift_velocity_se"][i] is None for i in steady)
    # its mean is within two errors of zero: no known sign, a zero band (not "goes to +x")
    assert abs(fld.drift_velocity[0]) <= 2.0 * want
    assert [(z["kind"], z["position"]) for z in fld.zeros] == [("one-sided", 0.0)]


def test_a_noisy_mean_is_a_zero_band_not_a_sign_change():
    """Two long-time means of opposite signs, each within two of its errors of zero, make no
    trap: with their errors as the band's width they are one zero band between positive
    neighbours (one-sided), where a scalar band saw a trap and a repeller."""
    x = np.arange(8) * (PERIOD / 8)
    v = np.array([3.0, 2.0, 1.0, 0.5, -0.4, 0.6, 2.0, 3.0])
    assert [z["kind"] for z in find_zeros(x, v, 0.01)] == ["trap", "repeller"]
    eps = np.array([0.01, 0.01, 0.01, 2 * 0.3, 2 * 0.5, 2 * 0.4, 0.01, 0.01])
    (zero,) = find_zeros(x, v, eps)
    assert zero["kind"] == "one-sided" and zero["bracket"] == [x[3], x[5]]


def test_a_field_of_noisy_means_only_has_no_known_direction():
    """Every sample a long-time mean within two of its errors of zero (V = 1 to 4, errors 3):
    no sign is known anywhere, so the field does not say it goes to +x everywhere."""
    from sawdrift.study.field import Field, _summarize

    x = np.arange(4) * (PERIOD / 4)
    fld = Field(label="", positions=x, drift_velocity=np.array([1.0, 2.0, 3.0, 4.0]),
                regimes=["bouncing"] * 4, settled=[False] * 4, zeros=[], scene=sd.Scene(),
                drift_velocity_se=np.full(4, 3.0))
    assert _summarize(fld).startswith("no known direction")
    fld.drift_velocity_se = np.full(4, np.nan)  # the same speeds, steady: it goes to +x
    assert _summarize(fld).startswith("goes to +x everywhere")


def test_the_field_csv_keeps_each_long_time_means_error(tmp_path, monkeypatch, capsys):
    # -o NAME.csv dropped drift_velocity_se: the zeros of a bouncing field could not be told
    # from noise
    import pandas as pd

    from sawdrift.cli import main

    out = tmp_path / "f.csv"
    monkeypatch.setattr(sys, "argv", ["sawdrift", "field", "--backward", "1", "--m-star", "0.1",
                                      "--points", "8", "--no-progress", "-o", str(out)])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code in (0, None)
    frame = pd.read_csv(out)
    assert "drift_velocity_se" in frame.columns
    means = frame["regime"] == "bouncing"
    assert means.any() and frame.loc[means, "drift_velocity_se"].notna().any()


def test_an_ejected_field_says_so_in_valid_json_with_the_warnings(monkeypatch, capsys):
    """The 2 um silica bead on quartz at 1 nm (a0 = 4.5e-14 m) is thrown off everywhere: the
    JSON held NaN for every V (no JSON: JSON.parse refuses it) and no warnings, the text said
    'no drift' and called the positions not settled."""
    import json
    from pathlib import Path

    from .cli_call import call

    example = Path(__file__).resolve().parents[1] / "examples" / "silica_bead_on_quartz.toml"
    args = ("field", str(example), "--backward", "0.5", "--points", "4", "--no-progress")
    code, out, err = call(monkeypatch, capsys, *args, "--json")
    assert code == 0, err
    data = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in the JSON"))
    assert data["regimes"] == ["ejected"] * 4 and data["drift_velocity"] == [None] * 4
    assert any("a0 < 1 nm" in w for w in data["warnings"])
    code, out, _ = call(monkeypatch, capsys, *args)
    assert out.splitlines()[0].startswith("ejected at every position")
    assert "NOT settled" not in out and "WARNING: a0 < 1 nm" in out


def test_a_device_field_holds_its_speeds_in_m_s_as_a_run_gives_them(monkeypatch, capsys,
                                                                   tmp_path):
    """The figure of a device field is in mm/s; the JSON and CSV held only x* per period, with
    no a0 (which differs per species) to convert them. Each speed in m/s is the run's at that
    position (examples/sorting.toml, the 0.2 mm bead at xi = 0.0625: 2.6056e-5 m/s)."""
    import json
    from pathlib import Path

    import pandas as pd

    from .cli_call import call

    example = Path(__file__).resolve().parents[1] / "examples" / "sorting.toml"
    args = ("field", str(example), "--axis", "device.particle.radius=0.2 mm,1 mm", "--points",
            "4", "--no-progress")
    code, out, err = call(monkeypatch, capsys, *args, "--json")
    assert code == 0, err
    small = json.loads(out)["species"][0]
    scene = sd.Scene.from_toml(example).with_updates(
        **{"device.particle.radius": 2e-4, "drive.position": small["positions"][1]})
    run = sd.run(scene)
    assert small["drift_velocity_m_s"][1] == pytest.approx(run.extra["drift_speed_m_s"],
                                                           rel=1e-9)
    code, _, err = call(monkeypatch, capsys, *args, "-o", str(tmp_path / "f.csv"))
    table = pd.read_csv(tmp_path / "f.csv")
    assert code == 0, err
    assert table["drift_velocity_m_s"].iloc[1] == pytest.approx(run.extra["drift_speed_m_s"],
                                                                rel=1e-9)


def test_no_zero_is_read_across_positions_without_a_drift():
    """An ejected (or failed) position has no drift: a sign change across it is no zero (a
    repeller was reported at xi = 0.064 bracketed by 0.3125 and 0.6875, across three ejected
    positions), and a zero band beside it has no known side."""
    from sawdrift.study.field import find_zeros

    x = np.arange(8) / 16.0
    nan = float("nan")
    v = np.array([nan, nan, nan, 30.0, -0.8, -0.5, nan, nan])
    zeros = find_zeros(x, v, 1e-6)
    assert [z["kind"] for z in zeros] == ["trap"]
    assert zeros[0]["bracket"] == [pytest.approx(0.1875), pytest.approx(0.25)]
    band = np.array([1.0, 0.0, nan, 1.0, -1.0, 1.0, 0.0, 1.0])
    kinds = [z["kind"] for z in find_zeros(x, band, 1e-6)]
    assert kinds == ["trap", "repeller", "one-sided"]  # none for the band beside the gap


def test_a_field_stuck_everywhere_has_no_direction(monkeypatch, capsys):
    """mmd m* 0.1, A* 0.02: every position sticks (creep of 1e-7 a0 f); the summary said 'goes
    to +x everywhere'."""
    from .cli_call import call

    code, out, err = call(monkeypatch, capsys, "field", "--model", "mmd", "--m-star", "0.1",
                          "--amplitude", "0.02", "--points", "4", "--no-progress", "--json")
    import json

    data = json.loads(out)
    assert code == 0 and data["regimes"] == ["stick"] * 4, err
    assert data["summary"] == "stuck at every position: no drift" and data["zeros"] == []


def test_a_warning_every_position_shares_is_listed_once():
    """A row holds its run's warnings joined by '; ': the device's a0 warning (which itself
    holds '; ') came back inside every position's text, printed three times for one bead."""
    from sawdrift.study.table import distinct_warnings

    a0 = ("a0 < 1 nm (a0 = 1.12e-10 m): adhesion and roughness, not gravity and preload, then "
          "set the contact; the model's assumptions do not hold")
    heat = ["long-time mean: the bounces heat up (1.67e+03 to 2.81e+03)",
            "long-time mean: the bounces heat up (9.66e+03 to 1.32e+04)"]
    rows = [a0, f"{a0}; {heat[0]}", f"{a0}; {heat[1]}", a0]
    assert distinct_warnings(rows) == [a0, *heat]
    assert distinct_warnings(reversed(rows)) == [a0, heat[1], heat[0]]  # as first seen
    # no position with the shared warning alone: still listed once
    assert distinct_warnings([f"{a0}; {heat[0]}", f"{a0}; {heat[1]}"]) == [a0, *heat]
    # a warning inside another's words is not cut out of them
    assert distinct_warnings(["slow", "very slow; other"]) == ["slow", "very slow; other"]
    assert distinct_warnings([]) == []


def test_a_start_without_a_direct_run_is_refused():
    """--start without --direct was ignored without a word."""
    from tests.cli_call import run_main

    out = run_main("field", "--start", "0.3", "--wavelength", "100")
    assert out.returncode == 2
    assert out.stderr.strip() == ("error: --start 0.3 is the start of the direct run: add "
                                  "--direct (or drop --start)")


def test_a_direct_run_too_long_is_refused_before_the_field(sawdrift_main, tmp_path):
    """--periods 9990000 is within numerics.periods' (0, 1e7], but the direct run goes one row
    interval past its end: the field was computed first, then the run failed naming
    numerics.periods = 10014975. Now one line names --periods and the most it takes, before any
    work, and the largest length it names runs."""
    from sawdrift.study.field_direct import MOST_PERIODS, direct_scenes

    out = tmp_path / "f"
    proc = sawdrift_main("field", "--backward", "0.5", "--direct", "--wavelength", "200",
                         "--periods", "9990000", "--points", "4", "-o", str(out))
    assert proc.returncode == 2 and proc.stderr.startswith("error: --periods = 9.99e+06")
    assert "give at most" in proc.stderr and not out.exists()
    most = float(proc.stderr.rsplit("give at most", 1)[1])
    scene = sd.Scene(drive={"backward": 0.5}).with_updates(
        **{"drive.wavelength": 200.0})
    _sc, longer, total, every = direct_scenes(scene, 0.0, most)
    assert longer.numerics.periods <= MOST_PERIODS and total > 0 and every >= 1


@pytest.mark.slow
def test_a_rigid_point_runs_through_a_two_wave_field_into_its_trap():
    """material_point m* 0.1, A* 0.1, backward 0.5, L* 200, from xi = 0.1: near the trap the
    drive's force nearly balances friction, a broken stick's slip velocity stays at rounding
    level for a while, and each slip was judged reversed at once: no progress, until a step
    held 4096 events (at t* = 1611, reported as an inelastic collapse). It reaches the trap
    the field predicts, xi = -0.00054, within 5e-4 of a wavelength."""
    scene = sd.Scene(model="material_point", particle={"m_star": 0.1},
                     drive={"amplitude": 0.1, "backward": 0.5, "wavelength": 200.0,
                            "position": 0.1},
                     numerics={"settle": False, "periods": 1800})
    res = sd.run(scene, trajectory=True)
    xi = 0.1 + float(res.trajectory["x"].iloc[-1]) / 200.0
    assert abs(xi - (-0.00054)) < 5e-4, xi


def test_refine_is_bounded_and_counted_in_the_size(monkeypatch, capsys):
    """--refine 99999999 ran for hours with no word, and --refine 20000 was estimated 'under
    1 s' and took 26 s: it is at most 60 rounds (Illinois converges superlinearly), and each
    round's runs (two zeros a species) count in the estimate the field prints."""
    from sawdrift.study import estimate

    from .cli_call import call

    code, _, err = call(monkeypatch, capsys, "field", "--backward", "0.5", "--points", "4",
                        "--periods", "5", "--refine", "99999999", "--no-progress")
    assert code == 2 and "refine = 99999999: give 0 to 60" in err
    seen = []
    real = estimate.size_check

    def spy(*args, **kw):
        seen.append(kw.get("extra_steps", 0.0))
        return real(*args, **kw)

    monkeypatch.setattr(estimate, "size_check", spy)
    for refine in (0, 60):
        code, _, err = call(monkeypatch, capsys, "field", "--backward", "0.5", "--points", "4",
                            "--periods", "5", "--refine", str(refine), "--no-progress",
                            "--json")
        assert code == 0, err
    one = estimate.cell_steps(sd.Scene(drive={"kind": "wave", "backward": 0.5},
                                       numerics={"periods": 5}))[0]
    assert seen[0] == 0.0 and seen[1] == pytest.approx(60 * 2 * one / 4, rel=0.2)


def interrupt_after(monkeypatch, cells: int) -> list[str]:
    """A Ctrl-C in the sweep's cell runner once ``cells`` cells have run (the list of those it
    returns; clear it to count again)."""
    import sawdrift.study.sweep as sweep_mod

    real = sweep_mod.run_cell
    ran: list[str] = []

    def interrupted(scene_json, **kwargs):
        if len(ran) == cells:
            raise KeyboardInterrupt
        ran.append(scene_json)
        return real(scene_json, **kwargs)

    monkeypatch.setattr(sweep_mod, "run_cell", interrupted)
    return ran


def test_ctrl_c_in_a_field_keeps_the_positions_that_ended(monkeypatch, capsys, tmp_path):
    """A field stopped by Ctrl-C printed and wrote nothing, though positions had ended: it
    shows and writes those (no zeros: a sign change between them may hide others) and exits
    130 saying how many of how many ran."""
    from .cli_call import call

    ran = interrupt_after(monkeypatch, 3)
    out = tmp_path / "f.csv"
    code, stdout, err = call(monkeypatch, capsys, "field", "--model", "material_point",
                             "--backward", "0.5", "--points", "8", "--workers", "1",
                             "--periods", "20", "-o", str(out))
    assert code == 130 and "after 3 of 8 positions" in err, err
    assert "interrupted: 3 of 8 positions run" in stdout
    table = pd.read_csv(out)
    assert len(table) == 3 and table["drift_velocity"].notna().all()
    # the JSON form says so too, beside the three positions
    ran.clear()
    code, stdout, _ = call(monkeypatch, capsys, "field", "--model", "material_point",
                           "--backward", "0.5", "--points", "8", "--workers", "1",
                           "--periods", "20", "--json")
    data = json.loads(stdout)
    assert code == 130 and data["interrupted"] == {"positions_run": 3, "positions": 8}
    assert len(data["positions"]) == 3 and data["zeros"] == []


def test_ctrl_c_while_refining_keeps_the_whole_field_and_its_unrefined_zeros(monkeypatch, capsys):
    """Every position had ended when Ctrl-C came during the refinement: the field keeps them all
    and the zeros of its sign changes (the first stop said 'no zeros located' of 128 of 128)."""
    import sawdrift.study.field as field_mod

    from .cli_call import call

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(field_mod, "_refine", interrupted)
    code, stdout, err = call(monkeypatch, capsys, "field", "--model", "mmd", "--m-star", "0.1",
                             "--backward", "0.5", "--points", "8", "--workers", "1", "--settle",
                             "--json")
    data = json.loads(stdout)
    assert code == 130 and "while refining the zeros" in err, err
    assert data["interrupted"] == {"positions_run": 8, "positions": 8}
    kinds = sorted(z["kind"] for z in data["zeros"])
    assert kinds == ["repeller", "trap"] and "not refined" in data["summary"]
    for z in data["zeros"]:  # each between two samples of opposite sign
        lo, hi = z["bracket"]
        assert lo < z["position"] < hi


def test_ctrl_c_with_a_species_axis_draws_the_species_that_ran(monkeypatch, capsys, tmp_path):
    """Cells run heaviest first: a stop can leave a species with no position, and the figure
    indexed its first position (exit 3, 'internal failure', only field.json written). The API
    still raises a KeyboardInterrupt, carrying the positions that ended."""
    from sawdrift.study.field import FieldInterrupted

    from .cli_call import call

    ran = interrupt_after(monkeypatch, 3)
    out = tmp_path / "fo"
    code, _, err = call(monkeypatch, capsys, "field", "--model", "material_point", "--backward",
                        "0.5", "--points", "8", "--axis", "particle.m_star=0.05,0.5",
                        "--workers", "1", "--periods", "20", "-o", str(out))
    assert code == 130 and "after 3 of 16 positions" in err, err
    assert (out / "field.png").stat().st_size > 0 and (out / "field.json").exists()
    ran.clear()
    scene = sd.Scene(model="material_point", drive={"backward": 0.5}, numerics={"periods": 20})
    with pytest.raises(FieldInterrupted) as stopped:
        drift_field(scene, 8, workers=1)
    assert isinstance(stopped.value, KeyboardInterrupt)
    assert stopped.value.study.interrupted == (3, 8)
