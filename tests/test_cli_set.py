"""``--set FIELD=VALUE`` on every command that takes a scene (issue 37, item 1)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from sawdrift.cli import app

from .cli_call import call

MOTOR = Path(__file__).resolve().parents[1] / "examples" / "saw_linear_motor.toml"
SHORT = ("--no-settle", "--periods", "2", "--steps-per-period", "64", "--json")




def _hertz(radius: float) -> tuple[float, float]:
    """(a0, m*) of the motor's steel ball of ``radius`` by Hertz (a0 = (9 W^2/(16 R E*^2))^(1/3))."""
    e_star = 1.0 / ((1 - 0.3**2) / 210e9 + (1 - 0.25**2) / 170e9)
    mass = 7850.0 * 4.0 / 3.0 * math.pi * radius**3
    weight = mass * 9.81 + 7.35e-3
    a0 = (9.0 * weight**2 / (16.0 * radius * e_star**2)) ** (1.0 / 3.0)
    return a0, a0 * mass * 9.6e6**2 / weight


def test_set_changes_device_fields_with_units(monkeypatch, capsys):
    code, out, err = call(monkeypatch, capsys, "run", str(MOTOR), "--set", "device.amplitude=20 nm",
                          "--set", "device.particle.radius='0.2 mm'", *SHORT)
    assert code == 0, err
    data = json.loads(out)
    a0, m_star = _hertz(0.2e-3)
    assert data["normalized"]["a0_m"] == pytest.approx(a0, rel=1e-9)
    assert data["m_star"] == pytest.approx(m_star, rel=1e-9)
    assert data["amplitude"] == pytest.approx(20e-9 / a0, rel=1e-9)


def test_a_derived_option_on_a_device_scene_points_at_set(monkeypatch, capsys):
    code, _, err = call(monkeypatch, capsys, "run", str(MOTOR), "--amplitude", "20")
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1
    assert lines[0].startswith("error: --amplitude 20: ")
    # A* = 20 on the motor (a0 = 18.13 nm) is 20 a0: the --set named gives that amplitude (it
    # named a fixed '20 nm', A* = 1.1)
    assert f'--set device.amplitude="{20 * _hertz(0.5e-3)[0] * 1e9:.6g} nm"' in lines[0]


@pytest.mark.parametrize(("item", "words"), [
    ("device.amplitude=20 MHz", ("device.amplitude", "length")),
    ("device.ampltude=20 nm", ("device.ampltude", "'amplitude'")),
    ("device.amplitude", ("FIELD=VALUE",)),
    ("material.mu=-1", ("material.mu",)),
])
def test_a_bad_set_is_one_line_naming_the_field(item, words, monkeypatch, capsys):
    scene = str(MOTOR) if item.startswith("device") else None
    args = ["run", *([scene] if scene else []), "--set", item, *SHORT]
    code, _, err = call(monkeypatch, capsys, *args)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("error: "), lines
    assert all(w in lines[0] for w in words), lines[0]


def test_every_command_that_takes_a_scene_has_set():
    import typer.main

    group = typer.main.get_command(app)
    takes_scene = [name for name, cmd in group.commands.items()
                   if any("--mu" in p.opts for p in getattr(cmd, "params", []))]
    assert {"run", "sweep", "load-curve", "force-velocity", "field", "bifurcation",
            "lammps"} <= set(takes_scene)
    for name in takes_scene:
        opts = {o for p in group.commands[name].params for o in p.opts}
        assert "--set" in opts, name


def test_integer_options_take_a_float_written_whole_number(monkeypatch, capsys):
    code, out, err = call(monkeypatch, capsys, "run", "--steps-per-period", "1e2", "--periods", "2",
                          "--no-settle", "--json")
    assert code == 0, err
    assert json.loads(out)["steps_per_period"] == 100
    code, _, err = call(monkeypatch, capsys, "run", "--steps-per-period", "64.5")
    assert code == 2 and "whole number" in err


