"""Every device quantity has a physical range: outside it, one line naming the field and the range.

A value out of range (``radius = "1 parsec"``) used to reach the integrator and end in "internal
failure (Maximum allowed dimension exceeded)"; a combination of values each in range may still
give an m* no integration can reach, or a load no friction holds, and is refused naming the
device fields that set it.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from sawdrift.errors import SceneError
from sawdrift.scene import build_scene

from .cli_call import run_main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
MOTOR = EXAMPLES / "saw_linear_motor.toml"
SILICA = EXAMPLES / "micro_silica_on_linbo3.toml"

#: one value beyond each field's range, with units, and the range the line must name
BEYOND = [
    ("device.particle.radius", "1 parsec", "1 nm to 10 cm"),
    ("device.particle.radius", "0.1 nm", "1 nm to 10 cm"),
    ("device.frequency", "1 THz", "1 Hz to 100 GHz"),
    ("device.frequency", "0.1 Hz", "1 Hz to 100 GHz"),
    ("device.amplitude", "5 cm", "0 to 1 cm"),
    ("device.particle.density", "1e5 kg/m^3", "1 kg/m^3 to 3e4 kg/m^3"),
    ("device.particle.youngs_modulus", "1 Pa", "1 kPa to 2 TPa"),
    ("device.substrate.youngs_modulus", "5 TPa", "1 kPa to 2 TPa"),
    ("device.substrate.density", "1e6 kg/m^3", "1 kg/m^3 to 3e4 kg/m^3"),
    ("device.gravity", "1e5 m/s^2", "0 to 1e4 m/s^2"),
    ("device.preload", "1 MN", "0 to 1 kN"),
    ("device.load", "-2 kN", "-1 kN to 1 kN"),
    ("device.wavelength", "1 km", "10 nm to 100 m"),
    ("device.incline", "88 deg", "-85 deg to 85 deg"),
    ("device.friction", "1e-5", "0.001 to 10"),
]


def _one_line(proc) -> str:
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    assert "Traceback" not in proc.stderr and "internal failure" not in proc.stderr
    return lines[0]


@pytest.mark.parametrize(("field", "value", "allowed"), BEYOND)
def test_a_set_value_beyond_its_range_is_one_line_naming_field_and_range(field, value, allowed):
    line = _one_line(run_main("run", MOTOR, "--set", f"{field}={value}", "--periods", "5"))
    assert f"{field} = " in line and f"allowed range {allowed}" in line, line


def test_every_range_is_tested_and_holds_the_examples():
    from sawdrift.scene.device import RANGES

    assert {f.removeprefix("device.") for f, _, _ in BEYOND} | {"particle.mass", "adhesion",
                                                                "particle.half_angle"} == set(RANGES)
    for path in (MOTOR, SILICA, EXAMPLES / "grain_on_incline.toml"):
        assert build_scene(tomllib.loads(path.read_text())).device is not None


@pytest.mark.parametrize(("table", "key", "value", "allowed"), [
    ("particle", "radius", '"1 parsec"', "1 nm to 10 cm"),
    ("device", "adhesion", '"50 J/m^2"', "0 to 10 J/m^2"),
])
def test_a_scene_file_beyond_a_range_is_one_line_too(tmp_path, table, key, value, allowed):
    text = SILICA.read_text()
    lines = text.splitlines()
    start = lines.index("[device]" if table == "device" else "[device.particle]")
    at = next(i for i in range(start, len(lines)) if lines[i].startswith(f"{key} ="))
    lines[at] = f"{key} = {value}"
    path = tmp_path / "bad.toml"
    path.write_text("\n".join(lines) + "\n")
    line = _one_line(run_main("run", path, "--periods", "5"))
    assert line.startswith(f"error: {path}: device.") and f"allowed range {allowed}" in line


def test_a_cones_mass_and_half_angle_have_ranges():
    data = tomllib.loads(MOTOR.read_text())
    part = {"shape": "cone", "half_angle": "80 deg", "mass": "1 t", "youngs_modulus": "210 GPa",
            "poisson": 0.3}
    data["device"]["particle"] = part
    with pytest.raises(SceneError, match=r"device\.particle\.mass = '1 t' is 1000 kg, outside the "
                                         r"allowed range 1e-24 kg to 100 kg"):
        build_scene(data)
    data["device"]["particle"] = {**part, "mass": "4 mg", "half_angle": "89.99 deg"}
    with pytest.raises(SceneError, match=r"particle\.half_angle = '89\.99 deg' is outside the "
                                         r"allowed range 1 deg to 89\.9 deg"):
        build_scene(data)


def test_a_heavy_combination_in_range_is_refused_naming_m_star():
    # a 10 cm steel ball on a 100 GHz wave (amplitude 0: no wave bound applies): each field is in
    # range, but a0 = (9 W^2 / (16 R E*^2))^(1/3) = 3.5 um with W = 322 N gives
    # m* = a0 f^2 / g = 3.6e15, beyond the 1e10 an integration can reach
    proc = run_main("run", MOTOR, "--set", "device.particle.radius=10 cm", "--set",
                    "device.frequency=100 GHz", "--set", "device.amplitude=0 nm", "--periods", "5")
    line = _one_line(proc)
    from sawdrift.scene.device import M_STAR_RANGE

    e_star = 1.0 / ((1 - 0.3**2) / 210e9 + (1 - 0.25**2) / 170e9)
    mass = 7850.0 * 4.0 / 3.0 * math.pi * 0.1**3
    weight = mass * 9.81 + 7.35e-3
    a0 = (9.0 * weight**2 / (16.0 * 0.1 * e_star**2)) ** (1.0 / 3.0)
    m_star = a0 * mass * 1e11**2 / weight
    assert m_star > M_STAR_RANGE[1]
    assert f"m* = a0 m f^2 / (M g) = {m_star:.3g}, above the range" in line
    assert "device.frequency" in line


def test_an_amplitude_beyond_the_largest_a_star_names_the_device_fields():
    """A 10 nm silica sphere (2200 kg/m^3, E* = 56 GPa) on a 10 nm wave: the wave's strain and
    speed bounds hold, but a0 = (9 (M g)^2 / (16 R E*^2))^(1/3) = 5.3e-18 m under its weight
    makes A* = 1.9e9, above the 1e9 the model integrates. The line named the derived
    drive.amplitude, a field a device scene cannot set; it names device.amplitude and the most
    it may be."""
    from sawdrift.scene.bounds import AMPLITUDE_MAX

    line = _one_line(run_main("run", SILICA, "--set", "device.particle.radius=10 nm", "--set",
                              "device.amplitude=10 nm"))
    e_star = 1.0 / ((1 - 0.17**2) / 73e9 + (1 - 0.3**2) / 200e9)
    weight = 2200.0 * 4.0 / 3.0 * math.pi * 1e-8**3 * 9.81
    a0 = (9.0 * weight**2 / (16.0 * 1e-8 * e_star**2)) ** (1.0 / 3.0)
    assert 1e-8 / a0 > AMPLITUDE_MAX
    assert f"A* = A_y / a0 = {1e-8 / a0:.3g}" in line
    assert f"device.amplitude must be below {AMPLITUDE_MAX * a0:.3g} m" in line
    assert "drive.amplitude" not in line


def test_the_threshold_scan_names_the_bound_that_refuses_its_start(tmp_path):
    """A 20 nm sphere's scan starts at 4e-8 m, 25 times below its wave's strain bound but above
    the largest A*: the line gives that reason, not the strain bound's."""
    line = _one_line(run_main("threshold", SILICA, "--axis", "device.particle.radius=20 nm,30 nm",
                              "--stop", "1 um", "-o", tmp_path / "t"))
    assert "above the 1e+09 the model integrates" in line and "strain" not in line


