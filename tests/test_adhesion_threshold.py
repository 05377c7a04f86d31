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

    found, runs, how = first_crossing(crosses, 0.1, 10 ** 0.25, 100.0, 30)
    assert found == pytest.approx(2.0, rel=1e-6) and how == "found"
    none, _, how = first_crossing(lambda x: False, 0.1, 2.0, 10.0, 5)
    assert math.isnan(none) and how == "above_stop"


def test_a_crossing_between_the_last_grid_point_and_stop_is_found():
    """The grid 0.1, 1, 10, ... and --stop 5: a crossing at 3 lies past the grid's last point
    below --stop, which is tested itself (it was reported as '> stop')."""
    found, _, how = first_crossing(lambda x: x >= 3.0, 0.1, 10.0, 5.0, 40)
    assert how == "found" and found == pytest.approx(3.0, rel=1e-6)
    none, _, how = first_crossing(lambda x: x >= 6.0, 0.1, 10.0, 5.0, 40)
    assert math.isnan(none) and how == "above_stop"


def test_a_crossing_at_the_first_amplitude_is_no_threshold():
    """Already crossed at the scan's start: the threshold lies below it, not at it (the start
    amplitude was printed as the threshold)."""
    value, runs, how = first_crossing(lambda x: True, 0.5, 2.0, 10.0, 8)
    assert math.isnan(value) and how == "below_start" and runs == 1


