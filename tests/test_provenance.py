"""Provenance: a run and a sweep table name the sawdrift version, the code and the whole scene."""

from __future__ import annotations

import importlib.metadata as im
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import sawdrift as sd
from sawdrift.study import sweep as sw
from sawdrift.study.table import table_metadata

from .cli_call import run_main


def test_run_json_has_version_from_metadata_and_the_scene():
    out = run_main("run", "--m-star", "0.2", "--json", "--periods", "20", check=True).stdout
    data = json.loads(out)
    assert data["version"] == im.version("sawdrift")
    assert data["scene"]["particle"]["m_star"] == 0.2
    assert sd.Scene.model_validate(data["scene"]).particle.m_star == 0.2


def test_table_metadata_names_version_code_and_base_scene(tmp_path):
    table = tmp_path / "t.parquet"
    base = sd.Scene(material={"mu": 0.2}, numerics={"periods": 20})
    sd.sweep(["mmd"], "0.1", "0.1,0.2", base=base, table=table, workers=1, progress=False)
    meta = table_metadata(table)
    assert meta["sawdrift_version"] == im.version("sawdrift")
    assert meta["base_scene"]["material"]["mu"] == 0.2
    stored = pd.read_parquet(table)
    assert set(stored["version"]) == {im.version("sawdrift")}
    code = sd.code_hash(["mmd"])
    assert len(code) == 12 and meta["code_hash"] == code and set(stored["code_hash"]) == {code}


