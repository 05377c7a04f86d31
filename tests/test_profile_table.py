"""Tabulated normal laws: any profile whose N*(a*) is known, for the memory-diagram laws."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import sawdrift as sd

from .cli_call import run_main


def _table(path, a, n):
    pd.DataFrame({"a": a, "N": n}).to_csv(path, index=False)
    return str(path)


@pytest.fixture
def sphere_csv(tmp_path):
    a = np.linspace(0.0, 6.0, 241)
    return _table(tmp_path / "sphere.csv", a, a**1.5)


@pytest.mark.parametrize("model", ["mmd", "mdr"])
def test_tabulated_sphere_reproduces_the_analytic_sphere(model, sphere_csv):
    ref = sd.run(sd.Scene(model=model))
    tab = sd.run(sd.Scene(model=model, particle={"profile": {"shape": "table", "file": sphere_csv}}))
    assert tab.regime == ref.regime
    assert tab.drift_ratio == pytest.approx(ref.drift_ratio, rel=1e-3)


def test_tabulated_cone_meets_the_general_monotonic_oracle(tmp_path):
    # for any profile, monotonic loading from b* = 0 at fixed a*: T* = N*(a*) - N*(a* - b*);
    # a table is exact up to its interpolation, whose error must fall at least like h^3 (PCHIP
    # is third order where the law is smooth): >= 8x smaller on a 4x finer table
    errors = []
    for rows in (161, 641):
        a = np.linspace(0.0, 4.0, rows)
        path = _table(tmp_path / f"cone{rows}.csv", a, a**2)
        scene = sd.Scene(model="mmd", particle={"profile": {"shape": "table", "file": path}},
                         drive={"kind": "prescribed", "waveform": "samples",
                                "a": [0.0, 1.5] + [1.5] * 50,
                                "b": [0.0, 0.0] + list(np.linspace(0.03, 1.5, 50))})
        tr = sd.run(scene).trajectory.iloc[2:]
        want = 1.5**2 - (1.5 - tr["b"].to_numpy()) ** 2
        errors.append(float(np.max(np.abs(tr["T_star"].to_numpy() - want))))
    assert errors[0] < 1e-4
    assert errors[1] < errors[0] / 8.0, errors


def test_compiled_kernel_agrees_with_reference_on_a_table(sphere_csv):
    prof = {"shape": "table", "file": sphere_csv}
    model = sd.model_for(sd.Scene(model="mmd", particle={"profile": prof}))
    rng = np.random.default_rng(3)
    a = np.concatenate([[0.0], np.abs(np.cumsum(rng.normal(0, 0.2, 400))) - 0.1])
    b = np.cumsum(rng.normal(0, 0.2, a.size))
    fast = sd.ContactHistory(model, "compiled").drive(a, b)
    slow = sd.ContactHistory(model, "python").drive(a, b)
    assert np.allclose(fast[1], slow[1], atol=1e-10)


@pytest.mark.parametrize(
    "a, n, needle",
    [
        (np.linspace(0, 2, 20), 2 * np.linspace(0, 2, 20) ** 1.5, r"N\(1\) = 1\.99"),
        (np.linspace(0, 2, 20), -np.linspace(0, 2, 20), "non-decreasing"),
        (np.array([0.0, 0.5, 0.4, 2.0]), np.array([0.0, 0.3, 0.2, 2.8]), "strictly increase"),
        (np.linspace(0, 0.9, 20), np.linspace(0, 0.9, 20), "cover a = 1"),
    ],
)
def test_bad_tables_are_one_line_errors(tmp_path, a, n, needle):
    path = _table(tmp_path / "bad.csv", a, n)
    with pytest.raises(sd.SceneError, match=needle):
        sd.scene.build_scene({"particle": {"profile": {"shape": "table", "file": path}}})


def test_missing_table_and_unsupported_model(tmp_path, sphere_csv):
    with pytest.raises(sd.SceneError, match="does not exist"):
        sd.scene.build_scene({"particle": {"profile": {"shape": "table",
                                                        "file": str(tmp_path / "no.csv")}}})
    with pytest.raises(sd.SceneError, match="does not support profile 'table'"):
        sd.bind(sd.scene.build_scene({"model": "jaeger",
                                      "particle": {"profile": {"shape": "table", "file": sphere_csv}}}))


def test_scene_file_finds_its_table_next_to_it(tmp_path, sphere_csv, monkeypatch):
    (tmp_path / "scene.toml").write_text(
        '[particle]\nprofile = { shape = "table", file = "sphere.csv" }\n[numerics]\nperiods = 20\n')
    monkeypatch.chdir("/")  # the table is found next to the scene, not in the working folder
    out = run_main("run", tmp_path / "scene.toml", "--json")  # in this process (tests/cli_call.py)
    assert out.returncode == 0, out.stderr
    assert '"profile": "table"' in out.stdout


def test_a_rewritten_law_file_is_another_base_scene_for_a_sweep(tmp_path):
    """A sweep resumed after its table's law file was rewritten (N = a^1.5, then a^2) computed
    only the new cells with the new law, beside the old ones: one table, two contact laws."""
    law = tmp_path / "law.csv"
    a = np.linspace(0.0, 6.0, 61)
    _table(law, a, a**1.5)
    base = sd.Scene(model="mmd", particle={"profile": {"shape": "table", "file": str(law)}},
                    numerics={"periods": 20})
    out = tmp_path / "t.parquet"
    sd.sweep("mmd", "0.1,1", "0.1", base=base, table=out)
    _table(law, a, a**2.0)
    from sawdrift.study.provenance import TableProvenanceError

    with pytest.raises(TableProvenanceError, match="file_sha1"):
        sd.sweep("mmd", "0.1,1,3", "0.1", base=base, table=out)
    _table(law, a, a**1.5)  # the same law again: the table resumes
    assert len(sd.sweep("mmd", "0.1,1,3", "0.1", base=base, table=out)) == 3


def test_a_table_shorter_than_the_compressions_of_its_drive_is_warned(tmp_path, sphere_csv):
    """A table ending at a* = 1.5 under A* = 1.2 (compressions to about 1 + 2 A* = 3.4): beyond
    its last point N* follows its last tangent (6.39 at a* = 3.3 where the tabulated law gives
    8.42), which nothing said. A table reaching a* = 6 gets no warning."""
    a = np.linspace(0.0, 1.5, 61)
    short = _table(tmp_path / "short.csv", a, a**1.5)

    def said(path: str) -> list[str]:
        res = sd.run(sd.Scene(model="mmd", drive={"amplitude": 1.2},
                              particle={"profile": {"shape": "table", "file": path}},
                              numerics={"settle": False}))
        return [w for w in res.warnings if w.startswith("profile table")]

    (warning,) = said(short)
    assert "ends at a* = 1.5" in warning and "about a* = 3.4" in warning
    assert said(sphere_csv) == []
