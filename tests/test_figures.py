"""Figures that explain themselves (issue 37, items 6 and 7): creep and the contact resonances
marked, the drift map's outer cells whole, comparisons that keep model and rotation differences
apart, a bounded width, signed load curves, the trajectory figures' labels."""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
from matplotlib.collections import PathCollection
from PIL import Image

import sawdrift as sd

REGIMES = ["stick", "drift_with", "drift_against", "hopping"]


@pytest.fixture
def figures(monkeypatch):
    """The figures the plotting code closes, kept open to be inspected."""
    kept: list = []
    close = plt.close
    monkeypatch.setattr(plt, "close", lambda fig=None: kept.append(fig))
    yield kept
    close("all")


def _table(model: str = "mmd", n: int = 4, seed: int = 0, **columns) -> pd.DataFrame:
    """A synthetic n x n sweep table over A* in [1e-2, 10] and m* in [1e-2, 1] (a sphere)."""
    rng = np.random.default_rng(seed)
    amps, masses = np.geomspace(1e-2, 10, n), np.geomspace(1e-2, 1, n)
    rows = []
    for m in masses:
        for a in amps:
            regime = REGIMES[int(rng.integers(len(REGIMES)))]
            rows.append({"model": model, "amplitude": a, "m_star": m, "regime": regime,
                         "settled": True, "mu": 0.1, "nu": 0.3, "profile": "sphere",
                         "drift_ratio": float(rng.normal(0, 0.2)),
                         "gross_slip_fraction": float(rng.choice([0.0, 0.3]))})
    frame = pd.DataFrame(rows)
    for key, value in columns.items():
        frame[key] = value
    return frame


def _legend_texts(fig) -> list[str]:
    return [t.get_text() for leg in fig.legends for t in leg.get_texts()]


def _flat_lines(ax) -> list[float]:
    """y of every horizontal line of ``ax`` (axhline)."""
    return [float(ln.get_ydata()[0]) for ln in ax.get_lines()
            if len(set(np.asarray(ln.get_ydata(), float))) == 1 and len(ln.get_xdata()) == 2]


# -- item 6: creep cells and the contact resonances are marked --------------------------------


def test_phase_diagram_marks_creep_cells_and_both_contact_resonances(tmp_path, figures):
    table = _table()
    sd.plot_phase_diagram(table, tmp_path / "pd.png", "mmd")
    fig = figures[-1]
    ax = fig.axes[0]
    # creep: drifting (with or against) with no gross slip, counted here from the table itself
    creeping = table[table["regime"].isin(["drift_with", "drift_against"])
                     & (table["gross_slip_fraction"] == 0.0)]
    assert len(creeping) > 0
    (dots,) = [c for c in ax.collections if isinstance(c, PathCollection)]
    got = sorted(map(tuple, np.round(np.log10(dots.get_offsets()), 9)))
    want = sorted(zip(np.round(np.log10(creeping["amplitude"]), 9),
                      np.round(np.log10(creeping["m_star"]), 9), strict=True))
    assert got == want
    # the resonances of a Hertz contact, written out: omega^2 = 1.5 / m* (normal) and
    # 1.5 / (theta m*) (tangential) equal to (2 pi)^2, theta = (2 - nu) / (2 (1 - nu))
    theta = (2 - 0.3) / (2 * (1 - 0.3))
    normal, tangential = 1.5 / (4 * math.pi**2), 1.5 / (4 * math.pi**2 * theta)
    np.testing.assert_allclose(sorted(_flat_lines(ax)), sorted([tangential, normal]), rtol=1e-12)
    texts = _legend_texts(fig)
    assert "creep: drift with no gross slip" in texts
    assert "normal contact resonance, m* = 0.038" in texts
    assert "tangential contact resonance, m* = 0.031" in texts
    # every legend entry lies inside the saved figure
    renderer = fig.canvas.get_renderer()
    for leg in fig.legends:
        for t in leg.get_texts():
            bb = t.get_window_extent(renderer)
            assert fig.bbox.x0 <= bb.x0 and bb.x1 <= fig.bbox.x1, t.get_text()


