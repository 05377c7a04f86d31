"""The resumable table of a sweep: its Parquet file, the journal beside it, and its provenance.

A sweep (:func:`sawdrift.study.sweep.sweep`) reads back the rows already finished, from the table
and from the journal of a sweep cut short (:func:`read_rows`), and at its end writes every row
into the table with an atomic replace (:func:`write_table`), whose metadata records the code and
the base scene the rows were computed with (:func:`table_metadata`).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._version import __version__
from ..contact.binding import bind
from ..errors import SceneError
from ..result.regimes import TABLE_REGIMES, check_table_regimes
from ..result.result import SUMMARY_FIELDS
from ..scene.schema import Scene, build_scene, set_dotted
from .axes import column_unit
from .journal import records
from .provenance import UNREADABLE_BASE, code_hash

#: Columns of a sweep table, in order: ``events_dropped`` counts the events the run could not log
#: (its evidence is then incomplete), ``code_hash`` names the code that computed the row
#: (:func:`sawdrift.study.provenance.code_hash`).
TABLE_COLUMNS = tuple(dict.fromkeys(("cell_id", "scene_id", *SUMMARY_FIELDS, "settled",
                                     "settle_periods", "orbit_period", "chaotic", "drift_ratio_se",
                                     "mean_acceleration", "detach_time", "resolved_as", "warnings",
                                     "events_dropped", "code_hash", "error")))

#: Parquet metadata keys of a sweep table (provenance).
META_VERSION, META_BASE_SCENE, META_CODE = b"sawdrift_version", b"base_scene", b"sawdrift_code"


def journal_path(table: Path) -> Path:
    """Where finished cells are journaled before consolidation."""
    return table.with_name(table.name + ".journal.jsonl")


def read_rows(table: Path) -> dict[str, dict[str, Any]]:
    """Rows already finished: from the Parquet table and the journal, by cell id.

    The journal's first line is its header (the sweep's base scene, see
    :func:`sawdrift.study.sweep.sweep`), not a row.
    """
    rows: dict[str, dict[str, Any]] = {}
    if table.exists():
        try:
            frame = pd.read_parquet(table)
        except Exception as exc:  # noqa: BLE001 - a foreign or broken file must not be overwritten
            raise SceneError(
                f"table {str(table)!r} exists but is not a readable Parquet file ({exc})"
            ) from None
        if "cell_id" not in frame.columns:
            raise SceneError(f"table {str(table)!r} is not a sawdrift sweep table (no cell_id column)")
        _check_resumable(table, frame)
        for rec in _records(frame):
            rec.setdefault("scene_id", None)
            rows[rec["cell_id"]] = rec
    for rec in records(journal_path(table)):  # a cell cut short by a kill is recomputed
        # and so is a row no run writes (a regime of none), whatever damaged it
        if "cell_id" in rec and rec.get("regime") in TABLE_REGIMES:
            rows[rec["cell_id"]] = rec
    return rows


#: the columns a table must hold for a sweep to go on in it
RESUMED_COLUMNS = ("model", "m_star", "amplitude", "regime")


def _check_resumable(table: Path, frame: pd.DataFrame) -> None:
    """A one-line SceneError where the table's cells are not what a sweep wrote: a column of
    :data:`RESUMED_COLUMNS` missing, an m* or A* that is not a finite number (m* > 0, A* >= 0),
    a regime no run gives. Such a table was resumed and written again with every regime, or
    every m*, missing, which the reports then failed on."""
    name = str(table)
    missing = [c for c in RESUMED_COLUMNS if c not in frame.columns]
    if missing:
        raise SceneError(f"table {name!r} has no {', '.join(missing)} column: it is not a whole "
                         "sweep table; write a new table")
    for column in ("m_star", "amplitude"):
        values = pd.to_numeric(frame[column], errors="coerce").to_numpy(float)
        # a prescribed drive's row has no amplitude (None): only a number there must be one
        bad = (~(values > 0.0) if column == "m_star" else
               (frame[column].notna().to_numpy() & ~(np.isfinite(values) & (values >= 0.0))))
        if bad.any():
            value = frame[column][bad].iloc[0]
            shown = f"{value:g}" if isinstance(value, (int, float, np.number)) else repr(value)
            raise SceneError(f"table {name!r} holds {column} = {shown}, which no sweep writes: "
                             "write a new table")
    check_table_regimes(frame["regime"], name, "write a new table")


def _records(frame: pd.DataFrame) -> list[dict[str, Any]]:
    """The table's rows as plain dicts of Python values, a missing value None, built column by
    column (4x faster than ``frame.to_dict("records")`` with the values cleaned row by row: an
    adaptive map reads its table back at every round)."""
    names = list(frame.columns)
    columns = []
    for name in names:
        series = frame[name]
        values = series.tolist()
        if series.dtype.kind == "f":
            values = [None if v != v else v for v in values]
        elif series.dtype.kind not in "iub":
            values = [_value(v) for v in values]
        columns.append(values)
    return [dict(zip(names, row, strict=True)) for row in zip(*columns, strict=True)]


def _value(v: Any) -> Any:
    """A cell of an object or string column as a Python value (None where missing)."""
    if v is None or v is pd.NA:
        return None
    if isinstance(v, np.generic):
        v = v.item()
    return None if isinstance(v, float) and math.isnan(v) else v


def drift_errors(rows: pd.DataFrame, column: str) -> np.ndarray:
    """The standard error of each row's drift ``column`` (``drift_ratio``, ``drift_velocity`` or a
    speed in m/s) where its drift is a long-time mean: ``drift_ratio_se`` scaled by the column's
    ratio to the drift ratio; NaN where the drift is steady or a value is missing."""
    if "drift_ratio_se" not in rows.columns:
        return np.full(len(rows), np.nan)
    se = pd.to_numeric(rows["drift_ratio_se"], errors="coerce").to_numpy(dtype=float)
    ratio = pd.to_numeric(rows["drift_ratio"], errors="coerce").to_numpy(dtype=float)
    value = pd.to_numeric(rows[column], errors="coerce").to_numpy(dtype=float)
    if column == "drift_ratio":
        out = np.where(np.isfinite(ratio), se, np.nan)
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            out = se * np.abs(value / ratio)
    return np.where(np.isfinite(out) & np.isfinite(value), out, np.nan)


def to_frame(rows: Iterable[dict[str, Any]]) -> pd.DataFrame:
    """Rows as a DataFrame with the table's columns (and any swept-field columns), sorted."""
    rows = list(rows)
    extra = sorted({k for r in rows for k in r} - set(TABLE_COLUMNS))
    frame = pd.DataFrame(rows, columns=[*TABLE_COLUMNS, *extra])
    for col in ("error", "regime", "model", "engine", "profile", "cell_id", "scene_id", "version",
                "code_hash"):
        frame[col] = frame[col].astype("string")
    frame = frame.sort_values(["model", "m_star", "amplitude", "cell_id"], kind="stable")
    return frame.reset_index(drop=True)


