"""Every subcommand answers bad input with one plain line on stderr and exit status 2."""

from __future__ import annotations

import re
import sys

import pytest

from sawdrift.cli import main

# class names of Python exceptions must never reach the user
_EXC_NAME = re.compile(r"\b[A-Z][A-Za-z]*(Error|Exception)\b|Traceback")


@pytest.fixture
def files(tmp_path):
    (tmp_path / "malformed.toml").write_text('model = "mmd"\n[particle\n')
    (tmp_path / "unknown.toml").write_text("[particle]\nmass = 3\n")
    (tmp_path / "binary.toml").write_bytes(b"\xff\xfe\x00model")
    (tmp_path / "bad.parquet").write_text("not parquet")
    (tmp_path / "adir").mkdir()
    import pandas as pd

    pd.DataFrame({"t": [0.0, 0.5], "x": [0.0, 0.1]}).to_parquet(tmp_path / "traj.parquet")
    # a small sweep table of two models on a 2 x 2 (A*, m*) grid: every figure can be drawn
    pd.DataFrame([{"model": model, "amplitude": a, "m_star": m, "regime": "stick",
                   "settled": True, "mu": 0.1, "nu": 0.3, "drift_ratio": 0.0}
                  for model in ("mmd", "jaeger") for a in (0.1, 1.0) for m in (0.1, 1.0)]
                 ).to_parquet(tmp_path / "sweep.parquet")
    (tmp_path / "amax.toml").write_text('[drive]\nkind = "prescribed"\na_max = 1e308\n')
    (tmp_path / "asamples.toml").write_text('[drive]\nkind = "prescribed"\nwaveform = "samples"\n'
                                            "a = [1e308, 1.0]\nb = [0.0, 0.0]\n")
    from pathlib import Path

    examples = Path(__file__).resolve().parents[1] / "examples"
    (tmp_path / "mixture.toml").write_text((examples / "mixture.toml").read_text())
    (tmp_path / "plate.toml").write_text((examples / "grain_on_vibrating_plate.toml").read_text())
    (tmp_path / "huge.csv").write_text("a,N\n0,0\n1,1\n2,2\n1e308,1e308\n")
    (tmp_path / "huge.toml").write_text('[particle.profile]\nshape = "table"\nfile = "huge.csv"\n')
    (tmp_path / "badcases").mkdir()
    (tmp_path / "badcases" / "case_bad.py").write_text("def (:\n")
    sweep = pd.read_parquet(tmp_path / "sweep.parquet")
    sweep.drop(columns=["drift_ratio"]).to_parquet(tmp_path / "nodrift.parquet")
    sweep.drop(columns=["mu"]).to_parquet(tmp_path / "nomu.parquet")
    return tmp_path


