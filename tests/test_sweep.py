"""Sweeps: executors agree, resume is lossless, and the material point's diagram is analytic."""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import pytest

import sawdrift as sd
from sawdrift.analytic import point_prediction
from sawdrift.errors import SceneError
from sawdrift.study.sweep import journal_path, parse_axis, run_cell


def _values(frame: pd.DataFrame) -> pd.DataFrame:
    return frame.drop(columns=["wall_time_s"]).reset_index(drop=True)


def test_parse_axis():
    assert np.allclose(parse_axis("1e-3:1e2:6"), [1e-3, 1e-2, 1e-1, 1, 10, 100], rtol=1e-12)
    assert np.allclose(parse_axis("0.1,0.2, 0.5"), [0.1, 0.2, 0.5])
    for bad in ["1:2", "a:b:3", "0:1:3", "1:10:0", "x,y", ""]:
        with pytest.raises(SceneError, match="m_star"):
            parse_axis(bad, "m_star")
    assert list(parse_axis("0.5:0.5:1")) == [0.5]  # one value: both ends are the same


@pytest.mark.parametrize(("spec", "words"), [
    ("0.1,,1", "empty value"), ("0.1,1,", "empty value"), (",0.1", "empty value"),
    ("0.1:1:1", "N >= 2"), ("log:0.1:1:1", "N >= 2"), ("lin:0.1:1:1", "N >= 2"),
])
def test_an_empty_item_or_a_range_of_one_value_is_refused(spec, words):
    """0.1,,1 swept 0.1 and 1 (the empty item dropped); 0.1:1:1 swept 0.1 alone although a
    range includes both ends. Both are one line naming the field, for --m-star as for --axis."""
    from sawdrift.study.axes import parse_values

    with pytest.raises(SceneError, match=words) as info:
        parse_values(spec, "material.mu")
    assert str(info.value).startswith(f"material.mu = {spec!r}") and "\n" not in str(info.value)
    if not spec.startswith(("lin", "log")):
        with pytest.raises(SceneError, match=words):
            parse_axis(spec, "m_star")


def test_a_sweep_says_how_many_cells_of_its_table_are_from_another_grid(tmp_path):
    table = tmp_path / "t.parquet"
    first = sd.sweep("material_point", "0.01,0.1", "0.1,1", base=BASE, table=table,
                     progress=False, workers=1)
    assert (first.attrs["table_cells"], first.attrs["other_cells"]) == (4, 0)
    other = sd.sweep("material_point", "1", "0.1,1", base=BASE, table=table, progress=False,
                     workers=1)
    assert len(other) == 2 and (other.attrs["table_cells"], other.attrs["other_cells"]) == (6, 4)
    assert len(pd.read_parquet(table)) == 6


BASE = sd.Scene(model="mmd", numerics={"periods": 20})


@pytest.mark.slow
def test_serial_processes_and_dask_agree():
    kwargs = dict(base=BASE, progress=False)
    serial = sd.sweep("mmd,material_point", "0.01:1:3", "0.05:0.5:3", workers=1, **kwargs)
    procs = sd.sweep("mmd,material_point", "0.01:1:3", "0.05:0.5:3", workers=2, **kwargs)
    from distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cl:
        dask = sd.sweep("mmd,material_point", "0.01:1:3", "0.05:0.5:3", scheduler=cl, **kwargs)
    assert len(serial) == 18
    pd.testing.assert_frame_equal(_values(serial), _values(procs))
    pd.testing.assert_frame_equal(_values(serial), _values(dask))


def test_resume_computes_only_missing_cells(tmp_path):
    table = tmp_path / "t.parquet"
    first = sd.sweep("material_point", "0.01,0.1", "0.1,1", base=BASE, table=table, progress=False,
                     workers=1)
    computed = []
    again = sd.sweep("material_point", "0.01,0.1,1", "0.1,1", base=BASE, table=table, progress=False,
                     workers=1, on_row=computed.append)
    assert len(first) == 4 and len(again) == 6
    assert len(computed) == 2 and {r["m_star"] for r in computed} == {1.0}
    assert not journal_path(table).exists()


