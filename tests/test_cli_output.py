"""What the command line shows (issue 30, items 3 and 5): figures whose legends fit and whose
unsettled cells are marked, grouped `run` text, two models on one scene, CSV output, unknown keys
named, progress on long commands."""

from __future__ import annotations

import json
import time
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest

import sawdrift as sd

from .cli_call import call, run_main

ROOT = Path(__file__).resolve().parents[1]
MOTOR = ROOT / "examples" / "saw_linear_motor.toml"




@pytest.fixture
def figures(monkeypatch):
    """The figures the plotting code closes, kept open to be inspected."""
    kept: list = []
    close = plt.close
    monkeypatch.setattr(plt, "close", lambda fig=None: kept.append(fig))
    yield kept
    close("all")


def _table(regimes: list[str], settled: list[bool], model: str = "mmd") -> pd.DataFrame:
    """A synthetic sweep table on a 2 x (n/2) grid of (A*, m*)."""
    n = len(regimes)
    amps = np.logspace(-2, 1, n // 2)
    rows = []
    for k, (regime, ok) in enumerate(zip(regimes, settled, strict=True)):
        rows.append({"model": model, "amplitude": amps[k % (n // 2)], "m_star": [0.1, 1.0][k // (n // 2)],
                     "regime": regime, "settled": ok, "mu": 0.1, "nu": 0.3,
                     "drift_ratio": 0.1 * k})
    return pd.DataFrame(rows)


ALL = ["stick", "oscillating_slip", "drift_with", "drift_against", "hopping", "bouncing"]


def _hatched(ax) -> bool:
    """Whether a collection of ``ax`` is hatched (a contour set keeps its hatches apart)."""
    return any(c.get_hatch() or any(getattr(c, "hatches", None) or []) for c in ax.collections)


# --- figures ----------------------------------------------------------------------------------


def test_phase_diagram_legend_lies_inside_the_saved_figure(tmp_path, figures):
    sd.plot_phase_diagram(_table(ALL, [True] * 6), tmp_path / "pd.png", "mmd")
    fig = figures[-1]
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    box = fig.bbox
    texts = [t for leg in fig.legends for t in leg.get_texts()]
    assert sorted(t.get_text() for t in texts) == sorted(ALL)
    for t in texts:
        bb = t.get_window_extent(renderer)
        assert box.x0 <= bb.x0 and bb.x1 <= box.x1 and box.y0 <= bb.y0 and bb.y1 <= box.y1, (
            t.get_text(), bb, box)


def test_phase_diagram_of_a_scattered_table_fills_each_points_region(tmp_path, figures):
    """An adaptive table's points (nested grids: 1 in 4 of the finest grid's places, here the
    coarse 5 x 5 and a refined band of 20) were drawn on the grid of all their coordinates,
    mostly empty (white stripes). Each computed point gets its region, as in the drift map,
    and the computed points are dotted."""
    rows = []
    fine = np.logspace(-2, 1, 17)
    for i, a in enumerate(fine):
        for j, m in enumerate(np.logspace(-3, 2, 17)):
            coarse = i % 4 == 0 and j % 4 == 0
            band = i == j + 1
            if coarse or band:
                rows.append({"model": "mmd", "amplitude": a, "m_star": m, "mu": 0.1, "nu": 0.3,
                             "regime": "stick" if i <= j else "hopping", "settled": True,
                             "drift_ratio": 0.0})
    table = pd.DataFrame(rows)
    points = len(table)
    assert points < 0.5 * 17 * 17  # the case at hand: scattered
    sd.plot_phase_diagram(table, tmp_path / "pd.png", "mmd")
    ax = figures[-1].axes[0]
    (mesh,) = [c for c in ax.collections if hasattr(c, "get_array") and c.get_array() is not None
               and np.ndim(c.get_array()) > 0 and np.size(c.get_array()) > 1000]
    codes = np.asarray(mesh.get_array())
    assert (codes > 0).all()  # no white (empty) region: code + 1 = 0 was a place with no cell
    dots = [line for line in ax.get_lines() if line.get_marker() == "."]
    assert len(dots) == 1 and len(dots[0].get_xdata()) == points


def test_phase_diagram_and_compare_hatch_unsettled_cells(tmp_path, figures):
    table = _table(ALL, [True, True, False, True, False, True])
    sd.plot_phase_diagram(table, tmp_path / "pd.png", "mmd")
    fig = figures[-1]
    assert _hatched(fig.axes[0])
    assert "not settled (2 of 6)" in fig.axes[0].get_title()
    both = pd.concat([table, _table(ALL, [True] * 6, "material_point")])
    sd.plot_compare(both, ["mmd", "material_point"], tmp_path / "cmp.png")
    fig = figures[-1]
    assert _hatched(fig.axes[0]) and not _hatched(fig.axes[1])
    # a table whose cells all settled has no hatching
    sd.plot_phase_diagram(_table(ALL, [True] * 6), tmp_path / "pd2.png", "mmd")
    assert not _hatched(figures[-1].axes[0])


def test_trajectory_figure_says_when_the_drift_is_not_settled(tmp_path, figures):
    scene = sd.Scene(model="material_point", particle={"m_star": 300.0}, drive={"amplitude": 0.5},
                     numerics={"periods": 10, "settle": False})
    res = sd.run(scene, trajectory=True)
    assert res.settled is False
    sd.plot_trajectory(res, tmp_path / "t.png")
    assert "NOT settled" in figures[-1]._suptitle.get_text()


# --- run: grouped text ----------------------------------------------------------------------

SECTIONS = ["regime", "drift", "settled", "evidence", "provenance"]


def _sections(text: str) -> list[str]:
    return [line.rstrip(":") for line in text.splitlines() if line and not line.startswith(" ")
            and line.endswith(":")]


def test_run_text_is_grouped_in_sections_without_none_or_dicts(monkeypatch, capsys):
    code, out, _ = call(monkeypatch, capsys, "run", "--model", "material_point", "--periods", "10")
    assert code == 0
    assert _sections(out) == SECTIONS
    assert "None" not in out and "{" not in out


def test_run_text_says_an_unsettled_drift_is_not_settled_beside_the_number(monkeypatch, capsys):
    code, out, _ = call(monkeypatch, capsys, "run", "--model", "mmd", "--m-star", "300",
                        "--amplitude", "0.5", "--periods", "20", "--no-settle")
    assert code == 0
    line = next(x for x in out.splitlines() if x.strip().startswith("drift_ratio"))
    assert "NOT settled" in line


def test_run_text_gives_a_long_time_mean_with_its_error(monkeypatch, capsys):
    """mmd m* = 0.1, A* = 1, mu = 0.1 is chaotic: its drift is a long-time mean, printed as
    drift +- error (the error of x*' scaled from the drift ratio's), not as a window's average."""
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 1.0}))
    assert res.chaotic and res.drift_ratio_se > 0.0
    code, out, _ = call(monkeypatch, capsys, "run", "--model", "mmd", "--m-star", "0.1",
                        "--amplitude", "1.0")
    assert code == 0
    lines = {x.split()[0]: x for x in out.splitlines() if x.strip()}
    assert f"{res.drift_ratio:.6g} +- {res.drift_ratio_se:.2g}" in lines["drift_ratio"]
    velocity_se = abs(res.drift_velocity / res.drift_ratio) * res.drift_ratio_se
    assert f"{res.drift_velocity:.6g} +- {velocity_se:.2g}" in lines["drift_velocity"]
    assert "long-time mean" in lines["drift_ratio"] and "over the window" not in out


