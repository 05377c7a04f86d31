"""Scene validation, defaults and TOML round trips."""

from __future__ import annotations

import math

import pytest
from pydantic import ValidationError

import sawdrift as sd
from sawdrift.contact.binding import bind, check_model_params, describe_body, model_for
from sawdrift.dynamics.assembly import steps_per_period
from sawdrift.errors import ModelNotFoundError, SceneError
from sawdrift.scene import build_scene


def test_defaults_follow_the_paper():
    s = sd.Scene()
    assert s.material.mu == 0.1 and s.material.nu == 0.3
    assert s.particle.profile.shape == "sphere" and s.particle.profile.p == 1.5
    assert s.drive.ramp_periods == 5.0
    assert s.horizontal_ratio == pytest.approx(sd.rayleigh_ratio(0.3), rel=1e-15)


@pytest.mark.parametrize(("drive", "field"), [
    ({"amplitude": float("nan")}, "drive.amplitude"),
    ({"kind": "impact", "velocity": -1.0}, "drive.velocity"),
    ({"kind": "prescribed", "typo": 1.0}, "drive.typo"),
])
def test_scene_constructor_names_drive_fields_as_written(drive, field):
    """sd.Scene(drive={"amplitude": nan}) named the drive union's internal drive.wave.amplitude."""
    from pydantic import ValidationError

    with pytest.raises(ValidationError) as info:
        sd.Scene(drive=drive)
    assert [".".join(map(str, e["loc"])) for e in info.value.errors()] == [field]
    assert f"\n{field}\n" in f"\n{info.value}" and ".wave." not in str(info.value)
    assert sd.scene.format_validation_error(info.value).startswith(field)


def test_scene_is_frozen():
    s = sd.Scene()
    with pytest.raises(Exception):  # noqa: B017 - pydantic raises ValidationError on frozen models
        s.particle.m_star = 2.0


@pytest.mark.parametrize(
    ("data", "pattern"),
    [
        ({"particle": {"m_star": -1}},
         r"particle\.m_star = -1 is outside the allowed range \[1e-12, 1e\+10\]"),
        ({"particle": {"m_star": 0}}, r"particle\.m_star"),
        ({"material": {"mu": 0}}, r"material\.mu = 0 is outside the allowed range \[1e-06, 10\]"),
        ({"material": {"nu": 0.5}}, r"material\.nu = 0.5 is outside the allowed range \(-1, 0.5\)"),
        ({"material": {"nu": -1.0}}, r"material\.nu"),
        ({"material": {"mu": float("nan")}}, r"material\.mu"),
        ({"drive": {"amplitude": -0.1}}, r"drive\.amplitude"),
        ({"drive": {"kind": "impact", "velocity": -1}}, r"^drive\.velocity = -1 is outside"),
        ({"numerics": {"order": 5}}, r"numerics\.order"),
        ({"particle": {"mass": 1}}, r"particle\.mass is not a known field"),
        ({"model": "material_point", "model_params": {"restitution": 2}}, r"restitution"),
        # an exponent beside a named shape or a table was stored but not used
        ({"particle": {"profile": {"exponent": 2}}},
         r"profile\.exponent = 2 is used only with profile\.shape = 'power'; shape 'sphere' "
         r"has p = 1\.5"),
        ({"particle": {"profile": {"shape": "flat", "exponent": 1}}}, r"shape 'flat' has p = 1"),
        # and so was a table's file beside another shape
        ({"particle": {"profile": {"file": "law.csv"}}},
         r"profile\.file = 'law\.csv' is used only with profile\.shape = 'table'"),
        # a window longer than the run it ends lengthened a fixed run to the window, unasked
        ({"numerics": {"periods": 10, "measure_periods": 30}},
         r"measure_periods = 30 is longer than periods = 10.*allowed: 1 to 10"),
        # a cap below the run's periods was passed over without a word
        ({"numerics": {"settle": True, "max_periods": 10}},
         r"max_periods = 10 is below periods = 60.*allowed: 60 to 1e\+07"),
    ],
)
def test_bad_fields_give_one_line_naming_the_field(data, pattern):
    # the scene's own fields (build_scene), then the model's parameters (bind)
    with pytest.raises(SceneError, match=pattern) as info:
        bind(build_scene(data))
    assert "\n" not in str(info.value)


def test_unknown_model_names_known_ones():
    with pytest.raises(ModelNotFoundError, match="known models: .*material_point"):
        bind(build_scene({"model": "no_such_model"}))


