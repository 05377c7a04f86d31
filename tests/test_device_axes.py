"""Device studies in SI units: axis ranges with units (issue 37, item 2)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from sawdrift.cli import main
from sawdrift.errors import SceneError
from sawdrift.study.axes import parse_values

MOTOR = Path(__file__).resolve().parents[1] / "examples" / "saw_linear_motor.toml"


def test_ranges_with_units_are_in_si():
    # log-spaced: the geometric mean of 2 and 30 MHz in the middle
    assert parse_values("2 MHz:30 MHz:3", "device.frequency") == pytest.approx(
        [2e6, math.sqrt(2e6 * 30e6), 30e6], rel=1e-12)
    assert parse_values("log:2 MHz:30000 kHz:3", "device.frequency") == pytest.approx(
        [2e6, math.sqrt(2e6 * 30e6), 30e6], rel=1e-12)
    assert parse_values("lin:10 nm:30 nm:3", "device.amplitude") == [1e-8, 2e-8, 3e-8]
    assert parse_values("lin:-5 deg:5 deg:3", "device.incline") == pytest.approx(
        np.radians([-5.0, 0.0, 5.0]).tolist(), rel=1e-11)
    assert parse_values("1e-3:1e2:3", "particle.m_star") == pytest.approx([1e-3, 10**-0.5, 1e2])


@pytest.mark.parametrize(("spec", "words"), [
    ("device.frequency=2 MHz:30 nm:15", ("device.frequency", "'30 nm'", "frequency")),
    ("device.frequency=2:30 MHz:15", ("device.frequency", "both ends")),
    ("device.amplitude=lin:10 nm:30 nm", ("device.amplitude", "lin:START:STOP:N")),
    ("material.mu=0.1 nm:0.2 nm:3", ("material.mu", "no units")),
])
def test_a_bad_range_is_one_line_naming_the_field(spec, words, monkeypatch, capsys, tmp_path):
    monkeypatch.setattr(sys, "argv", ["sawdrift", "sweep", str(MOTOR), "--axis", spec,
                                      "-o", str(tmp_path / "t.parquet")])
    with pytest.raises(SystemExit) as exc:
        main()
    lines = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(lines) == 1 and lines[0].startswith("error: "), lines
    assert all(w in lines[0] for w in words), lines[0]


def test_units_on_a_normalized_field_are_refused():
    with pytest.raises(SceneError, match="drive.amplitude"):
        parse_values("lin:1 nm:2 nm:2", "drive.amplitude")


# -- item 3: SI columns ----------------------------------------------------------------------

QUICK = {"numerics.settle": False, "numerics.periods": 4, "numerics.steps_per_period": 64}


def _motor(**updates):
    import sawdrift as sd

    return sd.Scene.from_toml(MOTOR).with_updates(**QUICK, **updates)


def _hertz_a0(radius: float = 0.5e-3, preload: float = 7.35e-3) -> float:
    e_star = 1.0 / ((1 - 0.3**2) / 210e9 + (1 - 0.25**2) / 170e9)
    weight = 7850.0 * 4.0 / 3.0 * math.pi * radius**3 * 9.81 + preload
    return (9.0 * weight**2 / (16.0 * radius * e_star**2)) ** (1.0 / 3.0)


@pytest.fixture(scope="module")
def device_table(tmp_path_factory):
    import sawdrift as sd

    path = tmp_path_factory.mktemp("si") / "t.parquet"
    sd.sweep(["mmd"], axes={"device.amplitude": "lin:10 nm:20 nm:2",
                            "device.load": "0 mN,-0.1 mN"},
             base=_motor(), table=path, workers=1, progress=False)
    return path


def test_device_tables_carry_si_columns_with_units(device_table):
    import pandas as pd

    from sawdrift.study.table import table_metadata

    frame = pd.read_parquet(device_table)
    a0 = _hertz_a0()
    assert frame["a0_m"].to_numpy() == pytest.approx(a0, rel=1e-9)
    # a normalized speed x*' is x*' a0 f in m/s
    assert frame["drift_speed_m_s"].to_numpy() == pytest.approx(
        frame["drift_velocity"].to_numpy() * a0 * 9.6e6, rel=1e-12)
    assert sorted(set(frame["device.amplitude"])) == pytest.approx([1e-8, 2e-8], rel=1e-12)
    assert sorted(set(frame["load_N"])) == pytest.approx([-1e-4, 0.0], abs=1e-15)
    units = table_metadata(device_table)["units"]
    assert units == {"device.amplitude": "m", "device.load": "N", "drift_speed_m_s": "m/s",
                     "a0_m": "m", "load_N": "N", "drift_speed_se_m_s": "m/s",
                     "detach_time_s": "s"}


def test_export_and_figures_label_device_axes_with_units(device_table, tmp_path, monkeypatch):
    import matplotlib.pyplot as plt
    import pandas as pd

    import sawdrift as sd

    ds = sd.write_grid(device_table, tmp_path / "g.nc")
    assert set(ds.sizes) == {"device.amplitude", "device.load"}
    assert ds["device.amplitude"].attrs["units"] == "m"
    assert ds["drift_speed_m_s"].attrs["units"] == "m/s"
    # A* = A_y / a0: a coordinate over the amplitude alone, not a third dimension
    assert ds["amplitude"].dims == ("device.amplitude",)
    assert ds["amplitude"].to_numpy() == pytest.approx(np.array([1e-8, 2e-8]) / _hertz_a0(),
                                                      rel=1e-9)
    kept = []
    monkeypatch.setattr(plt, "close", lambda fig=None: kept.append(fig))
    frame = pd.read_parquet(device_table)
    frame = frame[frame["device.load"] < 0].assign(**{"device.load": -1e-4})
    two = pd.concat([frame.assign(**{"device.preload": 7.35e-3}),
                     frame.assign(**{"device.preload": 8e-3})], ignore_index=True)
    sd.plot_phase_diagram(two, tmp_path / "p.png", x="device.amplitude", y="device.preload")
    ax = kept[-1].axes[0]
    assert ax.get_xlabel() == "device.amplitude (m)" and ax.get_ylabel() == "device.preload (N)"


# -- item 4: one-dimensional studies -------------------------------------------------------


@pytest.fixture(scope="module")
def frequency_table(tmp_path_factory):
    import sawdrift as sd

    path = tmp_path_factory.mktemp("one") / "f.parquet"
    sd.sweep(["mmd"], axes={"device.frequency": "5 MHz:20 MHz:3"}, base=_motor(), table=path,
             workers=1, progress=False)
    return path


def test_export_of_a_one_field_sweep_has_one_dimension(frequency_table, tmp_path):
    import sawdrift as sd

    ds = sd.write_grid(frequency_table, tmp_path / "g.nc")
    assert dict(ds.sizes) == {"device.frequency": 3}
    # m* = a0 m f^2 / (M g) with a0 independent of f: a coordinate growing as f^2
    f = ds["device.frequency"].to_numpy()
    assert f == pytest.approx([5e6, 1e7, 2e7], rel=1e-11)
    m = ds["m_star"].to_numpy()
    assert ds["m_star"].dims == ("device.frequency",)
    assert m / m[0] == pytest.approx((f / f[0]) ** 2, rel=1e-12)
    # A* does not change with f: no dimension, a scalar coordinate (its one value)
    assert "amplitude" not in ds.dims and ds["amplitude"].ndim == 0


def test_phase_diagram_of_a_one_field_sweep_is_a_line_plot(frequency_table, tmp_path, monkeypatch):
    import matplotlib.pyplot as plt
    import pandas as pd
    from matplotlib.collections import QuadMesh
    from matplotlib.colors import to_hex

    import sawdrift as sd
    from sawdrift.report.diagrams import COLOURS

    kept = []
    monkeypatch.setattr(plt, "close", lambda fig=None: kept.append(fig))
    frame = pd.read_parquet(frequency_table)
    settled = frame.index == 0  # one settled cell, two still on their approach
    frame = frame.assign(settled=settled)
    sd.plot_phase_diagram(frame, tmp_path / "p.png")
    ax = kept[-1].axes[0]
    assert not any(isinstance(c, QuadMesh) for c in ax.collections)  # no 2-D rectangle
    dots = [ln for ln in ax.lines if ln.get_marker() == "o"]
    assert len(dots) == len(frame) == 3
    by_x = {float(d.get_xdata()[0]): d for d in dots}
    for row in frame.itertuples():
        dot = by_x[float(frame.loc[row.Index, "device.frequency"])]
        colour = to_hex(COLOURS[row.regime])
        assert float(dot.get_ydata()[0]) == pytest.approx(row.drift_speed_m_s)
        if row.settled:
            assert to_hex(dot.get_markerfacecolor()) == colour
        else:  # open: white face, the regime's colour around it
            assert to_hex(dot.get_markerfacecolor()) == "#ffffff"
            assert to_hex(dot.get_markeredgecolor()) == colour
    # the ticks carry the prefixed unit (8 MHz, -50 mm/s): the labels name the quantity, with no
    # unit that would disagree with them ("(Hz)" over "8 MHz")
    assert ax.get_xlabel() == "device.frequency" and ax.get_ylabel() == "drift speed"
    assert ax.xaxis.get_major_formatter()(8e6) == "8 MHz"
    assert ax.yaxis.get_major_formatter()(-0.05).endswith("50 mm/s")


def test_a_one_field_sweep_prints_its_points_and_draws_them(monkeypatch, capsys, tmp_path):
    out = tmp_path / "amp.parquet"
    monkeypatch.setattr(sys, "argv", ["sawdrift", "sweep", str(MOTOR), "--axis",
                                      "device.amplitude=10 nm,20 nm", "--no-settle", "--periods",
                                      "4", "--steps-per-period", "64", "--workers", "1",
                                      "--no-progress", "-o", str(out)])
    with pytest.raises(SystemExit) as exc:
        main()
    text = capsys.readouterr().out
    assert exc.value.code == 0
    assert (tmp_path / "amp.png").stat().st_size > 10_000
    # the amplitudes are printed with their prefix (20 nm), so the header gives no "(m)"; the
    # speeds are bare numbers in m/s, which their header names
    header = next(line for line in text.splitlines() if line.strip().startswith("model "))
    assert header.split()[:3] == ["model", "device.amplitude", "drift"], header
    assert "(m)" not in header and header.rstrip().endswith("drift speed (m/s)  regime")
    assert "20 nm" in text and "(line plot)" in text


def test_a_line_plot_with_an_ejected_cell_spans_the_sweep_without_a_warning(tmp_path):
    """A sweep of the amplitude where the larger one throws the particle off: its cell has no
    drift (ejected), is counted apart from failures, and the axis spans both amplitudes (one
    drawn point on a log axis warned of a zero-width axis)."""
    import warnings

    import matplotlib.pyplot as plt
    import pandas as pd

    from sawdrift.report.diagrams import COLOURS
    from sawdrift.report.line_plot import plot_line

    table = pd.DataFrame({"model": ["mmd", "mmd"], "device.amplitude": [1e-11, 1e-9],
                          "drift_speed_m_s": [-6.6e-4, np.nan], "drift_ratio": [-0.3, np.nan],
                          "regime": ["bouncing", "ejected"], "settled": [True, False]})
    grabbed = {}
    close = plt.close
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            plt.close = lambda fig: grabbed.setdefault("fig", fig)
            plot_line(table, tmp_path / "line.png", field="device.amplitude", colours=COLOURS)
        finally:
            plt.close = close
    ax = grabbed["fig"].axes[0]
    lo, hi = ax.get_xlim()
    assert lo < 1e-11 and hi > 1e-9 and ax.get_xscale() == "log"
    title = ax.get_title()
    assert "1 without a drift" in title and "failed" not in title
    close(grabbed["fig"])


def test_a_long_time_mean_gets_its_error_in_the_line_plot_and_its_rows(tmp_path):
    """A cell whose drift is a long-time mean is drawn with its standard error as a bar and
    printed as drift +- error (a speed's error scaled from the drift ratio's)."""
    import matplotlib.pyplot as plt
    import pandas as pd

    from sawdrift.report.diagrams import COLOURS
    from sawdrift.report.line_plot import line_rows, plot_line

    table = pd.DataFrame({"model": ["mmd", "mmd"], "amplitude": [0.5, 1.0],
                          "drift_ratio": [0.5157, -0.0085], "drift_ratio_se": [np.nan, 0.092],
                          "drift_speed_m_s": [0.2, -0.004],
                          "regime": ["drift_with", "bouncing"], "settled": [True, False]})
    rows = line_rows(table, "amplitude", "drift_ratio")
    assert "long-time mean +- 0.092" in rows[2] and "+-" not in rows[1]
    speed = line_rows(table, "amplitude", "drift_speed_m_s")
    assert f"long-time mean +- {0.004 / 0.0085 * 0.092:.2g}" in speed[2]
    grabbed = {}
    close = plt.close
    try:
        plt.close = lambda fig: grabbed.setdefault("fig", fig)
        plot_line(table, tmp_path / "line.png", field="amplitude", value="drift_ratio",
                  colours=COLOURS)
    finally:
        plt.close = close
    ax = grabbed["fig"].axes[0]
    bars = [c for c in ax.containers if c.__class__.__name__ == "ErrorbarContainer"]
    assert len(bars) == 1
    (segment,) = bars[0].lines[2][0].get_segments()
    assert np.allclose(segment[:, 1], [-0.0085 - 0.092, -0.0085 + 0.092])
    assert "bars: long-time mean" in ax.get_title()
    close(grabbed["fig"])


def test_a_device_swept_over_two_fields_prints_its_points_in_si(sawdrift_main, tmp_path):
    """Two device axes: the sweep printed no table and drew no line, so the SI units were lost
    from its output. Each cell's line holds both fields with their units and the speed in m/s,
    which is the drift velocity times a0 f of that cell."""
    import pandas as pd

    table = tmp_path / "two.parquet"
    out = sawdrift_main("sweep", str(MOTOR), "--axis", "device.frequency=5 MHz,10 MHz",
                        "--axis", "device.amplitude=10 nm,20 nm", "-o", str(table))
    assert out.returncode == 0, out.stderr
    rows = [line for line in out.stdout.splitlines() if " MHz " in line and " nm " in line]
    assert len(rows) == 4
    frame = pd.read_parquet(table)
    for line in rows:
        amp, freq = line.split()[1:3], line.split()[3:5]
        speed = float(line.split()[5])
        cell = frame[np.isclose(frame["device.amplitude"], float(amp[0]) * 1e-9, rtol=1e-9, atol=0)
                     & np.isclose(frame["device.frequency"], float(freq[0]) * 1e6, rtol=1e-9, atol=0)]
        assert len(cell) == 1
        assert speed == pytest.approx(float(cell["drift_speed_m_s"].iloc[0]), rel=1e-5)


@pytest.mark.parametrize("axis, words", [("device.orbit=prograde,retrograde",
                                          ["prograde", "retrograde"]),
                                         ("effects.rotation=false,true", ["False", "True"])])
def test_a_sweep_over_words_prints_and_draws_them(axis, words, monkeypatch, capsys, tmp_path):
    # the text formatted every swept value as a number and the plot converted it to float: a
    # sweep over the orbit's sense stopped after its cells with 'internal failure', exit 3
    out = tmp_path / "w.parquet"
    monkeypatch.setattr(sys, "argv", ["sawdrift", "sweep", str(MOTOR), "--axis", axis,
                                      "--no-settle", "--periods", "4", "--steps-per-period",
                                      "64", "--workers", "1", "--no-progress", "-o", str(out)])
    with pytest.raises(SystemExit) as exc:
        main()
    text = capsys.readouterr().out
    assert exc.value.code == 0
    rows = [line.split() for line in text.splitlines() if line.strip().startswith("mmd ")]
    assert sorted(r[1] for r in rows if r[1] in words) == words, text
    assert (tmp_path / "w.png").stat().st_size > 10_000 and "(line plot)" in text


def test_device_tables_give_a_long_time_means_error_and_a_detach_time_in_si(tmp_path):
    """`run --json` gave detach_time_s and a speed's error in m/s; a device sweep's table only
    the normalized detach_time and drift_ratio_se. An ejected silica sphere (0.5 nm at 20 MHz)
    leaves at t* = detach_time, detach_time / f seconds."""
    import sawdrift as sd
    from sawdrift.scene.device import normalized
    from sawdrift.study.axes import add_columns, device_columns

    silica = Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml"
    base = sd.Scene.from_toml(silica)
    table = sd.sweep(base.model, axes={"device.amplitude": ["0.5 nm"]}, base=base,
                     table=tmp_path / "t.parquet", progress=False)
    row = table.iloc[0]
    assert row["regime"] == "ejected"
    assert row["detach_time_s"] == pytest.approx(row["detach_time"] / 20e6, rel=1e-12)
    # a long-time mean's error: drift_ratio_se times the surface speed 2 pi r A*, times a0 f
    scene = sd.Scene.from_toml(silica)
    si, scale = device_columns(scene)
    cell = {"drift_velocity": -0.5, "drift_ratio_se": 0.01, "amplitude": 2.0,
            "horizontal_ratio": 0.6, "detach_time": float("nan")}
    add_columns(cell, {**si, "_speed_scale": scale})
    norm = normalized(scene.device)
    assert cell["drift_speed_se_m_s"] == pytest.approx(
        0.01 * 2 * math.pi * 0.6 * 2.0 * norm["a0_m"] * norm["frequency_hz"], rel=1e-12)
    assert cell["detach_time_s"] is None and "_frequency" not in cell


_DEVICE_FIELDS = ["device.frequency", "device.amplitude", "device.particle.radius",
                  "device.particle.youngs_modulus", "device.particle.density",
                  "device.particle.mass", "device.gravity", "device.preload",
                  "device.particle.half_angle", "device.load", "device.incline",
                  "device.wavelength", "device.adhesion"]


@pytest.mark.parametrize("name", _DEVICE_FIELDS)
def test_a_malformed_device_range_shows_an_example_with_units_that_parses(name):
    """'device.amplitude=5 nm:15' was answered with the example 1e-3:1e2:11, a bare number a
    device field reads in SI units (1e-3 m)."""
    from sawdrift.study.axes import parse_range

    with pytest.raises(SceneError, match="with units on both ends, e.g. ") as info:
        parse_range("5:15", name)
    example = str(info.value).rsplit("e.g. ", 1)[1]
    values = parse_range(example, name)
    assert values is not None and len(values) >= 3
