"""Axes of a sweep: the values of one swept field, from a short text specification."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import SceneError
from ..scene.device import FIELD_KIND, UNITS, field_si, normalized
from ..scene.schema import Scene


def field_kind(name: str) -> str | None:
    """The kind of quantity (``"length"``, ``"frequency"``, ...) of a dotted device field, or None.

    ``device.particle.radius`` is a length, ``device.frequency`` a frequency
    (:data:`sawdrift.scene.device.FIELD_KIND`); a normalized field (``drive.amplitude``) or a
    pure number of a device (``device.friction``) has none.
    """
    if not name.startswith("device."):
        return None
    return FIELD_KIND.get(name.rsplit(".", 1)[-1])


def _end(text: str, spec: str, name: str, kind: str | None) -> tuple[float, bool]:
    """(SI value, had a unit) of one end of a range; one line naming ``name`` if it is not one."""
    try:
        return float(text), False
    except ValueError:
        pass
    if kind is None:
        raise SceneError(f"{name} = {spec!r}: {text.strip()!r} is not a number ({name} takes no "
                         "units; device fields do, e.g. device.frequency=2 MHz:30 MHz:15)")
    try:
        return field_si(name, text), True
    except ValueError as exc:
        raise SceneError(f"{name} = {spec!r}: {text.strip()!r} {exc}") from None


#: an example range of each kind of device field, with its units
RANGE_EXAMPLES = {"length": "10 nm:100 nm:10", "frequency": "2 MHz:30 MHz:15",
                  "force": "1 mN:10 mN:5", "pressure": "70 GPa:210 GPa:5",
                  "density": "1000 kg/m^3:8000 kg/m^3:5", "mass": "1 mg:10 mg:5",
                  "acceleration": "1 m/s^2:9.81 m/s^2:5", "angle": "lin:10 deg:30 deg:3",
                  "surface energy": "0.01 J/m^2:0.1 J/m^2:5"}


def parse_range(spec: str, name: str = "axis", tidy: bool = True) -> list[float] | None:
    """The values of a range ``[lin:|log:]START:STOP:N``, or None if ``spec`` is not a range.

    Without a prefix, and with ``log:``, N log-spaced values (ends included, both > 0); with
    ``lin:`` N evenly spaced ones. On a device field both ends may carry units
    (``2 MHz:30 MHz:15``); the values are then in SI units (Hz, m, N, Pa, kg, rad: what a bare
    number of that field means). A unit on one end only, or two of different dimensions, is one
    line naming the field. Log-spaced values are rounded to 12 significant digits (a column's
    name) unless ``tidy`` is false (the m* and A* axes, :func:`parse_axis`, keep them whole).
    """
    if ":" not in spec:
        return None
    head, _, rest = spec.partition(":")
    way = head.strip().lower() if head.strip().lower() in ("lin", "log") else "log"
    parts = (rest if head.strip().lower() in ("lin", "log") else spec).split(":")
    form = f"{'lin:' if way == 'lin' else ''}START:STOP:N"
    kind = field_kind(name)
    if len(parts) != 3:
        # a device field's example carries its units (it showed 1e-3:1e2:11 for '5 nm:15')
        example = ("e.g. 1e-3:1e2:11 or lin:0.1:1.5:15" if kind is None else
                   f"with units on both ends, e.g. {RANGE_EXAMPLES[kind]}")
        raise SceneError(f"{name} = {spec!r} must be {form} ({'evenly' if way == 'lin' else 'log'}"
                         f"-spaced values), {example}")
    (start, unit_a), (stop, unit_b) = (_end(p, spec, name, kind) for p in parts[:2])
    if unit_a != unit_b:
        raise SceneError(f"{name} = {spec!r}: give units on both ends or on neither (a bare "
                         f"number of {name} is in {_si_unit(kind)})")
    try:
        n = int(parts[2])
    except ValueError:
        raise SceneError(f"{name} = {spec!r}: N = {parts[2].strip()!r} must be an integer") from None
    _two_ends(spec, name, start, stop, n)
    if not 1 <= n <= 100_000:
        lowest = 1 if start == stop else 2  # a range of two ends holds both
        raise SceneError(f"{name} = {spec!r}: N must be in [{lowest}, 100000]")
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise SceneError(f"{name} = {spec!r}: START and STOP must be finite")
    if way == "lin":
        return _tidy(np.linspace(start, stop, n))
    if not (start > 0 and stop > 0):
        raise SceneError(f"{name} = {spec!r}: START and STOP must be > 0 for a log-spaced axis "
                         "(lin:START:STOP:N spaces them evenly)")
    values = np.geomspace(start, stop, n) if n > 1 else np.array([start])
    return _tidy(values) if tidy else [float(v) for v in values]


def _value_list(values: np.ndarray) -> str:
    return ", ".join(str(float(v)) for v in values[:3])


def _two_ends(spec: str, name: str, start: float, stop: float, n: int) -> None:
    """One line naming ``name`` for a range of two different ends and N = 1: the range holds
    both ends, so it needs N >= 2 (N = 1 would silently drop STOP)."""
    if n < 2 and start != stop:
        raise SceneError(f"{name} = {spec!r}: N = {n} cannot hold both ends of a range; give "
                         "N >= 2 (both ends included), or one value without a range")


def _items(spec: str, name: str) -> list[str]:
    """The items of a comma list, stripped; one line naming ``name`` for an empty one
    (``0.1,,1`` or a trailing comma), which would otherwise be dropped silently."""
    items = [v.strip() for v in spec.split(",")]
    if len(items) > 1 and not all(items):
        raise SceneError(f"{name} = {spec!r} has an empty value between commas; give a,b,c "
                         "with a value in every place")
    return [v for v in items if v]


def _tidy(values: np.ndarray) -> list[float]:
    """The values to 12 significant digits: 3e-08, not 3.0000000000000004e-08 (a column's name)."""
    return [float(f"{v:.12g}") for v in values]


def _si_unit(kind: str | None) -> str:
    return UNITS[kind][1] if kind is not None else "normalized units"


def parse_values(spec: str | Sequence[Any], name: str = "axis") -> list[Any]:
    """Values of one ``--axis FIELD=SPEC``: numbers, booleans, or strings with units.

    A range (:func:`parse_range`): ``START:STOP:N`` or ``log:START:STOP:N`` gives N log-spaced
    numbers, ``lin:START:STOP:N`` N evenly spaced ones, with units on both ends for a device
    field (``device.frequency=2 MHz:30 MHz:15``, values in SI units). A comma list gives its
    items: numbers, ``true``/``false``, or quantities with units ("5 nm") that the scene's
    device block converts.
    """
    if not isinstance(spec, str):
        return list(spec)
    values = parse_range(spec, name)
    if values is not None:
        return _once_each(values, name, spec)
    out: list[Any] = []
    for item in _items(spec, name):
        if item.lower() in ("true", "false"):
            out.append(item.lower() == "true")
            continue
        try:
            out.append(float(item))
        except ValueError:
            out.append(item)
    if not out:
        raise SceneError(f"{name} = {spec!r} must hold at least one value")
    return _once_each(out, name, spec)


def _once_each(values: list[Any], name: str, spec: str) -> list[Any]:
    """``values``, or one line where one is given twice: a number or a boolean equal to another,
    or a quantity written the same but for spaces (case counts: 1 mHz is not 1 MHz). The
    repeated cell ran twice (a field's species printed twice, a threshold's slopes n/a); m* and
    A* axes refuse it too."""
    seen: list[Any] = []
    for v in values:
        key = "".join(v.split()) if isinstance(v, str) else v
        if any(type(key) is type(k) and key == k for k in seen):
            shown = f"{v:g}" if isinstance(v, float) else str(v)
            raise SceneError(f"{name} = {spec!r} gives {shown} more than once: give each value once")
        seen.append(key)
    return values


#: the forms :func:`parse_axis` accepts, said by its errors
AXIS_FORMS = ("START:STOP:N or log:START:STOP:N (N log-spaced values, ends > 0), "
              "lin:START:STOP:N (N evenly spaced values) or a comma list a,b,c")


def parse_axis(spec: str | Sequence[float], name: str = "axis") -> np.ndarray:
    """Grid values of an m* or A* axis.

    ``START:STOP:N`` or ``log:START:STOP:N`` gives N log-spaced values (both ends included and
    > 0), ``lin:START:STOP:N`` N evenly spaced ones (as an ``--axis`` range does; a value the
    field does not allow is refused by the scene's validation), ``a,b,c`` its items (no empty
    one). A range needs N >= 2, or N = 1 when START = STOP.

    Parameters
    ----------
    spec
        The specification, or a sequence of numbers.
    name
        The axis's name, said in an error.

    Returns
    -------
    numpy.ndarray
        The values, all finite.

    Raises
    ------
    SceneError
        With one line naming ``name`` (and the accepted forms) when ``spec`` is malformed.
    """
    if not isinstance(spec, str):
        values = np.asarray(list(spec), dtype=float)
    elif ":" in spec:
        values = _axis_range(spec, name)
    else:
        items = _items(spec, name)
        try:
            values = np.array([float(v) for v in items], dtype=float)
        except ValueError:
            raise SceneError(f"{name} = {spec!r} must be {AXIS_FORMS} of numbers") from None
    if values.size == 0:
        raise SceneError(f"{name} = {spec!r} must hold at least one value")
    if not np.all(np.isfinite(values)):
        # '1,nan' was told it must hold at least one finite value
        raise SceneError(f"{name} = {spec!r} holds a value that is not a finite number "
                         f"({_value_list(values[~np.isfinite(values)])}): every value must be finite")
    distinct, counts = np.unique(values, return_counts=True)
    if isinstance(spec, str) and (counts > 1).any():
        # 0.1,0.1 or 0.1:0.1:3 collapsed to one cell without a word (bifurcation refuses them)
        raise SceneError(f"{name} = {spec!r} gives {distinct[counts > 1][0]:g} more than once: "
                         "give each value once (a range from START to STOP = START: N = 1)")
    return values


def _axis_range(spec: str, name: str) -> np.ndarray:
    """The values of a range ``[lin:|log:]START:STOP:N`` of :func:`parse_axis`
    (:func:`parse_range`, its log-spaced values kept whole); a malformed one names the forms an
    axis takes."""
    head, _, rest = spec.partition(":")
    if len((rest if head.strip().lower() in ("lin", "log") else spec).split(":")) != 3:
        raise SceneError(f"{name} = {spec!r} must be {AXIS_FORMS}")
    return np.array(parse_range(spec, name, tidy=False))


#: SI units of the device columns a sweep table adds (:func:`sawdrift.study.sweep.run_cell`)
SI_COLUMNS = {"drift_speed_m_s": "m/s", "drift_speed_se_m_s": "m/s", "a0_m": "m", "load_N": "N",
              "detach_time_s": "s"}

#: how the normalized columns are written on an axis
NORMALIZED_LABELS = {"amplitude": "A*", "m_star": "m*", "drift_ratio": "drift ratio",
                     "drift_velocity": "drift velocity x*' (a0 f)"}

_LONG = {"drift_speed_m_s": "drift speed", "a0_m": "static compression a0",
         "load_N": "tangential load on the particle, along +x",
         "drift_speed_se_m_s": "standard error of a long-time mean drift speed",
         "detach_time_s": "time of an ejected particle's last lift-off"}


def column_unit(column: str) -> str | None:
    """The SI unit of a table column (a device field, ``drift_speed_m_s``, ``a0_m``, ``load_N``),
    or None for a normalized or dimensionless one. An angle is in rad (a bare number of it)."""
    if column in SI_COLUMNS:
        return SI_COLUMNS[column]
    kind = field_kind(column)
    return None if kind is None else _si_unit(kind)


def column_label(column: str) -> str:
    """An axis label: ``A*``, ``m*``, ``drift speed (m/s)``, ``device.frequency (Hz)``."""
    unit = column_unit(column)
    name = _LONG.get(column, NORMALIZED_LABELS.get(column, column))
    return f"{name} ({unit})" if unit else name


def long_name(column: str) -> str | None:
    """A CF ``long_name`` of an SI column (None where the column's name says it)."""
    return _LONG.get(column)


def device_columns(scene: Scene) -> tuple[dict[str, float], float]:
    """The SI columns of a device cell (``a0_m``, ``load_N``) and its speed scale a0 f in m/s.

    A normalized speed x*' is x*' a0 f in m/s (:mod:`sawdrift.scene.device`); ``load_N`` is the
    tangential load F = device.load - m g sin(alpha) along +x.
    """
    norm = normalized(scene.device)  # type: ignore[arg-type]
    return ({"a0_m": norm["a0_m"], "load_N": norm["load_n"], "_frequency": norm["frequency_hz"]},
            norm["a0_m"] * norm["frequency_hz"])


def add_columns(row: dict[str, Any], columns: dict[str, Any]) -> None:
    """Add a cell's swept-field and SI columns to its row: ``drift_speed_m_s`` = x*' a0 f, its
    standard error (a long-time mean's: drift_ratio_se 2 pi r A* a0 f) and an ejection's
    ``detach_time_s`` = t* / f, as ``sawdrift run --json`` gives them."""
    extra = dict(columns)
    scale = extra.pop("_speed_scale", None)
    frequency = extra.pop("_frequency", None)
    row.update(extra)
    if scale is not None:
        v = row.get("drift_velocity")
        row["drift_speed_m_s"] = v * scale if v is not None else None
        se, a, r = (row.get(k) for k in ("drift_ratio_se", "amplitude", "horizontal_ratio"))
        row["drift_speed_se_m_s"] = (se * 2.0 * math.pi * r * a * scale
                                     if None not in (se, a, r) and math.isfinite(se) else None)
    if frequency is not None:
        t = row.get("detach_time")
        row["detach_time_s"] = t / frequency if t is not None and math.isfinite(t) else None