def test_runs_without_a_steady_state_are_not_told_to_run_longer(monkeypatch, capsys, tmp_path):
    """A runaway (load 0.2 > mu = 0.1) and an ejected micro-particle have no steady drift: their
    note says so, where it used to ask for a longer run or a higher period cap; a long-time mean
    is not called an average over the window."""
    code, _, err = call(monkeypatch, capsys, "run", "--model", "material_point", "--m-star",
                        "0.1", "--amplitude", "0", "--load", "0.2", "--mu", "0.1")
    assert code == 0 and "no steady state" in err and "raise" not in err
    scene = sd.Scene.model_validate({"model": "mmd", "device": {
        "frequency": "20 MHz", "amplitude": "1 nm", "orbit": "retrograde", "friction": 0.3,
        "particle": {"radius": "5 um", "density": "2200 kg/m^3", "youngs_modulus": "73 GPa",
                     "poisson": 0.17},
        "substrate": {"youngs_modulus": "200 GPa", "poisson": 0.3}}})
    scene.to_toml(tmp_path / "thrown.toml")
    code, out, err = call(monkeypatch, capsys, "run", str(tmp_path / "thrown.toml"))
    assert code == 0 and "ejected" in out
    assert "no steady state" in err and "raise" not in err
    code, _, err = call(monkeypatch, capsys, "run", "--model", "mmd", "--m-star", "0.1",
                        "--amplitude", "1.0")
    assert code == 0 and "long-time mean" in err and "over the window" not in err


