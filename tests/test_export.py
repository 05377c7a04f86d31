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
