"""Scene options for every command that builds a scene, generated from the Scene schema.

:data:`sawdrift._scene_options.OPTIONS` (frozen from the schema by
:mod:`sawdrift.scene.options`, checked by a test) gives one option per scene field with its name,
help and allowed range; :func:`with_scene_options` adds them to a command, so ``run``, ``sweep``
and the studies share them, and a new scene field is a new option without editing the command
line. ``--set FIELD=VALUE`` (repeatable) sets any dotted scene field the same way, the device
fields with their units (``--set device.amplitude="20 nm"``). The values reach the command as
``scene_overrides``, a ``{dotted field: value}`` dict (:class:`Overrides`, which also remembers
how each was typed) of the options that were given, which :func:`scene_from_options` applies to
the scene file (or the defaults) through :func:`sawdrift.scene.apply_overrides`, the one rule
for every path (a normalized field on a device scene is an error naming the ``--set`` of the
device field to give instead).
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from .._scene_options import OPTIONS

_TYPES: dict[str, Any] = {"float": float, "int": int, "choice": str}

#: the keyword of the ``--set`` option in a decorated command's signature
_SET = "set_fields"


def _number(text: str) -> float:
    """A float option: one line naming what was given ('abc' said "Input should be a valid
    number, unable to parse string as a number")."""
    try:
        return float(text)
    except ValueError:
        raise typer.BadParameter(f"{text!r} is not a number") from None


def _whole(text: str) -> int:
    """An integer option that also takes ``1e7`` (a whole number written as a float)."""
    value = _number(text)
    if not value.is_integer():
        raise typer.BadParameter(f"{text!r} is not a whole number")
    return int(value)


def _parameter(name: str, kind: str, help_text: str) -> inspect.Parameter:
    ident = name.replace("-", "_")
    if kind == "bool":
        option = typer.Option(f"--{name}/--no-{name}", help=help_text, show_default=False)
        annotation: Any = Annotated[bool | None, option]
    elif kind == "int":
        option = typer.Option(f"--{name}", help=help_text, show_default=False, parser=_whole,
                              metavar="INTEGER")
        annotation = Annotated[int | None, option]
    elif kind == "float":
        option = typer.Option(f"--{name}", help=help_text, show_default=False, parser=_number,
                              metavar="<float>")
        annotation = Annotated[float | None, option]
    else:
        option = typer.Option(f"--{name}", help=help_text, show_default=False)
        annotation = Annotated[_TYPES[kind] | None, option]
    return inspect.Parameter(ident, inspect.Parameter.KEYWORD_ONLY, default=None,
                             annotation=annotation)


def _set_parameter() -> inspect.Parameter:
    option = typer.Option(
        "--set", show_default=False,
        help="FIELD=VALUE, repeatable: any dotted scene field, checked like the scene file; "
             "device fields take units, e.g. --set device.amplitude=\"20 nm\" --set "
             "device.particle.radius=\"0.2 mm\"")
    return inspect.Parameter(_SET, inspect.Parameter.KEYWORD_ONLY, default=None,
                             annotation=Annotated[list[str] | None, option])


class Overrides(dict):
    """``{dotted field: value}`` of the scene options given, and how each was typed (``given``)."""

    def __init__(self, values: dict[str, Any], given: dict[str, str]) -> None:
        super().__init__(values)
        self.given = given


def typed_as(overrides: Any, field: str, default: str | None = None) -> str | None:
    """How the option that set ``field`` was typed (``--mu 0.5``, ``--set material.mu=0.5``),
    ``default`` where ``overrides`` does not say (a plain dict from the Python API)."""
    return getattr(overrides, "given", {}).get(field, default)


def axis_and_option(field: str, spec: str, overrides: Any) -> None:
    """One line where an option (or --set) sets the field an --axis sweeps: the option's value
    was dropped without a word (sweep --mu 0.5 --axis material.mu=0.1,0.2)."""
    if field in overrides:
        typed = typed_as(overrides, field, f"--set {field}")
        raise sd.SceneError(f"--axis {field}={spec} and {typed} both set {field}; give one of "
                            "them")


def parse_set(item: str) -> tuple[str, Any]:
    """``(dotted field, value)`` of one ``--set FIELD=VALUE``; one line (exit 2) if malformed.

    The value is read as JSON where it is one (numbers, ``true``/``false``), else kept as text
    (``"20 nm"``, ``prograde``), which the scene's validation converts or refuses.
    """
    import json

    from ..scene.schema import check_dotted

    field, sep, raw = item.partition("=")
    field, raw = field.strip(), raw.strip()
    if not sep or not field or not raw:
        raise sd.SceneError(f"--set {item!r} must look like FIELD=VALUE (e.g. "
                            "device.amplitude='20 nm' or material.mu=0.2)")
    check_dotted(field)  # a misspelled field: one line naming the nearest valid one
    if len(raw) >= 2 and raw[0] == raw[-1] and raw[0] in "'\"":
        return field, raw[1:-1]
    if raw.lower() in ("true", "false"):
        return field, raw.lower() == "true"
    try:
        value = json.loads(raw)
    except json.JSONDecodeError:
        return field, raw
    return field, value if isinstance(value, (int, float)) else raw


def with_scene_options(exclude: Iterable[str] = ()) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Decorate a command taking ``scene_overrides``: one option per scene field, except ``exclude``.

    ``exclude`` names options the command defines itself (e.g. sweep's ``--m-star`` takes an axis).
    """
    skip = set(exclude)
    rows = [(name, dotted, kind, text) for name, dotted, kind, _choices, text in OPTIONS
            if name not in skip]

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        sig = inspect.signature(func, eval_str=True)
        own = [p for p in sig.parameters.values() if p.name != "scene_overrides"]
        taken = {p.name for p in own}
        clash = taken & {name.replace("-", "_") for name, *_ in rows}
        if clash:
            raise TypeError(f"{func.__name__} defines scene options itself: {sorted(clash)}")
        extra = [_parameter(name, kind, text) for name, _dotted, kind, text in rows]
        extra.append(_set_parameter())

        @functools.wraps(func)
        def command(**kwargs: Any) -> Any:
            overrides: dict[str, Any] = {}
            given: dict[str, str] = {}
            for name, dotted, _kind, _text in rows:
                value = kwargs.pop(name.replace("-", "_"), None)
                if value is not None:
                    overrides[dotted] = value
                    shown = f"{value:g}" if isinstance(value, float) else str(value)
                    given[dotted] = f"--{name} {shown}"
            for item in kwargs.pop(_SET, None) or []:
                dotted, value = parse_set(item)
                if dotted in given:
                    raise sd.SceneError(f"--set {item!r}: {given[dotted]} already sets {dotted}; "
                                        "give it once")
                overrides[dotted] = value
                given[dotted] = f"--set {item}"
            return func(**kwargs, scene_overrides=Overrides(overrides, given))

        params = own + extra
        command.__signature__ = sig.replace(parameters=params)  # type: ignore[attr-defined]
        command.__annotations__ = {p.name: p.annotation for p in params}
        del command.__wrapped__  # typer must read the signature above, not func's
        return command

    return decorate


def scene_from_options(scene_file: Path | None, model: str | None = None,
                       params: dict[str, Any] | None = None,
                       overrides: dict[str, Any] | None = None,
                       swept: tuple[str, ...] = ()) -> sd.Scene:
    """Load a scene file (or the defaults), apply the command-line values, bind it to its model.

    ``overrides`` maps dotted scene fields to values; ``model`` and ``params`` set the model
    and its parameters (a file's parameters belong to the file's model and are dropped when
    another model is named). The scene is returned bound
    (:func:`sawdrift.contact.binding.bind`): a parameter the model does not take, a value out
    of its range or something the model cannot do is one line (exit 2) before any work, and
    so is an option the scene does not use (:func:`_unused_options`; ``swept``: the fields an
    axis sets cell by cell, which may make it used).
    """
    if scene_file is not None:
        _check_keys(scene_file, model)
    # the file's scene is checked against its own model first, as a file run alone would be
    base = sd.bind(sd.Scene.from_toml(scene_file), str(scene_file)) if scene_file is not None else None
    data = base.model_dump(exclude_none=True) if base is not None else {}
    values = dict(overrides or {})
    if model is not None:
        if "model" in values:  # --model won, and the --set was dropped without a word
            typed = typed_as(overrides, "model", f"--set model={values['model']}")
            raise sd.SceneError(f"{typed}: --model {model} already sets model; give it once")
        values["model"] = model
    if params:
        from ..contact.binding import check_model_params

        check_model_params(values.get("model") or (base.model if base is not None else "mmd"),
                           params)
        for key in params:
            # --param and --set of one parameter: the --param won without a word
            if f"model_params.{key}" in values:
                typed = typed_as(overrides, f"model_params.{key}", f"--set model_params.{key}")
                raise sd.SceneError(f"--param {key}: {typed} already sets model_params.{key}; "
                                    "give it once")
    # a file's parameters belong to the file's model, dropped when another model is named
    # (--model or --set model=): before the options, so that a --set model_params.X given with
    # it is kept (--set model=mmd on a hertz_mindlin_dem file named its rescale, a parameter the
    # user never gave)
    if base is not None and values.get("model") not in (None, base.model):
        data["model_params"] = {}
    # one rule for every path: on a device scene a derived (normalized) field is an error
    # naming the device field to set instead (sawdrift.scene.apply_overrides)
    data = apply_options(data, values, overrides)
    if params:
        data.setdefault("model_params", {}).update(params)
    source = str(scene_file) if scene_file else None
    scene = sd.bind(sd.scene.build_scene(data, source=source), source)
    _unused_options(scene, values, overrides, swept)
    if base is not None:
        _replaced_note(base, values, overrides, swept)
    return scene


def _replaced_note(base: sd.Scene, values: dict[str, Any], overrides: Any,
                   swept: tuple[str, ...]) -> None:
    """One note on stderr where the command line's mass replaces a device particle's density
    from the scene file, or its density the file's mass (a particle has one of them; the
    replacement is the rule of :func:`sawdrift.scene.overrides.drop_replaced`): it was done
    without a word. Both given on the command line must agree (the scene refuses them else)."""
    particle = base.device.particle if base.device is not None else None
    if particle is None:
        return
    for leaf, other, unit in (("mass", "density", "kg/m^3"), ("density", "mass", "kg")):
        field = f"device.particle.{leaf}"
        kept = getattr(particle, other)
        if kept is None or f"device.particle.{other}" in values:
            continue
        if field in values or field in swept:
            typed = typed_as(overrides, field, f"--axis {field}")
            typer.echo(f"note: {typed} replaces the scene file's device.particle.{other} = "
                       f"{kept:.6g} {unit} (a device particle is given by one of them)", err=True)


#: (option's field, the field that makes it used, what that must be, the option that gives it)
NEEDS: tuple[tuple[str, str, str, str], ...] = (
    ("material.mu", "effects.friction", "effects.friction = true", "--friction"),
    ("drive.horizontal_ratio", "effects.horizontal_wave", "effects.horizontal_wave = true",
     "--horizontal-wave"),
    ("drive.backward_phase", "drive.backward", "a second wave, drive.backward > 0",
     "--backward S"),
    ("drive.backward_phase_rate", "drive.backward", "a second wave, drive.backward > 0",
     "--backward S"),
)


def _unused_options(scene: sd.Scene, values: dict[str, Any], overrides: Any,
                    swept: tuple[str, ...] = ()) -> None:
    """One line where a value given on the command line is one the scene does not use: --mu
    with --no-friction, --horizontal-ratio with --no-horizontal-wave, --backward-phase(-rate)
    without a second wave. They were accepted and ignored (the same drift to the last bit), as
    --gyration without rotation is not."""
    enabled = {  # what each enabling field of NEEDS is on the scene built
        "effects.friction": scene.effects.friction,
        "effects.horizontal_wave": scene.effects.horizontal_wave,
        "drive.backward": float(getattr(scene.drive, "backward", 0.0) or 0.0) > 0.0,
    }
    for field, enabling, needs, option in NEEDS:
        if field in values and not enabled[enabling] and enabling not in swept:
            typed = typed_as(overrides, field, f"--set {field}")
            # the option that turned it off, as typed (--no-friction), or the scene file's
            given = typed_as(overrides, enabling, f"--set {enabling}")
            if enabling not in values:
                how = f"add {option}"
            elif isinstance(values[enabling], bool) and not given.startswith("--set"):
                how = f"drop --no-{option[2:]}"  # the flag that turned it off
            else:
                how = f"drop {given}"
            raise sd.SceneError(f"{typed} is used only with {needs}: {how}, or drop {typed}")


def refuse_unread_cap(scene: sd.Scene, overrides: Any, swept: tuple[str, ...] = ()) -> None:
    """One line (exit 2) where the command line gives a run's period cap (``--max-periods``,
    ``--set numerics.max_periods``) to a fixed run (``numerics.settle = false``): the cap bounds
    the settling run only, so ``run --no-settle --max-periods 100`` ran its periods and ignored
    it without a word. For the commands whose runs are :func:`sawdrift.run`'s (run, sweep); a
    study that budgets its own runs by the cap (bifurcation) reads it either way, and the scene
    (a file, the Python API) keeps accepting the field (a fixed run reads no cap).

    Parameters
    ----------
    scene
        The scene built from the file and the options.
    overrides
        The command line's ``{dotted field: value}`` (:class:`Overrides`).
    swept
        The fields an axis sets cell by cell: an axis over ``numerics.settle`` settles some cells.
    """
    field, enabling = "numerics.max_periods", "numerics.settle"
    if field not in overrides or enabling in swept or scene.numerics.settle is not False:
        return
    typed = typed_as(overrides, field, f"--set {field}")
    off = typed_as(overrides, enabling)
    if off is None:  # the scene file's numerics.settle = false
        how, off = "add --settle", "the scene file's numerics.settle = false"
    else:
        off = off if off.startswith("--set ") else "--no-settle"  # (typed '--settle False')
        how = f"drop {off}"
    raise sd.SceneError(f"{typed} and {off}: the period cap bounds the settling run only, and a "
                        "fixed run (numerics.settle = false) runs numerics.periods and reads no "
                        f"cap; {how}, or drop {typed}")


def apply_options(data: dict[str, Any], values: dict[str, Any],
                  overrides: dict[str, Any] | None) -> dict[str, Any]:
    """:func:`sawdrift.scene.apply_overrides` with the command line's words in its errors.

    A derived field set on a device scene (``run --amplitude 20`` on the SAW motor) names the
    option as typed and the ``--set device.FIELD=...`` to give instead, one line (exit 2).
    """
    from ..scene.overrides import DERIVED, DerivedFieldError

    try:
        return sd.scene.apply_overrides(data, values)
    except DerivedFieldError as exc:
        typed = typed_as(overrides, exc.field)
        if typed is None:
            raise
        shown = f"{exc.derived:.6g}" if isinstance(exc.derived, float) else repr(exc.derived)
        # without a setting computed for the value asked for, the fields that set it (a fixed
        # example such as radius "0.2 mm" read as the answer, and a cone has no radius)
        how = (f"set the device field with its unit instead: --set {exc.instead}" if exc.instead
               else f"set {DERIVED.get(exc.field, 'its device field')} instead")
        line = (f"{typed}: a device scene derives {exc.field} from its [device] table (here "
                f"{shown}); {how}")
        if exc.field == "drive.amplitude" and isinstance(exc.value, (int, float)):
            line += f" (A* = {exc.value:g} is {exc.value * exc.a0_m * 1e9:.6g} nm on this device)"
        raise sd.SceneError(line) from None


def _check_keys(scene_file: Path, model: str | None) -> None:
    """Name a misspelled key of a scene file with the nearest valid one (one line, exit 2).

    A file that cannot be read or parsed is left to :meth:`sawdrift.Scene.from_toml`'s own
    one-line errors.
    """
    import tomllib

    from ..contact.binding import check_model_params
    from ..scene.schema import check_known_fields

    try:
        data = tomllib.loads(Path(scene_file).read_text(encoding="utf-8-sig"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return
    check_known_fields(data, str(scene_file))
    params = data.get("model_params")
    if isinstance(params, dict) and model in (None, data.get("model", "mmd")):
        check_model_params(str(data.get("model", "mmd")), params, str(scene_file))


def refuse_given_load(scene: Any, command: str, how: str) -> None:
    """One line (exit 2) where a curve over loads (``command``: force-velocity, load-curve) is
    given a load of its own: ``particle.load`` on a normalized scene, ``device.load`` on a
    device (whose incline's pull stays: it is part of every force of the curve). ``how`` says
    how the command picks its loads."""
    device = getattr(scene, "device", None)
    if device is not None:
        if device.load != 0.0:
            raise sd.SceneError(f"device.load = {device.load:g} N: {command} {how}, so a given "
                                "load would be ignored (an incline's pull stays); the speed "
                                "under one load is `sawdrift run`'s")
    elif scene.particle.load != 0.0:
        raise sd.SceneError(f"particle.load = {scene.particle.load:g}: {command} {how}, so a "
                            "given load would be ignored; the speed under one load is `sawdrift "
                            "run --load`'s")