def test_a_mean_still_moving_gets_one_advice_and_no_settling_time(monkeypatch, capsys):
    """The motor at 1 um: a heavy bouncer whose long-time mean still moved when its budget ran
    out. Its warning said --mean-periods, the note 'raise numerics.max_periods' (which the mean
    does not read), and it quoted t90 = 0.067 s, the time to 90 % of a speed never reached."""
    code, out, err = call(monkeypatch, capsys, "run", str(MOTOR), "--set",
                          "device.amplitude=1 um", "--json")
    data = json.loads(out)
    assert code == 0 and data["settled"] is False
    assert any("--mean-periods" in w for w in data["warnings"])
    assert data["t90_periods"] is None and data["t90_s"] is None
    code, _, err = call(monkeypatch, capsys, "run", str(MOTOR), "--set", "device.amplitude=1 um")
    note = [line for line in err.splitlines() if line.startswith("note:")]
    assert code == 0 and len(note) == 1
    assert "--mean-periods" in note[0] and "max_periods" not in note[0]


def test_run_text_of_a_device_shows_m_per_s_first(monkeypatch, capsys):
    code, out, _ = call(monkeypatch, capsys, "run", str(MOTOR), "--no-settle", "--periods", "20")
    assert code == 0
    assert "m/s" in out.splitlines()[0]
    assert _sections(out) == SECTIONS
    assert "{" not in out


# --- run: two models on one scene -----------------------------------------------------------


def test_run_two_models_prints_a_table_and_overlays_their_trajectories(monkeypatch, capsys,
                                                                       tmp_path, figures):
    code, out, err = call(monkeypatch, capsys, "run", "--model", "material_point,mmd",
                          "--periods", "10", "-o", str(tmp_path / "two"))
    assert code == 0, err
    head = out.splitlines()[0].split()
    assert head[-2:] == ["material_point", "mmd"]
    rows = {line.split()[0] for line in out.splitlines()[1:] if line.strip()}
    assert {"regime", "drift_ratio", "settled"} <= rows
    x_axes = figures[-1].axes[0]
    assert sorted(line.get_label() for line in x_axes.get_lines()) == ["material_point", "mmd"]
    for name in ("material_point", "mmd"):
        assert (tmp_path / "two" / f"trajectory_{name}.parquet").exists()
    code, out, _ = call(monkeypatch, capsys, "run", "--model", "material_point,mmd",
                        "--periods", "10", "--json")
    assert [r["model"] for r in json.loads(out)] == ["material_point", "mmd"]


def test_run_several_models_gives_each_model_its_own_parameters(monkeypatch, capsys):
    """--param went to every model of --model a,b: mmd refused mdr's strips, so mdr at 4096
    strips could not be compared with mmd. A NAME goes to each model that takes it, MODEL.NAME
    to one; at 4096 strips mdr's gross slip is mmd's (0.19 at m* 0.3, A* 0.2; 0.06 at 256)."""
    args = ("run", "--model", "mmd,mdr", "--m-star", "0.3", "--amplitude", "0.2",
            "--periods", "20", "--json")
    code, out, err = call(monkeypatch, capsys, *args, "--param", "strips=4096")
    assert code == 0, err
    mmd, mdr = json.loads(out)
    assert mdr["scene"]["model_params"]["strips"] == 4096
    assert "strips" not in mmd["scene"]["model_params"]
    assert mdr["gross_slip_fraction"] == pytest.approx(mmd["gross_slip_fraction"], abs=0.01)
    code, out, _ = call(monkeypatch, capsys, *args, "--param", "mdr.z_max=4")
    assert code == 0 and json.loads(out)[1]["scene"]["model_params"]["z_max"] == 4
    # MODEL.NAME with the one model named too (it was refused: model_params.mdr.strips)
    code, out, err = call(monkeypatch, capsys, "run", "--model", "mdr", "--periods", "4",
                          "--json", "--param", "mdr.strips=64")
    assert code == 0 and json.loads(out)["scene"]["model_params"]["strips"] == 64, err
    for bad, says in (("foo=1", "--param foo is not a known parameter of --model mmd,mdr"),
                      ("jaeger.x=1", "'jaeger' is not one of --model"),
                      ("mdr.foo=1", "model 'mdr' takes no parameter 'foo'")):
        code, _, err = call(monkeypatch, capsys, *args, "--param", bad)
        assert code == 2 and says in err and len(err.strip().splitlines()) == 1


