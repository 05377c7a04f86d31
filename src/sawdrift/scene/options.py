"""Command-line options generated from the Scene schema (name, help, allowed range or choices).

Every field of the scene's parts (material, particle and its profile, the wave drive, numerics,
effects) becomes one option of the commands that build a scene (``run``, ``sweep`` and the
studies), named after the field (``particle.m_star`` -> ``--m-star``; a profile field after the
profile, ``particle.profile.exponent`` -> ``--profile-exponent``, its shape is ``--profile``).
A new scene field is thereby a new option without editing the command line.

Reading the schema imports pydantic and the scene (about 0.3 s), which ``sawdrift --help`` should
not pay: :func:`write_table` freezes the options into the plain module
``sawdrift/_scene_options.py``, and a test checks that it matches the schema (regenerate with
``python -m sawdrift.scene.options``).
"""

from __future__ import annotations

import types
import typing
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel

from .parts import Effects, Material, Numerics, Particle, Wave
from .profiles import Profile

#: (prefix of the dotted path, part model): the scene parts that become options
PARTS: tuple[tuple[str, type[BaseModel]], ...] = (
    ("material", Material),
    ("particle", Particle),
    ("particle.profile", Profile),
    ("drive", Wave),
    ("numerics", Numerics),
    ("effects", Effects),
)

#: fields that are not options: the drive's tag, the nested profile (its fields are options)
SKIP = {"drive.kind", "particle.profile", "particle.profile.file"}

GENERATED = Path(__file__).resolve().parents[1] / "_scene_options.py"


def _kind(annotation: Any) -> tuple[str, tuple[str, ...]]:
    """("float" | "int" | "bool" | "choice", choices) of a field annotation."""
    args = typing.get_args(annotation)
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        return _kind(args[0])
    if origin in (typing.Union, types.UnionType):
        inner = [a for a in args if a is not type(None)]
        return _kind(inner[0])
    if origin is Literal:
        return "choice", tuple(str(a) for a in args)
    if annotation is bool:
        return "bool", ()
    if annotation is int:
        return "int", ()
    if annotation is float:
        return "float", ()
    raise TypeError(f"no option type for {annotation!r}")


def _metadata(annotation: Any) -> list[Any]:
    """Constraint and validator objects of an annotation, through Optional and Annotated."""
    out: list[Any] = []
    args = typing.get_args(annotation)
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        for meta in args[1:]:
            out += [meta, *getattr(meta, "metadata", ())]  # a Field(...) carries its ge/le
        out += _metadata(args[0])
    elif origin in (typing.Union, types.UnionType):
        for a in args:
            out += _metadata(a)
    return out


def _range(field: Any) -> str:
    """The allowed interval of a field, from its validators or its ge/le constraints."""
    metadata = list(field.metadata) + _metadata(field.annotation)
    for meta in metadata:
        interval = getattr(getattr(meta, "func", None), "interval", None)
        if interval:
            return interval
    lo = hi = None
    lo_open = hi_open = False
    for meta in metadata:
        for attr, open_ in (("ge", False), ("gt", True)):
            if getattr(meta, attr, None) is not None:
                lo, lo_open = getattr(meta, attr), open_
        for attr, open_ in (("le", False), ("lt", True)):
            if getattr(meta, attr, None) is not None:
                hi, hi_open = getattr(meta, attr), open_
    if lo is None and hi is None:
        return ""
    left = ("(" if lo_open else "[") + ("-inf" if lo is None else f"{lo:g}")
    right = "inf)" if hi is None else f"{hi:g}" + (")" if hi_open else "]")
    return f"{left}, {right}"


#: options named otherwise than their field's leaf (two leaves would clash)
RENAMED = {"particle.profile.shape": "profile", "material.adhesion": "pulloff"}


def _name(dotted: str) -> str:
    if dotted in RENAMED:
        return RENAMED[dotted]
    if dotted.startswith("particle.profile."):
        return "profile-" + dotted.rsplit(".", 1)[1].replace("_", "-")
    return dotted.rsplit(".", 1)[1].replace("_", "-")


def scene_options() -> tuple[tuple[str, str, str, tuple[str, ...], str], ...]:
    """(option name, dotted field, kind, choices, help) for every scene field, schema order."""
    rows = []
    for prefix, model in PARTS:
        for field_name, field in model.model_fields.items():
            dotted = f"{prefix}.{field_name}"
            if dotted in SKIP:
                continue
            kind, choices = _kind(field.annotation)
            text = (field.description or "").rstrip(".")
            allowed = _range(field)
            if kind == "choice":
                text = f"{text}; one of {', '.join(choices)}" if text else f"one of {', '.join(choices)}"
            elif allowed and allowed not in text:
                text = f"{text}; in {allowed}" if text else f"in {allowed}"
            default = field.default
            if default is not None and kind != "bool":
                text += f"; scene default {default}"
            rows.append((_name(dotted), dotted, kind, choices, f"{dotted}: {text}"))
    names = [r[0] for r in rows]
    clash = {n for n in names if names.count(n) > 1}
    if clash:
        raise ValueError(f"scene fields give the same option name: {sorted(clash)}")
    return tuple(rows)


def render() -> str:
    """The source of ``sawdrift/_scene_options.py``."""
    lines = [
        "# ruff: noqa: E501",
        '"""Generated from the Scene schema by ``python -m sawdrift.scene.options``. Do not edit.',
        "",
        "One row per scene field: (option name, dotted field, kind, choices, help).",
        '"""',
        "",
        "OPTIONS = (",
    ]
    lines += [f"    {row!r}," for row in scene_options()]
    lines.append(")")
    return "\n".join(lines) + "\n"


def write_table(path: Path = GENERATED) -> Path:
    """Write :func:`render` to ``path``."""
    path.write_text(render())
    return path


if __name__ == "__main__":
    print(f"wrote {write_table()}")
