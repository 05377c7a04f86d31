"""Validators of a scene's numbers: a finite value in its interval, never a boolean.

Pydantic reads ``true`` as 1 for a number (``--set drive.amplitude=true`` ran at A* = 1, a TOML
``m_star = true`` at m* = 1, ``--param restitution=true`` at e = 1): a boolean given for a
number is a mistake to name, not a value to convert. The numeric fields of a scene, its device
and its profile are declared through :func:`bounded` (floats) or :func:`count` (integers), which
refuse it in one line (the sample lists of a prescribed path: :data:`Number`).
"""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import Field, ValidationError, WrapValidator

__all__ = ["AMPLITUDE_MAX", "M_STAR_RANGE", "Number", "bounded", "count", "interval",
           "not_bool"]

#: The range of m* = a0 m f^2 / (M g) a scene may have (a device's derived one too). m* is
#: 1.5 / (2 pi)^2 times the squared ratio of the wave's frequency to the contact's normal natural
#: frequency. Above 1e10 one window of a heavy particle's settle alone spans 3 periods of the
#: contact's oscillation, over a million wave periods; below 1e-12 the contact oscillates more
#: than 1e5 times a period, beyond the 1e7 steps a period a compliant model takes at most.
#: Beyond both the arithmetic overflowed (m* = 5e-324 or 1e308 ended in an internal failure).
M_STAR_RANGE = (1e-12, 1e10)

#: the largest A* a scene may have (a device's 1 cm on a static compression of 10 pm)
AMPLITUDE_MAX = 1e9

#: the message of a boolean given for a number
NOT_A_NUMBER = "is a boolean (true/false), not a number"


def not_bool(value: Any, handler: Any) -> Any:
    """A wrap validator's first step: refuse a boolean (module text), else validate ``value``
    as the field's type does."""
    if isinstance(value, bool):
        raise ValueError(NOT_A_NUMBER)
    return handler(value)


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
        try:
            value = not_bool(value, handler)
        except ValidationError:  # "Input should be a valid number" named no range ('0.3 m')
            raise ValueError(f"is not a number: give one in {text}" if what != "not finite"
                             else "is not a number") from None
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


#: a float that refuses a boolean, with no range (the samples of a prescribed path)
Number = Annotated[float, WrapValidator(not_bool)]


def count(lo: int, hi: int) -> Any:
    """An integer field in [lo, hi] that refuses a boolean (module text)."""
    return Annotated[int, WrapValidator(not_bool), Field(ge=lo, le=hi)]
