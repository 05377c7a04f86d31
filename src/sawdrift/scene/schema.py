"""The Scene: one whole experiment as a frozen, validated pydantic model (TOML in and out).

All quantities are the normalized ones of docs/physics.md (paper eq. 4-5): t* = f t, one
wave period is one unit of t*; m* = a0 m f^2 / (M g); A* = A_y / a0. The parts (material,
particle, drives, numerics, effects) are in :mod:`sawdrift.scene.parts`; a ``[device]`` table in
physical units is converted by :mod:`sawdrift.scene.device` under the rule of
:mod:`sawdrift.scene.overrides`, on every path that makes a Scene. Beside the Scene are the
checks of field names (:func:`check_known_fields`, with the nearest valid name) and
:func:`apply_overrides`, which sets dotted fields. The scene knows no contact model: its
``model`` and ``model_params`` are checked one layer up, by :func:`sawdrift.contact.binding.bind`.
"""

from __future__ import annotations

import tomllib
import typing
from collections.abc import Mapping
from pathlib import Path
from typing import Annotated, Any

import tomli_w
from pydantic import (
    BaseModel,
    Discriminator,
    Field,
    SerializerFunctionWrapHandler,
    Tag,
    ValidationError,
    model_serializer,
    model_validator,
)

from ..errors import SceneError
from .adhesion import adhesion_consistent
from .device import Device
from .dotted import get_dotted, set_dotted
from .messages import format_validation_error
from .overrides import DERIVED, apply_device, drop_replaced, nearest, plain_section, strip_derived
from .parts import (
    FROZEN,
    Biharmonic,
    Effects,
    Impact,
    Material,
    NonNegative,
    Numerics,
    Particle,
    Positive,
    Prescribed,
    Wave,
    bounded,
)
from .quoted import refuse_quoted_numbers
from .rayleigh import rayleigh_ratio, theta

__all__ = [
    "Biharmonic", "Effects", "Impact", "Material", "NonNegative", "Numerics", "Particle", "Positive",
    "Prescribed", "Scene", "Wave", "apply_overrides", "bounded", "build_scene", "check_dotted",
    "check_known_fields", "format_validation_error", "get_dotted", "set_dotted",
]


def _drive_kind(value: Any) -> str:
    # A drive without "kind" is a wave: the common case needs no tag in TOML or on the CLI.
    if isinstance(value, dict):
        return value.get("kind", "wave")
    return getattr(value, "kind", "wave")


