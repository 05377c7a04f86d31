"""Axes of a sweep: the values of one swept field, from a short text specification."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import SceneError


def parse_values(spec: str | Sequence[Any], name: str = "axis") -> list[Any]:
    """Values of one ``--axis FIELD=SPEC``: numbers, booleans, or strings with units.

    ``START:STOP:N`` gives N log-spaced numbers, ``lin:START:STOP:N`` N evenly spaced ones; a comma
    list gives its items: numbers, ``true``/``false``, or quantities with units ("5 nm") that the
    scene's device block converts.
    """
    if not isinstance(spec, str):
        return list(spec)
    if spec.startswith("lin:"):
        parts = spec.split(":")[1:]
        try:
            start, stop, n = float(parts[0]), float(parts[1]), int(parts[2])
            if len(parts) != 3 or not 1 <= n <= 100_000:
                raise ValueError
        except (ValueError, IndexError):
            raise SceneError(f"{name} = {spec!r} must be lin:START:STOP:N with 1 <= N <= 100000") from None
        return np.linspace(start, stop, n).tolist()
    if ":" in spec:
        return parse_axis(spec, name).tolist()
    out: list[Any] = []
    for item in (v.strip() for v in spec.split(",")):
        if not item:
            continue
        if item.lower() in ("true", "false"):
            out.append(item.lower() == "true")
            continue
        try:
            out.append(float(item))
        except ValueError:
            out.append(item)
    if not out:
        raise SceneError(f"{name} = {spec!r} must hold at least one value")
    return out


def parse_axis(spec: str | Sequence[float], name: str = "axis") -> np.ndarray:
    """Grid values from ``START:STOP:N`` (N log-spaced values, ends included) or ``a,b,c``.

    Raises
    ------
    SceneError
        With one line naming ``name`` when the specification is malformed.
    """
    if not isinstance(spec, str):
        values = np.asarray(list(spec), dtype=float)
    elif ":" in spec:
        parts = spec.split(":")
        if len(parts) != 3:
            raise SceneError(f"{name} = {spec!r} must be START:STOP:N (N log-spaced values)")
        try:
            start, stop, n = float(parts[0]), float(parts[1]), int(parts[2])
        except ValueError:
            raise SceneError(
                f"{name} = {spec!r} must be START:STOP:N with numbers START, STOP > 0 and an integer N"
            ) from None
        if not (start > 0 and stop > 0 and math.isfinite(start) and math.isfinite(stop)):
            raise SceneError(f"{name} = {spec!r}: START and STOP must be > 0 for a log-spaced axis")
        if not 1 <= n <= 100_000:
            raise SceneError(f"{name} = {spec!r}: N must be in [1, 100000]")
        values = np.geomspace(start, stop, n) if n > 1 else np.array([start])
    else:
        try:
            values = np.array([float(v) for v in spec.split(",") if v.strip()], dtype=float)
        except ValueError:
            raise SceneError(f"{name} = {spec!r} must be START:STOP:N or a comma list of numbers") from None
    if values.size == 0 or not np.all(np.isfinite(values)):
        raise SceneError(f"{name} = {spec!r} must hold at least one finite value")
    return values