CORPUS = [
    "sweep --model mmd --adaptive --m-star lin:0.1:1:5 --amplitude 0.1:1:5 -o {d}/ad.parquet",
    "run --m-star -1",
    "run --m-star abc",
    "run --mu 0",
    "run --nu 0.5",
    "run --model nosuch",
    "run --param unknown=1",
    "run --param noeq",
    "run --param =3",
    "run --engine gpu",
    "run --order 7",
    "run --profile blob",
    "run --periods 0",
    "run {d}/malformed.toml",
    "run {d}/unknown.toml",
    "run {d}/binary.toml",
    "run {d}/adir",
    "run {d}/missing.toml",
    "sweep -o {d}/t.parquet --m-star 1:2",
    "sweep -o {d}/t.parquet --m-star 0:1:3",
    "sweep -o {d}/t.parquet --model nosuch",
    "sweep -o {d}/t.parquet --workers 0 --m-star 1 --amplitude 1",
    "sweep -o {d}/bad.parquet --m-star 1 --amplitude 0.1 --workers 1",
    "phase-diagram {d}/missing.parquet -o {d}/x.png",
    "phase-diagram {d}/bad.parquet -o {d}/x.png",
    "phase-diagram {d}/adir -o {d}/x.png",
    "compare {d}/bad.parquet --models mmd -o {d}/x.png",
    "compare {d}/missing.parquet --models mmd -o {d}/x.png",
    "explore {d}/bad.parquet -o {d}/x.html",
    "explore {d}/missing.parquet -o {d}/x.html",
    "explore {d}/adir -o {d}/x.html",
    "explore {d}/unknown.toml -o {d}/x.html",
    "demo --n 1 -o {d}/demo",
    "demo --n 100000 -o {d}/demo",
    "sweep -o {d}/t.parquet --adaptive --levels 40",
    "sweep -o {d}/t.parquet --adaptive --budget 1000000000",
    "run -o /proc/sawdrift_out",
    "field --points 3 --backward 0.5",
    "field --backward 0.5 --direct --start 0.1",
    "field --backward 1.5",
    "load-curve --loads 1",
    "load-curve --workers 0",
    "run --restitution -0.5",
    "run --load 1000",
    # a wavelength of 1e-300 a0 ran at 128 steps a period and reported a drift
    "run --periods 5 --no-settle --wavelength 1e-300",
    # --position was ignored by a field (it runs its own positions); --start nan was reported
    # as drive.position
    "field --backward 1 --points 4 --position 0.2",
    "field --backward 1 --direct --wavelength 1000 --start nan",
    # a case file that does not load: exit 1 ("1 errors counted as failed"), the file unnamed
    "validate --no-progress --cases {d}/badcases -o {d}/vbad",
    "run -o {d}/malformed.toml",
    "sweep -o /proc/sawdrift.parquet --m-star 1 --amplitude 1",
    "sweep -o {d}/adir --m-star 1 --amplitude 1",
    "validate -o /proc/sawdrift_report --quick",
    "export {d}/bad.parquet -o /proc/x.nc",
    "run --model mdr --param strips=100000000",
    "run --model mmd --param max_memory_points=1000000000000",
    "validate --cases {d}/nosuchdir -o {d}/v",
    "bench work-precision --models nosuch",
    "models --bogus",
    "nosuchcommand",
    # a Parquet file that is not a sweep table (a run's trajectory): exit 3 before
    "phase-diagram {d}/traj.parquet -o {d}/x.png",
    "compare {d}/traj.parquet --models mmd,jaeger -o {d}/x.png",
    # checked before the size line (two lines before)
    "bifurcation --axis drive.amplitude=0.5 -o {d}/bo",
    "bifurcation --axis drive.amplitude=0.1:1:5 --samples 0 -o {d}/bo",
    "bifurcation --axis drive.amplitude=0.1:1:5 --tolerance -1 -o {d}/bo",
    "run -o {d}/malformed.toml/traj.csv",
    "force-velocity --model mmd --m-star 1 --load 0.2 -o {d}/fv",
    "field --points 3 -o {d}/f3",
    # conflicting sweep specifications: the first was dropped without a word
    "sweep --model mmd --axis material.mu=0.1,0.2 --axis material.mu=0.3 -o {d}/c2.parquet",
    "sweep --model mmd --m-star 0.1,1 --axis particle.m_star=0.5,5 -o {d}/c1.parquet",
    "sweep --model mmd,mmd --m-star 0.1 --amplitude 0.3 -o {d}/c3.parquet",
    # a figure suffix matplotlib cannot write: exit 3 (internal failure) after the drawing
    "phase-diagram {d}/sweep.parquet --model mmd -o {d}/x.jpg2",
    "phase-diagram {d}/sweep.parquet --model mmd --drift -o {d}/x.foo",
    "compare {d}/sweep.parquet --models mmd,jaeger -o {d}/x.jpg2",
    # --explain with --json: the JSON was ignored, the text printed
    "run --explain --json",
    "run --explain -o {d}/explained",
    # an exponent beside a named shape: stored with the scene, but the shape's own p was used
    "run --profile-exponent 2",
    "run --profile cone --profile-exponent 2.5",
    # an empty list item was dropped; a range of two ends with N = 1 gave its start only
    "sweep -o {d}/t.parquet --m-star 0.1,,1 --amplitude 0.5 --periods 5 --workers 1",
    "sweep -o {d}/t.parquet --m-star 0.1,1, --amplitude 0.5 --periods 5 --workers 1",
    "sweep -o {d}/t.parquet --m-star 0.1:1:1 --amplitude 0.5 --periods 5 --workers 1",
    "sweep -o {d}/t.parquet --m-star 0.5 --axis material.mu=lin:0.1:0.2:1 --periods 5 --workers 1",
    "sweep -o {d}/t.parquet --m-star 0.5 --axis material.mu=0.1,,0.2 --periods 5 --workers 1",
    # a table without a column the figure reads: exit 3, "internal failure ('drift_ratio')"
    "phase-diagram {d}/nodrift.parquet --model mmd --drift -o {d}/x.png",
    "phase-diagram {d}/sweep.parquet --model mmd --x particle.load -o {d}/x.png",
    # numpy's allocation of 1e26 samples: exit 3, and a journal left behind
    "bifurcation --axis drive.amplitude=0.2,0.3 --samples 99999999999999999999999999 --yes "
    "-o {d}/bife",
    # a value given twice on any axis ran its cell twice (m* and A* axes refused it)
    "sweep -o {d}/t.parquet --m-star 0.5 --amplitude 0.5 --axis material.mu=0.1,0.1 --workers 1",
    "sweep -o {d}/t.parquet --m-star 0.5 --amplitude 0.5 --axis effects.rotation=true,false,true",
    # a value the scene does not use, accepted and ignored (the same drift to the last bit)
    "run --periods 8 --no-friction --mu 0.5",
    "run --periods 8 --no-horizontal-wave --horizontal-ratio 0.5",
    "run --periods 8 --backward-phase 30",
    "run --periods 8 --backward-phase-rate 3",
    # a prescribed history past any force: two overflow warnings, then the model blamed
    "run {d}/amax.toml",
    "run {d}/asamples.toml",
    # a tabulated law past any float: two overflow warnings, then scipy's own message
    "run --periods 5 {d}/huge.toml",
    # 1e14 placements: "out of memory ... give fewer periods, cells or samples"
    "sort {d}/mixture.toml --seeds 99999999999999 --until 100 --no-progress",
    # its help says a device scene needs its axes: a one-cell table was written
    "sweep {d}/plate.toml -o {d}/y.parquet --no-progress",
    # a folder of results: -o x.json made a folder named x.json
    "lammps --model hertz_mindlin_dem --m-star 0.1 --amplitude 0.3 -o {d}/lmo.json",
]


