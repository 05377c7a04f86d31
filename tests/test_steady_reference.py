"""The stored full-inertia steady-drift reference is internally consistent (no simulation).

``validation/data/steady_reference.json`` (made by ``benchmarks/steady_reference.py``) is what
the steady-drift solver is checked against (validation/g9c_steady_vs_full_inertia.py). These
tests read it only: every cell passed both convergence checks, the run lengths and windows
follow the stated rules, the kinds agree with the measurements, and the cells cover the
family (at least 20 cells; 6 creep, 6 drifting, 2 hopping; m* from 30 to 1e4).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

DATA = Path(__file__).resolve().parents[1] / "validation" / "data" / "steady_reference.json"
REL, ABS = 1e-3, 2e-5


@pytest.fixture(scope="module")
def data() -> dict:
    """The stored reference file."""
    return json.loads(DATA.read_text())


@pytest.fixture(scope="module")
def cells(data: dict) -> list[dict]:
    """Its cells."""
    return data["cells"]


def _agree(a: float, b: float) -> bool:
    return abs(a - b) <= max(REL * abs(b), ABS)


def test_header_says_how_it_was_made(data: dict) -> None:
    """The header names the command, date, machine, version and commit."""
    hdr = data["header"]
    for key in ("command", "date", "machine", "versions", "commit", "method"):
        assert hdr.get(key), key
    assert "steady_reference.py" in hdr["command"]
    assert hdr["machine"]["cores"] >= 1


def test_coverage(cells: list[dict]) -> None:
    """At least 20 cells, 6 creep, 6 drifting, 2 hopping, three models, m* from 30 to 1e4."""
    kinds = [c["kind"] for c in cells]
    assert len(cells) >= 20
    assert kinds.count("creep") >= 6
    assert kinds.count("drifting") >= 6
    assert kinds.count("hopping") >= 2
    assert {"mmd", "hertz_mindlin_dem", "jaeger"} <= {c["model"] for c in cells}
    m = [c["m_star"] for c in cells]
    assert min(m) <= 30.0 and max(m) >= 1e4
    assert min(m) >= 30.0 and max(m) <= 1e4
    assert len({c["key"] for c in cells}) == len(cells)


def test_run_lengths_and_windows(cells: list[dict]) -> None:
    """N >= 40 m*/mu + 2000, W >= 0.3 N and >= 3 vertical periods, checks at N/2 and 2x steps."""
    for c in cells:
        n, w = c["periods"], c["measure_periods"]
        assert n >= 40.0 * c["m_star"] / c["mu"] + 2000, c["key"]
        assert w >= 0.3 * n - 1 and w >= 3.0 * 2.0 * math.pi * math.sqrt(c["m_star"] / 1.5), c["key"]
        assert w <= n, c["key"]
        assert c["half"]["periods"] == n // 2, c["key"]
        assert c["half"]["measure_periods"] >= 0.3 * c["half"]["periods"] - 1, c["key"]
        assert c["fine"]["steps_per_period"] == 2 * c["steps_per_period"], c["key"]


@pytest.mark.parametrize("check", ["half", "fine"])
def test_convergence_checks_within_bounds(cells: list[dict], check: str) -> None:
    """Each check agrees with the reference within 1e-3 relative or 2e-5 absolute."""
    for c in cells:
        v, other = c["drift_ratio"], c[check]["drift_ratio"]
        assert math.isfinite(v) and math.isfinite(other), c["key"]
        assert _agree(other, v), f"{c['key']}: {check} {other} vs {v}"
        assert c[check]["agrees"], c["key"]
        assert c[check]["abs_diff"] == pytest.approx(abs(other - v), rel=1e-12, abs=1e-15)


def test_kinds_match_measurements(cells: list[dict]) -> None:
    """hopping: contact lost; drifting: |V| > 1e-3 in contact; creep: 0 < |V| <= 1e-3 in contact."""
    for c in cells:
        v = abs(c["drift_ratio"])
        if c["kind"] == "hopping":
            assert c["contact_lost"] and c["regime"] == "hopping", c["key"]
        elif c["kind"] == "drifting":
            assert not c["contact_lost"] and v > 1e-3, c["key"]
            assert c["regime"] in ("drift_with", "drift_against"), c["key"]
        else:
            assert c["kind"] == "creep", c["key"]
            assert not c["contact_lost"] and 1e-7 < v <= 1e-3, c["key"]
            assert c["regime"] in ("stick", "oscillating_slip"), c["key"]