def test_an_amplitude_the_device_refuses_ends_the_scan():
    def crosses(x: float) -> bool:
        assert x <= 1.0, "an amplitude the device refuses was run"
        return False

    value, _, how = first_crossing(crosses, 0.01, 10.0, 100.0, 8, refuses=lambda x: x > 1.0)
    assert math.isnan(value) and how == "above_bound"


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
    """--stop 0.1 nm, above the scan's first amplitude (0.01 of the rigid removal amplitude, 16 pm
    at R = 1 um) and below both thresholds (about 1 nm): no crossing is found; the text says
    '> STOP', the JSON holds null (NaN is not JSON), and a slope of fewer than two thresholds is
    'n/a'."""
    import json

    from .cli_call import call

    example = str(Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml")
    code, out, _ = call(monkeypatch, capsys, "threshold", example, "--axis",
                        "device.particle.radius=1 um", "--stop", "0.1 nm")
    assert code == 0 and "nan" not in out
    assert out.splitlines()[1].split()[1:4] == [">", "0.1", "nm"]
    assert "slope of log removal_amplitude_m against log radius: n/a" in out
    code, out, _ = call(monkeypatch, capsys, "threshold", example, "--axis",
                        "device.particle.radius=1 um", "--stop", "0.1 nm", "--json")
    row = json.loads(out)["rows"][0]
    assert row["removal_amplitude_m"] is None and row["slide_amplitude_m"] is None


@pytest.mark.parametrize("stop", ["-1 nm", "0 nm", "10", "2 cm"])
def test_a_stop_that_is_not_a_positive_amplitude_is_refused(stop, monkeypatch, capsys):
    # it ran and printed '> -1 nm' for every row; 10 (read as 10 m) and 2 cm, outside a device
    # amplitude's range of 0 to 1 cm, ran too
    from .cli_call import call

    example = str(Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml")
    code, _, err = call(monkeypatch, capsys, "threshold", example, "--axis",
                        "device.particle.radius=1 um", "--stop", stop)
    assert code == 2 and len(err.strip().splitlines()) == 1 and "--stop" in err


def _cli(monkeypatch, capsys, *args):
    from .cli_call import call

    return call(monkeypatch, capsys, "threshold", str(EXAMPLE), *args)


def test_the_scanned_amplitude_is_no_axis(monkeypatch, capsys):
    # it ran, overwrote the axis with the scan and fitted a slope of 5e-17
    code, _, err = _cli(monkeypatch, capsys, "--axis", "device.amplitude=1 nm,2 nm")
    assert code == 2 and "device.amplitude" in err and len(err.strip().splitlines()) == 1


def test_a_one_point_range_with_two_ends_is_refused(monkeypatch, capsys):
    code, _, err = _cli(monkeypatch, capsys, "--axis", "device.particle.radius=1 um:2 um:1")
    assert code == 2 and "N = 1" in err


def test_a_scan_past_the_strain_bound_keeps_its_rows(monkeypatch, capsys, tmp_path):
    """At 30 GHz the wave's strain bound lies below the removal amplitude: the scan ends there
    ('> bound') instead of the whole study stopping with an error and its rows lost."""
    import json

    out = tmp_path / "th"
    code, text, err = _cli(monkeypatch, capsys, "--axis", "device.frequency=20 MHz,30 GHz",
                           "--set", 'device.substrate.density="4650 kg/m^3"', "--bisections",
                           "2", "-o", str(out))
    assert code == 0, err
    rows = json.loads((out / "threshold.json").read_text())["rows"]
    assert len(rows) == 2 and rows[1]["removal_found"] == "above_bound"
    assert rows[1]["removal_amplitude_m"] is None and "> bound" in text


def test_threshold_takes_set_and_carries_the_warnings(monkeypatch, capsys):
    """--set as on every command with a scene; a 1 um sphere pressed by 1 mN has a contact
    radius above 0.1 R: the warning is in the JSON rows and the text as in a run's."""
    import json

    args = ("--axis", "device.particle.radius=1 um", "--set", 'device.preload="1 mN"',
            "--start", "1e-4", "--stop", "100 nm", "--bisections", "1")
    code, out, err = _cli(monkeypatch, capsys, *args, "--json")
    assert code == 0, err
    assert any("above 0.1 R" in w for w in json.loads(out)["rows"][0]["warnings"])
    code, out, _ = _cli(monkeypatch, capsys, *args)
    assert "WARNING at device.particle.radius = 1e-06: contact radius" in out


def test_the_grid_ends_at_the_largest_amplitude_the_wave_may_have():
    """A crossing between the grid's last allowed point and the wave's bound (2.5 here) was
    never tried: the scan said '> bound'. The bound is located from the refusals alone (no
    run) and tried itself."""
    def refuses(x: float) -> bool:
        return x > 2.5

    def crosses(x: float) -> bool:
        assert not refuses(x), "an amplitude the device refuses was run"
        return x >= 2.2

    found, _, how = first_crossing(crosses, 0.01, 10.0, 100.0, 40, refuses)
    assert how == "found" and found == pytest.approx(2.2, rel=1e-6)

    tried = []

    def never(x: float) -> bool:
        assert not refuses(x), "an amplitude the device refuses was run"
        tried.append(x)
        return False

    none, _, how = first_crossing(never, 0.01, 10.0, 100.0, 4, refuses)
    assert math.isnan(none) and how == "above_bound"
    assert max(t for t in tried if t <= 2.5) == pytest.approx(2.5, rel=1e-9)


@pytest.mark.parametrize(("args", "needle"), [
    # it printed '> 10 nm' for both thresholds after 0 runs (removal is at 1.13 nm)
    (("--start", "100"), "above --stop"),
    (("--per-decade", "1000000"), "--per-decade = 1000000 must be in [1, 100]"),
])
def test_a_scan_that_cannot_say_anything_is_refused(args, needle, monkeypatch, capsys):
    code, _, err = _cli(monkeypatch, capsys, "--axis", "device.particle.radius=1 um", *args)
    assert code == 2 and len(err.strip().splitlines()) == 1 and needle in err, err


def test_an_output_with_a_file_suffix_is_refused_before_any_work(monkeypatch, capsys, tmp_path):
    """-o t.txt made a folder named t.txt, where run, field and load-curve refuse the suffix."""
    out = tmp_path / "t.txt"
    code, _, err = _cli(monkeypatch, capsys, "--axis", "device.particle.radius=1 um:2 um:2",
                        "-o", str(out))
    assert code == 2 and ".txt files are not written here; give a folder" in err
    assert not out.exists()


def test_the_scanned_amplitude_is_no_set_field(monkeypatch, capsys):
    # --set device.amplitude=5 nm ran, ignored: the scan sets the amplitude itself
    code, _, err = _cli(monkeypatch, capsys, "--axis", "device.particle.radius=2 um", "--set",
                        "device.amplitude=5 nm")
    assert code == 2 and "--set device.amplitude" in err and len(err.strip().splitlines()) == 1


def test_a_slope_needs_values_that_differ_by_more_than_rounding():
    """Radii written 1 um, 1000 nm and 1e-6 m differ only by rounding: no slope to fit (polyfit
    warned it was poorly conditioned and gave 0.733 for the rigid removal amplitude, an R^-2
    law); two radii a factor 2 apart give the law's -2."""
    import warnings

    from sawdrift.study.threshold import ThresholdRow, ThresholdStudy

    def row(r: float) -> ThresholdRow:
        a = 1e-10 * (r / 1e-6) ** -2.0
        return ThresholdRow(r, a, a, a, 1e-6, 1e-11, 1)

    same = ThresholdStudy("device.particle.radius",
                          [row(1e-6), row(1e-6 * (1 + 2e-16)), row(1.0000000000000002e-06)])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert math.isnan(same.slope("rigid_removal_m"))
    apart = ThresholdStudy("device.particle.radius", [row(1e-6), row(2e-6)])
    assert apart.slope("rigid_removal_m") == pytest.approx(-2.0, abs=1e-9)


def test_a_range_of_no_numbers_names_its_first_end():
    """'a:b:c' was told that N = 'c' must be an integer, not that 'a' is no length."""
    with pytest.raises(SceneError, match=r"--axis device.particle.radius: 'a' "):
        parse_device_axis("device.particle.radius=a:b:c")
