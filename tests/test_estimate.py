"""Size before time (issue 37, item 5): work estimated, printed and bounded before it starts."""

from __future__ import annotations

from pathlib import Path

import pytest

import sawdrift as sd
from sawdrift.study.estimate import MAX_SECONDS, Estimate, cell_steps, check

from .cli_call import call

MOTOR = Path(__file__).resolve().parents[1] / "examples" / "saw_linear_motor.toml"




def test_a_run_of_1e14_steps_is_refused_with_its_estimate(monkeypatch, capsys):
    code, _, err = call(monkeypatch, capsys, "run", "--steps-per-period", "1e7", "--periods", "1e7")
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, lines
    assert "about 1e+14 steps" in lines[0] and "--yes" in lines[0]
    assert "days" in lines[0]  # 1e14 steps at any rate below 1e9 steps/s


def test_a_long_run_says_its_size_unless_no_progress(monkeypatch, capsys):
    """A run above the quiet bound prints its size on stderr first; --no-progress leaves that
    line out, as the README says (run had no such option: "No such option: --no-progress")."""
    monkeypatch.setattr("sawdrift.study.estimate.QUIET_STEPS", 1e3)
    code, out, err = call(monkeypatch, capsys, "run", "--model", "mmd", "--json")
    assert code == 0 and "steps" in err, err
    code, out, err = call(monkeypatch, capsys, "run", "--model", "mmd", "--json", "--no-progress")
    assert code == 0 and err == "" and out.startswith("{"), err


def test_a_million_cell_sweep_is_refused_before_its_grid_is_built(monkeypatch, capsys, tmp_path):
    """The default 1000 x 1000 mmd sweep is estimated at about an hour on the 2-core machine (1 to
    1.3 h, with the calibration's rate): the bound is set to ten minutes here, so that a fast
    spell of the machine cannot start a million cells (it once did: 9 GB in each worker)."""
    import time

    from sawdrift.study import estimate

    monkeypatch.setattr(estimate, "MAX_SECONDS", 600.0)
    out = tmp_path / "t.parquet"
    t0 = time.perf_counter()
    code, _, err = call(monkeypatch, capsys, "sweep", "--model", "mmd", "--m-star", "1e-3:1e2:1000",
                        "--amplitude", "1e-2:10:1000", "-o", str(out))
    took = time.perf_counter() - t0
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, lines
    assert "1000000 cells" in lines[0] and "--yes" in lines[0]
    assert took < 10.0  # building the grid alone took 151 s
    assert not out.exists() and not list(tmp_path.iterdir())


def test_fixed_run_steps_are_periods_times_steps_per_period():
    scene = sd.bind(sd.Scene.from_toml(MOTOR).with_updates(
        **{"numerics.settle": False, "numerics.periods": 20, "numerics.steps_per_period": 96}))
    expected, most = cell_steps(scene)
    assert expected == most == 20 * 96
    assert sd.run(scene).steps == 20 * 96


def test_a_settling_run_is_estimated_within_a_factor_two():
    scene = sd.bind(sd.Scene.from_toml(MOTOR))  # m* = 929: settles over thousands of periods
    expected, most = cell_steps(scene)
    steps = sd.run(scene).steps
    assert 0.5 * steps <= expected <= 2.0 * steps, (expected, steps)
    assert steps <= most


def test_the_bound_refuses_in_one_line_unless_yes():
    big = Estimate("sweep", 100, 1e12, 1e12, 1e6, 2)
    assert big.seconds == pytest.approx(5e5)
    with pytest.raises(sd.SceneError, match=r"100 cells.*above 1 h; give --yes"):
        check(big, yes=False)
    check(big, yes=True)
    check(Estimate("sweep", 100, 1e6 * MAX_SECONDS, 0, 1e6, 2), yes=False)  # 30 min on 2


def test_a_sweep_prints_its_size_before_its_cells(monkeypatch, capsys, tmp_path):
    code, _, err = call(monkeypatch, capsys, "sweep", "--model", "mmd", "--m-star", "0.1",
                        "--amplitude", "0.2,0.3", "--periods", "10", "--workers", "1",
                        "-o", str(tmp_path / "t.parquet"))
    assert code == 0, err
    first = err.strip().splitlines()[0]
    # 2 cells of 10 periods at 128 steps each (the default for m* = 0.1 resolves sqrt(1.5/m*))
    k = sd.bind(sd.Scene(particle={"m_star": 0.1}, drive={"amplitude": 0.2}))
    from sawdrift.dynamics.assembly import steps_per_period

    assert first.startswith(f"sweep: 2 cells, about {2 * 10 * steps_per_period(k):.2g} steps")


def test_a_contact_too_stiff_for_the_probe_step_is_calibrated_at_its_own_step():
    """mmd m* = 1e-8 needs 229575 steps a period: the calibration probe at 4096 went non-finite
    at step 48, so the command line refused (and a sweep lost) a scene sawdrift.run integrates."""
    import math

    from sawdrift.study.estimate import calibrate

    scene = sd.Scene(model="mmd", particle={"m_star": 1e-8}, drive={"amplitude": 0.3})
    rate, overhead = calibrate(scene)
    assert math.isfinite(rate) and rate > 0.0 and overhead >= 0.0
    assert sd.run(scene).regime == "stick"