def test_set_model_beside_model_is_refused_not_dropped(monkeypatch, capsys):
    """'--model mmd --set model=mdr' ran mmd and dropped the --set without a word (a field set
    by an option and --set is refused)."""
    code, _, err = call(monkeypatch, capsys, "run", "--periods", "4", "--model", "mmd", "--set",
                        "model=mdr", "--json")
    assert code == 2
    assert err.strip() == "error: --set model=mdr: --model mmd already sets model; give it once"
    code, out, err = call(monkeypatch, capsys, "run", "--periods", "4", "--set", "model=mdr",
                          "--json")
    assert code == 0 and json.loads(out)["model"] == "mdr", err


def test_a_device_field_on_a_scene_without_a_device_says_so(monkeypatch, capsys):
    """--set device.amplitude on the default (normalized) scene answered only 'device.frequency
    is required', as if the scene had a device table that lacked it."""
    code, _, err = call(monkeypatch, capsys, "run", "--periods", "4", "--set",
                        'device.amplitude="10 nm"')
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "device.frequency is required" in err and "the scene has no [device] table" in err


def test_a_model_named_twice_is_refused(monkeypatch, capsys):
    """--model mmd,mmd ran the same scene twice side by side (compare refuses it)."""
    code, _, err = call(monkeypatch, capsys, "run", "--periods", "4", "--model", "mmd,mmd")
    assert code == 2 and err.strip() == ("error: --model 'mmd,mmd' names mmd twice: give each "
                                         "model once")


def test_a_repeated_derived_value_must_match_its_six_figures(monkeypatch, capsys):
    """The motor's m* is shown as 929.267: that is accepted as the device's own; 929.27 is
    another value (a relative 5e-6 took it), refused with a hint of six figures that gives it."""
    code, _, err = call(monkeypatch, capsys, "run", str(MOTOR), "--m-star", "929.267",
                        "--periods", "4")
    assert code == 0, err
    code, _, err = call(monkeypatch, capsys, "run", str(MOTOR), "--m-star", "929.27")
    assert code == 2 and 'device.particle.radius="500.001 um"' in err


def test_no_hint_names_a_load_the_device_would_refuse(monkeypatch, capsys):
    """L = 3e7 is beyond 100 times any normal load friction holds: the hint named a device.load
    (0.339 mN) that was itself refused; now the line names the fields without a value."""
    silica = MOTOR.parent / "micro_silica_on_linbo3.toml"
    code, _, err = call(monkeypatch, capsys, "run", str(silica), "--load", "3e7")
    assert code == 2 and "device.load" in err and 'device.load="' not in err


def test_a_model_parameter_given_twice_is_refused(monkeypatch, capsys):
    """--param and --set of one parameter, or --param twice: one of them won without a word."""
    for args, needle in (
            (("--param", "max_memory_points=16", "--set", "model_params.max_memory_points=32"),
             "already sets model_params.max_memory_points; give it once"),
            (("--param", "max_memory_points=16", "--param", "max_memory_points=32"),
             "--param max_memory_points is given twice; give it once")):
        code, _, err = call(monkeypatch, capsys, "run", "--periods", "4", *args)
        assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


def test_another_model_by_set_drops_the_files_parameters_and_keeps_those_given(
        monkeypatch, capsys, tmp_path):
    """--set model=mmd on a hertz_mindlin_dem file named the file model's rescale, a parameter
    the user never gave; and --model with --set model_params.X on a file dropped the X given."""
    scene = tmp_path / "dem.toml"
    scene.write_text('model = "hertz_mindlin_dem"\n[model_params]\nrescale = true\n')
    code, out, err = call(monkeypatch, capsys, "run", str(scene), "--periods", "4",
                          "--set", "model=mmd", "--json")
    assert code == 0, err
    code, out, err = call(monkeypatch, capsys, "run", str(scene), "--periods", "4", "--model",
                          "mmd", "--set", "model_params.max_memory_points=32", "--json")
    assert code == 0, err
    assert json.loads(out)["scene"]["model_params"] == {"max_memory_points": 32}