def test_a_load_beyond_a_hundred_normal_loads_names_the_device_load():
    # the motor holds M g = 7.39 mN: 1 N is 135 M g (today's line named particle.load instead)
    line = _one_line(run_main("run", MOTOR, "--set", "device.load=1 N", "--periods", "5"))
    assert "device.load = 1 N" in line and "135 times its normal load" in line


def test_the_threshold_study_refuses_a_radius_beyond_range_before_any_run(tmp_path):
    proc = run_main("threshold", SILICA, "--axis", "device.particle.radius=1 um,3e16 m", "-o",
                    tmp_path / "t")
    line = _one_line(proc)
    assert "device.particle.radius" in line and "'3e16 m' is 3e+16 m" in line
    assert "1 nm to 10 cm" in line and proc.stdout == ""


@pytest.mark.parametrize("corner", [
    # the heaviest corner (m* = 1e10), and one of the largest A* (1.2e18: a0 below 1e-29 m)
    {"frequency": "100 GHz", "amplitude": "0 nm", "preload": "1 kN", "load": "-1 kN",
     "friction": 0.001, "incline": "-85 deg",
     "particle": {"shape": "flat", "radius": "10 cm", "mass": "100 kg", "youngs_modulus": "2 TPa",
                  "poisson": -0.999},
     "substrate": {"youngs_modulus": "2 TPa", "poisson": -0.999}},
    {"frequency": "100 GHz", "amplitude": "1 pm", "friction": 10, "incline": "85 deg",
     "particle": {"shape": "flat", "radius": "1 nm", "mass": "1e-24 kg", "youngs_modulus": "2 TPa",
                  "poisson": -0.999},
     "substrate": {"youngs_modulus": "2 TPa", "poisson": -0.999}},
])
def test_corners_of_the_ranges_run_or_fail_in_one_line(tmp_path, corner):
    import tomli_w

    path = tmp_path / "corner.toml"
    path.write_text(tomli_w.dumps({"model": "mmd", "device": corner}))
    proc = run_main("run", path, "--periods", "5", "--no-settle")
    assert proc.returncode in (0, 2) and "internal failure" not in proc.stderr, proc.stderr