def write_table(frame: pd.DataFrame, table: Path, base: Scene | dict[str, Any] | None = None) -> None:
    """Write the Parquet table atomically (temporary file, then replace).

    The file's metadata records the sawdrift version (``sawdrift_version``), the code hash of
    the table's models now (``sawdrift_code``, see :mod:`sawdrift.study.provenance`; each row
    also names its own) and the base scene of the sweep as JSON (``base_scene``);
    :func:`table_metadata` reads them back.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    arrow = pa.Table.from_pandas(frame, preserve_index=False)
    # each column in SI units says which (Parquet field metadata, read by table_metadata)
    fields = [f.with_metadata({b"units": unit.encode()}) if (unit := column_unit(f.name)) else f
              for f in arrow.schema]
    arrow = arrow.cast(pa.schema(fields, metadata=arrow.schema.metadata))
    meta = dict(arrow.schema.metadata or {})
    meta[META_VERSION] = __version__.encode()
    meta[META_CODE] = code_hash(str(m) for m in frame["model"].dropna().unique()).encode()
    if not isinstance(base, dict):
        base = json.loads(bind(base if base is not None else Scene()).model_dump_json())
    meta[META_BASE_SCENE] = json.dumps(base).encode()
    tmp = table.with_name(f".{table.name}.{os.getpid()}.tmp")
    pq.write_table(arrow.replace_schema_metadata(meta), tmp)
    os.replace(tmp, table)


def table_metadata(table: str | Path) -> dict[str, Any]:
    """The provenance of a sweep table: ``{"sawdrift_version", "code_hash", "base_scene"}``.

    A key the table does not record (a table written before it existed) is None; ``units``
    maps each column in SI units to its unit (``{"drift_speed_m_s": "m/s", "device.frequency":
    "Hz"}``).
    """
    import pyarrow.parquet as pq

    schema = pq.read_schema(table)
    meta = schema.metadata or {}
    out: dict[str, Any] = {"sawdrift_version": None, "code_hash": None, "base_scene": None,
                           "units": {f.name: f.metadata[b"units"].decode() for f in schema
                                     if f.metadata and b"units" in f.metadata}}
    if META_VERSION in meta:
        out["sawdrift_version"] = meta[META_VERSION].decode()
    if META_CODE in meta:
        out["code_hash"] = meta[META_CODE].decode()
    if META_BASE_SCENE in meta:
        # a damaged entry is no base at all to check a resumed sweep against, and ended in an
        # internal failure of sweep and export
        try:
            base = json.loads(meta[META_BASE_SCENE].decode())
        except (json.JSONDecodeError, UnicodeDecodeError):
            base = UNREADABLE_BASE
        out["base_scene"] = base if isinstance(base, dict) else UNREADABLE_BASE
    return out


def base_json(base: Scene | None, overrides: dict[str, Any] | None) -> dict[str, Any]:
    """The scene every cell of a sweep starts from (``base`` with ``overrides``), as JSON data."""
    scene = base if base is not None else Scene()
    if overrides:
        data = scene.model_dump(exclude_none=True)
        for dotted, value in overrides.items():
            set_dotted(data, dotted, value)
        scene = build_scene(data)
    out = json.loads(bind(scene).model_dump_json())
    profile = scene.particle.profile
    if profile.shape == "table":
        # the law's values, not only its file's name: a rewritten file is another contact law
        # (a table swept with N = a^1.5 took N = a^2 cells on resume, without a word)
        law = np.ascontiguousarray(profile.law(), dtype=np.float64)
        out["particle"]["profile"]["file_sha1"] = hashlib.sha1(law.tobytes()).hexdigest()[:16]
    return out


def stored_base(table: Path) -> dict[str, Any] | None:
    """The base scene a table was swept from: its metadata's, else its journal's header
    (:data:`~.provenance.UNREADABLE_BASE` where that line is damaged: it was taken as no base at all, and a
    sweep of another base scene mixed its rows in)."""
    if table.exists():
        return table_metadata(table)["base_scene"]
    journal = journal_path(table)
    if journal.exists():
        with journal.open(encoding="utf-8", errors="replace") as fh:  # a damaged byte: no JSON
            line = fh.readline()
        if not line.strip():
            return None
        try:
            first = json.loads(line)
        except json.JSONDecodeError:
            return UNREADABLE_BASE
        if not isinstance(first, dict):
            return UNREADABLE_BASE
        # a sweep writes its header first: a journal that starts with a row lost it
        return first.get("base_scene") if "cell_id" not in first else UNREADABLE_BASE
    return None


def distinct_warnings(texts: Iterable[str]) -> list[str]:
    """The warnings of several rows, each text once, a warning they all begin with once. A row
    holds its run's warnings joined by "; " (:func:`~.sweep.run_cell`), so a warning every row
    shares (a device's "a0 < 1 nm", first among them) came back inside each row's text, three
    times for three positions of a field. A warning may itself hold "; ", so the texts are not
    split: the longest head every text begins with, ending where a "; " does or with the text,
    is listed once, then what each text adds to it, in the order first seen."""
    texts = list(dict.fromkeys(str(t) for t in texts))
    if len(texts) < 2:
        return texts
    first, common = texts[0], ""
    for cut in [i for i in range(len(first)) if first.startswith("; ", i)] + [len(first)]:
        head = first[:cut]
        if not all(t == head or t.startswith(head + "; ") for t in texts):
            break
        common = head
    if not common:
        return texts
    return [common, *dict.fromkeys(t[len(common) + 2:] for t in texts if t != common)]