@pytest.mark.parametrize("args", [
    ("sweep", "--mu", "0.5", "--axis", "material.mu=0.1,0.2", "-o", "{tmp}/t.parquet"),
    ("bifurcation", "--axis", "drive.amplitude=0.1,0.3", "--amplitude", "0.9", "-o", "{tmp}/b"),
    ("field", "--backward", "0.5", "--points", "4", "--axis", "particle.m_star=0.05,0.5",
     "--m-star", "0.1"),
])
def test_an_option_for_the_field_an_axis_sweeps_is_refused(args, monkeypatch, capsys, tmp_path):
    """The option's value was dropped without a word (the table held mu 0.1 and 0.2 only)."""
    code, _, err = call(monkeypatch, capsys, *(a.format(tmp=tmp_path) for a in args))
    assert code == 2 and "both set" in err and "give one of them" in err
    assert len(err.strip().splitlines()) == 1


def test_a_run_does_not_overwrite_a_sweep_table(monkeypatch, capsys, tmp_path):
    """run -o NAME.parquet on an existing sweep table replaced its cells by a trajectory without
    a word; a trajectory file of its own is still overwritten."""
    table = tmp_path / "t.parquet"
    code, _, err = call(monkeypatch, capsys, "sweep", "--m-star", "0.1,1", "--amplitude", "0.1",
                        "--periods", "4", "-o", str(table), "--no-progress")
    assert code == 0, err
    before = table.read_bytes()
    code, _, err = call(monkeypatch, capsys, "run", "--periods", "4", "-o", str(table))
    assert code == 2 and "is a sweep table" in err and table.read_bytes() == before
    traj = tmp_path / "traj.parquet"
    for _ in range(2):
        code, _, err = call(monkeypatch, capsys, "run", "--periods", "4", "-o", str(traj))
        assert code == 0, err


@pytest.mark.parametrize("args", [
    ("sweep", "--model", "mmd,,mdr", "--m-star", "0.1,1", "--amplitude", "0.1", "-o",
     "{tmp}/t.parquet"),
    ("run", "--model", "mmd,"),
    ("run", "--model", ""),
])
def test_an_empty_model_name_in_a_list_is_refused(args, monkeypatch, capsys, tmp_path):
    """'mmd,,mdr' and 'mmd,' ran the names that were there without a word."""
    code, _, err = call(monkeypatch, capsys, *(a.format(tmp=tmp_path) for a in args),
                        "--periods", "4")
    assert code == 2 and "has an empty model name" in err and len(err.strip().splitlines()) == 1


def test_ctrl_c_on_the_second_model_keeps_the_first_models_run(monkeypatch, capsys, tmp_path):
    """--model mmd,mdr stopped by Ctrl-C during mdr printed and wrote nothing, though mmd had
    ended: it shows mmd's result, writes it, and exits 130 saying so."""
    import sawdrift.cli.run as run_cli

    real = run_cli._run_one
    calls = []

    def second_interrupted(scene, engine, trajectory):
        calls.append(scene.model)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(scene, engine, trajectory)

    monkeypatch.setattr(run_cli, "_run_one", second_interrupted)
    out = tmp_path / "runs"
    code, stdout, err = call(monkeypatch, capsys, "run", "--model", "mmd,mdr", "--periods", "4",
                             "-o", str(out))
    assert code == 130 and "after 1 of 2 models" in err
    assert "drift_with" in stdout or "regime" in stdout
    assert any(out.iterdir())


def test_a_bifurcation_tolerance_without_locate_is_refused(monkeypatch, capsys, tmp_path):
    """--tolerance sets --locate's bracket; without --locate it was ignored without a word."""
    code, _, err = call(monkeypatch, capsys, "bifurcation", "--axis", "drive.amplitude=0.1,0.3",
                        "--tolerance", "1e-3", "-o", str(tmp_path / "b"))
    assert code == 2 and "--tolerance 0.001 belongs to --locate" in err
    assert not (tmp_path / "b").exists()