@pytest.mark.parametrize("line", [
    "bifurcation --axis drive.amplitude=0.5 -o {d}/refused",
    "force-velocity --model mmd --m-star 1 --load 0.2 -o {d}/refused",
    "field --points 3 -o {d}/refused",
])
def test_a_refused_command_leaves_no_output_folder(line, files, monkeypatch, capsys):
    """Every check comes before the output folder is made: a refused command left an empty
    folder behind."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", *line.format(d=files).split()])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code == 2
    assert not (files / "refused").exists()


def test_a_file_in_the_way_of_an_output_folder_is_named(files, monkeypatch, capsys):
    """-o under an existing file: the error named the file system's "File exists"."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", "-o",
                                      str(files / "malformed.toml" / "traj.csv")])
    with pytest.raises(SystemExit):
        main()
    err = capsys.readouterr().err
    assert "'" + str(files / "malformed.toml") + "' is a file, not a folder" in err


@pytest.mark.parametrize("line", CORPUS)
def test_bad_input_exits_2_with_one_plain_line(line, files, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["sawdrift", *line.format(d=files).split()])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2, (line, err)
    assert len(err) == 1 and err[0].startswith("error: "), err
    assert not _EXC_NAME.search(err[0]), err[0]


def test_an_internal_failure_is_not_confused_with_a_failed_check(monkeypatch, capsys):
    # exit 1 means "a check failed" (check-model, validate, bench); a bug gets its own status
    import sawdrift as sd
    from sawdrift.cli import INTERNAL_FAILURE

    def broken(*args, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(sd, "run", broken)
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run"])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert INTERNAL_FAILURE not in (0, 1, 2)
    assert exc.value.code == INTERNAL_FAILURE
    assert len(err) == 1 and "internal failure (boom)" in err[0]


@pytest.mark.parametrize("args", [["-o", ""], ["--out="], ["--out", " "]])
def test_an_empty_output_path_is_refused(args, tmp_path, monkeypatch, capsys):
    """-o "" read as the current folder: a run wrote its five files there (and replaced a
    scene.toml). It is refused in one line before anything runs."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", "--periods", "5", *args])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(err) == 1 and "empty path" in err[0]
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("args", [
    ["phase-diagram", "{d}/sweep.parquet", "--model", "mmd", "-o", "{d}/x.jpg2"],
    ["phase-diagram", "{d}/missing.parquet", "-o", "{d}/x.jpg2"],
    ["compare", "{d}/sweep.parquet", "--models", "mmd,jaeger", "-o", "{d}/x.foo"],
])
def test_a_figure_suffix_is_checked_first_and_the_allowed_ones_named(args, files, monkeypatch,
                                                                     capsys):
    """-o x.jpg2 drew the figure and then failed in matplotlib: "internal failure", exit 3.
    The suffix is checked before the table is read, and the error names -o and the formats."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", *(a.format(d=files) for a in args)])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(err) == 1, err
    assert err[0].startswith("error: -o ") and ".png, .pdf, .svg" in err[0], err
    assert not list(files.glob("x.*"))


