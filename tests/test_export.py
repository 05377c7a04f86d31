"""Gridded export of sweep tables (xarray, netCDF with CF regime flags, provenance)."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

import sawdrift as sd
from sawdrift.result.regimes import REGIMES

from .cli_call import run_main


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    path = tmp_path_factory.mktemp("export") / "t.parquet"
    base = sd.Scene(numerics={"periods": 20})
    sd.sweep(["mmd"], "0.01,0.1,1", "0.1,0.3,1", base=base, table=path, workers=1, progress=False)
    return path


def test_export_of_a_3x3_sweep_has_the_axes_and_cf_flags(table, tmp_path):
    out = tmp_path / "grid.nc"
    run = run_main("export", table, "-o", out)  # in this process (tests/cli_call.py)
    assert run.returncode == 0, run.stderr
    ds = xr.open_dataset(out)
    assert set(ds.sizes) == {"m_star", "amplitude"} and dict(ds.sizes) == {"m_star": 3, "amplitude": 3}
    assert ds["regime"].dtype.kind == "i"
    flags = ds["regime"].attrs["flag_meanings"].split()
    assert flags[: len(REGIMES)] == list(REGIMES)
    assert list(ds["regime"].attrs["flag_values"]) == list(range(len(flags)))
    # each cell's regime code decodes to the table's regime
    frame = sd.load_grid(out).to_dataframe().reset_index()
    rows = __import__("pandas").read_parquet(table)
    for r in rows.itertuples():
        code = frame[(frame.m_star == r.m_star) & (frame.amplitude == r.amplitude)]["regime"].item()
        assert flags[code] == r.regime
        got = frame[(frame.m_star == r.m_star) & (frame.amplitude == r.amplitude)]["drift_ratio"]
        assert np.isclose(got.item(), r.drift_ratio)
        settled = frame[(frame.m_star == r.m_star) & (frame.amplitude == r.amplitude)]["settled"]
        assert settled.item() == float(r.settled)
    assert ds.attrs["sawdrift_version"] == sd.__version__
    assert json.loads(ds.attrs["base_scene"])["numerics"]["periods"] == 20


def test_export_refuses_a_bad_output_and_a_table_without_axes(table, tmp_path, sawdrift_main):
    bad = sawdrift_main("export", str(table), "-o", str(tmp_path / "g.csv"))  # in this process
    assert bad.returncode == 2 and "must end in .nc or .zarr" in bad.stderr
    one = tmp_path / "one.parquet"
    sd.sweep(["mmd"], "0.1", "0.3", base=sd.Scene(numerics={"periods": 10}), table=one, workers=1,
             progress=False)
    with pytest.raises(sd.SceneError, match="no swept field"):
        sd.to_dataset(__import__("pandas").read_parquet(one))


@pytest.fixture(scope="module")
def irregular_table(tmp_path_factory):
    """A default sweep with chaotic and irregular cells (long-time means with their errors and
    warnings) beside settled hopping ones."""
    path = tmp_path_factory.mktemp("export_irregular") / "t.parquet"
    sd.sweep(["mmd"], "0.0316,0.1,1", "1.28,3", table=path, workers=1, progress=False)
    return path


def test_export_carries_errors_resolution_warnings_chaos_and_orbits(irregular_table, tmp_path):
    """The netCDF grid used to drop drift_ratio_se, resolved_as, warnings, chaotic and
    orbit_period: a chaotic cell's mean lost its error bar and its caveats."""
    import pandas as pd

    rows = pd.read_parquet(irregular_table)
    # the facts the export must carry are there to carry: errors, warnings, chaos, settled cells
    assert rows["drift_ratio_se"].notna().any() and rows["drift_ratio_se"].isna().any()
    assert rows["warnings"].notna().any() and rows["chaotic"].any()
    out = tmp_path / "grid.nc"
    run = run_main("export", irregular_table, "-o", out)
    assert run.returncode == 0, run.stderr
    ds = sd.load_grid(out)
    assert ds["resolved_as"].dtype.kind == "U" and ds["warnings"].dtype.kind == "U"
    for r in rows.itertuples():
        cell = ds.sel(m_star=r.m_star, amplitude=r.amplitude)
        se = float(cell["drift_ratio_se"])
        assert (se == r.drift_ratio_se) if r.drift_ratio_se == r.drift_ratio_se else se != se
        assert str(cell["resolved_as"].item()) == r.resolved_as
        assert str(cell["warnings"].item()) == (r.warnings if isinstance(r.warnings, str) else "")
        assert float(cell["chaotic"]) == float(r.chaotic)
        assert int(cell["orbit_period"]) == r.orbit_period
    assert "standard error" in ds["drift_ratio_se"].attrs["long_name"]