def test_code_hash_follows_the_source_not_git(tmp_path):
    """The same source gives the same hash from a copy outside git; one edited byte changes it."""
    from sawdrift.study import provenance

    here = provenance.code_hash(["mmd"])
    pkg = Path(sd.__file__).resolve().parent
    copy = tmp_path / "site" / "sawdrift"
    shutil.copytree(pkg, copy, ignore=shutil.ignore_patterns("__pycache__"))
    code = "import sawdrift; print(sawdrift.__file__); print(sawdrift.code_hash(['mmd']))"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(copy.parent), *sys.path])}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         cwd=tmp_path, check=True).stdout.split()
    assert out[0].startswith(str(copy)) and out[1] == here
    with (copy / "study" / "axes.py").open("a") as fh:
        fh.write("# an edit\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         cwd=tmp_path, check=True).stdout.split()
    assert out[1] != here


def _as_other_code(monkeypatch, models=("mmd",)):
    """Make this process's code hash of ``models`` another one, as after an edit of the source."""
    from sawdrift.study import provenance

    monkeypatch.setitem(provenance._CODES, tuple(sorted(models)), "0123456789ab")


def test_resuming_a_table_of_other_code_is_refused_unless_forced(tmp_path, monkeypatch):
    table = tmp_path / "t.parquet"
    kw = dict(base=sd.Scene(numerics={"periods": 20}), table=table, workers=1, progress=False)
    with monkeypatch.context() as m:
        _as_other_code(m)
        old = sd.sweep(["mmd"], "0.1", "0.1,0.2", **kw)
    assert set(old["code_hash"]) == {"0123456789ab"}
    computed = []
    with pytest.raises(sd.SawdriftError, match="2 rows computed by other code") as err:
        sd.sweep(["mmd"], "0.1", "0.1,0.2,0.4", on_row=computed.append, **kw)
    assert "\n" not in str(err.value) and "0123456789ab" in str(err.value)
    assert "--force" in str(err.value) and computed == []
    assert len(pd.read_parquet(table)) == 2  # the table is left as it was
    # forced: the two cells the table holds keep their rows, the new one is computed by this code
    mixed = sd.sweep(["mmd"], "0.1", "0.1,0.2,0.4", on_row=computed.append, force=True, **kw)
    assert [r["amplitude"] for r in computed] == [0.4]
    by_a = dict(zip(mixed["amplitude"], mixed["code_hash"], strict=True))
    assert by_a == {0.1: "0123456789ab", 0.2: "0123456789ab", 0.4: sd.code_hash(["mmd"])}
    stored = pd.read_parquet(table)
    assert len(stored) == 3 and set(stored["code_hash"]) == set(by_a.values())


def test_cell_id_names_the_code(monkeypatch):
    scene = sd.Scene(numerics={"periods": 20})
    now = sw.cell_id(scene)
    _as_other_code(monkeypatch)
    assert sw.cell_id(scene) != now


def test_the_command_line_refuses_a_table_of_other_code_in_one_line(tmp_path, monkeypatch):
    table = tmp_path / "t.parquet"
    with monkeypatch.context() as m:
        _as_other_code(m)
        sd.sweep(["mmd"], "0.1", "0.1", base=sd.Scene(model="mmd", numerics={"periods": 20}),
                 table=table, workers=1, progress=False)
    run = run_main("sweep", "--model", "mmd", "--m-star", "0.1", "--amplitude", "0.1,0.2",
                   "--periods", "20", "--workers", "1", "--no-progress", "-o", table)
    assert run.returncode == 2, run.stderr[-600:]
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: table") and "other code" in lines[0]


def test_two_base_scenes_do_not_merge_silently(tmp_path):
    table = tmp_path / "t.parquet"
    kw = dict(table=table, workers=1, progress=False)
    sd.sweep(["mmd"], "0.1", "0.1", base=sd.Scene(material={"mu": 0.2}, numerics={"periods": 20}), **kw)
    other = sd.Scene(material={"mu": 0.1}, numerics={"periods": 20})
    with pytest.raises(sd.SawdriftError, match=r"another base scene \(material\.mu: table 0\.2, "
                       r"this sweep 0\.1\)"):
        sd.sweep(["mmd"], "0.1", "0.2", base=other, **kw)
    assert len(pd.read_parquet(table)) == 1
    # the same base, extended: accepted; another model over the same base: accepted too
    sd.sweep(["mmd", "material_point"], "0.1", "0.1,0.2",
             base=sd.Scene(material={"mu": 0.2}, numerics={"periods": 20}), **kw)
    mixed = sd.sweep(["mmd"], "0.1", "0.3", base=other, force=True, **kw)
    assert mixed["mu"].tolist() == [0.1]
    assert len(pd.read_parquet(table)) == 5


def _interrupted(table: Path) -> sd.Scene:
    """A sweep of two cells into ``table`` stopped after its first (only the journal holds it);
    its base scene."""
    base = sd.Scene(material={"mu": 0.2}, numerics={"periods": 20})

    def stop(row):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        sd.sweep(["mmd"], "0.1", "0.1,0.2", base=base, table=table, workers=1, progress=False,
                 on_row=stop)
    return base


def test_an_interrupted_journal_keeps_its_base_scene(tmp_path):
    """Before the table exists, the journal's header names the base scene the rows belong to."""
    table = tmp_path / "t.parquet"
    base = _interrupted(table)
    assert not table.exists() and len(sw.read_rows(table)) == 1
    with pytest.raises(sd.SawdriftError, match=r"material\.mu: table 0\.2, this sweep 0\.3"):
        sd.sweep(["mmd"], "0.1", "0.1,0.2", base=sd.Scene(material={"mu": 0.3},
                 numerics={"periods": 20}), table=table, workers=1, progress=False)
    computed = []
    sd.sweep(["mmd"], "0.1", "0.1,0.2", base=base, table=table, workers=1, progress=False,
             on_row=computed.append)
    assert len(computed) == 1 and len(pd.read_parquet(table)) == 2


def test_a_journal_whose_header_is_damaged_is_not_mixed_with_another_base(tmp_path):
    """A garbled first line of the journal was read as no base scene at all: a sweep of another
    base scene took the journal's rows in as its own (25 new rows and 9 stale ones)."""
    table = tmp_path / "t.parquet"
    _interrupted(table)
    journal = sw.journal_path(table)
    lines = journal.read_text().splitlines()
    journal.write_text("\n".join(["{garbage", *lines[1:]]) + "\n")
    other = sd.Scene(material={"mu": 0.3}, numerics={"periods": 20})
    with pytest.raises(sd.SawdriftError, match=r"first line of its journal\) cannot be read"):
        sd.sweep(["mmd"], "0.1", "0.1,0.2", base=other, table=table, workers=1, progress=False)
    assert not table.exists() and journal.read_text().splitlines()[1:] == lines[1:]
    mixed = sd.sweep(["mmd"], "0.1", "0.1,0.2", base=other, table=table, workers=1,
                     progress=False, force=True)
    assert len(mixed) == 2


def test_a_table_of_one_engine_is_not_resumed_with_the_other(tmp_path):
    """Resuming with --engine python reused the compiled rows as python's, without a word: a
    cross-check of the two engines compared identical rows."""
    table = tmp_path / "t.parquet"
    kw = dict(table=table, workers=1, progress=False)
    base = sd.Scene(numerics={"periods": 20})
    sd.sweep(["material_point"], "0.01,1", "0.1", base=base, **kw)
    with pytest.raises(sd.SawdriftError, match=r"rows of the compiled engine; this sweep runs "
                       r"python"):
        sd.sweep(["material_point"], "0.01,1", "0.1", base=base, engine="python", **kw)
    assert set(pd.read_parquet(table)["engine"]) == {"compiled"}
    sd.sweep(["material_point"], "0.01,1", "0.1,1", base=base, **kw)  # the same engine: resumed
    assert len(pd.read_parquet(table)) == 4


@pytest.mark.parametrize("damage", ["not utf-8", "no header"])
def test_a_journal_damaged_in_its_bytes_or_without_its_header_is_refused(tmp_path, damage):
    """A journal that was not UTF-8 ended in an internal failure (exit 3); one whose header line
    was lost was read as having no base scene, so its rows were taken in unchecked."""
    table = tmp_path / "t.parquet"
    _interrupted(table)
    journal = sw.journal_path(table)
    lines = journal.read_bytes().splitlines()
    journal.write_bytes(b"\n".join([b"\xff\xfe\x00", *lines[1:]] if damage == "not utf-8"
                                   else lines[1:]) + b"\n")
    other = sd.Scene(material={"mu": 0.3}, numerics={"periods": 20})
    with pytest.raises(sd.SawdriftError, match=r"first line of its journal\) cannot be read"):
        sd.sweep(["mmd"], "0.1", "0.1,0.2", base=other, table=table, workers=1, progress=False)


def test_a_journal_row_no_run_writes_is_computed_again(tmp_path):
    """A journal row whose regime no run gives went into the table as it was (and compare then
    left its cell out without a word): it is run again, as a row cut by a kill is."""
    table = tmp_path / "t.parquet"
    base = _interrupted(table)
    journal = sw.journal_path(table)
    head, row = journal.read_text().splitlines()[:2]
    bad = {**json.loads(row), "regime": "bogus", "drift_ratio": None}
    journal.write_text("\n".join([head, json.dumps(bad)]) + "\n")
    computed = []
    out = sd.sweep(["mmd"], "0.1", "0.1,0.2", base=base, table=table, workers=1, progress=False,
                   on_row=computed.append)
    assert len(computed) == 2 and "bogus" not in set(out["regime"])


def _damaged_table(tmp_path, damage: str) -> Path:
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = tmp_path / "t.parquet"
    sd.sweep(["mmd"], "0.1", "0.1,0.2", base=sd.Scene(numerics={"periods": 20}), table=table,
             workers=1, progress=False)
    arrow = pq.read_table(table)
    meta = dict(arrow.schema.metadata)
    if damage == "metadata":
        meta[b"base_scene"] = b"{not json"
        arrow = arrow.replace_schema_metadata(meta)
    elif damage in ("regime", "m_star"):
        arrow = arrow.drop([damage])
    else:
        frame = arrow.to_pandas()
        frame.loc[0, "m_star"] = float("nan")
        arrow = pa.Table.from_pandas(frame, preserve_index=False).replace_schema_metadata(meta)
    pq.write_table(arrow, table)
    return table


@pytest.mark.parametrize("damage, words", [
    ("metadata", r"in its metadata, or the first line of its journal\) cannot be read"),
    ("regime", "has no regime column"), ("m_star", "has no m_star column"),
    ("nan m_star", "holds m_star = nan, which no sweep writes")])
def test_a_damaged_table_is_not_resumed_or_rewritten(tmp_path, damage, words):
    """A table without its regime or m_star column, or with a NaN m*, was resumed and written
    again with every regime (or m*) missing; one whose stored base scene was not JSON ended in
    an internal failure of sweep and export (exit 3)."""
    table = _damaged_table(tmp_path, damage)
    before = table.read_bytes()
    with pytest.raises(sd.SawdriftError, match=words):
        sd.sweep(["mmd"], "0.1", "0.1,0.2", base=sd.Scene(numerics={"periods": 20}),
                 table=table, workers=1, progress=False)
    assert table.read_bytes() == before
    if damage == "metadata":
        with pytest.raises(sd.SawdriftError, match="base scene in its metadata cannot be read"):
            sd.write_grid(table, tmp_path / "g.nc")


@pytest.mark.parametrize("kind", ["impact", "prescribed"])
def test_a_table_of_impacts_or_prescribed_paths_is_resumed(tmp_path, kind):
    """Runs of these drives name no regime of a drift ('impact', 'prescribed') and a prescribed
    path has no amplitude: the check of a resumed table refused the tables sweeps write."""
    table = tmp_path / "t.parquet"
    base = sd.Scene(drive={"kind": kind})
    sd.sweep(["mmd"], "0.1,0.2", base=base, table=table, workers=1, progress=False)
    again = sd.sweep(["mmd"], "0.1,0.2,0.3", base=base, table=table, workers=1, progress=False)
    assert len(again) == 3 and set(again["regime"]) == {kind}