class Scene(BaseModel):
    """One experiment: material, particle, drive, numerics, effects, and the contact model.

    ``model`` names a registered contact model and ``model_params`` are its parameters, held as
    given: the scene knows no contact model. :func:`sawdrift.contact.binding.bind` checks them
    against the model's own ``Params`` schema and capabilities and fills the defaults; every
    path that runs a scene (:func:`sawdrift.run`, the sweeps and studies, the command line)
    binds it first.
    """

    model_config = FROZEN

    model: str = "mmd"
    model_params: dict[str, Any] = Field(default_factory=dict)
    material: Material = Field(default_factory=Material)
    particle: Particle = Field(default_factory=Particle)
    drive: Annotated[
        Annotated[Wave, Tag("wave")]
        | Annotated[Prescribed, Tag("prescribed")]
        | Annotated[Impact, Tag("impact")]
        | Annotated[Biharmonic, Tag("biharmonic")],
        Discriminator(_drive_kind),
    ] = Field(default_factory=Wave)
    numerics: Numerics = Field(default_factory=Numerics)
    effects: Effects = Field(default_factory=Effects)
    device: Device | None = Field(
        None, description="physical units; when given, m*, A*, theta, mu, nu, r, the orbit and "
        "the profile are derived from it (sawdrift.scene.device; the rule in "
        "sawdrift.scene.overrides)"
    )

    def __init__(self, /, **data: Any) -> None:
        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise _untagged(exc) from None

    @model_validator(mode="before")
    @classmethod
    def _device_conversion(cls, data: Any) -> Any:
        # every path (Scene(**data), model_validate, build_scene) converts the device alike
        if isinstance(data, dict) and data.get("device") is not None:
            return apply_device(data)
        return data

    @model_serializer(mode="wrap")
    def _without_derived(self, handler: SerializerFunctionWrapHandler) -> Any:
        # a device scene is written without the fields its device derives (they come back,
        # from the device, on validation): a copy with new device fields has no stale ones
        out = handler(self)
        if self.device is not None and isinstance(out, dict):
            strip_derived(out)
        return out

    @model_validator(mode="after")
    def _consistent(self) -> Scene:
        # checks that need no contact model; the model's are sawdrift.contact.binding.bind's
        eff = self.effects
        kappa = self.particle.gyration
        if not eff.rotation and kappa != Particle.model_fields["gyration"].default:
            raise ValueError(
                f"particle.gyration = {kappa:g} is used only with effects.rotation = true; turn "
                "the rotation on or leave particle.gyration at its default 0.4"
            )
        if isinstance(self.drive, Prescribed) and not eff.friction:
            raise ValueError("effects.friction = false leaves nothing to compute for a prescribed drive")
        adhesion_consistent(self)
        _ = self.particle.profile.p
        return self

    # -- derived quantities -----------------------------------------------------------------
    @property
    def theta(self) -> float:
        """theta: the material's, or (2 - nu) / (2 (1 - nu)) for identical materials."""
        if self.material.theta is not None:
            return self.material.theta
        return theta(self.material.nu)

    @property
    def horizontal_ratio(self) -> float:
        """r: the scene's value or, by default, r(nu) from the Rayleigh equation."""
        drive = self.drive
        if isinstance(drive, Wave) and drive.horizontal_ratio is not None:
            return drive.horizontal_ratio
        return rayleigh_ratio(self.material.nu)

    def measure_periods(self) -> int:
        """Whole periods at the end of the run over which the drift is averaged."""
        if self.numerics.measure_periods is not None:
            return self.numerics.measure_periods
        ramp = float(getattr(self.drive, "ramp_periods", 0.0))  # a periodic drive's ramp
        return max(1, int((self.numerics.periods - ramp) // 2))

    # -- I/O ----------------------------------------------------------------------------------
    def to_toml(self, path: str | Path | None = None) -> str:
        """Serialize to TOML (None values are omitted); write to ``path`` if given.

        A device scene is written without the fields its device derives; a comment line at the
        top shows their values.
        """
        text = tomli_w.dumps(_drop_none(self.model_dump(mode="json")))
        if self.device is not None:
            text = _derived_comment(self) + text
        if path is not None:
            Path(path).write_text(text)
        return text

    @classmethod
    def from_toml(cls, path: str | Path) -> Scene:
        """Load a scene from a TOML file; a malformed file raises a one-line SceneError."""
        path = Path(path)
        data = read_toml(path)
        profile = data.get("particle", {}).get("profile") if isinstance(data.get("particle"), dict) else None
        if isinstance(profile, dict) and isinstance(profile.get("file"), str):
            # a table named in a scene file is found next to it
            table = Path(profile["file"])
            if not table.is_absolute():
                profile["file"] = str(path.parent / table)
        return build_scene(data, source=str(path))

    def with_updates(self, **updates: Any) -> Scene:
        """A copy with dotted-path updates, validated: ``with_updates(**{"particle.m_star": 2})``.

        Applied by :func:`sawdrift.scene.apply_overrides`: on a device scene a derived field
        (``particle.m_star``, ...) is a SceneError naming the device field to set instead.
        """
        return build_scene(apply_overrides(self, updates))




def _derived_comment(scene: Scene) -> str:
    """A TOML comment line with the values a device scene's device derives."""
    shown = []
    for field in DERIVED:
        value = getattr(getattr(scene, field.split(".")[0]), field.split(".")[1])
        if field == "particle.profile":
            value = value.shape
        shown.append(f"{field} = {value:.6g}" if isinstance(value, float) else f"{field} = {value}")
    return "# derived from [device]: " + ", ".join(shown) + "\n"


def _drop_none(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {k: _drop_none(v) for k, v in obj.items() if v is not None}
    if isinstance(obj, list):
        return [_drop_none(v) for v in obj]
    return obj


def _untagged(exc: ValidationError) -> ValidationError:
    """``exc`` with the fields named as the user wrote them: ``drive.amplitude``, not the drive
    union's internal ``drive.wave.amplitude`` (nor a validator's ``function-...`` step).

    Parameters
    ----------
    exc
        The error of validating a Scene.

    Returns
    -------
    pydantic.ValidationError
        The same errors with those locations, or ``exc`` itself if it cannot be rebuilt.
    """
    kinds = {"wave", "prescribed", "impact", "biharmonic"}
    details = []
    for err in exc.errors(include_url=False):
        loc = [p for p in err["loc"] if not str(p).startswith("function-")]
        if len(loc) > 1 and loc[0] == "drive" and loc[1] in kinds:
            del loc[1]
        detail = {"type": err["type"], "loc": tuple(loc), "input": err.get("input")}
        if "ctx" in err:
            detail["ctx"] = err["ctx"]
        details.append(detail)
    try:
        return ValidationError.from_exception_data(exc.title, details)  # type: ignore[arg-type]
    except Exception:  # noqa: BLE001 - a custom error type: keep pydantic's own message
        return exc


def build_scene(data: dict[str, Any], source: str | None = None) -> Scene:
    """Validate a nested dict into a Scene; errors become a one-line SceneError.

    A ``device`` table is converted by the rule of :mod:`sawdrift.scene.overrides`. The contact
    model is not looked at here: :func:`sawdrift.contact.binding.bind` checks ``model`` and
    ``model_params`` against it (and fills the defaults) before a scene runs.
    """
    try:
        data = apply_device(data)
    except SceneError as exc:
        raise SceneError(f"{source}: {exc}" if source else str(exc)) from None
    try:
        return Scene.model_validate(data)
    except ValidationError as exc:
        raise SceneError(format_validation_error(exc, source)) from None


# -- the fields of a scene, by name: checks and dotted overrides -------------------------------

#: tables of a scene file that another command reads, not the Scene
_ELSEWHERE = {"particles": "a [particles] table (many spheres) is read by `sawdrift lammps` and "
                            "`sawdrift sort` only"}


def _models_in(annotation: Any) -> list[type[BaseModel]]:
    """The pydantic models an annotation can hold (through Optional, Union and Annotated)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    found: list[type[BaseModel]] = []
    for arg in typing.get_args(annotation):
        for cls in _models_in(arg):
            if cls not in found:
                found.append(cls)
    return found


def check_known_fields(data: Mapping[str, Any], source: str | None = None,
                       models: list[type[BaseModel]] | None = None, prefix: str = "") -> None:
    """Raise a one-line SceneError naming the first key of ``data`` that is no scene field.

    Walks the Scene schema (``[device.particle]`` and the drives included), or ``models``, and
    suggests the nearest valid name of the same table: ``particle.m_stra is not a known field;
    did you mean 'm_star'?``. Values are not checked here (the schema does that);
    ``model_params`` belong to the model and are checked against it by
    :func:`sawdrift.contact.binding.check_model_params`.
    """
    fields: dict[str, Any] = {}
    for cls in models if models is not None else [Scene]:
        for name, info in cls.model_fields.items():
            fields.setdefault(name, []).append(info.annotation)
    where = f"{source}: " if source else ""
    for key, value in data.items():
        path = f"{prefix}{key}"
        if key not in fields:
            if path in _ELSEWHERE:
                raise SceneError(f"{where}{path} is not a scene field: {_ELSEWHERE[path]}")
            raise SceneError(f"{where}{path} is not a known field{nearest(str(key), list(fields))}")
        if path == "model_params" or not isinstance(value, Mapping):
            continue
        inner = [cls for ann in fields[key] for cls in _models_in(ann)]
        if inner:
            check_known_fields(value, source, inner, f"{path}.")


def check_dotted(dotted: str, source: str | None = None) -> None:
    """:func:`check_known_fields` for one dotted field (``"material.mu"``, an ``--axis``)."""
    node: Any = None
    for key in reversed(dotted.split(".")):
        node = {key: node}
    check_known_fields(node, source)


def apply_overrides(data: Mapping[str, Any] | BaseModel,
                    overrides: Mapping[str, Any]) -> dict[str, Any]:
    """A scene dict with dotted-path ``overrides`` set, by the rule for device scenes.

    This is the one function the command line and the sweeps use to set scene fields:
    ``apply_overrides(scene_dict, {"particle.m_star": 2.0, "device.amplitude": "5 nm"})``.
    Validate the result with :func:`sawdrift.scene.build_scene`. The rule for device scenes is
    :mod:`sawdrift.scene.overrides`'.

    Parameters
    ----------
    data
        A scene as a nested dict (TOML, ``model_dump``) or a Scene; it is not changed.
    overrides
        Dotted field paths and their values; None values are skipped. On a device scene a
        derived field may only repeat the device's value (``drive.orbit = "retrograde"`` on a
        retrograde device); any other value is an error.

    Returns
    -------
    dict
        A new nested dict. For a device scene its derived fields are left out (they are derived
        again, from the possibly new device fields, when the dict is validated).

    Raises
    ------
    SceneError
        One line naming the field: a field the Scene does not have (with the nearest one); on a
        device scene (one with a ``device`` table, in ``data`` or among the overrides) a derived
        field set to another value than the device derives names the device field to set
        instead; a bad device field names its unit.
    """
    if isinstance(data, BaseModel):
        out: dict[str, Any] = data.model_dump(exclude_none=True)
    else:
        out = {key: plain_section(value) for key, value in data.items()}
    had_device = out.get("device") is not None
    if had_device:
        # check the given scene against its own device, then drop what the device derives: the
        # overrides may change the device
        out = strip_derived(apply_device(out))
    drop_replaced(out, overrides)  # a mass set replaces a density given, and the other way
    for key, value in overrides.items():
        if value is None:
            continue
        try:
            set_dotted(out, key, value)
        except (AttributeError, TypeError):
            raise SceneError(f"{key} is not a known field: {key.rsplit('.', 1)[0]} is not a "
                             "table") from None
    for key in overrides:
        check_dotted(key)  # a misspelled field is named with the nearest one
    if out.get("device") is not None:
        try:
            out = strip_derived(apply_device(out))  # an overridden derived field must agree
        except SceneError as exc:
            if had_device or "is required" not in str(exc):
                raise
            # a device field set on a normalized scene builds a device from nothing: it said
            # only "device.frequency is required"
            raise SceneError(f"{exc}; the scene has no [device] table, so the device fields "
                             "set here are all it has (give a scene file with a whole [device] "
                             "table)") from None
    return out


def read_toml(path: Path) -> dict[str, Any]:
    """The table of a scene file, or a one-line SceneError naming the file and what is wrong:
    missing, a directory, unreadable, not UTF-8, malformed TOML (every command that reads a
    scene file says it alike: ``sort`` and ``lammps`` said "not valid UTF-8 TOML" for a syntax
    error and "cannot use 'scenes': Is a directory"), or a number written as text (``m_star =
    "10"``, :mod:`sawdrift.scene.quoted`)."""
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except FileNotFoundError:
        raise SceneError(f"scene file {str(path)!r} does not exist") from None
    except IsADirectoryError:
        raise SceneError(f"scene file {str(path)!r} is a directory, not a TOML file") from None
    except PermissionError:
        raise SceneError(f"scene file {str(path)!r} cannot be read (permission denied)") from None
    except UnicodeDecodeError as exc:
        raise SceneError(
            f"scene file {str(path)!r} is not UTF-8 text (byte {exc.start}); save it as UTF-8 TOML"
        ) from None
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"scene file {str(path)!r} is malformed TOML: {exc}") from None
    except OSError as exc:
        # another read error named no file (/proc/self/mem: "cannot use: Input/output error")
        raise SceneError(f"scene file {str(path)!r} cannot be read "
                         f"({exc.strerror or exc})") from None
    refuse_quoted_numbers(data, Scene, str(path))  # m_star = "10": lax pydantic ran it as 10
    return data
