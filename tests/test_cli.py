"""The command line: JSON output, determinism, one-line errors with exit status 2."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys

import pandas as pd
import pytest

import sawdrift as sd

from .cli_call import run_main


def process(*args: str, check: bool = False) -> subprocess.CompletedProcess:
    """``sawdrift ARGS`` in a new process (``python -m sawdrift``): for what only a process shows."""
    return subprocess.run(
        [sys.executable, "-m", "sawdrift", *args], capture_output=True, text=True, check=check,
        timeout=600,
    )


#: ``sawdrift ARGS`` in this process (tests/cli_call.py): the output and exit status of a process
#: without its 1-2 s of start-up
cli = run_main


REQUIRED = {"model", "m_star", "amplitude", "mu", "nu", "horizontal_ratio", "drift_velocity",
            "drift_ratio", "regime", "contact_lost", "steps", "wall_time_s"}


def test_models_json_lists_material_point_with_distribution():
    # a new process: the entry point, its plugin discovery from the installed metadata, status 0
    out = process("models", "--json", check=True)
    rows = {row["name"]: row for row in json.loads(out.stdout)}
    assert rows["material_point"]["distribution"] == "sawdrift"
    assert "restitution" in rows["material_point"]["parameters"]


def test_run_json_is_one_object_and_deterministic():
    args = ("run", "--model", "material_point", "--m-star", "0.1", "--amplitude", "0.1", "--json")
    first, second = cli(*args, check=True), cli(*args, check=True)
    a, b = json.loads(first.stdout), json.loads(second.stdout)
    assert REQUIRED <= set(a)
    assert a["regime"] == "drift_against"
    for timing in ("wall_time_s", "compile_s"):  # the only fields that depend on the machine
        a.pop(timing), b.pop(timing)
    assert a == b


def test_an_unsettled_run_says_so_on_stderr():
    """m* = 100, A* = 0.3 is transient after 60 fixed periods: settled False and a one-line note;
    with --settle (and by default: a heavy particle settles unless told not to) it settles and no
    note is printed."""
    args = ("run", "--model", "mmd", "--m-star", "100", "--amplitude", "0.3")
    short = cli(*args, "--no-settle", check=True)
    assert re.search(r"settled\s+NO, not confirmed by its fixed window", short.stdout)
    notes = short.stderr.strip().splitlines()
    assert len(notes) == 1 and "m*/mu = 1000" in notes[0] and "--settle" in notes[0]
    for flag in (("--settle",), ()):
        settled = cli(*args, *flag, check=True)
        assert re.search(r"settled\s+yes", settled.stdout) and settled.stderr.strip() == "", flag


def test_a_heating_bouncer_is_not_told_that_a_longer_mean_tightens_its_error():
    """mmd m* = 0.1, A* = 1 bounces chaotically and heats up (its warnings say so): its note says
    a longer run gives another mean; mmd m* = 5.62, A* = 0.891, an irregular heavy bouncer whose
    energy does not grow, keeps the note that --mean-periods tightens the error."""
    heating = cli("run", "--model", "mmd", "--m-star", "0.1", "--amplitude", "1", check=True)
    notes = heating.stderr.strip().splitlines()
    assert len(notes) == 1 and "heat up" in notes[0] and "tighter" not in notes[0], notes
    assert "heat up" in heating.stdout  # the warning itself, with the numbers
    steady = cli("run", "--model", "mmd", "--m-star", "5.623413251903491", "--amplitude",
                 "0.8912509381337456", check=True)
    notes = steady.stderr.strip().splitlines()
    assert len(notes) == 1 and "--mean-periods for a tighter error" in notes[0], notes


def test_run_writes_parquet_and_png(tmp_path):
    # a fixed run (the default would go on to the hop's periodic orbit, past the 10 periods)
    cli("run", "--model", "material_point", "--periods", "10", "--no-settle", "-o", str(tmp_path),
        check=True)
    frame = pd.read_parquet(tmp_path / "trajectory.parquet")
    assert {"t", "x", "a", "N_star", "T_star"} <= set(frame.columns)
    assert frame["t"].iloc[-1] == pytest.approx(10.0, abs=0.01)
    assert (tmp_path / "trajectory.png").stat().st_size > 10_000


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (("--m-star", "-1"), "particle.m_star"),
        (("--m-star", "0"), "particle.m_star"),
        (("--mu", "0"), "material.mu"),
        (("--mu", "-0.5"), "material.mu"),
        (("--nu", "0.5"), "material.nu"),
        (("--nu", "-1.5"), "material.nu"),
        (("--model", "no_such_model"), "no_such_model"),
        (("--m-star", "abc"), "m-star"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(args, needle, sawdrift_main):
    # in this process (tests/conftest.py): the error comes before any run
    out = sawdrift_main("run", *(() if "--model" in args else ("--model", "material_point")), *args)
    assert out.returncode == 2
    err = [line for line in out.stderr.splitlines() if line.startswith("error")]
    assert len(err) == 1 and needle in err[0]
    assert "Traceback" not in out.stderr


def test_malformed_scene_file(tmp_path, sawdrift_main):
    path = tmp_path / "scene.toml"
    path.write_text("model = 'material_point'\n[particle\n")
    out = sawdrift_main("run", str(path))
    assert out.returncode == 2
    assert "malformed TOML" in out.stderr and "Traceback" not in out.stderr


def test_scene_file_with_bad_value(tmp_path, sawdrift_main):
    path = tmp_path / "scene.toml"
    path.write_text("model = 'material_point'\n[material]\nnu = 0.7\n")
    out = sawdrift_main("run", str(path))
    assert out.returncode == 2
    assert "material.nu = 0.7 is outside the allowed range (-1, 0.5)" in out.stderr


@pytest.mark.parametrize(
    ("model", "params"),
    [("material_point", ()), ("mmd", ()), ("mdr", ("--param", "strips=64")), ("jaeger", ()),
     ("hertz_mindlin_dem", ("--param", "rescale=true")), ("hertz_tsuji", ("--param", "damping=0.2"))],
)
def test_every_model_runs_the_wave_scene(model, params):
    if model == "hertz_tsuji":
        pytest.importorskip("sawdrift_tsuji")
    out = cli("run", "--model", model, "--m-star", "0.1", "--amplitude", "0.316", "--periods", "20",
              *params, "--json")
    assert out.returncode == 0, out.stderr
    row = json.loads(out.stdout)
    # the CLI is a thin layer: its numbers are the Python API's for the same scene, exactly
    api = sd.run(sd.Scene.model_validate(row["scene"]))
    assert row["model"] == model
    assert row["regime"] == api.regime and row["drift_ratio"] == api.drift_ratio
    assert row["steps"] == api.steps and row["gross_slip_fraction"] == api.gross_slip_fraction


def test_bad_model_parameter_is_one_line(sawdrift_main):
    out = sawdrift_main("run", "--model", "mdr", "--param", "strips=1")
    assert out.returncode == 2 and "strips" in out.stderr and "Traceback" not in out.stderr


def test_prescribed_history_from_a_scene_file(tmp_path):
    scene = tmp_path / "loop.toml"
    scene.write_text('model = "mmd"\n[drive]\nkind = "prescribed"\nwaveform = "mindlin_loop"\n'
                     "a_max = 1.0\nb_amplitude = 2.0\ncycles = 1\nsamples_per_segment = 2000\n")
    out = cli("run", str(scene), "-o", str(tmp_path / "out"), "--json")
    assert out.returncode == 0, out.stderr
    row = json.loads(out.stdout)
    # cycling far past full sliding (|b*| = 2 > a* = 1): the loop is a Coulomb rectangle
    # minus the Mindlin corners; its area must exceed the q = 1 Mindlin loop, 0.8 a*^(5/2)
    assert row["regime"] == "prescribed" and row["dissipated_work"] > 0.8
    frame = pd.read_parquet(tmp_path / "out" / "trajectory.parquet")
    assert (frame["T_star"].abs() <= frame["N_star"] + 1e-12).all()


@pytest.mark.slow
def test_an_axis_sweeps_over_the_default_plane(tmp_path):
    # README: `sweep --axis effects.rotation=false,true` compares rotation off and on over the
    # (m*, A*) plane; the axis multiplies the default 11 x 11 plane instead of replacing it.
    # What is checked is the shape of the table, so the runs are short fixed ones (5 periods,
    # --no-settle): the default 60 periods, settled, spent ~20 s of CPU on the heavy cells
    short = ("--periods", "5", "--no-settle")
    out = tmp_path / "rot.parquet"
    cli("sweep", "--model", "material_point", "--axis", "effects.rotation=false,true", *short,
        "--workers", "1", "--no-progress", "-o", str(out), check=True)
    frame = pd.read_parquet(out)
    assert len(frame) == 2 * 11 * 11
    assert frame["m_star"].nunique() == 11 and frame["amplitude"].nunique() == 11
    # an axis over m* replaces the default m* axis only
    out2 = tmp_path / "mu.parquet"
    cli("sweep", "--model", "material_point", "--axis", "particle.m_star=0.1,1", *short,
        "--amplitude", "0.1,1,2", "--workers", "1", "--no-progress", "-o", str(out2), check=True)
    assert len(pd.read_parquet(out2)) == 2 * 3


def test_scene_options_are_generated_from_the_schema():
    # the frozen option table matches the schema: a new scene field is a new option
    from sawdrift.scene import options

    assert options.GENERATED.read_text() == options.render(), (
        "src/sawdrift/_scene_options.py is stale: regenerate it with "
        "python -m sawdrift.scene.options")
    dotted = {row[1] for row in options.scene_options()}
    for name, part in (("material", sd.scene.Material), ("numerics", sd.scene.Numerics),
                       ("effects", sd.scene.Effects)):
        assert {f"{name}.{f}" for f in part.model_fields} <= dotted


@pytest.mark.slow
def test_every_scene_field_reaches_the_scene_from_run_and_sweep(tmp_path):
    # fields that had no hand-written option before (ramp, measuring window, drift tolerance)
    out = json.loads(cli("run", "--model", "material_point", "--ramp-periods", "0",
                         "--measure-periods", "7", "--drift-tolerance", "0.01", "--json",
                         check=True).stdout)
    assert out["ramp_periods"] == 0.0 and out["measure_periods"] == 7
    assert out["scene"]["numerics"]["drift_tolerance"] == 0.01
    table = tmp_path / "t.parquet"
    cli("sweep", "--model", "material_point", "--m-star", "0.1", "--amplitude", "0.1,0.2",
        "--ramp-periods", "2", "--no-progress", "--workers", "1", "-o", str(table), check=True)
    assert (pd.read_parquet(table)["ramp_periods"] == 2.0).all()


@pytest.mark.slow
def test_adaptive_sweep_reports_what_it_wrote(tmp_path):
    # the count printed for the table is the count of rows in it (inferred points are extra);
    # a count, so the cells are short fixed runs (5 periods, --no-settle: the default settled
    # runs spent 15.6 s of CPU on the heavy cells)
    table = tmp_path / "ad.parquet"
    proc = cli("sweep", "--model", "material_point", "--adaptive", "--budget", "120", "--m-star",
               "1e-3:1e2:9", "--amplitude", "1e-2:10:9", "--levels", "1", "--no-progress",
               "--periods", "5", "--no-settle", "-o", str(table), check=True)
    line = proc.stdout.strip().splitlines()[-1]
    computed = int(line.split("(")[1].split(" cells computed")[0])
    assert computed == len(pd.read_parquet(table))


@pytest.mark.slow
def test_bifurcation_locates_the_bouncing_balls_doubling_from_the_command_line(tmp_path):
    # Gamma = 4 pi^2 m* A*; the completely inelastic ball doubles at sqrt(4 + pi^2) = 3.7242
    proc = cli("bifurcation", "--model", "material_point", "--m-star", "0.1",
               "--horizontal-ratio", "0", "--axis", "drive.amplitude=lin:0.85:1.0:16", "--locate",
               "--no-progress", "--json", "-o", str(tmp_path / "bif"), check=True)
    found = [b for b in json.loads(proc.stdout)["bifurcations"] if b["kind"] == "period_doubling"]
    assert len(found) == 1
    gamma = 4 * math.pi**2 * 0.1 * found[0]["value"]
    assert abs(gamma - math.sqrt(4 + math.pi**2)) <= 1e-3
    assert (tmp_path / "bif" / "bifurcation.png").stat().st_size > 10_000