def test_the_scene_holds_model_params_as_given_and_bind_checks_and_fills_them():
    # the scene layer knows no contact model: a wrong parameter is the binding's error, with
    # the text build_scene gave when the scene checked it itself
    raw = sd.Scene(model="mdr", model_params={"strip": 3})
    assert raw.model_params == {"strip": 3}
    with pytest.raises(SceneError) as info:
        bind(raw, "f.toml")
    assert str(info.value) == ("f.toml: model_params.strip is not a known field (model 'mdr' "
                               "takes: strips, z_max)")
    with pytest.raises(SceneError, match=r"^model_params\.strips = 1: .*\(model 'mdr' takes"):
        bind(sd.Scene(model="mdr", model_params={"strips": 1}))
    with pytest.raises(SceneError, match=r"^scene: model 'material_point' is rigid: the prescribed"):
        bind(sd.Scene(model="material_point", drive={"kind": "prescribed"}))
    bound = bind(sd.Scene(model="mdr"))
    assert set(bound.model_params) == {"strips", "z_max"}
    assert bind(bound) is bound  # binding is idempotent
    assert bound == bind(build_scene(bound.model_dump()))
    model = model_for(bound)
    assert type(model).name == "mdr" and model.params.strips == bound.model_params["strips"]
    with pytest.raises(SceneError, match="model_params.strip "):
        sd.run(raw)  # the run binds the scene before any work


def test_check_model_params_names_the_nearest_parameter():
    with pytest.raises(SceneError, match=r"model_params\.strip is not a known parameter of model "
                                         r"'mdr'; did you mean 'strips'\? \(it takes: strips, z_max\)"):
        check_model_params("mdr", {"strip": 3})
    check_model_params("mdr", {"strips": 3})
    check_model_params("no_such_model", {"x": 1})  # left to the registry's own error


def test_toml_round_trip(tmp_path):
    s = sd.Scene(model="material_point", particle={"m_star": 0.25}, drive={"amplitude": 0.5},
                 numerics={"periods": 12})
    path = tmp_path / "scene.toml"
    s.to_toml(path)
    assert sd.Scene.from_toml(path) == s


