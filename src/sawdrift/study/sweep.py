"""Parameter sweeps over (model, m*, A*): executors, a resumable table, and lossless resume.

Every finished cell is appended, as one JSON line, to a journal next to the table
(``TABLE.journal.jsonl``) the moment it completes; one ``write`` of a short line, flushed, so a
kill -9 loses at most the cells still running. Re-running the same sweep reads the table and
the journal (:mod:`sawdrift.study.table`), skips every cell already there (cells are identified
by a hash of their whole scene), and computes only the rest. At the end the rows are
consolidated into the Parquet table with an atomic replace and the journal is removed.

Executors (:class:`sawdrift.study.executor.Executor`, shared by every study): ``serial``; local
processes (default, all cores); or an existing dask.distributed cluster (``scheduler=ADDRESS``).
All run the same cell function, so they give identical values.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from functools import partial
from pathlib import Path
from typing import Any

import pandas as pd

from .._paths import write_problem
from .._version import __version__
from ..contact.binding import bind
from ..errors import SawdriftError, SceneError
from ..result.runner import run
from ..scene.schema import Scene, build_scene, get_dotted, set_dotted
from .axes import add_columns, device_columns, parse_axis, parse_values
from .estimate import announce, check, estimate_sweep
from .executor import Executor, resolve_workers
from .progress import progress as make_progress
from .provenance import check_resume, code_hash
from .table import (
    TABLE_COLUMNS,
    base_json,
    journal_path,
    read_rows,
    stored_base,
    to_frame,
    write_table,
)
from .traces import append_trace, consolidate_traces, read_traces, run_traced


def resolved_as(row: dict[str, Any]) -> str:
    """How a cell's steady state was resolved, or why not (the ``resolved_as`` column).

    ``periodic_orbit`` (settled, the state repeats after ``orbit_period`` periods),
    ``quasi_periodic`` (settled, having lost contact, but its state does not repeat: its window
    means agree to the tolerance on a motion that beats, such as a hop against the undamped
    contact oscillation; no orbit stands behind the drift), ``fixed_point`` (settled in
    contact: a steady drift or sticking), ``chaotic_mean`` (a chaotic
    window's long-time mean with its standard error), ``long_time_mean`` (the same for a
    motion without a positive Lyapunov exponent that did not settle and is irregular: lift-offs
    that find no orbit, or window means that wander in contact), ``runaway`` or ``ejected`` (no steady
    state, named), else ``not_settled`` (the run ended before its drift had settled: a slow
    approach, or a regular motion that found no periodic orbit within its budget).
    """
    regime = row.get("regime")
    if regime in ("runaway", "ejected"):
        return str(regime)
    if row.get("settled"):
        if (row.get("orbit_period") or 0) > 0:
            return "periodic_orbit"
        return "quasi_periodic" if row.get("contact_lost") else "fixed_point"
    se = row.get("drift_ratio_se")
    if se is not None and se == se:
        return "chaotic_mean" if row.get("chaotic") else "long_time_mean"
    return "not_settled"


#: cells from which building a sweep's grid shows a progress bar of its own
PREPARE_BAR = 2000


def scene_id(scene: Scene) -> str:
    """Identifier of a cell's scene alone: a hash of the whole validated scene."""
    return hashlib.sha1(scene.model_dump_json().encode()).hexdigest()[:16]


def cell_id(scene: Scene) -> str:
    """Identifier of a computed cell: a hash of the sawdrift version, the code and the whole scene.

    The code is :func:`~sawdrift.study.provenance.code_hash` of the scene's model (sawdrift's
    source and the model's plugin): a cell computed by other code has another identifier.
    """
    key = f"{__version__}\n{code_hash([scene.model])}\n{scene.model_dump_json()}"
    return hashlib.sha1(key.encode()).hexdigest()[:16]


def supersede(rows: Iterable[dict[str, Any]]) -> list[dict[str, Any]]:
    """Keep, for every scene, only one row: the one computed by the current code if there is one."""

    def current(row: dict[str, Any]) -> bool:
        return row.get("code_hash") == code_hash([str(row.get("model"))])

    best: dict[str, dict[str, Any]] = {}
    for row in rows:
        key = row.get("scene_id") or row["cell_id"]
        old = best.get(key)
        if old is None or (current(row) and not current(old)):
            best[key] = row
    return list(best.values())