def test_profile_exponent_beside_a_named_shape_names_the_field_and_power(monkeypatch, capsys):
    """--profile-exponent 2 on the default sphere was stored (2.0) but p = 1.5 was used."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", "--profile-exponent", "2"])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err
    assert exc.value.code == 2
    assert "profile.exponent = 2" in err and "'power'" in err and "p = 1.5" in err



@pytest.mark.parametrize(("option", "value", "named"), [
    ("--bisections", "-1", "--bisections = -1 must be in [0, 60]"),
    ("--start", "0", "--start = 0 must be in (0, 1000)"),
    ("--per-decade", "0", "--per-decade = 0 must be in [1, 100]"),
    ("--periods", "5", "--periods = 5 must be >= 10"),
])
def test_a_bad_threshold_option_is_named_alone(option, value, named, monkeypatch, capsys):
    """--bisections -1 gave one line listing the ranges of all four scan options."""
    from pathlib import Path

    example = Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml"
    monkeypatch.setattr(sys, "argv", ["sawdrift", "threshold", str(example), "--axis",
                                      "device.particle.radius=1 um", option, value])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and err == [f"error: {named}" + (
        " (units of the rigid removal amplitude)" if option == "--start" else "")], err
    others = {"--start", "--per-decade", "--bisections", "--periods"} - {option}
    assert not any(o in err[0] for o in others)


def test_a_progress_line_before_the_first_value_prints_no_nan_eta(monkeypatch, capsys):
    """`sawdrift threshold` (a counter without a size estimate) printed "ETA nan s" on its first
    line, drawn by the clock before the first value was done."""
    from sawdrift.study import progress as pg

    clock = iter([0.0, 1.0, 3.0])
    monkeypatch.setattr(pg.time, "perf_counter", lambda: next(clock))
    bar = pg._Lines(15, 0, "value", "threshold")  # t0 = 0
    bar.tick()  # at 1 s, nothing done
    bar.update(1)  # at 3 s
    first, second = capsys.readouterr().err.strip().splitlines()
    assert first == "threshold: 0/15 values (0%), 1.0 s so far"
    assert second.startswith("threshold: 1/15 values (7%), 0.3 values/s, ETA 42.0 s")


@pytest.mark.parametrize("command", ["run", "check-model"])
def test_a_bad_model_parameter_names_what_the_model_takes(command, monkeypatch, capsys):
    # check-model said only "model_params.strips = 1: ..." where run names the parameters
    args = ["--model", "mdr"] if command == "run" else ["mdr"]
    monkeypatch.setattr(sys, "argv", ["sawdrift", command, *args, "--param", "strips=1"])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(err) == 1
    assert "model_params.strips" in err[0] and "(model 'mdr' takes: strips, z_max)" in err[0]


def test_out_of_memory_is_one_line_and_exit_2(monkeypatch, capsys):
    """numpy's MemoryError ("Unable to allocate 2.10 GiB ...") was an internal failure, exit 3,
    asking for a bug report."""
    import sawdrift as sd

    from .cli_call import call

    def too_big(*args, **kwargs):
        raise MemoryError("Unable to allocate 2.10 GiB for an array with shape (25600000, 11)")

    monkeypatch.setattr(sd, "run", too_big)
    code, _, err = call(monkeypatch, capsys, "run", "--periods", "10")
    lines = err.strip().splitlines()
    assert code == 2 and lines[-1].startswith("error: out of memory") and "internal" not in err


@pytest.mark.parametrize(("line", "said"), [
    ("run --mu 0.2 --mu=0.3", "--mu is given twice"),
    ("run --settle --periods 10 --no-settle", "--settle and --no-settle are both given"),
    ("sweep --model mmd -o {d}/a.parquet -o {d}/b.parquet", "-o is given twice"),
])
def test_an_option_given_twice_is_refused(line, said, files, monkeypatch, capsys):
    """The parser kept the last of two values: ``--mu 0.2 --mu 0.3`` ran at 0.3 in silence."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", *line.format(d=files).split()])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(err) == 1 and err[0].startswith(f"error: {said}"), err