def test_a_grid_point_without_a_cell_has_empty_text(irregular_table):
    import pandas as pd

    rows = pd.read_parquet(irregular_table)
    gone = rows.iloc[0]
    ds = sd.to_dataset(rows.drop(index=rows.index[0]))
    cell = ds.sel(m_star=gone.m_star, amplitude=gone.amplitude)
    assert str(cell["resolved_as"].item()) == "" and str(cell["warnings"].item()) == ""
    assert int(cell["regime"]) == -1 and float(cell["drift_ratio_se"]) != float(cell["drift_ratio_se"])


def test_fixed_scene_values_and_runaway_columns_reach_the_grid(tmp_path):
    # a line over A* at m* 0.5 wrote no m* at all, and base_scene (the scene the sweep started
    # from) said 0.1; mean_acceleration, a runaway's only number, was dropped
    table = tmp_path / "t.parquet"
    base = sd.Scene(model="mmd", particle={"m_star": 0.5, "load": 0.2},
                    numerics={"settle": False, "periods": 10})
    sd.sweep("mmd", [0.5], [0.1, 1.0], base=base, table=table, progress=False)
    from sawdrift.study.export import write_grid

    ds = write_grid(table, tmp_path / "g.nc")
    assert list(ds.sizes) == ["amplitude"]
    assert float(ds["m_star"]) == 0.5 and float(ds["mu"]) == 0.1
    assert "mean_acceleration" in ds and np.isfinite(ds["mean_acceleration"]).all()
    # m* 0.5 x'' = L - mu: a load of 0.2 above mu = 0.1 runs away at 0.2 per period squared
    assert np.allclose(ds["mean_acceleration"], (0.2 - 0.1) / 0.5, rtol=1e-6)


def test_a_table_extended_with_an_axis_exports_each_cell_at_its_own_point(tmp_path):
    """A 2 x 2 grid at mu = 0.1, then m* 0.01 over mu = 0.1, 0.5 into the same table: the first
    grid's m* = 1 cells had no material.mu (NaN), and the export put them at m* = 0.01,
    mu = 0.5 (0.2366 and -0.855 where that point's own cells are 0 and 0), m* no dimension."""
    table = tmp_path / "t.parquet"
    base = sd.Scene(model="material_point")
    sd.sweep("material_point", [0.01, 1.0], [0.1, 1.0], base=base, table=table, progress=False)
    sd.sweep("material_point", [0.01], [0.1, 1.0], base=base, table=table, progress=False,
             axes={"material.mu": [0.1, 0.5]})
    from sawdrift.study.export import write_grid

    ds = write_grid(table, tmp_path / "g.nc")
    assert set(ds["drift_ratio"].dims) == {"material.mu", "m_star", "amplitude"}
    import pandas as pd

    rows = pd.read_parquet(table)
    assert len(rows) == 6 and rows["material.mu"].notna().all()
    for _, row in rows.iterrows():
        point = ds["drift_ratio"].sel({"material.mu": row["material.mu"], "m_star": row["m_star"],
                                       "amplitude": row["amplitude"]})
        assert float(point) == pytest.approx(row["drift_ratio"], abs=1e-15)
    # m* = 1 at mu = 0.5 was never run: no cell there
    assert np.isnan(ds["drift_ratio"].sel({"material.mu": 0.5, "m_star": 1.0})).all()


def test_export_says_how_many_grid_points_hold_no_cell(table, tmp_path):
    """A table whose cells do not fill its grid (an adaptive map, two grids in one table) gave
    NaN at the empty points with nothing said but the file's regime comment."""
    import pandas as pd

    holes = tmp_path / "holes.parquet"
    rows = pd.read_parquet(table)
    rows.drop(index=rows.index[:2]).to_parquet(holes)
    run = run_main("export", holes, "-o", tmp_path / "holes.nc")
    assert run.returncode == 0, run.stderr
    assert "2 of 9 grid points hold no cell of the table" in run.stdout
    full = run_main("export", table, "-o", tmp_path / "full.nc")
    assert "hold no cell" not in full.stdout
