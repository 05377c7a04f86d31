"""Stored traces: a decimated copy of each sweep cell's last periods, in a side file.

A sweep run with traces keeps, for every cell, x*, a*, N* and T* against t* over its last few
wave periods, decimated to a few hundred samples (:func:`trace_of`), so that a page built from
the table (:mod:`sawdrift.report.explore`) can draw what happens in a cell without running it
again.

The traces live next to the table ``TABLE.parquet`` in ``TABLE.traces.parquet`` (one row per
``cell_id``; columns ``t``, ``x``, ``a``, ``N``, ``T`` hold float32 lists). They are written the
way the table is: every finished cell is appended at once, as one flushed JSON line, to the
journal ``TABLE.traces.journal.jsonl`` (:func:`append_trace`); :func:`consolidate_traces` merges
the journal into the Parquet file with a write to a temporary file and an atomic rename, then
removes the journal. A killed sweep therefore loses at most the line being written, and
:func:`read_traces` reads file and journal alike.
"""

from __future__ import annotations

import base64
import json
import math
import os
import zlib
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..dynamics.assembly import steps_per_period
from ..errors import SawdriftError
from ..result.runner import run
from .journal import records

if TYPE_CHECKING:
    from ..result.result import Result
    from ..scene.schema import Scene

#: A trace: field name -> float32 samples, all of one length (fields :data:`TRACE_FIELDS`).
Trace = dict[str, np.ndarray]

#: The fields of a stored trace: t*, x*, a*, N*, T* (in wave periods and the scene's units).
TRACE_FIELDS = ("t", "x", "a", "N", "T")

#: The trajectory column(s) each trace field is read from, first present wins: the runner's
#: friction force column is ``T`` (``T_star`` after its rename), and so on for the others.
SOURCE_COLUMNS: dict[str, tuple[str, ...]] = {
    "t": ("t", "t_star"),
    "x": ("x", "x_star"),
    "a": ("a", "a_star"),
    "N": ("N", "N_star"),
    "T": ("T", "T_star"),
}

#: Defaults: the last 4 periods (a period-4 orbit shows whole), 400 samples (100 per period).
DEFAULT_PERIODS, DEFAULT_SAMPLES = 4.0, 400