def grid(
    models: Sequence[str],
    m_star: Iterable[float] | None = None,
    amplitude: Iterable[float] | None = None,
    base: Scene | None = None,
    overrides: dict[str, Any] | None = None,
    axes: dict[str, Sequence[Any]] | None = None,
    tick: Callable[[], None] | None = None,
) -> list[Scene]:
    """The scenes of a grid: models x m* x A* x every other axis (a dotted scene field each).

    All other fields come from ``base`` and ``overrides``; ``tick`` is called after each scene
    (a progress bar over a large grid). Each scene is bound to its model
    (:func:`sawdrift.contact.binding.bind`): a wrong model parameter or one the model cannot take
    is a one-line error before any cell runs.
    """
    data = base.model_dump(exclude_none=True) if base is not None else {}
    for dotted, value in (overrides or {}).items():
        set_dotted(data, dotted, value)
    all_axes: dict[str, list[Any]] = {}
    if m_star is not None:
        all_axes["particle.m_star"] = [float(v) for v in m_star]
    if amplitude is not None:
        all_axes["drive.amplitude"] = [float(v) for v in amplitude]
    for field, values in (axes or {}).items():
        all_axes[field] = list(values)
    scenes = []
    for model in models:
        per_model = dict(data, model=model)
        if base is not None and model != base.model:
            per_model["model_params"] = {}
        for combo in itertools.product(*all_axes.values()):
            cell = json.loads(json.dumps(per_model))
            values = dict(zip(all_axes, combo, strict=True))
            if "model" in values and values["model"] != cell.get("model"):
                # a model axis (--axis model=a,b) is a list of models, set first: the parameters
                # so far are another model's (mdr's strips named to mmd were "not a known
                # field"); a model_params axis applies after it
                cell["model"] = values.pop("model")
                cell["model_params"] = {}
            for field, value in values.items():
                set_dotted(cell, field, value)
            scenes.append(bind(build_scene(cell)))
            if tick is not None:
                tick()
    return scenes


def run_cell(scene_json: str, engine: str = "compiled", traces: bool = False) -> dict[str, Any]:
    """Run one cell from its scene JSON and return its table row; an error fills ``error``.

    A model that raises or returns NaN fails only its own cell. With ``traces`` the row also
    holds ``"trace"``, the cell's last periods (:func:`sawdrift.study.traces.run_traced`).
    """
    scene = Scene.model_validate_json(scene_json)
    row: dict[str, Any] = {key: None for key in TABLE_COLUMNS}
    row["cell_id"] = cell_id(scene)
    row["scene_id"] = scene_id(scene)
    row["code_hash"] = code_hash([scene.model])
    trace = None
    try:
        if traces:
            result, trace = run_traced(scene, engine)
        else:
            result = run(scene, engine=engine)  # type: ignore[arg-type]
        row.update(result.summary())
        row["warnings"] = "; ".join(row.get("warnings") or ()) or None
        row["resolved_as"] = resolved_as(row)
        row["events_dropped"] = int(getattr(result, "events_dropped",
                                            result.extra.get("events_dropped", 0)))
        row["error"] = None
    except Exception as exc:  # noqa: BLE001 - recorded in the table, the sweep goes on
        kind = "" if isinstance(exc, SawdriftError) else f"{type(exc).__name__}: "
        row.update(
            model=scene.model,
            m_star=scene.particle.m_star,
            amplitude=getattr(scene.drive, "amplitude", None),
            mu=scene.material.mu,
            nu=scene.material.nu,
            profile=scene.particle.profile.shape,
            regime="error",
            error=(kind + str(exc)).splitlines()[0],
            version=__version__,  # a failed row names its code too ("sawdrift None code ...")
        )
    out = {key: row.get(key) for key in TABLE_COLUMNS}
    if trace is not None and row["error"] is None:
        out["trace"] = trace
    return out