def test_rigid_point_has_no_contact_resonance_and_a_creep_column_is_read(tmp_path, figures):
    sd.plot_phase_diagram(_table("material_point"), tmp_path / "mp.png", "material_point")
    assert _flat_lines(figures[-1].axes[0]) == []
    assert not any("resonance" in t for t in _legend_texts(figures[-1]))
    # a table's own creep column is what is marked (here: no cell creeps)
    sd.plot_phase_diagram(_table(creep=False), tmp_path / "nc.png", "mmd")
    assert not [c for c in figures[-1].axes[0].collections if isinstance(c, PathCollection)]
    assert "creep: drift with no gross slip" not in _legend_texts(figures[-1])


def test_turning_sphere_moves_the_tangential_resonance_by_one_plus_one_over_kappa(tmp_path,
                                                                                   figures):
    table = pd.concat([_table(**{"effects.rotation": False}), _table(**{"effects.rotation": True})])
    sd.plot_compare(table, ["mmd"], tmp_path / "rot.png", by="effects.rotation")
    off, on = figures[-1].axes[:2]
    theta = (2 - 0.3) / (2 * (1 - 0.3))
    tangential = 1.5 / (4 * math.pi**2 * theta)
    assert min(_flat_lines(off)) == pytest.approx(tangential, rel=1e-12)
    # a solid sphere (kappa = 2/5): the contact point is 1 + 1/kappa = 3.5 times lighter
    assert max(_flat_lines(on)) == pytest.approx(3.5 * tangential, rel=1e-12)
    # the legend tells the two dotted lines apart (two identical entries said only their m*)
    texts = [t for t in _legend_texts(figures[-1]) if "tangential" in t]
    assert any("(rolling sphere)" in t for t in texts)
    assert any("(rolling sphere)" not in t for t in texts)


# -- item 7: the drift map, the comparisons --------------------------------------------------


def test_drift_map_outer_cells_are_whole_and_grid_points_are_not_dotted(tmp_path, figures):
    table = _table(n=5)
    sd.plot_drift_map(table, tmp_path / "d.png", "mmd")
    fig = figures[-1]
    amps, masses = np.geomspace(1e-2, 10, 5), np.geomspace(1e-2, 1, 5)
    half_a, half_m = math.sqrt(amps[1] / amps[0]), math.sqrt(masses[1] / masses[0])
    for ax in fig.axes[:2]:
        # the outer cells reach half a cell beyond the outer points, like the inner ones
        np.testing.assert_allclose(ax.get_xlim(), [amps[0] / half_a, amps[-1] * half_a], rtol=1e-9)
        np.testing.assert_allclose(ax.get_ylim(), [masses[0] / half_m, masses[-1] * half_m],
                                   rtol=1e-9)
    assert not [ln for ln in fig.axes[0].get_lines() if ln.get_marker() in (",", ".")]
    assert "computed point" not in _legend_texts(fig)
    # a scattered (adaptive) table dots its computed points and says what the dots are
    scattered = pd.concat([table, table.iloc[[3]].assign(amplitude=0.05, m_star=0.05)])
    sd.plot_drift_map(scattered, tmp_path / "s.png", "mmd")
    assert "computed point" in _legend_texts(figures[-1])


