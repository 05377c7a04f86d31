"""The Python API answers bad arguments with one line (a SceneError), as the command line does,
and never with a traceback from inside numpy, pathlib or the contact binding."""

from __future__ import annotations

import pytest

import sawdrift as sd


@pytest.mark.parametrize("call", [lambda: sd.run({"model": "mmd"}),
                                  lambda: sd.run("examples/saw_linear_motor.toml"),
                                  lambda: sd.explain({"model": "mmd"})])
def test_a_scene_that_is_not_a_scene_is_named(call):
    # AttributeError: 'dict' object has no attribute 'model', from the contact binding
    with pytest.raises(sd.SceneError, match="scene must be a sawdrift.Scene, not a") as info:
        call()
    assert "Scene.from_toml(path)" in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("every", [0, -3, 2.5])
def test_a_recording_interval_below_one_step_is_refused(every):
    # 0 and -3 were taken as 1 (every step recorded)
    with pytest.raises(sd.SceneError, match="record_every"):
        sd.run(sd.Scene(numerics={"periods": 4}), trajectory=True, record_every=every)


@pytest.mark.parametrize(("kwargs", "words"), [
    ({"table": "/proc/sawdrift-no/t.parquet"}, "cannot be written"),
    ({"table": "t.csv"}, "give a name ending in .parquet"),
])
def test_a_sweep_table_it_cannot_write_is_refused_before_any_cell(kwargs, words, tmp_path,
                                                                  monkeypatch):
    # /proc: FileNotFoundError from the journal's first write; t.csv got Parquet bytes
    monkeypatch.chdir(tmp_path)
    with pytest.raises(sd.SceneError, match=words):
        sd.sweep("mmd", "0.1:1:2", "0.1:1:2", **kwargs)
    assert not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize("points", [[(1.0,)], [("a", 1.0)], [(1.0, 2.0, 3.0)]])
def test_a_point_that_is_not_an_m_star_amplitude_pair_is_named(points):
    # ValueError: not enough values to unpack (expected 2, got 1), from inside the sweep
    with pytest.raises(sd.SceneError, match=r"is not an \(m\*, A\*\) pair"):
        sd.sweep("mmd", points=points)


def test_a_run_within_the_ramp_reports_its_own_window_and_is_not_settled():
    """A run that ends within the drive's start-up ramp measured its window there, but took its
    evidence from the ramp's end on: none. A particle in the air for its last periods (A* 1000,
    4 periods of a 10-period ramp) was reported in contact, drift_with, with an empty minimum
    compression. The window is its own evidence now, the trajectory agrees with it, and the run
    says it is not settled and why."""
    res = sd.run(sd.Scene(drive={"amplitude": 1000.0, "ramp_periods": 10.0},
                          numerics={"periods": 4, "settle": False}), trajectory=True)
    tr = res.trajectory
    airborne = float((tr[tr["t"] >= 3.0]["a"] <= 0.0).mean())
    assert airborne == 1.0  # the trajectory: out of contact all through the last period
    assert res.contact_lost and res.out_of_contact_fraction > 0.5
    assert res.settled is False and "within the drive's start-up ramp" in res.warnings[0]