def sweep(
    models: str | Sequence[str],
    m_star: str | Sequence[float] | None = None,
    amplitude: str | Sequence[float] | None = None,
    *,
    axes: dict[str, str | Sequence[Any]] | None = None,
    points: Sequence[tuple[float, float]] | None = None,
    base: Scene | None = None,
    overrides: dict[str, Any] | None = None,
    table: str | Path | None = None,
    workers: int | None = None,
    scheduler: Any = None,
    progress: bool = True,
    engine: str = "compiled",
    on_row: Callable[[dict[str, Any]], None] | None = None,
    force: bool = False,
    traces: bool = False,
    label: tuple[str, str] = ("sweep", "cell"),
    executor: Executor | None = None,
    size: bool = False,
    yes: bool = False,
) -> pd.DataFrame:
    """Run a (model, m*, A*) grid and return one row per cell as a DataFrame.

    Parameters
    ----------
    models
        Model names (a list or a comma-separated string).
    m_star, amplitude
        Axes: ``"START:STOP:N"`` (log-spaced, ends included), ``"a,b,c"``, or a sequence; None
        keeps the base scene's value.
    axes
        More axes, ``{dotted scene field: spec}`` (see :func:`parse_values`), e.g.
        ``{"material.mu": "0.05,0.1,0.2", "device.amplitude": "5 nm,10 nm"}``. Every swept field
        becomes a column of the table (device fields in SI units).
    points
        Instead of a grid: explicit (m*, A*) cells (used by the adaptive sweep).
    base, overrides
        The scene every cell starts from, and dotted-path overrides (``{"material.mu": 0.2}``).
    table
        Parquet file. Finished cells already in it (or in its journal) are not recomputed; its
        cells outside this grid are kept (the returned frame's ``attrs`` say how many:
        ``other_cells``, of ``table_cells`` in the written table). A
        table whose rows were computed by other code (another sawdrift source or model plugin,
        :mod:`sawdrift.study.provenance`), or swept from another base scene, is refused with a
        :class:`~sawdrift.study.provenance.TableProvenanceError` unless ``force``.
    workers
        1 runs serially; K > 1 uses K local processes; default: all cores.
    scheduler
        Address of a dask.distributed scheduler (or a ``Client``/``LocalCluster``) to run on.
    progress
        Show a progress bar (tqdm) on stderr.
    engine
        ``"compiled"`` (numba) or ``"python"`` (reference implementations).
    on_row
        Called with each finished row (in completion order).
    force
        Add to a table of other code or another base scene anyway: a cell whose scene the table
        already holds keeps its row, whatever code computed it (each row names its code).
    traces
        Also store each cell's last periods, decimated, in ``TABLE.traces.parquet``
        (:mod:`sawdrift.study.traces`); a cell of the table without one is run again for it.
    label
        (what, unit) of the progress line: ``sweep: k/N cells``; a drift field says
        ``("field", "point")``.
    executor
        An open :class:`~sawdrift.study.executor.Executor` to run on (then ``workers`` and
        ``scheduler`` are its own; the caller closes it); None opens one for this sweep.
    size
        Estimate the work before the grid is built
        (:func:`~sawdrift.study.estimate.estimate_sweep`), print it on stderr (with
        ``progress``) and refuse it, a one-line SceneError, above
        :data:`~sawdrift.study.estimate.MAX_SECONDS` unless ``yes``.
    yes
        Start a sweep whose estimate is above the bound.
    """
    if engine not in ("compiled", "python"):
        raise SceneError(f"engine = {engine!r} is not allowed; use 'compiled' or 'python'")
    names = [m.strip() for m in models.split(",")] if isinstance(models, str) else list(models)
    if not names or any(not n for n in names):
        raise SceneError(f"models = {models!r} must name at least one model")
    extra_axes = {field: parse_values(spec, field) for field, spec in (axes or {}).items()}
    m_values = None if m_star is None else parse_axis(m_star, "m_star")
    a_values = None if amplitude is None else parse_axis(amplitude, "amplitude")
    path = _table_path(table)
    points = _points(points)
    done = read_rows(path) if path is not None else {}
    if traces and path is None:
        raise SceneError("traces are stored next to a table: give table= (--out)")
    have = set(read_traces(path)) if traces and path is not None else set()
    swept_from = base_json(base, overrides)
    if path is not None:
        check_resume(path, done.values(), stored_base(path), swept_from, force, engine)
    cells = expected = None
    if size:
        est = estimate_sweep(grid, names, m_values, a_values, extra_axes, points, base,
                             overrides, workers, engine, label[0])
        if not done:  # a resumed table is checked on the cells it still runs, below
            check(est, yes, smaller="fewer cells or periods")
        cells, expected = est.cells, est.seconds
    # a large grid takes a while to build: its size first, then a bar; a small one is built
    # (and every cell checked, one line for a bad one) before its size is printed
    large = progress and cells is not None and cells >= PREPARE_BAR
    if large:
        announce(est)
    prep = make_progress(cells, f"{label[0]}: preparing", label[1]) if large else None
    tick = prep.update if prep is not None else None
    if points is not None:
        scenes = [s for m, a in points
                  for s in grid(names, [m], [a], base, overrides, extra_axes, tick)]
    else:
        scenes = grid(names, m_values, a_values, base, overrides, extra_axes, tick)
    if prep is not None:
        prep.close()
    if size and progress and not large and not done:
        announce(est)
    todo, wanted, columns = _plan_cells(scenes, done, force, extra_axes, traces, have)
    if size and done and est.cells:
        # the cells still to run, not the whole grid (a finished table was estimated at 14 s
        # and the 1 h gate read the whole grid's size)
        left = len(todo) / est.cells
        est = replace(est, cells=len(todo), steps=est.steps * left, most=est.most * left)
        check(est, yes, smaller="fewer cells or periods")
        expected = est.seconds
        if progress and todo and not large:
            announce(est)
    own = executor is None
    if executor is None:
        executor = Executor(resolve_workers(workers), scheduler)
    rows = {cid: row for cid, row in done.items() if cid in wanted}
    for cid, row in rows.items():
        # a kept cell gets this sweep's columns too: an axis added to an existing table (the
        # mu = 0.1 half of a grid whose cells were there) had NaN for its value
        add_columns(row, columns.get(cid, {}))
    if progress and rows and todo and path is not None:
        # the size printed above is the whole grid's: say what a resumed sweep still runs
        print(f"{label[0]}: {len(rows)} of the {len(wanted)} cells already in {path.name}, "
              f"{len(todo)} to run", file=sys.stderr)
    bar = None
    if progress and todo:
        bar = make_progress(len(wanted), label[0], label[1], initial=len(rows), expected=expected)
    try:
        _run_cells(executor, todo, rows, columns, path, swept_from,
                   partial(run_cell, engine=engine, traces=traces), on_row, bar)
    finally:
        if own:
            executor.close()
        if bar is not None:
            bar.close()
    frame = to_frame(rows.values())
    if path is not None:
        _write_back(frame, path, done, rows, wanted, swept_from, traces)
    return frame


