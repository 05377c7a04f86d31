"""The reviewer's residue: bad input the command line accepted, and failures it exited 0 on."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import sawdrift as sd
from sawdrift.contact.binding import bind

from .cli_call import call

# class names of Python exceptions must never reach the user
_EXC_NAME = re.compile(r"\b[A-Z][A-Za-z]*(Error|Exception)\b|Traceback")


def _one_line(code: int, err: str) -> str:
    """The one plain error line of a refused command (exit status 2)."""
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("error: "), (code, err)
    assert not _EXC_NAME.search(lines[0]), lines[0]
    return lines[0]


@pytest.mark.parametrize(("args", "off"), [
    (["run", "--periods", "5", "--no-settle", "--max-periods", "100"], "--no-settle"),
    (["run", "--periods", "5", "--max-periods", "100", "--set", "numerics.settle=false"],
     "--set numerics.settle=false"),
    (["sweep", "--m-star", "0.1", "--amplitude", "0.3", "--periods", "5", "--no-settle",
      "--max-periods", "100", "-o", "{d}/t.parquet"], "--no-settle"),
])
def test_a_period_cap_given_to_a_fixed_run_is_refused(args, off, tmp_path, monkeypatch, capsys):
    """``run --no-settle --max-periods N`` ran its fixed periods and ignored the cap (it bounds
    the settling run only) without a word; the line names both options, and nothing is written."""
    code, _, err = call(monkeypatch, capsys, *(a.format(d=tmp_path) for a in args))
    line = _one_line(code, err)
    assert "--max-periods 100" in line and off in line, line
    assert not list(tmp_path.iterdir())


def test_a_period_cap_stays_accepted_where_it_is_read(tmp_path, monkeypatch, capsys):
    """The cap with a settling run is used; a scene (file or Python) with a cap and settle =
    false stays accepted (benchmarks/bench_audit.py builds such scenes), and so does a file's
    cap with --no-settle (examples/saw_linear_motor.toml has max_periods = 1e6)."""
    code, _, err = call(monkeypatch, capsys, "run", "--explain", "--settle", "--max-periods",
                        "100")
    assert code == 0, err
    fixed = sd.Scene(numerics={"settle": False, "periods": 200, "measure_periods": 100,
                               "max_periods": 200})
    assert fixed.numerics.max_periods == 200
    scene = tmp_path / "capped.toml"
    scene.write_text("[numerics]\nmax_periods = 1e6\n")
    code, _, err = call(monkeypatch, capsys, "run", str(scene), "--explain", "--no-settle")
    assert code == 0, err


#: an mmd whose memory diagram is too small for A* = 0.1 at m* = 1 (that cell fails, 1 runs)
_FAILING = ["--model", "mmd", "--param", "max_memory_points=16", "--m-star", "1",
            "--no-progress", "--workers", "1"]


@pytest.mark.parametrize("study", ["sweep", "bifurcation", "bifurcation-json"])
def test_a_study_with_failed_cells_saves_them_and_exits_1(study, tmp_path, monkeypatch, capsys):
    """A sweep or bifurcation in which a cell failed (its table's 'error' column) exited 0, as
    if every cell had run. It saves everything, keeps its summary and exits 1 (the input was
    valid: not 2), with one line on stderr saying how many failed and where the reasons are."""
    import pandas as pd

    if study.startswith("sweep"):
        table = tmp_path / "t.parquet"
        args = ["sweep", *_FAILING, "--amplitude", "0.1,1", "-o", str(table)]
        what = "cells"
    else:
        table = tmp_path / "b" / "bifurcation.parquet"
        args = ["bifurcation", *_FAILING, "--axis", "drive.amplitude=0.1,1", "--samples", "4",
                "-o", str(tmp_path / "b")] + (["--json"] if study.endswith("json") else [])
        what = "values"
    code, out, err = call(monkeypatch, capsys, *args)
    assert code == 1, err
    lines = [line for line in err.strip().splitlines() if not line.startswith("note:")]
    assert lines == [f"failed: 1 of 2 {what}; each one's reason is in the 'error' column of "
                     f"{table} (the results are saved)"], err
    rows = pd.read_parquet(table)
    failed = rows[rows["error"].notna()]
    assert not failed.empty and "memory" in failed["error"].iloc[0]
    assert rows[rows["error"].isna()]["period" if "bifurcation" in study else "drift_ratio"
                                      ].notna().all()
    if study == "sweep":
        assert "(2 cells, 1 with errors)" in out  # the summary is kept
    elif study == "bifurcation":
        assert "failed at drive.amplitude = 0.1: " in out and "wrote " in out
        assert (tmp_path / "b" / "bifurcation.png").exists()


@pytest.mark.parametrize(("text", "field", "fix"), [
    ('[particle]\nm_star = "10"\n', "particle.m_star = '10'", "write m_star = 10 without quotes"),
    ('[numerics]\nperiods = " 20 "\n', "numerics.periods = ' 20 '", "write periods = 20"),
    ('[model_params]\nmax_memory_points = "64"\n', "model_params.max_memory_points = '64'",
     "write max_memory_points = 64"),
    ('[drive]\nkind = "prescribed"\nwaveform = "samples"\na = [0.1, "1.0"]\nb = [0.0, 0.0]\n',
     "drive.a[1] = '1.0'", "write 1.0 without quotes"),
])
def test_a_number_written_as_text_in_a_scene_file_is_refused(text, field, fix, tmp_path,
                                                             monkeypatch, capsys):
    """``m_star = "10"`` in a scene file ran at m* = 10 (pydantic's lax mode reads the text):
    one line naming the dotted field and that a number is expected, exit 2."""
    scene = tmp_path / "quoted.toml"
    scene.write_text(text)
    code, _, err = call(monkeypatch, capsys, "run", str(scene), "--explain")
    line = _one_line(code, err)
    assert f"{field} is a number written as text" in line and "a number is expected" in line
    assert fix in line and str(scene) in line, line
    with pytest.raises(sd.SceneError, match="a number is expected"):
        # the scene knows no model: its parameters are read where it is bound to one
        bind(sd.Scene.from_toml(scene))


def test_a_number_written_as_text_on_the_command_line_is_read(tmp_path, monkeypatch, capsys):
    """--set values arrive as text and are parsed on purpose; a device's quantities are text
    with units in a file (radius = "0.5 mm"), and so is a bare number there (SI)."""
    import json

    code, out, err = call(monkeypatch, capsys, "run", "--periods", "2", "--no-settle",
                          "--steps-per-period", "64", "--set", "particle.m_star=10", "--json")
    assert code == 0 and json.loads(out)["m_star"] == 10.0, err
    motor = (Path(__file__).resolve().parents[1] / "examples" / "saw_linear_motor.toml")
    scene = tmp_path / "motor.toml"
    scene.write_text(motor.read_text().replace('"0.5 mm"', '"0.0005"'))
    assert sd.Scene.from_toml(scene).device.particle.radius == 0.0005


_MOTOR = Path(__file__).resolve().parents[1] / "examples" / "saw_linear_motor.toml"


def test_a_mass_that_replaces_a_files_density_says_so(monkeypatch, capsys):
    """--set device.particle.mass on the motor (a steel ball given by its density) replaced the
    density without a word. The replacement stays (a density-based example is run and swept with
    a mass: tests/test_device.py), and a note names both fields."""
    code, _, err = call(monkeypatch, capsys, "run", str(_MOTOR), "--explain", "--set",
                        "device.particle.mass=8 mg")
    assert code == 0, err
    notes = [line for line in err.splitlines() if "replaces" in line]
    assert notes == ["note: --set device.particle.mass=8 mg replaces the scene file's "
                     "device.particle.density = 7850 kg/m^3 (a device particle is given by one "
                     "of them)"], err


def test_a_mass_and_a_density_both_given_must_agree(monkeypatch, capsys):
    """Both given (on the command line or in a file) is over-determined: they were refused even
    where they agree ('give exactly one'), and the line gave neither value. Within 1e-9 they are
    accepted; otherwise one line names both and the mass the density gives."""
    import math

    same = 7850.0 * 4.0 / 3.0 * math.pi * 0.5e-3 ** 3
    code, _, err = call(monkeypatch, capsys, "run", str(_MOTOR), "--explain", "--set",
                        f"device.particle.mass={same * (1 + 2e-10)!r}", "--set",
                        "device.particle.density=7850 kg/m^3")
    assert code == 0, err
    code, _, err = call(monkeypatch, capsys, "run", str(_MOTOR), "--explain", "--set",
                        "device.particle.mass=4 mg", "--set", "device.particle.density=7850 kg/m^3")
    line = _one_line(code, err)
    assert "mass = 4e-06 kg and density = 7850 kg/m^3" in line and "4.11025e-06 kg" in line, line


@pytest.mark.parametrize(("text", "field"), [
    ('[effects]\nrotation = "true"\n', "effects.rotation = 'true'"),
    ('[effects]\nrotation = "yes"\n', "effects.rotation = 'yes'"),
    ('[numerics]\nsettle = "false"\n', "numerics.settle = 'false'"),
    ('[effects]\nfriction = 1\n', "effects.friction = 1"),
])
def test_a_boolean_written_as_text_or_a_number_in_a_scene_file_is_refused(text, field, tmp_path,
                                                                          monkeypatch, capsys):
    """rotation = "yes" turned rotation on, settle = "false" made a fixed run, friction = 1 kept
    friction: pydantic's lax mode reads them as booleans. One line naming the field, exit 2."""
    scene = tmp_path / "flag.toml"
    scene.write_text(text)
    code, _, err = call(monkeypatch, capsys, "run", str(scene), "--explain")
    line = _one_line(code, err)
    assert f"{field} is not a boolean" in line and "true or false is expected" in line, line


@pytest.mark.parametrize("field, value", [("count", "200"), ("fraction", "0.5"), ("seed", "0")])
def test_a_number_written_as_text_in_a_particles_table_is_refused(field, value, tmp_path,
                                                                  monkeypatch, capsys):
    """sort and lammps read a [particles] table beside the scene: count = "200" placed 200
    spheres without a word. One line naming particles.FIELD, exit 2, nothing written."""
    text = Path(sd.__file__).parents[2].joinpath("examples", "mixture.toml").read_text()
    quoted, n = re.subn(rf"(?m)^{field} = {re.escape(value)}$", f'{field} = "{value}"', text)
    assert n == 1
    scene = tmp_path / "mix.toml"
    scene.write_text(quoted)
    out = tmp_path / "out"
    code, _, err = call(monkeypatch, capsys, "sort", str(scene), "-o", str(out))
    line = _one_line(code, err)
    assert f"particles.{field} = '{value}' is a number written as text" in line, line
    assert not out.exists()


def test_an_infinity_written_as_text_is_not_told_to_lose_its_quotes(tmp_path, monkeypatch, capsys):
    """m_star = "inf" was told 'write m_star = inf without quotes', which the field's range
    refuses in turn: the line says a finite number is expected."""
    scene = tmp_path / "inf.toml"
    scene.write_text('[particle]\nm_star = "inf"\n')
    code, _, err = call(monkeypatch, capsys, "run", str(scene))
    line = _one_line(code, err)
    assert "particle.m_star = 'inf'" in line and "a finite number is expected" in line, line
    assert "without quotes" not in line
