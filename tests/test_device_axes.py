"""Device studies in SI units: axis ranges with units (issue 37, item 2)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from sawdrift.cli import main
from sawdrift.errors import SceneError
from sawdrift.study.axes import parse_values

MOTOR = Path(__file__).resolve().parents[1] / "examples" / "saw_linear_motor.toml"


def test_ranges_with_units_are_in_si():
    # log-spaced: the geometric mean of 2 and 30 MHz in the middle
    assert parse_values("2 MHz:30 MHz:3", "device.frequency") == pytest.approx(
        [2e6, math.sqrt(2e6 * 30e6), 30e6], rel=1e-12)
    assert parse_values("log:2 MHz:30000 kHz:3", "device.frequency") == pytest.approx(
        [2e6, math.sqrt(2e6 * 30e6), 30e6], rel=1e-12)
    assert parse_values("lin:10 nm:30 nm:3", "device.amplitude") == [1e-8, 2e-8, 3e-8]
    assert parse_values("lin:-5 deg:5 deg:3", "device.incline") == pytest.approx(
        np.radians([-5.0, 0.0, 5.0]).tolist(), rel=1e-11)
    assert parse_values("1e-3:1e2:3", "particle.m_star") == pytest.approx([1e-3, 10**-0.5, 1e2])


@pytest.mark.parametrize(("spec", "words"), [
    ("device.frequency=2 MHz:30 nm:15", ("device.frequency", "'30 nm'", "frequency")),
    ("device.frequency=2:30 MHz:15", ("device.frequency", "both ends")),
    ("device.amplitude=lin:10 nm:30 nm", ("device.amplitude", "lin:START:STOP:N")),
    ("material.mu=0.1 nm:0.2 nm:3", ("material.mu", "no units")),
])
def test_a_bad_range_is_one_line_naming_the_field(spec, words, monkeypatch, capsys, tmp_path):
    monkeypatch.setattr(sys, "argv", ["sawdrift", "sweep", str(MOTOR), "--axis", spec,
                                      "-o", str(tmp_path / "t.parquet")])
    with pytest.raises(SystemExit) as exc:
        main()
    lines = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(lines) == 1 and lines[0].startswith("error: "), lines
    assert all(w in lines[0] for w in words), lines[0]


def test_units_on_a_normalized_field_are_refused():
    with pytest.raises(SceneError, match="drive.amplitude"):
        parse_values("lin:1 nm:2 nm:2", "drive.amplitude")
