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
