"""Figures of a table swept over another column too (``--axis particle.load=0,0.2``).

phase-diagram and compare never draw one map of several values of that column (a patchwork):
they refuse in one line naming it, its values and ``--where`` (or ``--by``), and ``--where
FIELD=VALUE`` draws one value. The explorer's ``-o`` takes a page name only.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest

from sawdrift.errors import SceneError
from sawdrift.report import compare_plot, diagrams
from tests.cli_call import run_main

MASSES, AMPS, LOADS = [0.01, 0.1, 1.0], [0.1, 1.0, 10.0], [0.0, 0.2]
#: regimes of the load-0 cells (row by row over m*, A*); at load 0.2 every cell runs away
MP = ["stick", "drift_with", "hopping", "stick", "drift_with", "hopping", "stick", "bouncing",
      "bouncing"]
MMD = ["stick", "drift_against", "hopping", "oscillating_slip", "drift_with", "hopping", "stick",
       "hopping", "drift_with"]
#: load-0 cells where the models disagree, and mmd's unsettled load-0 cells
DISAGREE, MMD_UNSETTLED = 4, 2


def two_load_table() -> pd.DataFrame:
    """Two models on a 3 x 3 (m*, A*) grid at two loads; regimes as above."""
    rows = []
    for model, regimes in (("material_point", MP), ("mmd", MMD)):
        for load in LOADS:
            for k, (m, a) in enumerate((m, a) for m in MASSES for a in AMPS):
                runaway = load > 0
                rows.append({
                    "cell_id": f"{model[:3]}{load:g}{k}", "model": model, "m_star": m,
                    "amplitude": a, "mu": 0.1, "nu": 0.3, "particle.load": load,
                    "regime": "runaway" if runaway else regimes[k],
                    "drift_ratio": np.nan if runaway else 0.1 * k,
                    "settled": not runaway and not (model == "mmd" and k < MMD_UNSETTLED),
                    "mean_acceleration": load / m if runaway else np.nan})
    return pd.DataFrame(rows)


@pytest.fixture
def table(tmp_path):
    path = tmp_path / "two_load.parquet"
    two_load_table().to_parquet(path)
    return path


def _one_error_line(result) -> str:
    assert result.returncode == 2, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and "Traceback" not in result.stderr
    return lines[0]


@pytest.mark.parametrize("extra", [[], ["--drift"]])
def test_phase_diagram_refuses_to_mix_the_values_of_another_swept_column(table, tmp_path, extra):
    out = tmp_path / "pd.png"
    line = _one_error_line(run_main("phase-diagram", table, "--model", "mmd", "-o", out, *extra))
    assert "particle.load" in line and "(0, 0.2)" in line
    assert "--where particle.load=VALUE" in line
    assert not out.exists()


def _drawn(monkeypatch) -> list:
    """The figures the report modules close (after saving), to read their titles."""
    figures: list = []
    close = plt.close

    def keep(fig=None):
        figures.append(fig)
        close(fig)

    monkeypatch.setattr(plt, "close", keep)
    return figures


def test_phase_diagram_where_draws_one_value_and_counts_its_cells(table, tmp_path, monkeypatch):
    figures = _drawn(monkeypatch)
    result = run_main("phase-diagram", table, "--model", "mmd", "--where", "particle.load=0",
                      "-o", tmp_path / "pd.png")
    assert result.returncode == 0, result.stderr
    (fig,) = figures
    title = fig.axes[0].get_title()
    # the nine load-0 cells of mmd, of which two are unsettled (not 9 of 9: load 0.2 runs away)
    assert "mmd, particle.load = 0:" in title
    assert f"hatched: not settled ({MMD_UNSETTLED} of 9)" in title
    codes = diagrams.regime_grid(two_load_table(), "mmd", where={"particle.load": 0.0})[2]
    assert [diagrams._ORDER[c] for c in codes.ravel()] == MMD


def test_drift_map_where_counts_the_cells_of_its_value(table, tmp_path, monkeypatch):
    figures = _drawn(monkeypatch)
    result = run_main("phase-diagram", table, "--model", "mmd", "--drift", "--where",
                      "particle.load=0.2", "-o", tmp_path / "pdd.png")
    assert result.returncode == 0, result.stderr
    (fig,) = figures
    titles = [ax.get_title() for ax in fig.axes]
    assert titles[0] == "mmd, particle.load = 0.2: regimes"
    assert any("hatched: not settled (9 of 9)" in t for t in titles)  # not (11 of 18)


@pytest.mark.parametrize(("where", "needles"), [
    ("particle.lod=0.2", ["'particle.lod' is not a column", "particle.load"]),
    ("particle.load=0.3", ["no cell with that value", "values of particle.load: 0, 0.2"]),
    ("particle.load=heavy", ["no cell with that value", "0, 0.2"]),
    ("particle.load", ["must look like FIELD=VALUE"]),
])
def test_a_bad_where_is_one_line(table, tmp_path, where, needles):
    for command in (["phase-diagram", table, "--model", "mmd"],
                    ["compare", table, "--models", "material_point,mmd"]):
        out = tmp_path / "x.png"
        line = _one_error_line(run_main(*command, "--where", where, "-o", out))
        assert "--where" in line and all(n in line for n in needles), line
        assert not out.exists()


def test_compare_without_by_refuses_to_mix_and_where_compares_one_value(table, tmp_path):
    out = tmp_path / "cmp.png"
    line = _one_error_line(run_main("compare", table, "--models", "material_point,mmd", "-o", out))
    assert "particle.load" in line and "(0, 0.2)" in line
    assert "--where particle.load=VALUE" in line and "--by particle.load" in line
    assert not out.exists()
    result = run_main("compare", table, "--models", "material_point,mmd", "--where",
                      "particle.load=0", "-o", out)
    assert result.returncode == 0, result.stderr
    same = 9 - DISAGREE
    assert f"| material_point | mmd | 9 | {same} | {same / 9:.1%} |" in result.stdout
    assert f"| 9 | {same} |" in out.with_suffix(".md").read_text()


def test_compare_by_the_column_still_draws_a_panel_per_value(table, tmp_path):
    fig, md = compare_plot.compare_figure(two_load_table(), ["material_point", "mmd"],
                                          by="particle.load")
    plt.close(fig)
    assert "| material_point, particle.load = 0.0 | mmd, particle.load = 0.0 | 9 | 5 |" in md
    # a third swept column, not named by --by: each panel would mix its values
    third = pd.concat([two_load_table().assign(**{"particle.gyration": g}) for g in (0.4, 0.5)])
    with pytest.raises(SceneError, match=r"several values of particle.gyration \(0.4, 0.5\)"):
        compare_plot.compare_figure(third, ["material_point", "mmd"], by="particle.load")


def test_compare_by_a_value_one_model_lacks_is_one_line():
    """One model swept at both loads, the other at one: --by particle.load had a panel with no
    cells, an internal failure (exit 3); it names the model and the values it lacks."""
    both = two_load_table()
    lacking = both[~((both["model"] == "mmd") & (both["particle.load"] == 0.2))]
    with pytest.raises(SceneError, match=r"model mmd has no cells at particle.load = 0.2 "
                                         r"\(its table holds particle.load = 0\)"):
        compare_plot.compare_figure(lacking, ["material_point", "mmd"], by="particle.load")


def test_explore_refuses_a_suffix_that_is_not_a_page(table, tmp_path):
    out = tmp_path / "ex.txt"
    line = _one_error_line(run_main("explore", table, "-o", out))
    assert "-o" in line and ".txt" in line and ".html" in line
    assert not out.exists()
    line = _one_error_line(run_main("explore", table, "-o", tmp_path))
    assert "is a directory" in line
    result = run_main("explore", table, "-o", tmp_path / "page")  # no suffix: .html
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "page.html").read_text().lstrip().lower().startswith("<!doctype html")
    assert "page.html" in result.stdout and not (tmp_path / "page").exists()


@pytest.mark.parametrize(("cmd", "axis", "needle"), [
    (["phase-diagram", "--model", "mmd"], ["--y", "drift_ratio"], "an output of the runs"),
    (["phase-diagram", "--model", "mmd", "--drift"], ["--y", "drift_ratio"], "an output"),
    (["phase-diagram", "--model", "mmd"], ["--x", "settled"], "an output of the runs"),
    (["compare", "--models", "mmd,material_point"], ["--x", "regime"], "an output of the runs"),
])
def test_a_map_over_an_output_is_refused_in_one_line(table, tmp_path, cmd, axis, needle):
    # --y drift_ratio ended in 'internal failure (x and y arguments to pcolormesh cannot have
    # non-finite values)', exit 3
    out = run_main(cmd[0], str(table), *cmd[1:], *axis, "--where", "particle.load=0",
                   "-o", str(tmp_path / "m.png"))
    assert needle in _one_error_line(out)


def test_a_map_over_a_column_of_words_is_refused(tmp_path):
    # --x effects.rotation (bools) and particle.profile.shape (words) ended in internal failures
    frame = two_load_table()
    frame["effects.rotation"] = frame["particle.load"] > 0.0
    path = tmp_path / "rot.parquet"
    frame.to_parquet(path)
    out = run_main("phase-diagram", str(path), "--model", "mmd", "--x", "effects.rotation",
                   "--where", "amplitude=1", "-o", str(tmp_path / "m.png"))
    assert "holds no numbers" in _one_error_line(out)


def test_where_takes_a_value_as_the_error_prints_it(tmp_path):
    # the error listed 'its values of amplitude: ..., 0.316228, ...' and refused 0.316228
    frame = two_load_table()
    frame["amplitude"] = frame["amplitude"].replace(1.0, 10 ** -0.5)
    path = tmp_path / "t.parquet"
    frame.to_parquet(path)
    bad = run_main("phase-diagram", str(path), "--model", "mmd", "--x", "m_star", "--y",
                   "particle.load", "--where", "amplitude=0.3", "-o", str(tmp_path / "m.png"))
    assert "0.316228" in _one_error_line(bad)
    frame = frame[frame["particle.load"] == 0.0]
    frame.to_parquet(path)
    ok = run_main("phase-diagram", str(path), "--model", "mmd",
                  "--where", "amplitude=0.316228", "--x", "m_star", "--y", "mu",
                  "-o", str(tmp_path / "m.png"))
    assert ok.returncode == 0, ok.stderr


def test_a_map_over_an_axis_holding_zero_is_refused(table, tmp_path):
    # the maps are drawn on log axes: --x particle.load (0 and 0.2) ended in an internal failure
    out = run_main("phase-diagram", str(table), "--model", "mmd", "--x", "particle.load",
                   "--where", "amplitude=1", "-o", str(tmp_path / "m.png"))
    assert "holds values <= 0" in _one_error_line(out)


def test_a_swept_field_is_named_before_the_step_it_changes(tmp_path):
    """A table swept over effects.rotation also holds two steps per period (rotation sets the
    step): the refusal names the swept field, whose values draw whole maps, not the step."""
    base = two_load_table()
    base = base[base["particle.load"] == 0.0].drop(columns="particle.load")
    # as a sweep writes it: the scene's columns (the step among them) before the swept field
    table = pd.concat([base.assign(**{"steps_per_period": 128, "effects.rotation": False}),
                       base.assign(**{"steps_per_period": 130 + np.arange(len(base)),
                                      "effects.rotation": True})])
    path = tmp_path / "rot.parquet"
    table.to_parquet(path)
    line = _one_error_line(run_main("phase-diagram", path, "--model", "mmd", "-o",
                                    tmp_path / "x.png"))
    assert "several values of effects.rotation" in line and "--where effects.rotation=" in line


def test_compare_refuses_an_empty_table_and_by_model_in_one_line(table, tmp_path):
    """An empty table and --by model ended in an internal failure (exit 3: 'single positional
    indexer is out-of-bounds')."""
    empty = tmp_path / "empty.parquet"
    two_load_table().iloc[:0].to_parquet(empty)
    line = _one_error_line(run_main("compare", empty, "--models", "mmd,material_point", "-o",
                                    tmp_path / "c.png"))
    assert "holds no cells" in line
    line = _one_error_line(run_main("compare", table, "--models", "mmd,material_point", "--by",
                                    "model", "-o", tmp_path / "c.png"))
    assert "--by 'model' is not a swept field" in line


@pytest.mark.parametrize("command", [["compare", "--models", "mmd,material_point"],
                                     ["phase-diagram", "--model", "mmd"], ["export"],
                                     ["explore"]])
def test_a_regime_no_run_gives_is_refused_in_one_line(command, tmp_path):
    """A table whose regime column holds a word no run gives drew it as a missing cell, and
    compare agreed on 'nan%' with exit 0."""
    bad = two_load_table()
    bad = bad[bad["particle.load"] == 0.0].drop(columns="particle.load")
    bad["regime"] = "bogus_regime"
    path = tmp_path / "bad.parquet"
    bad.to_parquet(path)
    suffix = {"export": ".nc", "explore": ".html"}.get(command[0], ".png")
    line = _one_error_line(run_main(command[0], path, *command[1:], "-o",
                                    tmp_path / f"out{suffix}"))
    assert "holds regime 'bogus_regime', which no run gives" in line


def test_a_nan_on_an_axis_is_named_as_such(tmp_path):
    """A NaN m* was reported as "axis 'm_star' holds values <= 0 (0.01)", the smallest of the
    other values."""
    bad = two_load_table()
    bad = bad[bad["particle.load"] == 0.0].drop(columns="particle.load")
    bad.loc[bad.index[0], "m_star"] = float("nan")
    path = tmp_path / "nan.parquet"
    bad.to_parquet(path)
    line = _one_error_line(run_main("compare", path, "--models", "mmd,material_point", "-o",
                                    tmp_path / "c.png"))
    assert "axis 'm_star' holds nan for some cells" in line and "<= 0" not in line