def test_malformed_toml_is_one_line(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[particle\nm_star = 1\n")
    with pytest.raises(SceneError, match="malformed TOML") as info:
        sd.Scene.from_toml(path)
    assert "\n" not in str(info.value)


def test_automatic_steps_resolve_the_natural_frequency():
    for m_star in [1e-4, 1e-2, 1.0, 100.0]:
        s = sd.Scene(particle={"m_star": m_star}, drive={"amplitude": 0.1})
        omega = math.sqrt(1.5 / m_star)  # small-amplitude normal frequency per unit t*
        k = steps_per_period(s)
        assert k >= 128
        assert omega / k <= 0.06


def test_with_updates_validates():
    s = sd.Scene(model="material_point")
    assert s.with_updates(**{"particle.m_star": 2.0}).particle.m_star == 2.0
    with pytest.raises(SceneError, match="particle.m_star"):
        s.with_updates(**{"particle.m_star": -2.0})


def test_gyration_without_rotation_is_an_error_naming_both_fields():
    for make in (lambda: build_scene({"particle": {"gyration": 0.5}}),
                 lambda: sd.Scene().with_updates(**{"particle.gyration": 2 / 3})):
        with pytest.raises(SceneError, match=r"particle\.gyration = 0\.\d+ .*effects\.rotation"):
            make()
    on = build_scene({"particle": {"gyration": 0.5}, "effects": {"rotation": True}})
    assert on.particle.gyration == 0.5
    assert build_scene({"effects": {"rotation": False}}).particle.gyration == 0.4


def test_a_rigid_model_with_rotation_is_labelled_a_rigid_sphere():
    point = sd.Scene(model="material_point")
    assert describe_body(point) == "rigid point"
    spun = point.with_updates(**{"effects.rotation": True, "particle.gyration": 2 / 3})
    assert describe_body(spun) == "rigid sphere, turning, kappa = 0.666667"
    assert describe_body(sd.Scene(model="mmd")) == "compliant sphere (N* = a*^p, p = 1.5), not turning"
    assert "(rigid sphere, turning, kappa = 0.666667)" in sd.explain(spun)


def test_schema_module_is_split_below_500_lines_and_keeps_its_imports():
    from pathlib import Path

    from sawdrift.scene import schema

    names = ("Effects", "Impact", "Material", "Numerics", "Particle", "Prescribed", "Scene",
             "Wave", "build_scene", "format_validation_error", "set_dotted")
    assert all(hasattr(schema, name) for name in names)  # what other modules import from it
    for module in Path(schema.__file__).parent.glob("*.py"):
        assert len(module.read_text().splitlines()) < 500, module.name


def test_a_power_profile_takes_its_exponent():
    assert build_scene({"particle": {"profile": {"shape": "power", "exponent": 2}}}).particle.profile.p == 2.0



def test_a_phase_given_alone_survives_updates_dumps_and_sweeps(tmp_path):
    # its dump carried the default orbit 'prograde', which read back conflicted with phase 0:
    # with_updates, every sweep cell and lammps --compare refused a scene that runs
    scene = sd.Scene.model_validate({"drive": {"phase": 0.0}})
    assert scene.with_updates(**{"numerics.settle": False}).drive.phase == 0.0
    assert sd.Scene.model_validate_json(scene.model_dump_json()) == scene
    table = sd.sweep("mmd", [0.1], [0.3], base=scene.with_updates(**{"numerics.settle": False}),
                     table=tmp_path / "t.parquet", progress=False)
    assert table["error"].isna().all()
    # an orbit given with a phase that disagrees is still refused
    from pydantic import ValidationError

    with pytest.raises(ValidationError, match="disagree"):
        sd.Scene.model_validate({"drive": {"phase": 0.0, "orbit": "prograde"}})


@pytest.mark.parametrize("data", [
    {"particle": {"m_star": True}}, {"drive": {"amplitude": True}}, {"numerics": {"order": True}},
    {"numerics": {"periods": False}}, {"particle": {"load": True}},
    {"model": "material_point", "model_params": {"restitution": True}},
    {"particle": {"profile": {"shape": "power", "exponent": True}}},
    {"drive": {"kind": "prescribed", "waveform": "random", "seed": True}},
    {"drive": {"kind": "prescribed", "waveform": "samples", "a": [True, 0.5], "b": [0.0, 0.1]}}])
def test_a_boolean_given_for_a_number_is_refused_naming_the_field(data):
    """pydantic reads true as 1: '--set drive.amplitude=true' ran at A* = 1, a TOML
    'm_star = true' at m* = 1, '--param restitution=true' at e = 1."""
    with pytest.raises((ValidationError, SceneError), match="is a boolean") as info:
        sd.run(sd.Scene.model_validate(data))
    section, fields = next(iter((k, v) for k, v in data.items() if isinstance(v, dict)))
    name = next(k for k, v in fields.items()
                if v is True or v is False or isinstance(v, dict) or (isinstance(v, list)
                                                                       and True in v))
    assert f"{section}.{name}" in str(info.value)


def test_a_boolean_in_a_scene_file_is_one_line_exit_2(tmp_path):
    from tests.cli_call import run_main

    path = tmp_path / "s.toml"
    path.write_text('model = "mmd"\n[particle]\nm_star = true\n')
    out = run_main("run", path, "--json")
    assert out.returncode == 2
    assert out.stderr.strip().splitlines() == [
        f"error: {path}: particle.m_star = true is a boolean (true/false), not a number"]


def test_a_boolean_for_a_device_number_is_refused():
    """device.horizontal_ratio = true gave r = 1."""
    from pathlib import Path

    motor = sd.Scene.from_toml(Path(__file__).parents[1] / "examples" / "saw_linear_motor.toml")
    with pytest.raises((ValidationError, SceneError), match="is a boolean"):
        motor.with_updates(**{"device.horizontal_ratio": True})


def test_a_scene_file_that_fails_to_read_names_itself():
    """/proc/self/mem opens but cannot be read: the line said 'cannot use: Input/output error'
    and named no file."""
    import os

    if not os.path.exists("/proc/self/mem"):
        pytest.skip("no /proc/self/mem here")
    with pytest.raises(sd.SceneError, match=r"scene file '/proc/self/mem' cannot be read"):
        sd.Scene.from_toml("/proc/self/mem")


def test_an_unknown_kind_of_drive_names_the_kinds_not_an_internal_function():
    """--set drive.kind=foo said "Input tag 'foo' found using _drive_kind() does not match"."""
    with pytest.raises(SceneError, match=r"drive.kind = 'foo' is not a kind of drive: use one of "
                                         r"'wave', 'prescribed', 'impact', 'biharmonic'") as err:
        build_scene({"drive": {"kind": "foo"}})
    assert "_drive_kind" not in str(err.value)