def record_every(scene: Scene, periods: float = DEFAULT_PERIODS, samples: int = DEFAULT_SAMPLES) -> int:
    """Recording stride (steps) for a run whose trace is wanted: about ``samples`` in ``periods``.

    Passed as ``run(scene, trajectory=True, record_every=...)`` it keeps the recorded trajectory
    (and its cost) no denser than the trace needs.
    """
    per_period = max(1.0, samples / max(periods, 1e-9))
    return max(1, int(steps_per_period(scene) // math.ceil(per_period)))


def _column(frame: Any, field: str) -> np.ndarray:
    for name in SOURCE_COLUMNS[field]:
        if name in frame.columns:
            return frame[name].to_numpy(dtype=float)
    raise SawdriftError(f"the trajectory has no {field!r} column (looked for "
                        f"{', '.join(SOURCE_COLUMNS[field])})")


def trace_of(result: Result, periods: float = DEFAULT_PERIODS, samples: int = DEFAULT_SAMPLES) -> Trace:
    """A decimated copy of the last ``periods`` wave periods of ``result.trajectory``.

    The samples kept are evenly spaced in index (the trajectory is recorded at a fixed step, so
    evenly in t*), at most ``samples`` of them, first and last included.

    Raises
    ------
    SawdriftError
        When the result carries no trajectory (run it with ``trajectory=True``), or when
        ``periods``/``samples`` are not positive.
    """
    if result.trajectory is None:
        raise SawdriftError("the result has no trajectory; run it with trajectory=True")
    if not (periods > 0 and samples >= 2):
        raise SawdriftError(f"trace: periods = {periods} must be > 0 and samples = {samples} >= 2")
    frame = result.trajectory
    t = _column(frame, "t")
    if t.size == 0:
        raise SawdriftError("the result's trajectory is empty")
    # a hair of slack so that a window of exactly `periods` keeps its first sample
    keep = np.flatnonzero(t >= t[-1] - periods - 1e-9 * max(1.0, abs(t[-1])))
    if keep.size > samples:
        keep = keep[np.unique(np.round(np.linspace(0, keep.size - 1, samples)).astype(int))]
    return {f: _column(frame, f)[keep].astype(np.float32) for f in TRACE_FIELDS}


def run_traced(scene: Scene, engine: str = "compiled", periods: float = DEFAULT_PERIODS,
               samples: int = DEFAULT_SAMPLES) -> tuple[Result, Trace]:
    """Run ``scene`` recording its trajectory no denser than its trace needs; (result, trace).

    The result is the one ``run(scene)`` gives (recording does not change the integration).
    """
    result = run(scene, engine=engine, trajectory=True,  # type: ignore[arg-type]
                 record_every=record_every(scene, periods, samples))
    return result, trace_of(result, periods, samples)


def check_trace(trace: Mapping[str, Any], where: str = "trace") -> Trace:
    """``trace`` as float32 arrays of one length with every field of :data:`TRACE_FIELDS`."""
    missing = [f for f in TRACE_FIELDS if f not in trace]
    if missing:
        raise SawdriftError(f"{where} lacks the field(s) {', '.join(missing)}; it needs "
                            f"{', '.join(TRACE_FIELDS)}")
    out = {f: np.asarray(trace[f], dtype=np.float32).ravel() for f in TRACE_FIELDS}
    sizes = {v.size for v in out.values()}
    if len(sizes) != 1:
        raise SawdriftError(f"{where}: its fields have different lengths {sorted(sizes)}")
    return out


# -- the side file ---------------------------------------------------------------------------


def traces_path(table: str | Path) -> Path:
    """The traces file of ``table``: ``X.parquet`` -> ``X.traces.parquet``."""
    table = Path(table)
    stem = table.name[: -len(".parquet")] if table.name.endswith(".parquet") else table.name
    return table.with_name(f"{stem}.traces.parquet")


def traces_journal(table: str | Path) -> Path:
    """Where traces are journaled before consolidation: ``X.traces.journal.jsonl``."""
    side = traces_path(table)
    return side.with_name(side.name[: -len(".parquet")] + ".journal.jsonl")


def _encode(trace: Trace) -> dict[str, str]:
    return {f: base64.b64encode(trace[f].astype("<f4").tobytes()).decode("ascii") for f in TRACE_FIELDS}


def _decode(fields: Mapping[str, str]) -> Trace:
    return {f: np.frombuffer(base64.b64decode(fields[f]), dtype="<f4").astype(np.float32)
            for f in TRACE_FIELDS}


def append_trace(table: str | Path, cell_id: str, trace: Mapping[str, Any]) -> None:
    """Journal one cell's trace next to ``table`` (one flushed line; call from one process)."""
    line = json.dumps({"cell_id": str(cell_id), **_encode(check_trace(trace, f"trace of {cell_id}"))})
    journal = traces_journal(table)
    journal.parent.mkdir(parents=True, exist_ok=True)
    with journal.open("a") as fh:
        fh.write(line + "\n")
        fh.flush()


def _read_parquet(path: Path) -> dict[str, Trace]:
    import pyarrow.parquet as pq

    try:
        arrow = pq.read_table(path)
    except Exception as exc:  # noqa: BLE001 - any reader failure is the user's file
        raise SawdriftError(f"traces {str(path)!r} is not a readable Parquet file "
                            f"({str(exc).splitlines()[0] if str(exc) else type(exc).__name__})") from None
    names = set(arrow.column_names)
    if "cell_id" not in names or not set(TRACE_FIELDS) <= names:
        raise SawdriftError(f"traces {str(path)!r} is not a sawdrift traces file (it needs columns "
                            f"cell_id, {', '.join(TRACE_FIELDS)})")
    ids = arrow.column("cell_id").to_pylist()
    columns = {f: arrow.column(f).combine_chunks() for f in TRACE_FIELDS}
    out: dict[str, Trace] = {}
    for f, col in columns.items():
        flat = col.flatten().to_numpy(zero_copy_only=False).astype(np.float32)
        offsets = col.offsets.to_numpy()
        for i, cid in enumerate(ids):
            out.setdefault(cid, {})[f] = flat[offsets[i]:offsets[i + 1]]
    return out


def read_traces_file(path: str | Path) -> dict[str, Trace]:
    """The traces of one traces file (no journal), by cell id; a one-line error if unreadable."""
    path = Path(path)
    if not path.is_file():
        what = "is a folder, not a traces file" if path.is_dir() else "does not exist"
        raise SawdriftError(f"traces {str(path)!r} {what}")
    return _read_parquet(path)


def read_traces(table: str | Path) -> dict[str, Trace]:
    """Every stored trace of ``table`` by cell id: its traces file, then its journal.

    A missing file gives an empty dict; a journal line cut by a kill mid-write is skipped (that
    cell simply has no trace).
    """
    side = traces_path(table)
    out = _read_parquet(side) if side.exists() else {}
    for rec in records(traces_journal(table)):
        try:
            out[rec["cell_id"]] = _decode(rec)
        except (KeyError, ValueError, TypeError):
            continue
    return out


def write_traces(path: str | Path, traces: Mapping[str, Mapping[str, Any]]) -> Path:
    """Write ``{cell_id: trace}`` to a traces file atomically (temporary file, then rename)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    path = Path(path)
    ids = sorted(traces)
    checked = [check_trace(traces[c], f"trace of {c}") for c in ids]
    columns: dict[str, Any] = {"cell_id": pa.array(ids, type=pa.string())}
    for f in TRACE_FIELDS:
        columns[f] = pa.array([t[f] for t in checked], type=pa.list_(pa.float32()))
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    pq.write_table(pa.table(columns), tmp)
    os.replace(tmp, path)
    return path


#: The plotted fields, in the order :func:`pack_traces` stores them.
PACKED_FIELDS = ("x", "a", "N", "T")


def pack_traces(traces: Sequence[Mapping[str, Any]], samples: int = DEFAULT_SAMPLES) -> tuple[bytes, int]:
    """Traces in the compact form an HTML page carries: zlib-compressed 8-bit samples.

    Every trace is resampled (linear interpolation) onto ``m`` evenly spaced times between its
    first and last t*, ``m = min(samples, longest trace)``; each of x*, a*, N*, T*
    (:data:`PACKED_FIELDS`) is quantized to 256 levels between its own minimum and maximum
    (error at most 1/510 of its range, below a pixel of the page's plots) and stored as
    differences of consecutive levels (mod 256), which compress well. The uncompressed layout
    (little-endian) is a float32 header of 10 numbers per trace (t0, t1, then low and high of
    each field) followed by the uint8 codes, ``[trace][field][sample]``.

    Returns the compressed bytes (zlib, RFC 1950) and ``m``.
    """
    checked = [check_trace(t) for t in traces]
    m = max(2, min(int(samples), max((t["t"].size for t in checked), default=2)))
    header = np.zeros((len(checked), 2 + 2 * len(PACKED_FIELDS)), dtype="<f4")
    codes = np.zeros((len(checked), len(PACKED_FIELDS), m), dtype=np.uint8)
    for k, tr in enumerate(checked):
        t = tr["t"].astype(float)
        grid = np.linspace(t[0], t[-1], m)
        header[k, :2] = t[0], t[-1]
        for j, f in enumerate(PACKED_FIELDS):
            v = np.interp(grid, t, tr[f].astype(float)) if t.size > 1 else np.full(m, tr[f][0], float)
            v = np.where(np.isfinite(v), v, np.nan)
            lo = np.float32(np.nanmin(v)) if np.isfinite(v).any() else np.float32(0.0)
            hi = np.float32(np.nanmax(v)) if np.isfinite(v).any() else np.float32(0.0)
            header[k, 2 + 2 * j: 4 + 2 * j] = lo, hi
            span = float(hi) - float(lo)
            level = np.zeros(m) if span <= 0 else np.round((v - float(lo)) / span * 255.0)
            level = np.clip(np.nan_to_num(level), 0, 255).astype(np.int64)
            codes[k, j] = np.diff(level, prepend=0) % 256
    return zlib.compress(header.tobytes() + codes.tobytes(), 9), m


def consolidate_traces(table: str | Path, keep: Iterable[str] | None = None) -> Path | None:
    """Merge the journal into ``TABLE.traces.parquet`` (atomic replace), then drop the journal.

    ``keep``, if given, limits the file to those cell ids (e.g. the table's). Returns the file's
    path, or None when there is nothing to write.
    """
    traces = read_traces(table)
    if keep is not None:
        wanted = set(keep)
        traces = {c: t for c, t in traces.items() if c in wanted}
    side = traces_path(table)
    journal = traces_journal(table)
    if not traces and not side.exists():
        journal.unlink(missing_ok=True)
        return None
    write_traces(side, traces)
    journal.unlink(missing_ok=True)
    return side