# --- models ---------------------------------------------------------------------------------


def test_models_lists_each_models_parameters(monkeypatch, capsys):
    code, out, _ = call(monkeypatch, capsys, "models")
    assert code == 0
    assert "strips = 256" in out and "z_max = 2" in out and "max_memory_points" in out


# --- -o FILE ----------------------------------------------------------------------------------


def test_run_o_csv_writes_the_trajectory(monkeypatch, capsys, tmp_path):
    path = tmp_path / "out.csv"
    code, out, err = call(monkeypatch, capsys, "run", "--model", "material_point", "--periods",
                          "10", "-o", str(path))
    assert code == 0, err
    scene = sd.Scene(model="material_point", numerics={"periods": 10})
    expected = sd.run(scene, trajectory=True).trajectory
    got = pd.read_csv(path)
    assert list(got.columns) == list(expected.columns)
    assert len(got) == len(expected)
    assert np.allclose(got["x"], expected["x"])
    assert f"wrote {path}" in out


@pytest.mark.parametrize("args", [
    ("run", "--model", "material_point", "--periods", "5", "-o", "{d}/out.txt"),
    ("run", "--model", "material_point", "--periods", "5", "-o", "{d}/out.png"),
    ("sweep", "--m-star", "1", "--amplitude", "1", "-o", "{d}/t.csv"),
    ("bifurcation", "--axis", "drive.amplitude=0.1,0.2", "-o", "{d}/b.csv"),
    ("field", "--backward", "0.5", "--points", "4", "-o", "{d}/f.txt"),
])
def test_o_with_an_unsupported_suffix_is_refused_in_one_line(args, monkeypatch, capsys, tmp_path):
    code, _, err = call(monkeypatch, capsys, *(a.format(d=tmp_path) for a in args))
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("error: -o"), err
    assert not any(tmp_path.iterdir())


@pytest.fixture(scope="module")
def load_curve_csv(tmp_path_factory):
    """``sawdrift load-curve ... -o curve.csv`` with progress left at its default, run once for
    the tests of its file and of its progress lines: (the path, the finished process)."""
    path = tmp_path_factory.mktemp("load_curve") / "curve.csv"
    proc = run_main("load-curve", "--model", "material_point", "--loads", "3", "--periods", "10",
                    "--workers", "1", "-o", path)
    return path, proc


def test_load_curve_o_csv_writes_the_curve(load_curve_csv):
    path, proc = load_curve_csv
    assert proc.returncode == 0, proc.stderr
    got = pd.read_csv(path)
    assert list(got.columns) == ["load", "drift_velocity", "drift_velocity_se", "power",
                                 "regime", "settled"]
    assert len(got) == 3
    # a settled drift has no standard error: the column is empty there, never a made-up 0
    settled = got["settled"].astype(bool)
    assert got.loc[settled, "drift_velocity_se"].isna().all()


# --- unknown keys ---------------------------------------------------------------------------

_MOTOR = MOTOR.read_text()

UNKNOWN = [
    ("toml", 'modle = "mmd"\n', "modle", "model"),
    ("toml", "[partcle]\nm_star = 0.1\n", "partcle", "particle"),
    ("toml", "[particle]\nm_stra = 0.1\n", "m_stra", "m_star"),
    ("toml", "[numerics]\nperiod = 10\n", "period", "periods"),
    ("toml", _MOTOR.replace('frequency = "9.6 MHz"', 'frequncy = "9.6 MHz"'), "frequncy", "frequency"),
    ("toml", _MOTOR.replace('radius = "0.5 mm"', 'radus = "0.5 mm"'), "radus", "radius"),
    ("toml", 'model = "mdr"\n[model_params]\nstrip = 3\n', "strip", "strips"),
    ("run --model mdr --param strip=300", None, "strip", "strips"),
    ("sweep -o {d}/t.parquet --axis material.muu=0.1,0.2", None, "muu", "mu"),
    ("sweep -o {d}/t.parquet --axis materal.mu=0.1,0.2", None, "materal", "material"),
    ("field --axis particle.m_stra=0.05,0.5", None, "m_stra", "m_star"),
    ("load-curve --axis particle.mstar=0.05,0.5", None, "mstar", "m_star"),
]