def test_rotation_comparison_is_narrow_and_keeps_model_and_rotation_differences_apart(tmp_path,
                                                                                      figures):
    parts = [_table(m, n=5, seed=k, **{"effects.rotation": r})
             for k, (m, r) in enumerate([("material_point", False), ("material_point", True),
                                         ("mmd", False), ("mmd", True)])]
    table = pd.concat(parts)
    path, _ = sd.plot_compare(table, ["material_point", "mmd"], tmp_path / "rot.png",
                              by="effects.rotation")
    assert Image.open(path).size[0] <= 1500
    titles = [ax.get_title() for ax in figures[-1].axes]

    def differ(a: pd.DataFrame, b: pd.DataFrame) -> int:
        return int((a["regime"].to_numpy() != b["regime"].to_numpy()).sum())

    for model, off, on in (("material_point", parts[0], parts[1]), ("mmd", parts[2], parts[3])):
        assert (f"cells where rotation changes {model}'s regime\n({differ(off, on)} of 25 cells "
                "all computed)") in titles
    for value, a, b in ((False, parts[0], parts[2]), (True, parts[1], parts[3])):
        assert (f"cells where the models disagree, rotation = {value}\n({differ(a, b)} of 25 "
                "cells all computed)") in titles
    assert not any(t.startswith("cells where they disagree") for t in titles)


def test_model_comparison_wraps_to_a_bounded_width(tmp_path):
    table = pd.concat([_table(m, seed=k) for k, m in enumerate(["a", "b", "c", "d"])])
    path, md = sd.plot_compare(table, ["a", "b", "c", "d"], tmp_path / "four.png")
    assert Image.open(path).size[0] <= 1500
    assert md.count("\n") == 2 + 6  # header, rule, and the 6 pairs


# -- item 7: the paper's Fig. 2 ---------------------------------------------------------------


def test_fig2_drift_against_cell_settles():
    from sawdrift.report.fig2 import CELLS, fig2_scene

    (label, m, a), = [c for c in CELLS if c[0] == "drift against the wave"]
    res = sd.run(fig2_scene(m, a))
    assert res.regime == "drift_against" and res.settled is True
    assert res.drift_ratio < -0.1


def test_fig2_last_period_sits_beside_the_run_and_parameters_stay_off_the_curves(tmp_path,
                                                                                  figures):
    from sawdrift.report.fig2 import CELLS, plot_fig2

    cells = tuple(c for c in CELLS if c[0].startswith("drift"))
    plot_fig2(tmp_path / "fig2.png", cells=cells)
    fig = figures[-1]
    fig.canvas.draw()
    axes = fig.get_axes()
    mains = [ax for ax in axes if ax.get_xlabel().startswith("t* (wave")]
    assert len(mains) == len(cells) == 2
    for ax in mains:
        box = ax.get_window_extent()
        # no other axes (the last period's) covers any of the run, its last periods included
        for other in axes:
            if other is not ax:
                assert not box.overlaps(other.get_window_extent()), other.get_title()
        line = ax.get_lines()[0]
        t_end = line.get_xdata()[-1]
        assert ax.get_xlim()[1] >= t_end  # the run's end is inside the panel
        # the parameters are in the panel's heading, not in a legend over the curve
        assert ax.get_legend() is None and not ax.texts
    headings = [sub._suptitle.get_text() for sub in fig.subfigs]
    for (label, m, a), text in zip(cells, headings, strict=True):
        assert text.startswith(f"{label}: m* = {m:g}, A* = {a:g}") and "settled after" in text


# -- item 7: the default scene's trajectory figure ---------------------------------------------


def test_trajectory_figure_names_its_ramp_band_and_defines_v(tmp_path, figures):
    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316},
                          numerics={"periods": 20}), trajectory=True)
    sd.plot_trajectory(res, tmp_path / "t.png")
    fig = figures[-1]
    texts = _legend_texts(fig)
    assert f"wave ramp: the amplitude rises from 0 to A* over {res.ramp_periods:g} periods" in texts
    assert any(t.startswith("measuring window") for t in texts)
    # the grey band spans the ramp, t* in [0, ramp_periods], on every row
    for ax in fig.axes:
        spans = [(round(p.get_x(), 9), round(p.get_x() + p.get_width(), 9)) for p in ax.patches]
        assert (0.0, res.ramp_periods) in spans
    title = fig._suptitle.get_text()
    assert "V = <x*'> / (2 pi r A*)" in title and f"V = {res.drift_ratio:.3g}" in title