def _plan_cells(scenes: list[Scene], done: dict[str, dict[str, Any]], force: bool,
                extra_axes: dict[str, Any], traces: bool, have: set[str]
                ) -> tuple[list[str], set[str], dict[str, dict[str, Any]]]:
    """The cells of a sweep still to run (scene JSON, the heaviest particles first), the ids of
    every cell it wants, and each cell's swept fields' values as the validated scene holds them
    (SI for devices) with a device's SI columns."""
    # with force, a scene the table holds keeps its row, whatever code computed it
    held = {r["scene_id"]: cid for cid, r in done.items() if r.get("scene_id")} if force else {}
    todo: list[str] = []
    weights: list[float] = []
    wanted: set[str] = set()
    columns: dict[str, dict[str, Any]] = {}
    loaded = any(s.device is not None and device_columns(s)[0].get("load_N") for s in scenes)
    for scene in scenes:
        cid = cell_id(scene)
        if cid not in done and held:
            cid = held.get(scene_id(scene), cid)
        if extra_axes:
            dumped = scene.model_dump()
            columns[cid] = {f: get_dotted(dumped, f) for f in extra_axes}
        if scene.device is not None:
            si, scale = device_columns(scene)
            if not loaded:
                si.pop("load_N")
            columns.setdefault(cid, {}).update(si, _speed_scale=scale)
        rerun = traces and cid in done and cid not in have and not done[cid].get("error")
        if (cid not in done or rerun) and cid not in wanted:
            todo.append(scene.model_dump_json())
            weights.append(-scene.particle.m_star)
        wanted.add(cid)
    # the heaviest particles first: they take the longest (the relaxation, the windows and the
    # records grow with m*), and a batch that ends on them leaves a worker idle
    todo = [todo[i] for i in sorted(range(len(todo)), key=weights.__getitem__)]
    return todo, wanted, columns