def test_collecting_options_a_repeated_flag_and_negative_values_still_parse(monkeypatch, capsys):
    """What may repeat still does: a flag twice, and a value that starts with '-' is a value."""
    line = "run --json --json --no-settle --periods 4 --load -0.01 --param max_memory_points=64"
    monkeypatch.setattr(sys, "argv", ["sawdrift", *line.split()])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code == 0, capsys.readouterr().err
    assert '"load": -0.01' in capsys.readouterr().out


def test_a_float_option_that_is_no_number_says_what_was_given(monkeypatch, capsys):
    """--mu abc said "Input should be a valid number, unable to parse string as a number"."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", "--mu", "abc"])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and err == ["error: Invalid value for '--mu': 'abc' is not a number"]


def test_a_second_ctrl_c_while_the_first_is_handled_ends_in_one_line(sawdrift_main, monkeypatch):
    """A KeyboardInterrupt that escapes the command (a second Ctrl-C while the first was being
    handled: ``timeout -s INT`` signals the command and then its process group) printed a
    traceback; it ends with one line and exit status 130."""
    import importlib

    module = importlib.import_module("sawdrift.cli.app")

    def interrupted_twice(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(type(module.app), "__call__", interrupted_twice)
    proc = sawdrift_main("run", "--model", "mmd")
    assert proc.returncode == 130
    assert proc.stderr.strip().startswith("interrupted") and "\n" not in proc.stderr.strip()


def test_an_interrupted_command_puts_the_ctrl_c_handler_back(sawdrift_main, monkeypatch):
    """A command stopped by Ctrl-C ignores further ones while it ends; called in-process (as
    these tests call it) it left SIGINT ignored for the rest of the process and for every
    process started after, and a later test's study could not be interrupted."""
    import importlib
    import signal

    module = importlib.import_module("sawdrift.cli.app")
    before = signal.getsignal(signal.SIGINT)

    def stopped(*args, **kwargs):
        module.interrupted("interrupted: nothing kept")

    monkeypatch.setattr(type(module.app), "__call__", stopped)
    proc = sawdrift_main("run", "--model", "mmd")
    assert proc.returncode == 130 and "interrupted" in proc.stderr
    assert signal.getsignal(signal.SIGINT) is before


def test_an_option_an_axis_makes_used_is_accepted(files, monkeypatch, capsys):
    """--backward-phase is used where an axis gives a second wave, in the cells that have one."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", "sweep", "--m-star", "0.5", "--amplitude", "0.5",
                                      "--axis", "drive.backward=0,0.5", "--backward-phase", "30",
                                      "--periods", "8", "--workers", "1", "--no-progress",
                                      "-o", str(files / "bw.parquet")])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code == 0, capsys.readouterr().err
    import pandas as pd

    orbits = sorted(pd.read_parquet(files / "bw.parquet")["orbit"])
    assert orbits[0] == "prograde" and "psi 30" in orbits[1], orbits  # the phase where it is used


def test_an_unused_option_says_what_makes_it_used(files, monkeypatch, capsys):
    """A scene file that turns friction off: the line said 'drop --no-friction', an option
    never given; it says what to add. A field's species axis may give the second wave."""
    (files / "nofric.toml").write_text("[effects]\nfriction = false\n")
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", str(files / "nofric.toml"), "--mu", "0.2"])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err
    assert exc.value.code == 2 and "add --friction, or drop --mu 0.2" in err, err
    monkeypatch.setattr(sys, "argv", ["sawdrift", "field", "--axis", "drive.backward=0.5,1",
                                      "--backward-phase", "90", "--points", "4", "--periods", "8",
                                      "--refine", "0", "--workers", "1", "--no-progress"])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code in (0, None), capsys.readouterr().err


