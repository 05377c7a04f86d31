"""The tutorial notebook executes as written, and the documentation site builds without warnings."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

# a notebook kernel and a strict mkdocs build: seconds each
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]


def test_tutorial_notebook_executes(tmp_path):
    nbformat = pytest.importorskip("nbformat", reason="pip install -e '.[test]' brings nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(ROOT / "examples" / "tutorial.ipynb", as_version=4)
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors
    assert (tmp_path / "tutorial_out" / "compare.png").exists()


def test_docs_site_builds_with_warnings_as_errors(tmp_path):
    pytest.importorskip("mkdocs", reason="pip install -e '.[docs]' brings mkdocs")
    env = dict(os.environ, NO_MKDOCS_2_WARNING="1")
    out = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-d",
                          str(tmp_path / "site")], cwd=ROOT, capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr[-2000:]
    assert (tmp_path / "site" / "physics" / "index.html").exists()
