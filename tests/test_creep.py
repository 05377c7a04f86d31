"""Creep: a drift in permanent contact without gross slip, flagged on the Result and in tables."""

from __future__ import annotations

import pandas as pd
import pytest

import sawdrift as sd
from sawdrift.result.regimes import creep
from sawdrift.study.sweep import TABLE_COLUMNS, run_cell

#: a heavy sphere at a small amplitude (mu = 0.1, nu = 0.3), run to its steady drift
CELL = {"particle": {"m_star": 10.0}, "drive": {"amplitude": 0.05},
        "numerics": {"periods": 40, "settle": True}}


def _slip_events(result: sd.Result) -> int:
    kinds = result.events["kind"].astype(str)
    return int(kinds.isin(["slip_start", "slip_end"]).sum())


def test_incremental_spring_creeps_where_the_exact_law_sticks():
    dem = sd.run(sd.Scene(model="hertz_mindlin_dem", **CELL))
    exact = sd.run(sd.Scene(model="jaeger", **CELL))
    # the event log, read on its own, shows that neither contact ever slides as a whole
    assert _slip_events(dem) == 0 and _slip_events(exact) == 0
    assert not dem.contact_lost and not exact.contact_lost
    # yet the incremental spring drifts, at several times the drift tolerance (1e-3)
    assert dem.regime == "drift_with" and dem.drift_ratio > 3e-3
    assert dem.gross_slip_fraction == 0.0 and dem.creep is True
    # and the exact memory law sticks there: no drift, no creep
    assert exact.regime == "stick" and abs(exact.drift_ratio) < 1e-4
    assert exact.creep is False
    assert dem.summary()["creep"] is True and exact.summary()["creep"] is False


def test_sweep_rows_carry_gross_slip_and_creep():
    assert {"gross_slip_fraction", "creep"} <= set(TABLE_COLUMNS)
    row = run_cell(sd.Scene(model="hertz_mindlin_dem", **CELL).model_dump_json())
    assert row["regime"] == "drift_with"
    assert row["gross_slip_fraction"] == 0.0 and row["creep"] is True
    assert pd.DataFrame([row])["creep"].dtype == bool


@pytest.mark.parametrize("regime, slip, expect", [
    ("drift_with", 0.0, True), ("drift_against", 0.0, True), ("drift_with", 0.2, False),
    ("stick", 0.0, False), ("bouncing", 0.0, False), ("drift_with", float("nan"), False)])
def test_creep_is_drift_without_gross_slip(regime, slip, expect):
    assert creep(regime, slip) is expect


def test_run_text_and_export_carry_creep():
    """The run's text output names creep in its evidence, and an exported sweep keeps the flag."""
    from typer.testing import CliRunner

    from sawdrift.cli import app
    from sawdrift.study.export import VARIABLES

    out = CliRunner().invoke(app, ["run", "--model", "hertz_mindlin_dem", "--m-star", "10",
                                   "--amplitude", "0.05", "--settle"])
    assert out.exit_code == 0, out.output
    line = next(ln for ln in out.output.splitlines() if ln.strip().startswith("creep"))
    assert line.split()[-1] == "yes"
    assert "creep" in VARIABLES