# -- item 7: load curves, one sign convention ---------------------------------------------------


def _curve(direction: int):
    from sawdrift.study.load_curve import LoadCurve

    loads = np.array([0.0, 0.02, 0.04, 0.06])
    speeds = np.array([0.30, 0.21, 0.10, -0.02])  # along the unloaded drift: it stalls near 0.06
    return LoadCurve(direction=direction, loads=loads, velocities=speeds,
                     regimes=("drift_against",) * 4, settled=(True,) * 4, stall_load=0.06,
                     stall_bracket=(0.04, 0.06), max_load=0.1, threshold=1e-3, m_star=10.0,
                     runs=4, wall_time_s=0.1)


@pytest.mark.parametrize("direction", [1, -1])
def test_single_and_multi_load_curves_draw_the_same_signed_speeds(tmp_path, direction):
    from sawdrift.report.load_curve_plot import plot_load_curve, plot_load_curves

    curve = _curve(direction)
    signed = direction * np.array([0.30, 0.21, 0.10, -0.02])  # along +x
    single = plot_load_curve(curve)
    multi = plot_load_curves([("slider", curve)])
    for fig in (single, multi):
        ax = fig.axes[0]
        np.testing.assert_allclose(ax.get_lines()[0].get_ydata(), signed, rtol=0, atol=0)
        assert "along +x" in ax.get_ylabel()
        lo, hi = ax.get_ylim()
        assert lo < min(signed) and max(signed) < hi  # every point is drawn
        plt.close(fig)
    # the power F v keeps its sign (positive while the particle advances against the load)
    power = single.axes[1].get_lines()[0].get_ydata()
    np.testing.assert_allclose(power, curve.loads * curve.velocities, rtol=1e-12)
    # both of the single figure's zeros at the same height
    (a0, a1), (b0, b1) = single.axes[0].get_ylim(), single.axes[1].get_ylim()
    assert -a0 / (a1 - a0) == pytest.approx(-b0 / (b1 - b0), rel=1e-12)


# -- item 7: the hatch means one thing --------------------------------------------------------


def test_the_hatch_means_not_settled_whatever_the_regime_under_it(tmp_path, figures):
    from sawdrift.report.demo import hatch_note
    from sawdrift.report.diagrams import HATCH_LABEL

    table = _table()
    table.loc[table["regime"] == "drift_against", "settled"] = False  # a slow approach
    sd.plot_phase_diagram(table, tmp_path / "h.png", "mmd")
    assert HATCH_LABEL in _legend_texts(figures[-1])
    note = hatch_note(3, 441)
    assert HATCH_LABEL in note and "bouncing" not in note and note.startswith("3 of 441")


# -- item 7: device axes -------------------------------------------------------------------------


def test_device_axis_tick_labels_do_not_overlap_and_carry_units(tmp_path, figures):
    amps, freqs = np.linspace(5e-9, 4e-8, 4), np.geomspace(5e6, 2e7, 5)
    rows = [{"model": "mmd", "device.amplitude": a, "device.frequency": f, "regime": "stick",
             "settled": True, "mu": 0.2, "nu": 0.25, "drift_ratio": 0.0, "m_star": 250.0,
             "amplitude": 0.5} for a in amps for f in freqs]
    table = pd.DataFrame(rows)
    for plot in (sd.plot_phase_diagram,):  # the drift map formats its axes with the same call
        plot(table, tmp_path / "dev.png", "mmd", x="device.amplitude", y="device.frequency")
        fig = figures[-1]
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        for axis, unit in ((fig.axes[0].xaxis, "m"), (fig.axes[0].yaxis, "Hz")):
            lo, hi = sorted(axis.get_view_interval())
            k = int(axis is fig.axes[0].yaxis)
            shown = [t for t in axis.get_majorticklabels() + axis.get_minorticklabels()
                     if t.get_visible() and t.get_text() and lo <= t.get_position()[k] <= hi]
            assert len(shown) >= 2
            assert all(t.get_text().endswith(unit) for t in shown)
            boxes = sorted((t.get_window_extent(renderer) for t in shown),
                           key=lambda b: (b.x0, b.y0))
            for a, b in zip(boxes, boxes[1:], strict=False):
                assert not a.overlaps(b), [t.get_text() for t in shown]