def _run_cells(executor: Executor, todo: list[str], rows: dict[str, dict[str, Any]],
               columns: dict[str, dict[str, Any]], path: Path | None,
               swept_from: dict[str, Any], cell: Callable[[str], dict[str, Any]],
               on_row: Callable[[dict[str, Any]], None] | None, bar: Any) -> None:
    """Run ``todo`` on ``executor`` into ``rows``: each finished row gets its swept columns,
    its trace stored, and is appended to the table's journal the moment it completes."""
    journal = journal_path(path) if path is not None else None
    fh = None
    if journal is not None and todo:
        header = not journal.exists()
        fh = journal.open("a")
        if header:  # what the rows belong to, until the table's metadata records it
            fh.write(json.dumps({"base_scene": swept_from}) + "\n")
    try:
        for _i, row in executor.imap(cell, todo):
            trace = row.pop("trace", None)
            if trace is not None and path is not None:
                append_trace(path, row["cell_id"], trace)
            add_columns(row, columns.get(row["cell_id"], {}))
            rows[row["cell_id"]] = row
            if fh is not None:
                fh.write(json.dumps(row) + "\n")
                fh.flush()
            if on_row is not None:
                on_row(row)
            if bar is not None:
                bar.update(1)
    finally:
        if fh is not None:
            fh.close()


#: summary columns that hold a swept field's value in every row (a row swept before the field
#: was an axis has its value there)
PLAIN_COLUMNS = {"particle.m_star": "m_star", "drive.amplitude": "amplitude", "material.mu": "mu",
                 "material.nu": "nu", "drive.horizontal_ratio": "horizontal_ratio"}


def fill_axes(rows: list[dict[str, Any]], swept_from: dict[str, Any]) -> None:
    """Give every row a value of each swept field (dotted column) some row has: a row of an
    earlier sweep of the table, without that axis, ran at the base scene's value (the table's
    base scene is one), or holds it in its summary column (``mu`` for ``material.mu``). Without
    it the row's axis value was NaN, and an export put the row at another point of the grid
    (m* = 1, mu = 0.1 written at m* = 0.01, mu = 0.5)."""
    axes = {k for row in rows for k in row if "." in k}
    for row in rows:
        for key in axes:
            value = row.get(key)
            if value is not None and not (isinstance(value, float) and math.isnan(value)):
                continue
            plain = PLAIN_COLUMNS.get(key)
            fill = row.get(plain) if plain is not None else get_dotted(swept_from, key)
            if fill is not None:
                row[key] = fill


def _table_path(table: str | Path | None) -> Path | None:
    """The Parquet table's path, or one line (SceneError) for a name that is not ``.parquet``
    (a ``.csv`` got Parquet bytes) or a folder that cannot hold it (the error came from the
    journal's first write, as a FileNotFoundError)."""
    if table is None:
        return None
    path = Path(table)
    if path.suffix.lower() != ".parquet":
        raise SceneError(f"table = {str(path)!r}: a sweep table is Parquet; give a name ending "
                         "in .parquet (sawdrift export turns it into NetCDF or CSV)")
    problem = write_problem(path.parent)  # the folder made, before any cell runs
    if problem is not None:
        raise SceneError(f"table = {str(path)!r} cannot be written ({problem})")
    return path


def _points(points: Sequence[Sequence[float]] | None) -> list[tuple[float, float]] | None:
    """``points`` as (m*, A*) pairs of numbers, or one line (SceneError); their values are
    checked by the scenes they make."""
    if points is None:
        return None
    out = []
    for point in points:
        try:
            m, a = (float(v) for v in point)
        except (TypeError, ValueError):
            raise SceneError(f"points: {point!r} is not an (m*, A*) pair of numbers") from None
        out.append((m, a))
    return out


def _write_back(frame: pd.DataFrame, path: Path, done: dict[str, dict[str, Any]],
                rows: dict[str, dict[str, Any]], wanted: set[str], swept_from: dict[str, Any],
                traces: bool) -> None:
    """Consolidate a sweep's rows into its table, keeping the table's cells from other grids.

    ``done`` holds the table's and the journal's rows, ``rows`` this grid's (``wanted``, their
    cell ids). The journal is removed (and the traces consolidated). ``frame.attrs`` get
    ``table_cells``, the rows of the written table, and ``other_cells``, those outside this
    grid (an earlier sweep into the same file), for the caller to say so.
    """
    everything = dict(done)
    everything.update(rows)
    kept = supersede(everything.values())
    fill_axes(kept, swept_from)
    write_table(to_frame(kept), path, swept_from)
    frame.attrs["table_cells"] = len(kept)
    frame.attrs["other_cells"] = sum(1 for r in kept if r["cell_id"] not in wanted)
    journal = journal_path(path)
    if journal.exists():
        journal.unlink()
    if traces:
        consolidate_traces(path)