def test_error_in_one_cell_is_recorded_and_the_sweep_goes_on(tmp_path):
    # m* so small that the fixed step is far too coarse: AB4 blows up in that cell only
    base = sd.Scene(model="mmd", numerics={"periods": 20, "steps_per_period": 8, "order": 4})
    frame = sd.sweep("mmd", "1e-4,1", "0.1", base=base, table=tmp_path / "t.parquet",
                     progress=False, workers=1)
    bad = frame[frame.m_star == 1e-4].iloc[0]
    good = frame[frame.m_star == 1].iloc[0]
    assert bad.regime == "error" and "non-finite state" in bad.error
    assert pd.isna(good.error) and good.regime in sd.REGIMES


@pytest.mark.slow
@pytest.mark.skipif(sys.platform == "win32", reason="kill -9")
def test_kill_9_then_resume_equals_uninterrupted(tmp_path):
    args = ["sweep", "--model", "mmd", "--m-star", "0.01:1:6", "--amplitude", "0.05:0.8:6",
            "--periods", "400", "--workers", "1", "--no-progress"]
    table = tmp_path / "killed.parquet"
    proc = subprocess.Popen([sys.executable, "-m", "sawdrift", *args, "-o", str(table)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    journal = journal_path(table)
    deadline = time.time() + 120
    while time.time() < deadline:
        if journal.exists() and len(journal.read_text().splitlines()) >= 13:  # header + 12 rows
            break
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    lines = [json.loads(line) for line in journal.read_text().splitlines() if line.endswith("}")]
    before = [rec["cell_id"] for rec in lines if "cell_id" in rec]
    assert 12 <= len(before) < 36, "the kill must land halfway"
    assert not table.exists()
    subprocess.run([sys.executable, "-m", "sawdrift", *args, "-o", str(table)], check=True,
                   capture_output=True, timeout=600)
    resumed = pd.read_parquet(table)
    assert resumed["cell_id"].is_unique and len(resumed) == 36
    clean = tmp_path / "clean.parquet"
    subprocess.run([sys.executable, "-m", "sawdrift", *args, "-o", str(clean)], check=True,
                   capture_output=True, timeout=600)
    pd.testing.assert_frame_equal(_values(resumed), _values(pd.read_parquet(clean)))


# -- the material point's phase diagram against the analytic thresholds ----------------------

MU = 0.1


def _regime_class(regime: str) -> str:
    return "lost" if regime in sd.regimes.CONTACT_LOST else regime


def test_material_point_diagram_matches_analytic_thresholds():
    """Away from the analytic boundaries every cell of the 21 x 21 map has the predicted regime.

    Fixed runs of 20 periods (``settle = false``): the classes compared are stick, drift_against
    and contact lost, which the first 20 periods decide. Settling (the default) ran the heavy
    bouncing cells (m* >= 3) on to 5e4 periods: all 441 cells had the same class either way,
    measured, for 57 s of CPU against 4 s.
    """
    n = 21
    fixed = sd.Scene(numerics={"periods": 20, "settle": False})
    frame = sd.sweep("material_point", f"1e-3:1e2:{n}", f"1e-2:10:{n}", base=fixed, progress=False,
                     workers=1)
    r = sd.rayleigh_ratio(0.3)
    masses = np.sort(frame.m_star.unique())
    amps = np.sort(frame.amplitude.unique())
    got = {(m, a): _regime_class(g) for m, a, g in zip(frame.m_star, frame.amplitude, frame.regime,
                                                        strict=True)}
    pred = {}
    for m in masses:
        for a in amps:
            gz = 4 * math.pi**2 * m * a
            pred[(m, a)] = point_prediction(gz, r * gz)
    checked = 0
    for i, m in enumerate(masses):
        for j, a in enumerate(amps):
            neigh = {pred[(masses[i2], amps[j2])] for i2 in range(max(0, i - 1), min(n, i + 2))
                     for j2 in range(max(0, j - 1), min(n, j + 2))}
            if len(neigh) > 1:
                continue  # adjacent to a boundary
            checked += 1
            assert got[(m, a)] == pred[(m, a)], (m, a, got[(m, a)], pred[(m, a)])
    assert checked > 300
    assert "drift_with" not in set(frame.regime)


def test_mmd_diagram_shows_all_four_regimes():
    """The light half of the map (m* 1e-3 to 1, 7 x 11 cells, default numerics: 1.9 s) holds
    all four among its settled cells (fixed points, periodic orbits and settled drifts of
    motions that do not repeat; measured 35 stick, 10
    drift_with, 5 drift_against, 7 lost). The fixed 20-period runs this used were mostly still
    on their approach (settled in 17 of 121 cells)."""
    frame = sd.sweep("mmd", "1e-3:1:7", "1e-2:10:11", base=sd.Scene(model="mmd"),
                     progress=False)
    steady = frame[frame["resolved_as"].isin(["fixed_point", "periodic_orbit", "quasi_periodic"])]
    found = {_regime_class(g) for g in steady.regime}
    assert {"stick", "drift_with", "drift_against", "lost"} <= found


def test_a_settled_hop_that_does_not_repeat_is_not_called_an_orbit_or_a_fixed_point():
    """mmd m* 0.178, A* 2.51 hops once a period at a drift its windows agree on, but its
    stroboscopic state stays about 0.02 (scaled) from repeating: the undamped contact
    oscillation beats against the hop. Its drift is settled, its motion is neither a fixed point
    nor a periodic orbit (``resolved_as`` called it a fixed point); the bouncing ball at
    Gamma = 4 pi^2 m* A* = 3.6, below its period doubling, repeats after one period to 1e-8 and
    is a periodic orbit."""
    scenes = [sd.Scene(model="mmd", particle={"m_star": 0.178}, drive={"amplitude": 2.51}),
              sd.Scene(model="material_point", particle={"m_star": 0.025330295910584444},
                       drive={"amplitude": 3.6, "horizontal_ratio": 0.0})]
    rows = [run_cell(s.model_dump_json()) for s in scenes]
    beat, ball = rows
    assert beat["settled"] and beat["contact_lost"] and beat["orbit_period"] == 0
    assert beat["periodicity"] > 1e-3  # far from repeating, not on its way to an orbit
    assert beat["resolved_as"] == "quasi_periodic"
    assert ball["settled"] and ball["orbit_period"] == 1 and ball["periodicity"] < 1e-8
    assert ball["resolved_as"] == "periodic_orbit"


def test_sweep_table_says_which_cells_have_settled(tmp_path):
    """m* = 100, A* = 0.3 is still on its approach after 60 fixed periods (drift 0.006 against a
    steady 0.19); the table says so, a settled sweep reaches it (so does the default, which
    settles a heavy cell), and the drift map draws the unsettled cells. m* = 0.1, A* = 0.5 has
    settled in its 60 periods (its window's thirds within 1e-3 relative)."""
    fixed = sd.Scene(model="mmd", numerics={"settle": False})
    table = sd.sweep("mmd", "0.1,100", "0.3,0.5", base=fixed, progress=False,
                     workers=1, table=tmp_path / "plain.parquet")
    plain = table[table.amplitude == 0.3]
    settled = sd.sweep("mmd", "0.1,100", "0.3",
                       base=sd.Scene(model="mmd", numerics={"settle": True, "max_periods": 1e5}),
                       progress=False, workers=1)
    by_m = {r.m_star: r for r in plain.itertuples()}
    light = table[(table.amplitude == 0.5) & (table.m_star == 0.1)].iloc[0]
    assert bool(light.settled) and not bool(by_m[100.0].settled)
    assert by_m[100.0].settle_periods == 60.0
    heavy = settled[settled.m_star == 100.0].iloc[0]
    assert bool(heavy.settled) and heavy.drift_ratio > 0.15 > 0.01 > by_m[100.0].drift_ratio
    default = sd.sweep("mmd", "100", "0.3", base=sd.Scene(model="mmd"), progress=False, workers=1)
    assert bool(default.settled.iloc[0]) and default.drift_ratio.iloc[0] > 0.15
    png = sd.plot_drift_map(pd.read_parquet(tmp_path / "plain.parquet"), tmp_path / "d.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_sweep_rows_carry_events_dropped_as_the_run_reports_it(tmp_path):
    """Every row has ``events_dropped``, an integer equal to what the run of that scene reports."""
    base = sd.Scene(model="mmd", numerics={"periods": 20})
    frame = sd.sweep("mmd", "0.1,3", "0.1,1.2", base=base, table=tmp_path / "t.parquet",
                     workers=1, progress=False)
    stored = pd.read_parquet(tmp_path / "t.parquet")
    assert stored["events_dropped"].dtype.kind == "i" and len(stored) == 4
    for row in frame.itertuples():
        scene = sd.Scene(model="mmd", particle={"m_star": row.m_star},
                         drive={"amplitude": row.amplitude}, numerics={"periods": 20})
        result = sd.run(scene)
        want = getattr(result, "events_dropped", result.extra.get("events_dropped", 0))
        assert row.events_dropped == want and isinstance(row.events_dropped, int | np.integer)


def test_a_dask_client_is_accepted_as_the_scheduler_and_left_open():
    """The docstring promises an address, a cluster or a Client; Client(Client) raised TypeError.

    What is checked is the scheduler argument, so the cluster's one worker is a thread of this
    process (processes=False); worker processes are tested by the slow
    test_serial_processes_and_dask_agree. Alone: 5.6 s with a worker process, 1.7 s without."""
    from distributed import Client, LocalCluster

    kwargs = dict(base=BASE, progress=False)
    serial = sd.sweep("material_point", "0.01:1:3", "0.05:0.5:2", workers=1, **kwargs)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cl, Client(cl) as client:
        got = sd.sweep("material_point", "0.01:1:3", "0.05:0.5:2", scheduler=client, **kwargs)
        assert client.status == "running"
    pd.testing.assert_frame_equal(_values(serial), _values(got))


def test_table_rows_read_back_as_pandas_gives_them(tmp_path):
    """The rows read back from a table (column by column) equal pandas' own records with every
    missing value None and numpy scalars as Python values, over every dtype of the table:
    strings with missing values, floats with NaN, ints, bools, objects."""
    import numpy as np

    from sawdrift.study.table import _records

    table = tmp_path / "t.parquet"
    sd.sweep("mmd", "0.01,3", "0.05,2", base=sd.Scene(numerics={"periods": 10, "settle": False}),
             table=table, progress=False, workers=1)
    frame = pd.read_parquet(table)
    assert frame.isna().any().any()  # missing values to convert

    def plain(v):
        if v is None or v is pd.NA:
            return None
        if isinstance(v, np.generic):
            v = v.item()
        return None if isinstance(v, float) and v != v else v

    expected = [{k: plain(v) for k, v in rec.items()} for rec in frame.to_dict("records")]
    got = _records(frame)
    assert [[(type(v), repr(v)) for v in r.values()] for r in got] == \
        [[(type(v), repr(v)) for v in r.values()] for r in expected]



def test_a_resumed_sweep_says_how_many_of_its_cells_it_still_runs(tmp_path, capsys):
    """The size printed before a sweep is the whole grid's; a sweep resumed into a table that
    already holds some of its cells said nothing of them until its bar started part-way."""
    import sawdrift as sd

    table = tmp_path / "t.parquet"
    base = sd.Scene(model="mmd", numerics={"periods": 12})
    sd.sweep("mmd", "0.1:1:2", "0.1:1:2", base=base, table=table, progress=False)
    capsys.readouterr()
    sd.sweep("mmd", "0.1:1:3", "0.1:1:2", base=base, table=table, progress=True, size=True)
    err = capsys.readouterr().err
    assert "4 of the 6 cells already in t.parquet, 2 to run" in err
    # and the size it prints (and the 1 h gate reads) is of the 2 cells it runs, not the 6
    (size,) = [line for line in err.splitlines() if line.startswith("sweep: ") and "steps" in line]
    assert size.startswith("sweep: 2 cells, ")


def test_parse_axis_takes_lin_and_log_ranges_as_the_other_axes_do():
    """``lin:START:STOP:N`` was refused for m* and A* ("must be START:STOP:N (N log-spaced
    values)") while ``axes={'material.mu': 'lin:...'}`` took it; its error now lists the forms."""
    assert parse_axis("lin:0:1:3").tolist() == [0.0, 0.5, 1.0]
    assert parse_axis("lin:0.1:1:3", "m_star").tolist() == [0.1, 0.55, 1.0]
    assert np.allclose(parse_axis("log:1:100:3"), [1.0, 10.0, 100.0], rtol=1e-12)
    with pytest.raises(SceneError, match="> 0 for a log-spaced axis"):
        parse_axis("log:0:1:3", "m_star")
    with pytest.raises(SceneError) as info:
        parse_axis("1:2", "m_star")
    assert all(form in str(info.value) for form in ("START:STOP:N", "log:START:STOP:N",
                                                    "lin:START:STOP:N", "a,b,c"))
    fixed = sd.Scene(numerics={"periods": 2, "settle": False})
    frame = sd.sweep("mmd", "lin:0.1:1:3", "0.3", base=fixed, progress=False, workers=1)
    assert sorted(frame["m_star"]) == [0.1, 0.55, 1.0]
    with pytest.raises(SceneError, match="m_star"):  # the scene refuses m* = 0, in one line
        sd.sweep("mmd", "lin:0:1:3", "0.3", base=fixed, progress=False, workers=1)


def test_an_axis_added_to_a_table_reaches_the_cells_it_keeps(tmp_path):
    # the cells already in the table (mu = 0.1, the default) kept NaN for material.mu: the
    # mu = 0.1 half of the grid could not be selected, and export refused the table
    table = tmp_path / "t.parquet"
    base = sd.Scene(model="mmd", numerics={"settle": False, "periods": 10})
    sd.sweep("mmd", [0.01, 1.0], [0.1, 1.0], base=base, table=table, progress=False)
    frame = sd.sweep("mmd", [0.01, 1.0], [0.1, 1.0], axes={"material.mu": [0.1, 0.2]}, base=base,
                     table=table, progress=False)
    assert len(frame) == 8 and frame["material.mu"].notna().all()
    assert sorted(frame["material.mu"].value_counts().to_dict().items()) == [(0.1, 4), (0.2, 4)]


def test_a_cell_whose_model_fails_does_not_stop_the_size_estimate(tmp_path, sawdrift_main):
    # the calibration probe ran the grid's first cell, whose memory diagram overflows: the whole
    # sweep stopped with that error (exit 2, no table), while the same cells in another order
    # ran and tabled the failing ones as error rows
    out = tmp_path / "t.parquet"
    done = sawdrift_main("sweep", "--model", "mmd", "--param", "max_memory_points=16",
                         "--m-star", "1,2", "--amplitude", "0.1,1,2", "-o", str(out))
    assert done.returncode == 1, done.stderr  # the table written, two of its cells failed
    frame = pd.read_parquet(out)
    failed = frame[frame["error"].notna()]
    assert len(frame) == 6 and len(failed) == 2
    assert (failed["amplitude"] == 0.1).all() and failed["error"].str.contains("memory").all()


def test_a_failed_cell_names_its_version():
    """A failed row stored version None: a later refusal of other code read 'sawdrift None
    code ...'."""
    from sawdrift.study.sweep import run_cell

    scene = sd.Scene(model="mmd", model_params={"max_memory_points": 16},
                     particle={"m_star": 0.01}, drive={"amplitude": 5.0})
    row = run_cell(scene.model_dump_json())
    assert row["regime"] == "error" and row["version"] == sd.__version__


def test_an_interrupted_first_sweep_names_its_journal_not_a_missing_table(tmp_path, monkeypatch,
                                                                           capsys):
    """Ctrl-C in a new sweep: the finished cells are in the journal only; the line said they
    were kept in the table, which did not exist (phase-diagram and export then refused it)."""
    from .cli_call import call

    out = tmp_path / "im.parquet"
    real = sd.sweep

    def stop_after_two(*args, **kwargs):
        seen = []

        def on_row(row):
            seen.append(row)
            if len(seen) == 2:
                raise KeyboardInterrupt

        return real(*args, **kwargs, on_row=on_row)

    monkeypatch.setattr(sd, "sweep", stop_after_two)
    code, _, err = call(monkeypatch, capsys, "sweep", "--model", "material_point", "--m-star",
                        "0.01,0.1,1", "--amplitude", "0.1", "--periods", "10", "--workers", "1",
                        "--no-progress", "-o", str(out))
    assert code == 130 and not out.exists() and journal_path(out).exists()
    assert (f"interrupted: 2 finished cells are kept in {journal_path(out)} ({out} is written "
            "when the sweep completes)") in err


def test_a_period_cap_below_the_size_probe_does_not_refuse_the_sweep():
    """The size estimate probes each sampled cell with a fixed run of about 20000 steps (156
    periods at 128 a period) but kept the scene's cap: --max-periods 100 made every sweep fail
    with "max_periods = 100 is below periods = 156.25". A fixed run reads no cap."""
    base = sd.Scene(model="mmd", numerics={"settle": True, "max_periods": 100})
    frame = sd.sweep("mmd", "1,2", "0.1,0.2", base=base, progress=False, size=True)
    assert len(frame) == 4 and frame["error"].isna().all()
    fixed = sd.Scene(numerics={"settle": False, "periods": 200, "max_periods": 100})
    assert fixed.numerics.max_periods == 100  # the cap of a fixed run is not refused


@pytest.mark.parametrize("spec", ["0.1,0.1", "0.1:0.1:3", "0.2,0.1,0.2"])
def test_an_axis_that_repeats_a_value_is_refused(spec):
    """0.1,0.1 and 0.1:0.1:3 collapsed to one cell without a word (bifurcation refuses them)."""
    from sawdrift.study.sweep import parse_axis

    with pytest.raises(sd.SceneError, match=r"more than once: give each value once"):
        parse_axis(spec, "m_star")
    assert list(parse_axis("0.1:0.1:1", "m_star")) == [0.1]


def test_a_model_axis_keeps_the_files_parameters_for_their_model_only():
    """--axis model=mdr,mmd on a scene of mdr with strips = 64 stopped before any cell:
    'model_params.strips is not a known field (model mmd ...)'. A model axis is a list of
    models, as --model mdr,mmd is: the parameters stay with their model."""
    from sawdrift.study.sweep import grid

    base = sd.Scene(model="mdr", model_params={"strips": 64})
    scenes = grid(["mdr"], base=base, axes={"model": ["mdr", "mmd"]})
    by_model = {s.model: s for s in scenes}
    assert by_model["mdr"].model_params["strips"] == 64
    assert "strips" not in by_model["mmd"].model_params


def test_a_parameter_axis_of_a_model_named_apart_from_the_base_is_swept():
    """sweep('mdr', axes={'model_params.strips': '16,64'}) on a default (mmd) base: the model
    axis rule emptied the parameters after the axes were set, and every cell ran 256 strips."""
    from sawdrift.study.sweep import grid

    scenes = grid(["mdr"], [1.0], [0.5], base=sd.Scene(), axes={"model_params.strips": [16, 64]})
    assert sorted(s.model_params["strips"] for s in scenes) == [16, 64]
