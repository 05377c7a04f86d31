"""Validators of a scene's numbers: a finite value in its interval, never a boolean.

Pydantic reads ``true`` as 1 for a number (``--set drive.amplitude=true`` ran at A* = 1, a TOML
``m_star = true`` at m* = 1, ``--param restitution=true`` at e = 1): a boolean given for a
number is a mistake to name, not a value to convert. Every numeric field of a scene is declared
through :func:`bounded` (floats) or :func:`count` (integers), which refuse it in one line.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import Field, WrapValidator

__all__ = ["bounded", "count", "interval"]

#: the message of a boolean given for a number
NOT_A_NUMBER = "is a boolean (true/false), not a number"


def interval(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    """``[lo, hi)`` and the like, as the one-line errors and the option help show it."""
    left = ("(" if lo_open else "[") + ("-inf" if lo is None else f"{lo:g}")
    right = "inf)" if hi is None else f"{hi:g}" + (")" if hi_open else "]")
    return f"{left}, {right}"


def bounded(
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
) -> WrapValidator:
    """A validator that rejects booleans, NaN, infinities and values outside an interval,
    naming it."""
    text = interval(lo, hi, lo_open, hi_open)
    # a field bounded by another field: its finite check says so, not "outside [-inf, inf)"
    what = "outside the allowed range " + text if lo is not None or hi is not None else "not finite"

    def check(value: Any, handler: Any) -> float:
        if isinstance(value, bool):
            raise ValueError(NOT_A_NUMBER)
        value = handler(value)
        ok = math.isfinite(value)
        if ok and lo is not None:
            ok = value > lo if lo_open else value >= lo
        if ok and hi is not None:
            ok = value < hi if hi_open else value <= hi
        if not ok:
            raise ValueError(f"is {what}")
        return value

    # read by sawdrift.scene.options (a field bounded by another field says so in its description)
    check.interval = text if lo is not None or hi is not None else ""  # type: ignore[attr-defined]
    return WrapValidator(check)


def _whole(value: Any, handler: Any) -> int:
    if isinstance(value, bool):
        raise ValueError(NOT_A_NUMBER)
    return handler(value)


def count(lo: int, hi: int) -> Any:
    """An integer field in [lo, hi] that refuses a boolean (module text)."""
    return Annotated[int, WrapValidator(_whole), Field(ge=lo, le=hi)]