def _silica(**device):
    data = tomllib.loads(SILICA.read_text())
    for dotted, value in device.items():
        node = data["device"]
        *path, leaf = dotted.split(".")
        for key in path:
            node = node.setdefault(key, {})
        node[leaf] = value
    return data


def test_an_adhesive_particle_takes_loads_friction_can_hold():
    """The 10 um silica sphere holds mu (M g + 2 F_pull) = 7.07e-7 N by friction, 6.3e4 M g: a
    load of 2e-9 N (177 M g) is a scene (it was refused at 100 M g, and load-curve failed on
    its own stall load); beyond 100 (M g + 2 F_pull) the line names device.load."""
    scene = build_scene(_silica(load="2e-9 N"))
    assert scene.particle.load == pytest.approx(2e-9 / 1.1305e-11, rel=2e-3)
    with pytest.raises(SceneError, match=r"device.load = 0.001 N .* times its normal load M g "
                                         r"\+ 2 F_pull"):
        build_scene(_silica(load="1 mN"))


def test_the_normalized_load_bound_grows_with_the_pulloff():
    base = {"model": "mmd", "particle": {"load": 150.0}}
    with pytest.raises(SceneError, match=r"particle.load = 150.0 .*\[-100, 100\]"):
        build_scene(base)
    adhesive = {**base, "effects": {"adhesion": "dmt"}, "material": {"adhesion": 1.0}}
    assert build_scene(adhesive).particle.load == 150.0
    with pytest.raises(SceneError, match=r"\[-300, 300\] = 100 \(1 \+ 2 material.adhesion\)"):
        build_scene({**adhesive, "particle": {"load": 350.0}})


