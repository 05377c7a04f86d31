"""The Scene: one whole experiment as a frozen, validated pydantic model (TOML in and out).

All quantities are the normalized ones of docs/physics.md (paper eq. 4-5): t* = f t, one
wave period is one unit of t*; m* = a0 m f^2 / (M g); A* = A_y / a0.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Annotated, Any, Literal

import tomli_w
from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Discriminator,
    Field,
    Tag,
    ValidationError,
    model_validator,
)

from ..errors import SceneError
from .device import Device, apply_device
from .profiles import Profile
from .rayleigh import rayleigh_ratio, theta


def _interval(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    left = ("(" if lo_open else "[") + ("-inf" if lo is None else f"{lo:g}")
    right = "inf)" if hi is None else f"{hi:g}" + (")" if hi_open else "]")
    return f"{left}, {right}"


def bounded(
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
) -> AfterValidator:
    """A validator that rejects NaN, infinities and values outside an interval, naming it."""
    text = _interval(lo, hi, lo_open, hi_open)

    def check(value: float) -> float:
        ok = math.isfinite(value)
        if ok and lo is not None:
            ok = value > lo if lo_open else value >= lo
        if ok and hi is not None:
            ok = value < hi if hi_open else value <= hi
        if not ok:
            raise ValueError(f"is outside the allowed range {text}")
        return value

    return AfterValidator(check)


Positive = Annotated[float, bounded(0.0, None, lo_open=True)]
NonNegative = Annotated[float, bounded(0.0, None)]

_FROZEN = ConfigDict(frozen=True, extra="forbid")


class Material(BaseModel):
    """Friction coefficient, Poisson's ratio and, for two materials, the contact's theta."""

    model_config = _FROZEN

    mu: Annotated[float, bounded(0.0, 10.0, lo_open=True)] = Field(
        0.1, description="Coulomb friction coefficient mu, in (0, 10]"
    )
    nu: Annotated[float, bounded(-1.0, 0.5, lo_open=True, hi_open=True)] = Field(
        0.3, description="Poisson's ratio nu, in (-1, 0.5) (the substrate's, for r(nu))"
    )
    theta: Annotated[float, bounded(0.0, 10.0, lo_open=True)] | None = Field(
        None,
        description=(
            "theta = E*/(4 G*) of the contact, in (0, 10]; default (2 - nu)/(2 (1 - nu)) for "
            "identical materials"
        ),
    )


class Particle(BaseModel):
    """The particle: normalized mass, profile, and optional external preload."""

    model_config = _FROZEN

    m_star: Positive = Field(
        0.1, description="m* = a0 m f^2 / (M g) (paper eq. 4), > 0"
    )
    profile: Profile = Field(default_factory=Profile)
    gyration: Annotated[float, bounded(0.0, 1.0, lo_open=True)] = Field(
        0.4,
        description=(
            "kappa = I / (m R^2), in (0, 1]: 2/5 solid sphere, 2/3 thin shell; used with "
            "effects.rotation"
        ),
    )
    preload: NonNegative = Field(
        0.0,
        description=(
            "F_ext / (m g). It enters the normalized equations only through M = m + F_ext/g in "
            "m*; kept for conversion from dimensional inputs"
        ),
    )


class Wave(BaseModel):
    """Rayleigh wave drive (paper eq. 1 with the ramp R(t*) of docs/physics.md)."""

    model_config = _FROZEN

    kind: Literal["wave"] = "wave"
    amplitude: NonNegative = Field(0.316, description="A* = A_y / a0, >= 0")
    horizontal_ratio: Annotated[float, bounded(0.0, 100.0)] | None = Field(
        None,
        description="r = horizontal / vertical surface amplitude; default r(nu) (Rayleigh eq.)",
    )
    ramp_periods: Annotated[float, bounded(0.0, 1e6)] = Field(
        5.0, description="length of the smooth ramp R(t*) = sin^2(pi t* / (2 T_ramp)), periods"
    )
    orbit: Literal["prograde", "retrograde"] = Field(
        "prograde",
        description=(
            "prograde: eq. 1 as printed with y* into the substrate (the crest moves with the "
            "wave, the paper's figures); retrograde: a Rayleigh wave on an isotropic half-space "
            "(the mirror x -> -x: every drift changes sign)"
        ),
    )


class Prescribed(BaseModel):
    """A prescribed contact history a*(t*), b*(t*): the contact law alone, no dynamics.

    Either sampled arrays (``waveform = "samples"`` with ``a`` and ``b``) or a built-in waveform:

    * ``mindlin_loop``: load to a* = ``a_max`` at b* = 0, then cycle b* between
      +-``b_amplitude`` for ``cycles`` cycles at constant a*;
    * ``proportional``: b* = ``slope`` a* from zero up to ``a_max``;
    * ``random``: a random piecewise-linear walk in (a*, b*) (seeded), a* crossing zero.
    """

    model_config = _FROZEN

    kind: Literal["prescribed"] = "prescribed"
    waveform: Literal["samples", "mindlin_loop", "proportional", "random"] = "mindlin_loop"
    a: list[float] | None = None
    b: list[float] | None = None
    a_max: Positive = 1.0
    b_amplitude: NonNegative = 0.5
    slope: Annotated[float, bounded(-10.0, 10.0)] = 0.5
    cycles: Annotated[int, Field(ge=1, le=100000)] = 2
    samples_per_segment: Annotated[int, Field(ge=1, le=1_000_000)] = 200
    seed: int = 0

    @model_validator(mode="after")
    def _samples_given(self) -> Prescribed:
        if self.waveform == "samples":
            if self.a is None or self.b is None:
                raise ValueError("waveform 'samples' needs both 'a' and 'b' arrays")
            if len(self.a) != len(self.b) or len(self.a) < 1:
                raise ValueError("'a' and 'b' must be non-empty and of equal length")
            if not all(math.isfinite(v) for v in [*self.a, *self.b]):
                raise ValueError("'a' and 'b' must be finite")
        return self


class Impact(BaseModel):
    """A free normal impact: the particle touches the substrate (a* = 0) moving into it.

    The substrate is at rest (no wave); the run ends when contact is lost again. The result
    carries the rebound speed ratio |a*'_out| / |a*'_in| (1 for an elastic, undamped contact).
    """

    model_config = _FROZEN

    kind: Literal["impact"] = "impact"
    velocity: Annotated[float, bounded(0.0, 1e3, lo_open=True)] = Field(
        1.0, description="approach speed a*' at first touch, > 0"
    )
    tangential_velocity: Annotated[float, bounded(-1e3, 1e3)] = Field(
        0.0, description="tangential speed x*' at first touch"
    )


class Numerics(BaseModel):
    """Integrator and measurement settings."""

    model_config = _FROZEN

    order: Annotated[int, Field(ge=1, le=4)] = Field(
        4,
        description=(
            "Adams-Bashforth order 1-4 (default 4: on the undamped normal oscillation its "
            "amplitude error per step is O((h omega)^6), AB3's is (3/8)(h omega)^4, which over "
            "thousands of periods changes the drift). The first order-1 steps use the lower "
            "orders (start-up from rest at the static compression, where the derivative "
            "history is exact)"
        ),
    )
    steps_per_period: Annotated[int, Field(ge=8, le=10_000_000)] | None = Field(
        None, description="steps per wave period; default resolves sqrt(1.5/m*) and the wave"
    )
    periods: Annotated[float, bounded(0.0, 1e7, lo_open=True)] = Field(
        60.0, description="simulated periods (with settle: the minimum)"
    )
    measure_periods: Annotated[int, Field(ge=1)] | None = Field(
        None, description="whole periods at the end over which the drift is measured"
    )
    drift_tolerance: Annotated[float, bounded(0.0, 1.0)] = Field(
        1e-3, description="|drift_ratio| below this is 'stick' (no steady drift)"
    )
    settle: bool = Field(
        False, description="run on, in chunks of measure_periods, until the drift has settled"
    )
    settle_tolerance: Annotated[float, bounded(0.0, 1.0, lo_open=True)] = 1e-3
    max_periods: Annotated[float, bounded(1.0, 1e7)] | None = Field(
        None, description="settle: stop after this many periods even if not settled; default "
        "max(5000, 50 m*_x/mu + 20 windows), m*_x the horizontal inertia of the settle method"
    )


class Effects(BaseModel):
    """Which physics is on (LAMMPS-style slots; an off slot is never computed)."""

    model_config = _FROZEN

    friction: bool = Field(
        True, description="tangential friction; off: x* is not integrated, no tangential law"
    )
    vertical_inertia: bool = Field(
        True, description="rigid point only: off gives N* = 1 (no vertical inertia)"
    )
    normal_damping: NonNegative = Field(
        0.0, description="viscous normal damping c: N* += c a*' while in contact"
    )
    horizontal_wave: bool = Field(True, description="the horizontal wave component u_x")
    rolling_resistance: NonNegative = Field(
        0.0,
        description=(
            "rolling friction coefficient mu_r of an elastic-plastic rolling spring (needs "
            "rotation and a compliant model; 0: off); physically mu_r ~ (contact radius)/R = "
            "sqrt(a0/R) times a factor of order 1"
        ),
    )
    rotation: bool = Field(
        False,
        description=(
            "the sphere turns: I phi'' = -R T with I = kappa m R^2 (particle.gyration); the "
            "contact point then moves like a mass m kappa / (1 + kappa)"
        ),
    )
    vertical_wave: bool = Field(True, description="the vertical wave component u_y")


def _drive_kind(value: Any) -> str:
    # A drive without "kind" is a wave: the common case needs no tag in TOML or on the CLI.
    if isinstance(value, dict):
        return value.get("kind", "wave")
    return getattr(value, "kind", "wave")


class Scene(BaseModel):
    """One experiment: material, particle, drive, numerics, effects, and the contact model.

    The model's parameters are validated by the model's own ``Params`` schema.
    """

    model_config = _FROZEN

    model: str = "mmd"
    model_params: dict[str, Any] = Field(default_factory=dict)
    material: Material = Field(default_factory=Material)
    particle: Particle = Field(default_factory=Particle)
    drive: Annotated[
        Annotated[Wave, Tag("wave")]
        | Annotated[Prescribed, Tag("prescribed")]
        | Annotated[Impact, Tag("impact")],
        Discriminator(_drive_kind),
    ] = Field(default_factory=Wave)
    numerics: Numerics = Field(default_factory=Numerics)
    effects: Effects = Field(default_factory=Effects)
    device: Device | None = Field(
        None, description="physical units; when given, m*, A*, theta, mu, nu, r and the orbit "
        "are derived from it (sawdrift.scene.device)"
    )

    @model_validator(mode="after")
    def _model_schema(self) -> Scene:
        from ..contact.registry import get_model

        cls = get_model(self.model)
        try:
            params = cls.Params.model_validate(self.model_params)
        except ValidationError as exc:
            line = format_validation_error(exc)
            known = ", ".join(cls.Params.model_fields) or "no parameters"
            raise ValueError(f"model_params.{line} (model {self.model!r} takes: {known})") from None
        object.__setattr__(self, "model_params", params.model_dump())
        shape = self.particle.profile.shape
        if shape not in cls.capabilities.profiles:
            raise ValueError(
                f"model {self.model!r} does not support profile {shape!r}; it supports "
                + ", ".join(cls.capabilities.profiles)
            )
        rigid = cls.capabilities.rigid
        eff = self.effects
        if isinstance(self.drive, (Prescribed, Impact)) and rigid:
            raise ValueError(
                f"model {self.model!r} is rigid: a {self.drive.kind} drive needs a compliant model"
            )
        if not eff.vertical_inertia and not rigid:
            raise ValueError(
                "effects.vertical_inertia = false applies to a rigid point only; a compliant "
                f"model ({self.model!r}) gets its normal force from the contact compression"
            )
        if eff.normal_damping > 0.0 and rigid:
            raise ValueError(
                f"effects.normal_damping needs a compliant model; {self.model!r} is rigid"
            )
        if eff.rolling_resistance > 0.0 and (rigid or not eff.rotation):
            raise ValueError(
                "effects.rolling_resistance needs effects.rotation = true and a compliant model"
                + (f"; {self.model!r} is rigid" if rigid else "")
            )
        if isinstance(self.drive, Prescribed) and not eff.friction:
            raise ValueError("effects.friction = false leaves nothing to compute for a prescribed drive")
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

    def model_instance(self):
        """The configured ContactModel instance."""
        from ..contact.registry import get_model

        cls = get_model(self.model)
        return cls(cls.Params.model_validate(self.model_params), self.particle.profile)

    def steps_per_period(self) -> int:
        """Steps per period: the scene's, or the automatic default.

        For a rigid model the default is 256 (nothing stiff to resolve). Otherwise it resolves
        the contact's small-amplitude natural frequency
        omega = sqrt(k / m*) (per unit t*, docs/physics.md) with h omega <= 0.06, where
        k = p a_ref^(p-1) max(1, c/theta) bounds the normal and tangential stiffness at the
        largest expected compression a_ref = 1 + 2 A* (c = 1 + 1/kappa with rotation, else 1),
        and never goes below 128 per period.
        """
        if self.numerics.steps_per_period is not None:
            return self.numerics.steps_per_period
        from ..contact.registry import get_model

        if get_model(self.model).capabilities.rigid:
            # no contact stiffness to resolve; events are located by bisection inside steps
            return 256
        p = self.particle.profile.p
        amp = self.drive.amplitude if isinstance(self.drive, Wave) else 0.0
        a_ref = 1.0 + 2.0 * amp
        if isinstance(self.drive, Impact):
            # largest compression from the energy balance with gravity:
            # a^(p+1) / (p+1) - a = m* v^2 / 2, solved by fixed-point iteration
            energy = 0.5 * self.particle.m_star * self.drive.velocity**2
            a_ref = 1.0
            for _ in range(60):
                a_ref = ((p + 1.0) * (energy + a_ref)) ** (1.0 / (p + 1.0))
        # a rolling contact point is lighter by c = 1 + 1/kappa: its tangential frequency is
        # sqrt(c) higher
        c = 1.0 + 1.0 / self.particle.gyration if self.effects.rotation else 1.0
        k = p * a_ref ** (p - 1.0) * max(1.0, c / self.theta)
        if self.effects.rotation and self.effects.rolling_resistance > 0.0:
            # the rolling spring 2.25 mu_r^2 dN*/da* acts on the rotational inertia kappa m*
            mu_r = self.effects.rolling_resistance
            k = max(k, 2.25 * mu_r**2 * p * a_ref ** (p - 1.0) / self.particle.gyration)
        omega = math.sqrt(k / self.particle.m_star)
        return int(min(10_000_000, max(128, math.ceil(omega / 0.06))))

    def measure_periods(self) -> int:
        """Whole periods at the end of the run over which the drift is averaged."""
        if self.numerics.measure_periods is not None:
            return self.numerics.measure_periods
        ramp = self.drive.ramp_periods if isinstance(self.drive, Wave) else 0.0
        return max(1, int((self.numerics.periods - ramp) // 2))

    # -- I/O ----------------------------------------------------------------------------------
    def to_toml(self, path: str | Path | None = None) -> str:
        """Serialize to TOML (None values are omitted); write to ``path`` if given."""
        text = tomli_w.dumps(_drop_none(self.model_dump(mode="json")))
        if path is not None:
            Path(path).write_text(text)
        return text

    @classmethod
    def from_toml(cls, path: str | Path) -> Scene:
        """Load a scene from a TOML file; a malformed file raises a one-line SceneError."""
        path = Path(path)
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
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
        profile = data.get("particle", {}).get("profile") if isinstance(data.get("particle"), dict) else None
        if isinstance(profile, dict) and isinstance(profile.get("file"), str):
            # a table named in a scene file is found next to it
            table = Path(profile["file"])
            if not table.is_absolute():
                profile["file"] = str(path.parent / table)
        return build_scene(data, source=str(path))

    def with_updates(self, **updates: Any) -> Scene:
        """A copy with dotted-path updates, validated: ``with_updates(**{"particle.m_star": 2})``."""
        data = self.model_dump()
        for dotted, value in updates.items():
            set_dotted(data, dotted, value)
        return build_scene(data)


def _drop_none(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {k: _drop_none(v) for k, v in obj.items() if v is not None}
    if isinstance(obj, list):
        return [_drop_none(v) for v in obj]
    return obj


def set_dotted(data: dict[str, Any], dotted: str, value: Any) -> None:
    """Set ``data["a"]["b"] = value`` for ``dotted = "a.b"``, creating levels as needed."""
    keys = dotted.split(".")
    node = data
    for key in keys[:-1]:
        node = node.setdefault(key, {})
    node[keys[-1]] = value


#: Tags of the drive union (the ``kind`` of each drive class).
_DRIVE_KINDS = tuple(cls.model_fields["kind"].default for cls in (Wave, Prescribed, Impact))


def format_validation_error(exc: ValidationError, source: str | None = None) -> str:
    """One line naming the first offending field, its value and what is allowed."""
    err = exc.errors()[0]
    parts = [str(p) for p in err["loc"] if not str(p).startswith("function-")]
    if len(parts) > 1 and parts[0] == "drive" and parts[1] in _DRIVE_KINDS:
        del parts[1]  # the union's tag is not a field the user wrote
    loc = ".".join(parts)
    msg = err["msg"].removeprefix("Value error, ")
    where = f"{source}: " if source else ""
    if err["type"] == "missing":
        return f"{where}{loc} is required"
    if err["type"] == "extra_forbidden":
        return f"{where}{loc} is not a known field"
    if loc:
        value = err.get("input")
        if isinstance(value, (int, float, str, bool)):
            return f"{where}{loc} = {value!r} {msg}" if msg.startswith("is ") else (
                f"{where}{loc} = {value!r}: {msg}"
            )
        return f"{where}{loc}: {msg}"
    if msg.startswith("model_params."):
        return f"{where}{msg}"
    return f"{where}scene: {msg}"


def build_scene(data: dict[str, Any], source: str | None = None) -> Scene:
    """Validate a nested dict into a Scene; errors become a one-line SceneError.

    A SawdriftError raised inside validation (an unknown model) passes through unchanged.
    """
    try:
        data = apply_device(data)
    except SceneError as exc:
        raise SceneError(f"{source}: {exc}" if source else str(exc)) from None
    try:
        return Scene.model_validate(data)
    except ValidationError as exc:
        raise SceneError(format_validation_error(exc, source)) from None
