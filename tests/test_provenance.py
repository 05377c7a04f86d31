"""Provenance: a run and a sweep table name the sawdrift version and the whole scene."""

from __future__ import annotations

import importlib.metadata as im
import json
import subprocess
import sys

import pandas as pd

import sawdrift as sd
from sawdrift.study import sweep as sw


def test_run_json_has_version_from_metadata_and_the_scene():
    out = subprocess.run([sys.executable, "-m", "sawdrift", "run", "--m-star", "0.2", "--json",
                          "--periods", "20"], capture_output=True, text=True, check=True).stdout
    data = json.loads(out)
    assert data["version"] == im.version("sawdrift")
    assert data["scene"]["particle"]["m_star"] == 0.2
    assert sd.Scene.model_validate(data["scene"]).particle.m_star == 0.2


def test_table_metadata_names_version_and_base_scene(tmp_path):
    table = tmp_path / "t.parquet"
    base = sd.Scene(material={"mu": 0.2}, numerics={"periods": 20})
    sd.sweep(["mmd"], "0.1", "0.1,0.2", base=base, table=table, workers=1, progress=False)
    meta = sw.table_metadata(table)
    assert meta["sawdrift_version"] == im.version("sawdrift")
    assert meta["base_scene"]["material"]["mu"] == 0.2
    assert set(pd.read_parquet(table)["version"]) == {im.version("sawdrift")}


def test_resuming_after_an_upgrade_recomputes_and_supersedes(tmp_path, monkeypatch):
    table = tmp_path / "t.parquet"
    kw = dict(base=sd.Scene(numerics={"periods": 20}), table=table, workers=1, progress=False)
    monkeypatch.setattr(sd, "__version__", "0.0.1-old")
    old = sd.sweep(["mmd"], "0.1", "0.1,0.2", **kw)
    monkeypatch.setattr(sd, "__version__", "9.9.9-new")
    computed = []
    new = sd.sweep(["mmd"], "0.1", "0.1,0.2", on_row=computed.append, **kw)
    assert len(computed) == 2, "cells of another version must be recomputed"
    assert set(old["cell_id"]).isdisjoint(new["cell_id"])
    stored = pd.read_parquet(table)
    assert len(stored) == 2 and set(stored["version"]) == {"9.9.9-new"}
