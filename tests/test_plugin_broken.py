"""The installed example plugin made to raise on import: a warning names it, the rest works."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from .cli_call import run_main

pytest.importorskip("sawdrift_tsuji")


def test_broken_example_plugin_warns_and_others_work(tmp_path):
    # shadow the installed plugin package with one whose model module raises on import
    pkg = tmp_path / "sawdrift_tsuji"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "hertz_tsuji.py").write_text("raise RuntimeError('plugin deliberately broken')\n")
    env = dict(os.environ, PYTHONPATH=str(tmp_path) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-m", "sawdrift", "models", "--json"], capture_output=True,
                         text=True, env=env, timeout=300)
    assert out.returncode == 0
    names = {row["name"] for row in json.loads(out.stdout)}
    assert {"material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem"} <= names
    assert "hertz_tsuji" not in names
    warning = [line for line in out.stderr.splitlines() if line.startswith("warning")]
    assert len(warning) == 1
    assert "'hertz_tsuji'" in warning[0] and "sawdrift-tsuji" in warning[0]
    assert "deliberately broken" in warning[0]
    run = subprocess.run([sys.executable, "-m", "sawdrift", "run", "--model", "mmd", "--periods", "10",
                          "--json"], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0 and json.loads(run.stdout)["model"] == "mmd"


def test_plugin_listed_with_parameters_when_installed():
    out = run_main("models", "--json", check=True)  # in this process (tests/cli_call.py)
    rows = {row["name"]: row for row in json.loads(out.stdout)}
    assert rows["hertz_tsuji"]["distribution"] == "sawdrift-tsuji"
    assert "damping" in rows["hertz_tsuji"]["parameters"]
    for name in ("material_point", "mmd", "mdr", "jaeger", "hertz_mindlin_dem", "hertz_tsuji"):
        assert isinstance(rows[name]["parameters"], dict)
