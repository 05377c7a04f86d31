"""The plugin guide's example (docs/examples/coulomb_spring.py) works as the guide says."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

import sawdrift as sd
from sawdrift.cli import main

EXAMPLE = Path(__file__).resolve().parents[1] / "docs" / "examples" / "coulomb_spring.py"


@pytest.fixture(scope="module")
def spring():
    spec = importlib.util.spec_from_file_location("coulomb_spring", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # as an installed plugin would be (numba's cache needs it)
    spec.loader.exec_module(module)
    (cls,) = module.sawdrift_contact_models()
    sd.registry.register(cls, distribution="docs-example")
    yield cls
    sd.registry.unregister(cls.name)
    sys.modules.pop(spec.name, None)


def test_example_is_under_50_lines():
    assert len(EXAMPLE.read_text().splitlines()) < 50


@pytest.mark.slow
def test_example_runs_the_wave_scene_and_passes_check_model(spring):
    res = sd.run(sd.Scene(model="coulomb_spring", particle={"m_star": 0.1},
                          drive={"amplitude": 0.316}))
    assert res.regime in sd.REGIMES and abs(res.drift_ratio) < 1.0
    python = sd.run(sd.Scene(model="coulomb_spring", numerics={"periods": 8}), engine="python")
    compiled = sd.run(sd.Scene(model="coulomb_spring", numerics={"periods": 8}))
    assert python.drift_ratio == pytest.approx(compiled.drift_ratio, abs=1e-12)
    conf = sd.check_model("coulomb_spring")
    assert conf.passed, conf.table()
    assert conf.get("passivity").status == "pass"


def test_example_appears_in_models(spring, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["sawdrift", "models"])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code == 0
    assert "coulomb_spring" in capsys.readouterr().out


@pytest.mark.slow
def test_a_law_defined_in_a_script_runs_compiled_in_memory(spring, tmp_path):
    # a law written in a notebook or a script lives in __main__: it cannot be imported by name,
    # so its contact and loop are compiled in memory (no disk cache); the physics is the same
    import os
    import subprocess

    source = EXAMPLE.read_text().replace("@njit(cache=True)", "@njit")
    script = tmp_path / "my_law.py"
    script.write_text(source + "\n\nimport sawdrift as sd\n\nsd.registry.register(CoulombSpring)\n"
                      "print(repr(sd.run(sd.Scene(model='coulomb_spring', "
                      "numerics={'periods': 10, 'measure_periods': 5})).drift_ratio))\n")
    env = {**os.environ, "SAWDRIFT_CACHE_DIR": str(tmp_path / "cache")}
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env,
                         timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    here = sd.run(sd.Scene(model=spring.name, numerics={"periods": 10, "measure_periods": 5}))
    assert float(out.stdout.strip().splitlines()[-1]) == here.drift_ratio