def test_the_pulloff_bound_is_the_laws_own():
    """JKR pulls with 1.5 pi R w: at g = 1.2e-6 m/s^2 that is 8.5e11 M g, inside the 1e12
    bound (it was refused quoting DMT's 2 pi R w); DMT's 1.1e12 is refused, named so."""
    jkr = build_scene(_silica(gravity="1.2e-6 m/s^2"))
    assert jkr.material.adhesion == pytest.approx(8.5e11, rel=0.02)
    dmt = _silica(gravity="1.2e-6 m/s^2")
    dmt["effects"]["adhesion"] = "dmt"
    with pytest.raises(SceneError, match=r"2 pi R w = .* above 1e\+12"):
        build_scene(dmt)


def test_validity_warnings_see_the_adhesive_contact():
    """A pull-off far below M g does not set the contact: a0 < 1 nm still warns (it was dropped
    whenever adhesion was on); an adhesive contact radius above 0.1 R warns (only the Hertz
    radius under M g was looked at): a 0.5 um polymer sphere, w = 0.1 J/m^2, c = 0.118 R."""
    from sawdrift.scene.validity import device_warnings

    weak = build_scene(_silica(adhesion="1e-18 J/m^2"))
    assert weak.material.adhesion < 1e-3
    assert any("a0 < 1 nm" in w for w in device_warnings(weak.device, "jkr"))
    held = build_scene(_silica())
    assert not any("a0 < 1 nm" in w for w in device_warnings(held.device, "jkr"))
    soft = build_scene({"model": "hertz_mindlin_dem", "effects": {"adhesion": "jkr"},
                        "device": {"frequency": "20 MHz", "amplitude": "0.01 nm",
                                   "friction": 0.3, "adhesion": "0.1 J/m^2",
                                   "particle": {"radius": "0.5 um", "density": "1050 kg/m^3",
                                                "youngs_modulus": "3 GPa", "poisson": 0.35},
                                   "substrate": {"youngs_modulus": "3 GPa", "poisson": 0.35}}})
    warned = [w for w in device_warnings(soft.device, "jkr") if "above 0.1 R" in w]
    assert len(warned) == 1 and "5.91e-08 m" in warned[0]


def _punch_or_cone(shape: str, **particle) -> dict:
    return {"model": "mmd", "device": {
        "frequency": "100 Hz", "amplitude": "2 um", "friction": 0.3,
        "particle": {"shape": shape, "mass": "1 kg", "youngs_modulus": "1 MPa", "poisson": 0.3,
                     **particle},
        "substrate": {"youngs_modulus": "1 MPa", "poisson": 0.3}}}


def test_a_flat_punch_compressed_beyond_small_strain_warns():
    """A 1 mm punch of 1 kg on 100 MPa: a0 = M g / (2 E* R) = 89 um, 0.089 of the punch radius,
    ran without a word (a sphere's contact radius above 0.1 R warns). On 1 MPa (a0 = 8.9 mm,
    nine times its radius) it is refused, as a sphere whose contact is wider than itself is:
    it ran with the warning."""
    from sawdrift.scene.validity import device_warnings

    data = _punch_or_cone("flat", radius="1 mm", youngs_modulus="100 MPa")
    data["device"]["substrate"]["youngs_modulus"] = "100 MPa"
    soft = build_scene(data)
    e_star = 1e8 / (2.0 * (1.0 - 0.3**2))
    a0 = 1.0 * 9.81 / (2.0 * e_star * 1e-3)
    (warned,) = [w for w in device_warnings(soft.device) if "above 0.01 R" in w]
    assert f"a0 = {a0:.3g} m" in warned and f"a0/R = {a0 / 1e-3:.3g}" in warned
    data = _punch_or_cone("flat", radius="1 mm", youngs_modulus="100 GPa")
    data["device"]["substrate"]["youngs_modulus"] = "100 GPa"
    stiff = build_scene(data)  # a0 = 89 nm
    assert not any("above 0.01 R" in w for w in device_warnings(stiff.device))
    with pytest.raises(SceneError, match="exceeds its radius 0.001 m: no elastic contact") as info:
        build_scene(_punch_or_cone("flat", radius="1 mm"))
    assert "\n" not in str(info.value) and f"{a0 * 100:.3g} m" in str(info.value)