@pytest.mark.parametrize(("kind", "text", "key", "near"), UNKNOWN, ids=[u[2] for u in UNKNOWN])
def test_a_misspelled_key_is_named_with_the_nearest_valid_one(kind, text, key, near, monkeypatch,
                                                               capsys, tmp_path):
    if kind == "toml":
        (tmp_path / "s.toml").write_text(text)
        args = ["run", str(tmp_path / "s.toml"), "--explain"]
    else:
        args = kind.format(d=tmp_path).split()
    code, _, err = call(monkeypatch, capsys, *args)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("error: "), err
    assert key in lines[0] and ("unknown" in lines[0] or "not a known" in lines[0]), lines[0]
    assert f"did you mean {near}" in lines[0] or f"did you mean '{near}'" in lines[0], lines[0]


# --- progress -------------------------------------------------------------------------------


def test_field_shows_progress_by_default(monkeypatch, capsys):
    code, _, err = call(monkeypatch, capsys, "field", "--model", "material_point", "--backward",
                        "0.5", "--points", "4", "--refine", "0", "--periods", "10", "--workers", "1")
    assert code == 0, err
    assert "field: 4/4 points (100%)" in err  # the executor's label is the study's


def test_load_curve_shows_progress_by_default(load_curve_csv):
    _, proc = load_curve_csv  # no --progress / --no-progress given
    assert proc.returncode == 0, proc.stderr
    assert "load-curve:" in proc.stderr and "stall load" in proc.stderr


def test_a_slow_step_announces_itself(capsys):
    from sawdrift.study.progress import notice

    with notice("compiling", after=0.05):
        time.sleep(0.3)
    with notice("never shown", after=5.0):
        pass
    err = capsys.readouterr().err
    assert "compiling" in err and "never shown" not in err


def test_demo_announces_its_first_compilation(monkeypatch, capsys, tmp_path):
    import sawdrift.report.demo as demo_mod
    import sawdrift.study.progress as progress_mod

    class Stop(Exception):
        pass

    def slow_run(*_args, **_kwargs):
        time.sleep(0.4)
        raise Stop

    monkeypatch.setattr(progress_mod, "NOTICE_AFTER", 0.05)
    monkeypatch.setattr(demo_mod, "run", slow_run)
    with pytest.raises(Stop):
        demo_mod.demo(tmp_path / "demo", 2, 1, echo=lambda _line: None)
    assert "compil" in capsys.readouterr().err


def test_sweep_and_field_text_count_unsettled_cells(monkeypatch, capsys, tmp_path):
    code, out, err = call(monkeypatch, capsys, "sweep", "--model", "mmd", "--m-star", "0.1,300",
                          "--amplitude", "0.5", "--periods", "20", "--no-settle", "--workers", "1",
                          "--no-progress", "-o", str(tmp_path / "t.parquet"))
    assert code == 0, err
    table = pd.read_parquet(tmp_path / "t.parquet")
    loose = int((table["settled"] == False).sum())  # noqa: E712
    assert loose >= 1
    assert sum(int(line.split("(")[1].split()[0]) for line in out.splitlines()
               if "NOT settled" in line) == loose
    code, out, err = call(monkeypatch, capsys, "field", "--model", "mmd", "--m-star", "300",
                          "--backward", "0.5", "--points", "4", "--refine", "0", "--periods", "20",
                          "--no-settle", "--workers", "1", "--no-progress")
    assert code == 0, err
    assert "4 of 4 positions NOT settled" in out


# --- what the text says it wrote, and the warnings it shows -----------------------------------

BEAD = ROOT / "examples" / "silica_bead_on_quartz.toml"


def test_phase_diagram_without_a_suffix_names_the_png_it_writes(monkeypatch, capsys, tmp_path):
    """-o x wrote x.png (matplotlib's default format) and printed "wrote x"; so did compare."""
    table = tmp_path / "t.parquet"
    pd.concat([_table(ALL, [True] * 6), _table(ALL, [True] * 6, "jaeger")]).to_parquet(table)
    for command, name in ((["phase-diagram", "--model", "mmd"], "pd"),
                          (["compare", "--models", "mmd,jaeger"], "cmp")):
        code, out, err = call(monkeypatch, capsys, command[0], str(table), *command[1:], "-o",
                              str(tmp_path / name))
        assert code == 0, err
        assert (tmp_path / f"{name}.png").is_file() and not (tmp_path / name).exists()
        assert f"wrote {tmp_path / name}.png" in out


