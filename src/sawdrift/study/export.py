"""Sweep tables as gridded datasets: xarray, netCDF (CF conventions), zarr.

A sweep table has one row per cell. :func:`to_dataset` turns it into an ``xarray.Dataset`` whose
dimensions are the swept fields (:func:`dimensions`: the columns that vary across cells and are
not fixed by the others: every ``--axis`` field, m_star and amplitude when swept themselves, and
model when the table holds several), with

* the columns a swept field fixes (m* and A* of a device swept over its frequency) as
  non-dimension coordinates over the fields that fix them, not as more dimensions;
* the SI columns of a device sweep (``drift_speed_m_s``, ``a0_m``, ``load_N``) and the device
  fields with their ``units`` in ``attrs``;

* ``regime`` as an integer variable carrying CF ``flag_values`` / ``flag_meanings`` (-1: no cell);
* the drift (``drift_ratio``, ``drift_velocity``, the standard error ``drift_ratio_se`` of a
  long-time mean, NaN where the drift settled) and the evidence of each cell as variables;
* how each cell was resolved (``resolved_as``) and its ``warnings`` (joined with "; ", as the
  table stores them; "" for none or no cell) as string variables, ``chaotic`` as 1/0 and
  ``orbit_period`` (0: no periodic orbit);
* the provenance in ``attrs``: ``sawdrift_version``, ``sawdrift_code`` (the code hash, see
  :mod:`sawdrift.study.provenance`), ``base_scene`` (the sweep's base scene as
  JSON, when the table's metadata has it) and ``Conventions = "CF-1.8"``.

:func:`load_grid` reads a file written by :func:`write_grid` (``.nc`` or ``.zarr``) back.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..errors import SceneError
from ..result.regimes import REGIMES
from .axes import column_unit, long_name
from .provenance import UNREADABLE_BASE
from .table import table_metadata

#: per-cell variables exported when present
VARIABLES = (
    "drift_ratio", "drift_velocity", "gross_slip_fraction", "creep", "liftoffs_per_period",
    "hop_period",
    "liftoff_phase", "liftoff_phase_spread", "lyapunov", "periodicity", "out_of_contact_fraction",
    "min_compression", "contact_lost", "spin_rate", "steps_per_period", "wall_time_s", "settled",
    "settle_periods", "events_dropped", "drift_speed_m_s", "a0_m", "load_N", "drift_ratio_se",
    "chaotic", "orbit_period", "drift_speed_se_m_s", "mean_acceleration", "detach_time",
    "detach_time_s",
)

#: scene columns every table holds: kept as scalar coordinates where they take one value (a
#: reader of the file otherwise had only base_scene, the scene the sweep started from, whose
#: m* = 0.1 was not the cells' 0.5)
FIXED = ("m_star", "amplitude", "mu", "nu", "horizontal_ratio")

#: per-cell text variables exported when present, as strings ("" where a cell has none)
STRINGS = ("resolved_as", "warnings")

#: descriptions of the exported variables that sawdrift.study.axes does not name
_LONG_NAMES = {
    "drift_ratio_se": "standard error of drift_ratio of a long-time mean (batch means, or a "
                      "heavy bouncer's weighted mean where its record is quasi-periodic); NaN "
                      "where the drift settled",
    "resolved_as": "how the cell's steady state was resolved: periodic_orbit, "
                   "quasi_periodic, fixed_point, chaotic_mean, long_time_mean, runaway, ejected "
                   "or not_settled",
    "warnings": "the cell's warnings, joined with '; ' ('' for none)",
    "chaotic": "1 if the largest Lyapunov exponent shows chaos, 0 if not (NaN: no cell)",
    "orbit_period": "periods after which the stroboscopic state repeats (0: no periodic orbit)",
    "mean_acceleration": "a runaway's mean acceleration, x* per period squared (NaN otherwise)",
    "detach_time": "an ejected particle's last lift-off, t* in periods (NaN otherwise)",
    "drift_velocity": "the cell's drift velocity (its steady drift, long-time mean or window "
                      "mean), in static compressions a0 per wave period (times a0 f: m/s, the "
                      "drift_speed_m_s of a device sweep)",
}

#: units of normalized variables (CF: "1" for a number of sawdrift's scaling, its long_name
#: saying which); the SI columns get theirs from sawdrift.study.axes.column_unit
_NORMALIZED_UNITS = {"drift_velocity": "1", "drift_ratio": "1", "drift_ratio_se": "1"}

#: regime codes: flag_values are 0..n-1 in the order of sawdrift.result.regimes.REGIMES
REGIME_FLAGS = (*REGIMES, "error")


def _candidates(table: pd.DataFrame) -> list[str]:
    """Columns that may be swept, the explicit axes (dotted fields) before m* and A*."""
    out = ["model", *[c for c in table.columns if "." in c], "m_star", "amplitude"]
    return [c for c in out if c in table.columns and table[c].nunique(dropna=True) > 1]


def _fixed_by(table: pd.DataFrame, column: str, by: list[str]) -> bool:
    """Whether ``column`` takes one value for each combination of the columns ``by``."""
    if not by:
        return table[column].nunique(dropna=True) <= 1
    counts = table.groupby(by, dropna=False)[column].nunique(dropna=True)
    return bool((counts <= 1).all())


def dimensions(table: pd.DataFrame) -> list[str]:
    """The swept columns: those that vary and are not fixed by the swept columns before them.

    The explicit axes (dotted fields: ``device.frequency``) come first; m* and A* are
    dimensions only where they vary on their own (a normalized sweep), not where a device field
    fixes them (a sweep over ``device.frequency`` changes m*: m* is then a coordinate,
    :func:`derived`).
    """
    dims: list[str] = []
    for column in _candidates(table):
        if column == "model" or not _fixed_by(table, column, dims):
            dims.append(column)
    return dims


def derived(table: pd.DataFrame, dims: list[str] | None = None) -> dict[str, list[str]]:
    """``{column: the dimensions that fix it}`` of each varying column that is no dimension."""
    from itertools import combinations

    dims = dimensions(table) if dims is None else dims
    out: dict[str, list[str]] = {}
    for column in _candidates(table):
        if column in dims:
            continue
        for size in range(1, len(dims) + 1):
            found = next((list(c) for c in combinations(dims, size)
                          if _fixed_by(table, column, list(c))), None)
            if found is not None:
                out[column] = found
                break
    return out


def to_dataset(table: pd.DataFrame, metadata: dict[str, Any] | None = None):
    """The table as an ``xarray.Dataset`` over its swept fields (see the module docstring)."""
    import xarray as xr

    dims = dimensions(table)
    if not dims:
        raise SceneError("the table has no swept field (every cell has the same m*, A* and axes)")
    for dim in dims:
        missing = int(table[dim].isna().sum())
        if missing:
            # a row with no value of an axis went to another point of the grid (a table
            # extended with an axis before sweeps filled it in the rows they kept)
            raise SceneError(
                f"{missing} cells have no value of {dim} (cells of an earlier sweep, without that "
                f"axis): run a sweep into the table again (it fills them), or export a table of "
                f"one grid")
    frame = table.copy()
    frame["regime_code"] = [REGIME_FLAGS.index(r) if r in REGIME_FLAGS else REGIME_FLAGS.index("error")
                            for r in frame["regime"]]
    strings = [v for v in STRINGS if v in frame.columns]
    for name in strings:  # missing text (no warning) as "", the rest as plain str objects
        frame[name] = np.array([_text(v) for v in frame[name]], dtype=object)
    keep = ["regime_code", *[v for v in VARIABLES if v in frame.columns], *strings]
    indexed = frame.set_index(dims)[keep]
    if indexed.index.has_duplicates:
        raise SceneError("the table holds two cells for one point of its swept fields")
    ds = xr.Dataset.from_dataframe(indexed)
    for name in list(ds.data_vars):
        if name in strings:  # a point of the grid without a cell: ""
            ds[name] = ds[name].fillna("").astype(str)
        elif ds[name].dtype == bool or ds[name].dtype == object:
            ds[name] = ds[name].astype(float)
    codes = ds["regime_code"].fillna(-1).astype(np.int16)
    ds = ds.drop_vars("regime_code")
    ds["regime"] = codes
    ds["regime"].attrs.update(
        long_name="motion regime",
        flag_values=np.arange(len(REGIME_FLAGS), dtype=np.int16),
        flag_meanings=" ".join(REGIME_FLAGS),
        comment="-1: no cell at this point of the grid",
    )
    ds["drift_ratio"].attrs.update(long_name="mean x*' / (2 pi r A*) over the measurement window")
    if "settled" in ds:
        ds["settled"].attrs.update(long_name="1 if the drift is the steady one, 0 if still on "
                                   "its approach (NaN: no cell)")
    varied = derived(table, dims)
    for column, over in varied.items():
        values = frame.groupby(over)[column].first().to_xarray()
        ds = ds.assign_coords({column: values})
    for column in [*FIXED, *(c for c in table.columns if "." in c)]:
        if (column in table.columns and column not in dims and column not in varied
                and column not in ds.coords and table[column].nunique(dropna=True) == 1):
            value = table[column].dropna().iloc[0]
            ds = ds.assign_coords({column: value if not isinstance(value, np.bool_) else bool(value)})
    _describe(ds)
    meta = metadata or {}
    ds.attrs.update(
        Conventions="CF-1.8",
        title="sawdrift sweep",
        sawdrift_version=str(meta.get("sawdrift_version") or _versions(table)),
        sawdrift_code=str(meta.get("code_hash") or _codes(table)),
        base_scene=json.dumps(meta["base_scene"]) if meta.get("base_scene") else "",
        base_scene_note="the scene the sweep started from; each cell's own values are the "
                        "dimensions and coordinates",
    )
    return ds


def _describe(ds) -> None:
    """``long_name`` and ``units`` of the normalized and SI coordinates and variables."""
    names = {"m_star": "m* = a0 m f^2 / (M g)", "amplitude": "A* = A_y / a0", **_LONG_NAMES}
    for name in [*ds.coords, *ds.data_vars]:
        text = names.get(str(name)) or long_name(str(name))
        if text:
            ds[name].attrs["long_name"] = text
        unit = column_unit(str(name)) or _NORMALIZED_UNITS.get(str(name))
        if unit:
            ds[name].attrs["units"] = unit


def _text(value: Any) -> str:
    """A table's text cell as a string: "" for a missing one, a sequence (warnings kept as a
    list) joined with "; " as sweep tables join them."""
    if value is None or (isinstance(value, float) and value != value) or value is pd.NA:
        return ""
    if isinstance(value, (list, tuple, np.ndarray)):
        return "; ".join(str(v) for v in value)
    return str(value)


def _codes(table: pd.DataFrame) -> str:
    return ", ".join(sorted(str(v) for v in table.get("code_hash", pd.Series(dtype=str)).dropna().unique()))


def _versions(table: pd.DataFrame) -> str:
    return ", ".join(sorted(str(v) for v in table.get("version", pd.Series(dtype=str)).dropna().unique()))


def write_grid(table_path: str | Path, out: str | Path):
    """Export a sweep table (Parquet) to ``out`` (``.nc``, or ``.zarr`` where zarr is installed)."""
    table_path, out = Path(table_path), Path(out)
    meta = table_metadata(table_path)
    if meta["base_scene"] is UNREADABLE_BASE:
        raise SceneError(f"table {str(table_path)!r}: the base scene in its metadata cannot be "
                         "read (not JSON), and the export carries it as provenance: sweep the "
                         "table again")
    ds = to_dataset(pd.read_parquet(table_path), meta)
    if out.suffix == ".zarr":
        try:
            import zarr  # noqa: F401
        except ImportError:
            raise SceneError("writing .zarr needs zarr: pip install zarr (or write .nc)") from None
        ds.to_zarr(out, mode="w")
    elif out.suffix == ".nc":
        ds.to_netcdf(out)
    else:
        raise SceneError(f"-o {str(out)!r}: the output must end in .nc or .zarr")
    return ds


def load_grid(path: str | Path):
    """Open a grid written by :func:`write_grid` (``.nc`` or ``.zarr``) as an ``xarray.Dataset``."""
    import xarray as xr

    path = Path(path)
    if not path.exists():
        raise SceneError(f"grid {str(path)!r} does not exist")
    if path.suffix == ".zarr":
        return xr.open_zarr(path)
    return xr.load_dataset(path)