@pytest.mark.parametrize("angle", [20.0, 55.0])
def test_a_sharp_cone_warning_names_its_own_half_angle(angle):
    """The warning read "(by 27 % at 42 deg)" for every half-angle below 60 deg."""
    from sawdrift.scene.validity import device_warnings

    cone = build_scene(_punch_or_cone("cone", half_angle=f"{angle:g} deg"))
    (warned,) = [w for w in device_warnings(cone.device) if "below 60 deg" in w]
    assert warned.startswith(f"half-angle {angle:.3g} deg below 60 deg")


@pytest.mark.parametrize("value", [float("-inf"), float("nan"), float("inf")])
def test_a_non_finite_load_is_refused_with_its_real_range(value):
    # it said "outside the allowed range [-inf, inf)"
    with pytest.raises(SceneError, match=r"particle.load = .* is not finite: give a load in "
                                         r"\[-100, 100\]"):
        build_scene({"model": "mmd", "particle": {"load": value}})


@pytest.mark.parametrize(("field", "value", "said"), [
    # inf and nan said "is not > 0"
    ("device.friction", "inf", "is not finite: the friction coefficient, in 0.001 to 10"),
    ("device.friction", "nan", "is not finite: the friction coefficient, in 0.001 to 10"),
    # "Input should be a valid number, unable to parse string as a number", no range
    ("device.particle.poisson", "0.3 m", "is not a number: give one in (-1, 0.5)"),
    ("device.horizontal_ratio", "0.68 m", "is not a number: give one in"),
])
def test_a_value_that_is_no_number_names_the_range(field, value, said):
    line = _one_line(run_main("run", MOTOR, "--set", f"{field}={value}", "--periods", "5"))
    assert f"{field} = " in line and said in line, line


def test_no_gravity_and_no_preload_says_why_with_and_without_adhesion():
    """g = 0 with no preload leaves no unit of force (M g + preload); an adhesive particle is
    still held (by 1.2 uN here), so the line must not say that nothing holds it."""
    adhesive = _one_line(run_main("run", SILICA, "--set", "device.gravity=0"))
    assert "adhesion holds the particle" in adhesive and "preload" in adhesive
    assert "nothing would hold" not in adhesive
    plain = _one_line(run_main("run", MOTOR, "--set", "device.gravity=0", "--set",
                               "device.preload=0 N"))
    assert "nothing would hold the particle" in plain


def test_a_contact_spanning_part_of_a_wavelength_warns():
    """The motor's 0.5 mm ball on a 10 nm wave: a 3.0 um contact spans 300 wavelengths, where
    the model moves the contact with the surface at one point; it ran without a word. The Hertz
    contact radius (M g 3 R / 4 E*)^(1/3) is in the warning, with its share of the wavelength;
    the motor's 9.6 MHz wave at 350 um has none."""
    from sawdrift.scene.validity import device_warnings

    data = tomllib.loads(MOTOR.read_text())
    data["device"].update(wavelength="10 nm", amplitude="1 pm")
    scene = build_scene(data)
    mass = 7850.0 * 4.0 / 3.0 * math.pi * 0.5e-3**3
    e1, e2 = 210e9 / (1 - 0.3**2), 170e9 / (1 - 0.25**2)
    e_star = 1.0 / (1.0 / e1 + 1.0 / e2)
    radius = (3.0 * (7.35e-3 + mass * 9.81) * 0.5e-3 / (4.0 * e_star)) ** (1.0 / 3.0)
    (warned,) = [w for w in device_warnings(scene.device) if "wavelengths" in w]
    assert f"contact radius {radius:.3g} m" in warned and f"{radius / 1e-8:.2g} wavelengths" in warned
    data["device"].update(wavelength="350 um", amplitude="10 nm")
    assert not any("wavelengths" in w for w in device_warnings(build_scene(data).device))
