"""Numbers written as text in a scene file: ``m_star = "10"`` is a user error, not a number.

pydantic's lax mode reads the string ``"10"`` as the number 10, so a quoted number in a TOML
file ran as if it had been written without quotes. In a file a number has its own syntax; a
quoted one is a typo of type (often a number pasted with its quotes from elsewhere), refused in
one line naming the dotted field. The command line is another matter: ``--set
particle.m_star=10`` arrives as text and is parsed on purpose (:func:`sawdrift.cli.scene_options
.parse_set`), and does not come through here. A device quantity (``radius = "0.5 mm"``,
:data:`~sawdrift.scene.units.FIELD_KIND`) is text by design and is not looked at.
"""

from __future__ import annotations

import math
import types
import typing
from collections.abc import Mapping
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator

from ..errors import SceneError
from .units import FIELD_KIND

__all__ = ["refuse_quoted_fields", "refuse_quoted_numbers"]


def _parts(annotation: Any) -> tuple[list[Any], list[Any]]:
    """The types an annotation can hold (through Annotated, Optional and Union; None left out)
    and the metadata met on the way (validators)."""
    if typing.get_origin(annotation) is Annotated:
        base, *extra = typing.get_args(annotation)
        inner, more = _parts(base)
        return inner, [*extra, *more]
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        kinds: list[Any] = []
        meta: list[Any] = []
        for arg in typing.get_args(annotation):
            if arg is type(None):
                continue
            inner, more = _parts(arg)
            kinds += inner
            meta += more
        return kinds, meta
    return [annotation], []


def _is_number(annotation: Any, metadata: list[Any], leaf: str) -> bool:
    """Whether a field holds a plain number (float or int, not bool), not text: a device
    quantity reads its own text with units (a BeforeValidator on a :data:`FIELD_KIND` field)."""
    kinds, meta = _parts(annotation)
    meta = [*metadata, *meta]
    if not kinds or any(k not in (float, int) for k in kinds):
        return False
    return not (leaf in FIELD_KIND and any(isinstance(m, BeforeValidator) for m in meta))


def _models(annotation: Any) -> list[type[BaseModel]]:
    """The pydantic models a field can hold."""
    kinds, _ = _parts(annotation)
    return [k for k in kinds if isinstance(k, type) and issubclass(k, BaseModel)]


def _items(annotation: Any) -> Any:
    """The item annotation of a list field (the samples of a prescribed path), or None."""
    kinds, _ = _parts(annotation)
    for kind in kinds:
        if typing.get_origin(kind) in (list, tuple) and typing.get_args(kind):
            return typing.get_args(kind)[0]
    return None


def _refuse(path: str, value: str, source: str | None) -> None:
    """One line if ``value`` (text) is a number written as text."""
    try:
        number = float(value.strip())
    except ValueError:
        return  # not a number: the schema names what is wrong with it
    where = f"{source}: " if source else ""
    if not math.isfinite(number):  # "inf" unquoted is refused by the field's range in turn
        raise SceneError(f"{where}{path} = {value!r} is text (in quotes), and not a finite "
                         "number: a finite number is expected")
    leaf = path.rsplit(".", 1)[-1]
    shown = value.strip() if "[" in leaf else f"{leaf} = {value.strip()}"
    raise SceneError(f"{where}{path} = {value!r} is a number written as text (in quotes): a "
                     f"number is expected; write {shown} without quotes")


def _is_bool(annotation: Any) -> bool:
    """Whether a field holds a boolean (Optional or not)."""
    kinds, _ = _parts(annotation)
    return kinds == [bool]


def _refuse_bool(path: str, value: Any, source: str | None) -> None:
    """One line for a boolean field given text or a number (pydantic's lax mode read "yes",
    "off", "true" and 1 as booleans)."""
    where = f"{source}: " if source else ""
    leaf = path.rsplit(".", 1)[-1]
    raise SceneError(f"{where}{path} = {value!r} is not a boolean: true or false is expected; "
                     f"write {leaf} = true or {leaf} = false, without quotes")


def _walk(data: Mapping[str, Any], models: list[type[BaseModel]], source: str | None,
          prefix: str) -> None:
    """:func:`refuse_quoted_numbers` of one table read against the ``models`` it may be (a
    drive of any kind): a field is a number (or a boolean) where every model that has it says
    so."""
    for key, value in data.items():
        infos = [m.model_fields[key] for m in models if key in m.model_fields]
        if not infos:
            continue  # not a field (check_known_fields names it), or model_params (bind's)
        path = f"{prefix}{key}"
        if not isinstance(value, bool) and all(_is_bool(i.annotation) for i in infos):
            _refuse_bool(path, value, source)
        if isinstance(value, str):
            if all(_is_number(i.annotation, i.metadata, key) for i in infos):
                _refuse(path, value, source)
        elif isinstance(value, Mapping):
            inner = [m for i in infos for m in _models(i.annotation)]
            if inner:
                _walk(value, inner, source, f"{path}.")
        elif isinstance(value, list):
            items = [_items(i.annotation) for i in infos]
            if items and all(t is not None and _is_number(t, [], key) for t in items):
                for n, item in enumerate(value):
                    if isinstance(item, str):
                        _refuse(f"{path}[{n}]", item, source)


def refuse_quoted_numbers(data: Mapping[str, Any], scene: type[BaseModel],
                          source: str | None = None) -> None:
    """Raise a one-line SceneError for the first number written as text in a scene file's
    table ``data`` (the module text), naming its dotted field.

    Parameters
    ----------
    data
        The file's table, as ``tomllib`` read it.
    scene
        The Scene class (its fields, ``[device]`` and the drives included, are walked).
    source
        The file, to name in the line.

    Raises
    ------
    SceneError
        ``FILE: particle.m_star = '10' is a number written as text (in quotes): a number is
        expected; write m_star = 10 without quotes``. The model's parameters
        (``[model_params]``), which this layer knows nothing of, are read when the scene is
        bound to its model (:func:`refuse_quoted_fields`, from
        :func:`sawdrift.contact.binding.bind`): from a file or from Python alike.
    """
    _walk(data, [scene], source, "")


def refuse_quoted_fields(table: Mapping[str, Any], schema: Any, source: str | None,
                         prefix: str) -> None:
    """:func:`refuse_quoted_numbers` for another table read against its own pydantic class
    ``schema`` (nothing where it is not one), its fields named ``prefix`` + name: a model's
    ``[model_params]`` (``"model_params."``, :func:`sawdrift.contact.binding.bind`), a
    mixture's ``[particles]`` (``"particles."``)."""
    if isinstance(schema, type) and issubclass(schema, BaseModel):
        _walk(table, [schema], source, prefix)