def test_run_of_two_models_shows_the_device_warnings(monkeypatch, capsys):
    """The single-model text shows a device's validity warnings; two models side by side
    did not (only the Parquet and JSON had them)."""
    code, out, err = call(monkeypatch, capsys, "run", str(BEAD), "--model", "mmd,jaeger",
                          "--set", "device.amplitude=1e-5 nm")
    assert code == 0, err
    lines = [line for line in out.splitlines() if "a0 < 1 nm" in line]
    assert len(lines) == 1 and lines[0].strip().startswith("all models: a0 < 1 nm"), out


def test_sweep_text_summarizes_the_cells_warnings(monkeypatch, capsys, tmp_path):
    """A sweep printed none of its cells' warnings; now one line per kind, with its count."""
    code, out, err = call(monkeypatch, capsys, "sweep", str(BEAD), "--axis",
                          "device.amplitude=1e-5 nm,2e-5 nm", "--workers", "1", "--no-progress",
                          "-o", str(tmp_path / "sq.parquet"))
    assert code == 0, err
    table = pd.read_parquet(tmp_path / "sq.parquet")
    assert table["warnings"].str.contains("a0 < 1 nm").all()
    lines = [line for line in out.splitlines() if "a0 < 1 nm" in line]
    assert len(lines) == 1 and lines[0].strip().startswith("2 cells: a0 < 1 nm"), out
    assert "warnings: 2 of 2 cells" in out


def test_sweep_into_a_table_of_another_grid_says_what_the_table_holds(monkeypatch, capsys,
                                                                      tmp_path):
    """A second grid into the same -o printed "wrote t.parquet (2 cells ...)" of a table that
    held 6; resuming the same grid says nothing more."""
    table = str(tmp_path / "t.parquet")
    common = ["--model", "material_point", "--periods", "10", "--workers", "1", "--no-progress",
              "-o", table]
    code, out, err = call(monkeypatch, capsys, "sweep", "--m-star", "0.1,1", "--amplitude",
                          "0.1,1", *common)
    assert code == 0, err
    assert "earlier sweep" not in out
    code, out, err = call(monkeypatch, capsys, "sweep", "--m-star", "2,5", "--amplitude", "0.5",
                          *common)
    assert code == 0, err
    assert f"wrote {table} (2 cells" in out
    assert f"{table} now holds 6 cells: 4 from an earlier sweep outside this grid" in out
    assert len(pd.read_parquet(table)) == 6
    code, out, err = call(monkeypatch, capsys, "sweep", "--m-star", "2,5", "--amplitude", "0.5",
                          *common)
    assert code == 0 and "now holds 6 cells: 4 from an earlier sweep" in out



def test_command_help_paragraphs_are_reflowed_not_broken_at_the_source_lines():
    """The help renderer keeps a docstring's single line breaks: at 80 columns a paragraph
    wrapped at the source's 100 came out ragged ("... under the loads / of the beads it /
    touches ..."). Each prose paragraph of every command's help is one line; list items stay."""
    import importlib

    from sawdrift.cli import app  # every command registered

    commands = [*app.registered_commands,
                *importlib.import_module("sawdrift.cli.app").bench_app.registered_commands]
    assert len(commands) >= 19
    ragged = []
    for command in commands:
        text = command.help or ""
        assert text, command.name
        for paragraph in text.split("\n\n"):
            lines = paragraph.splitlines()
            if len(lines) > 1 and not any(line.startswith(("- ", "* ", " ")) for line in lines):
                ragged.append((command.name, lines[0][:40]))
    assert not ragged