def test_an_air_drag_the_step_cannot_resolve_is_named(monkeypatch, capsys):
    """--air-drag 1e308 (in [0, inf)) blew the state up and the error blamed the step size and
    the contact model: it names the drag and the steps it would need. A drag the default step
    could not resolve (c h / m* = 0.94 at 128 steps: 12 on m* = 0.1) takes more steps and runs;
    at steps given explicitly the failure names the drag and the order's stability limit."""
    def run(*args: str) -> tuple[int, list[str]]:
        monkeypatch.setattr(sys, "argv", ["sawdrift", "run", "--periods", "5", *args])
        with pytest.raises(SystemExit) as exc:
            main()
        return exc.value.code, capsys.readouterr().err.strip().splitlines()

    code, err = run("--air-drag", "1e308")
    assert code == 2 and len(err) == 1
    assert "effects.air_drag = 1e+308" in err[0] and "steps a period" in err[0], err[0]
    assert run("--air-drag", "12", "--m-star", "0.1")[0] in (0, None)
    code, err = run("--air-drag", "12", "--m-star", "0.1", "--steps-per-period", "128")
    assert code == 2 and "effects.air_drag = 12" in err[0] and "order-4" in err[0], err


def test_a_prescribed_sample_past_any_force_is_the_scenes_error(files, monkeypatch, capsys):
    """a* = 1e308 in a prescribed history was blamed on the contact model ('returned a
    non-finite force'): the scene bounds |a*|, |b*| and says so."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", str(files / "asamples.toml")])
    with pytest.raises(SystemExit) as exc:
        main()
    err = capsys.readouterr().err
    assert exc.value.code == 2 and "within +-1e+06" in err and "model" not in err, err


def test_after_ctrl_c_a_pool_shutting_down_prints_no_traceback(monkeypatch, capsys):
    """A resumed sweep stopped by Ctrl-C printed, 3 times in 20, "Exception ignored in: <module
    'threading'>" and an OSError's traceback from concurrent.futures after its "interrupted"
    line: the pool's manager thread met its killed workers during the interpreter's shutdown.
    After an interrupt that is dropped; any other unraisable error is still printed."""
    import importlib

    import typer

    cli_app = importlib.import_module("sawdrift.cli.app")  # the module, not the Typer app

    monkeypatch.setattr(sys, "unraisablehook", sys.__unraisablehook__)
    said = cli_app._INTERRUPT_SAID[0]
    try:
        with pytest.raises(typer.Exit):
            cli_app.interrupted("interrupted (Ctrl-C): test")
    finally:
        cli_app._restore_interrupts()  # interrupted() ignores a second Ctrl-C until then
        cli_app._INTERRUPT_SAID[0] = said

    def unraisable(filename: str, exc: BaseException) -> None:
        """An error raised in a finalizer of code from ``filename``: Python hands it to
        sys.unraisablehook (as it does the pool thread's at shutdown)."""
        space: dict = {}
        exec(compile("class Doomed:\n    def __del__(self):\n        raise exc\n", filename,
                     "exec"), {"exc": exc}, space)
        doomed = space["Doomed"]()
        del doomed

    capsys.readouterr()
    unraisable("/usr/lib/python3/concurrent/futures/process.py", OSError(9, "Bad file descriptor"))
    assert capsys.readouterr().err == ""
    unraisable("/somewhere/else.py", OSError(9, "Bad file descriptor"))
    assert "Bad file descriptor" in capsys.readouterr().err


@pytest.mark.parametrize("line", [
    "phase-diagram {d}/nomu.parquet --model jaeger -o {d}/p.png",
    "compare {d}/nomu.parquet --models mmd,jaeger -o {d}/c.png",
])
def test_a_table_without_mu_is_drawn(line, files, monkeypatch, capsys):
    """The figure's material label read mu and nu: a table without one failed as an internal
    error ('mu'), exit 3. The label shows what the table has."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", *line.format(d=files).split()])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code in (0, None), capsys.readouterr().err
    figure = files / ("p.png" if line.startswith("phase") else "c.png")
    assert figure.stat().st_size > 1000