def test_explorer_circles_the_creep_cells(tmp_path):
    from bokeh.models import Scatter

    from sawdrift.report.explore import explorer_data
    from sawdrift.report.explore_page import build_document

    table = _table()
    table["cell_id"] = [f"c{k:015d}" for k in range(len(table))]
    data = explorer_data(table, traces={})
    doc = build_document(data)
    fig = doc.get_model_by_name("regimes-0")
    (dots,) = [r for r in fig.renderers if isinstance(r.glyph, Scatter)]
    src = data.sources[0]
    want = [i for i, (r, g) in enumerate(zip(data.panels[0].rows["regime"],
                                             data.panels[0].rows["gross_slip_fraction"],
                                             strict=True))
            if r in ("drift_with", "drift_against") and g == 0.0]
    assert sorted(dots.view.filter.indices) == want and len(want) > 0
    assert [src["creep"][i] for i in want] == ["yes"] * len(want)


def test_a_table_that_turns_without_a_rotation_column_is_read_from_its_spin(tmp_path, figures):
    # a sweep whose base scene turns has no effects.rotation column; its spin rate says it turns
    sd.plot_phase_diagram(_table(spin_rate=0.3), tmp_path / "spin.png", "mmd")
    theta = (2 - 0.3) / (2 * (1 - 0.3))
    lines = sorted(_flat_lines(figures[-1].axes[0]))
    assert lines == pytest.approx([1.5 / (4 * math.pi**2), 3.5 * 1.5 / (4 * math.pi**2 * theta)],
                                  rel=1e-12)


def test_fig2_names_a_long_time_mean_and_its_error():
    """A chaotic panel's drift is the long-time mean with its batch-means error, and its heading
    says so with that error (not 'the mean of its last window')."""
    import sawdrift as sd
    from sawdrift.report.fig2 import verdict

    res = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.01}, drive={"amplitude": 5.0},
                          numerics={"settle": True}))
    assert res.settled is False and res.drift_ratio_se > 0.0
    assert f"long-time mean +- {res.drift_ratio_se:.3f}" in verdict(res)


def test_a_sticking_drift_in_a_title_is_not_a_negative_zero():
    """The demo's stick panel read 'V = -0.000' for a drift ratio of -3e-7."""
    from sawdrift.report.fig2 import signed

    assert signed(-3.1e-7) == "-3.1e-07" and signed(0.709) == "+0.709"
    assert signed(-0.2553) == "-0.255" and "-0.000" not in signed(-4e-4)


def test_drift_map_titles_wrap_and_a_map_of_runaways_draws_without_warning(tmp_path, figures):
    """Two --where values made the panel titles run into each other and off the figure; a map
    whose every drift is NaN (all runaways) printed "All-NaN slice encountered"."""
    import warnings

    table = _table(n=4, **{"particle.load": 0.05, "effects.rotation": True})
    table["regime"], table["drift_ratio"] = "runaway", math.nan
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sd.plot_drift_map(table, tmp_path / "d.png", "mmd",
                          where={"particle.load": "0.05", "effects.rotation": "true"})
    fig = figures[-1]
    titles = [ax.get_title() for ax in fig.axes[:2]]
    assert all("particle.load = 0.05" in t.replace("\n", " ") for t in titles)
    assert max(len(line) for t in titles for line in t.split("\n")) <= 60
