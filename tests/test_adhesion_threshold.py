"""sawdrift threshold: first crossings from below, the axis with units, the rigid small-particle end."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from sawdrift.errors import SceneError
from sawdrift.scene.schema import Scene
from sawdrift.study.threshold import first_crossing, parse_device_axis, thresholds

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml"


def test_first_crossing_is_located_from_below():
    # crosses on [2, 4) and again from 8 on: the first crossing is 2, not 8
    def crosses(x: float) -> bool:
        return 2.0 <= x < 4.0 or x >= 8.0

    found, runs = first_crossing(crosses, 0.1, 10 ** 0.25, 100.0, 30)
    assert found == pytest.approx(2.0, rel=1e-6)
    assert math.isnan(first_crossing(lambda x: False, 0.1, 2.0, 10.0, 5)[0])


def test_axis_with_units_and_its_errors():
    name, values = parse_device_axis("device.particle.radius=1 um:50 um:15")
    assert name == "device.particle.radius" and len(values) == 15
    assert values[0] == pytest.approx(1e-6) and values[-1] == pytest.approx(5e-5)
    for bad, text in (("device.particle.radius", "FIELD=START"),
                      ("particle.m_star=1:2:3", "device"),
                      ("device.particle.radius=1 s:5 um:3", "length"),
                      ("device.particle.radus=1 um:5 um:3", "did you mean")):
        with pytest.raises(SceneError, match=text):
            parse_device_axis(bad)


def test_small_particle_is_removed_at_the_rigid_limit():
    """A 0.2 um silica sphere: its contact far stiffer than the drive, removal within 3 % of
    (F_pull + m g) / (m (2 pi f)^2) (measured 0.951 at 0.42 um, 0.997 at 0.2 um)."""
    study = thresholds(Scene.from_toml(EXAMPLE), "device.particle.radius", [2e-7],
                       stop=1e-7, bisections=6, show=False)
    row = study.rows[0]
    assert row.removal_amplitude_m / row.rigid_removal_m == pytest.approx(1.0, abs=0.03)
    assert row.slide_amplitude_m <= row.removal_amplitude_m


def test_a_threshold_above_the_scan_is_named_not_printed_as_nan(monkeypatch, capsys):
    """--stop below the first amplitude of the scan (0.01 of the rigid removal amplitude, 16 pm
    at R = 1 um): no crossing is found; the text says '> STOP', the JSON holds null (NaN is not
    JSON), and a slope of fewer than two thresholds is 'n/a'."""
    import json

    from .cli_call import call

    example = str(Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml")
    code, out, _ = call(monkeypatch, capsys, "threshold", example, "--axis",
                        "device.particle.radius=1 um", "--stop", "0.01 nm")
    assert code == 0 and "nan" not in out
    assert out.splitlines()[1].split()[1:4] == [">", "0.01", "nm"]
    assert "slope of log removal_amplitude_m against log radius: n/a" in out
    code, out, _ = call(monkeypatch, capsys, "threshold", example, "--axis",
                        "device.particle.radius=1 um", "--stop", "0.01 nm", "--json")
    row = json.loads(out)["rows"][0]
    assert row["removal_amplitude_m"] is None and row["slide_amplitude_m"] is None


@pytest.mark.parametrize("stop", ["-1 nm", "0 nm"])
def test_a_stop_that_is_not_a_positive_amplitude_is_refused(stop, monkeypatch, capsys):
    # it ran and printed '> -1 nm' for every row
    from .cli_call import call

    example = str(Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml")
    code, _, err = call(monkeypatch, capsys, "threshold", example, "--axis",
                        "device.particle.radius=1 um", "--stop", stop)
    assert code == 2 and len(err.strip().splitlines()) == 1 and "--stop" in err