@pytest.mark.parametrize("command", ["run", "sweep", "field", "bench"])
def test_help_at_80_columns_cuts_no_option_or_field_name(command):
    """At 80 columns (a pipe, a standard terminal) the option tables cut every word longer than
    their column: 28 names of ``run --help`` ended in an ellipsis (``--rolling-resista…``,
    ``material.restitut…``). Folded, every option of the command appears whole."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "COLUMNS": "80", "TERM": "dumb"}
    out = subprocess.run([sys.executable, "-m", "sawdrift", command, "--help"], env=env,
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert "…" not in out.stdout
    assert max(len(line) for line in out.stdout.splitlines()) <= 80
    if command == "run":
        lines = out.stdout.splitlines()
        for name in ("--rolling-resistance", "--no-vertical-inertia", "material.restitution"):
            assert _in_a_column(lines, name), name


def _in_a_column(lines: list[str], name: str) -> bool:
    """Whether ``name`` is in the text whole, or folded: a head ending a line's cell and the rest
    starting the next line at the same column."""
    for line, below in zip(lines, [*lines[1:], ""], strict=True):
        if name in line:
            return True
        for k in range(4, len(name)):
            col = line.find(name[:k] + " ")
            if col >= 0 and below[col:].startswith(name[k:]):
                return True
    return False


def test_ctrl_c_says_so_in_every_command(monkeypatch, capsys, tmp_path):
    """Typer turns Ctrl-C into exit status 130 with no word: run, field, threshold, load-curve
    and bifurcation stopped in silence (bifurcation keeping its journals without saying so)."""
    import sawdrift.study.bifurcation as bif

    def stop(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(sd, "run", stop)
    code, _, err = call(monkeypatch, capsys, "run", "--periods", "10")
    assert code == 130 and err.strip().splitlines()[-1].startswith("interrupted (Ctrl-C)")
    monkeypatch.setattr(bif, "bifurcation", stop)
    code, _, err = call(monkeypatch, capsys, "bifurcation", "--axis",
                        "drive.amplitude=lin:0.1:0.2:3", "--periods", "10", "-o",
                        str(tmp_path / "bif"))
    (line,) = err.strip().splitlines()[-1:]
    assert code == 130 and line.startswith("interrupted: the values done are kept in ")
    assert "run the same command again to resume" in line


def test_a_lightly_refined_adaptive_table_is_drawn_as_regions_too(tmp_path, figures):
    """An adaptive map refined once (39 computed points on the 7 x 7 grid of their coordinates)
    filled more than half of that grid and was drawn as it, with 10 white cells; every table that
    fills less than 90 % of its grid is drawn as each point's region."""
    rows = []
    values = np.logspace(-2, 1, 7)
    missing = {(i, j) for i in (1, 3, 5) for j in (1, 3, 5)} | {(6, 1)}
    for i, a in enumerate(values):
        for j, m in enumerate(values):
            if (i, j) not in missing:
                rows.append({"model": "mmd", "amplitude": a, "m_star": m, "mu": 0.1, "nu": 0.3,
                             "regime": "stick" if i <= j else "hopping", "settled": True,
                             "drift_ratio": 0.0})
    assert len(rows) == 39
    sd.plot_phase_diagram(pd.DataFrame(rows), tmp_path / "pd.png", "mmd")
    ax = figures[-1].axes[0]
    (mesh,) = [c for c in ax.collections if hasattr(c, "get_array") and c.get_array() is not None
               and np.size(c.get_array()) > 1000]
    assert (np.asarray(mesh.get_array()) > 0).all()


def test_no_arguments_print_the_help_and_no_empty_error_line():
    """``sawdrift`` alone printed its help, then a line reading just 'error: '."""
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-m", "sawdrift"], capture_output=True, text=True,
                         timeout=60)
    assert "Usage:" in out.stdout and "run" in out.stdout
    assert "error" not in out.stderr


def test_no_option_help_states_its_interval_twice():
    """A field whose description wrote its interval in another format ('in [1e-6, 10]') got the
    validator's ('in [1e-06, 10]') added after it: --mu, --m-star and --amplitude said it twice."""
    import re

    from sawdrift._scene_options import OPTIONS

    twice = [o[0] for o in OPTIONS if len(re.findall(r"in [\[(][^\])]*[\])]", o[-1])) > 1]
    assert twice == []


def test_an_uncertain_solved_drift_says_so_not_still_changing(monkeypatch, capsys):
    """A loaded drift solved directly whose slow-cycle average is uncertain was printed as
    'NO, still changing after 119 periods' with the advice to raise numerics.max_periods, which
    changes nothing there."""
    code, out, err = call(monkeypatch, capsys, "run", "--model", "mmd", "--m-star", "100",
                          "--amplitude", "3", "--mu", "0.2", "--load", "-0.15")
    text = out + err
    assert code == 0 and "NO: solved directly, its average uncertain" in text, text
    assert "still changing" not in text and "raise numerics.max_periods" not in text
