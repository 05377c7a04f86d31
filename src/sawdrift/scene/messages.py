"""One-line validation messages of the scene's parts: the first offending field, its value and
what is allowed."""

from __future__ import annotations

import math
from typing import Any

from pydantic import ValidationError

from .parts import Impact, Prescribed, Wave

#: Tags of the drive union (the ``kind`` of each drive class).
_DRIVE_KINDS = tuple(cls.model_fields["kind"].default for cls in (Wave, Prescribed, Impact))


#: pydantic's error types of a numeric bound
_BOUNDS = ("greater_than", "greater_than_equal", "less_than", "less_than_equal")


def _finite(value: Any) -> bool:
    """Whether ``value`` reads as a finite number (what is not a number at all passes: its own
    error says so)."""
    try:
        return math.isfinite(float(value))
    except (TypeError, ValueError, OverflowError):
        return True


def format_validation_error(exc: ValidationError, source: str | None = None) -> str:
    """One line naming the first offending field, its value and what is allowed; a field not
    known comes first (a typo 'radii' was reported as 'radius is required' alone)."""
    errors = exc.errors()
    err = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
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
    if err["type"] == "union_tag_invalid":
        # pydantic's text named the discriminator function ("found using _drive_kind()")
        ctx = err.get("ctx", {})
        return (f"{where}{loc}.kind = {ctx.get('tag')!r} is not a kind of drive: use one of "
                f"{ctx.get('expected_tags')}")
    if loc:
        value = err.get("input")
        if err["type"] in _BOUNDS and not _finite(value):
            # 'nan' met only the bound it was compared with: "Input should be less than 1"
            return f"{where}{loc} = {value!r} is not a finite number ({msg[:1].lower()}{msg[1:]})"
        if isinstance(value, (int, float, str, bool)):
            shown = str(value).lower() if isinstance(value, bool) else repr(value)  # as in TOML
            return f"{where}{loc} = {shown} {msg}" if msg.startswith("is ") else (
                f"{where}{loc} = {shown}: {msg}"
            )
        return f"{where}{loc}: {msg}"
    if msg.startswith("model_params."):
        return f"{where}{msg}"
    return f"{where}scene: {msg}"
