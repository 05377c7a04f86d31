"""Bifurcation diagrams: how the motion changes along one scene field, for one or more models.

For every value of the axis the particle is run to its attractor, warm-started from the previous
value's final state (a continuation along the branch, :mod:`sawdrift.study.branch`), and K
stroboscopic samples of the Poincare section (the state at integer t*: a*, a*' and x*' - u_x')
are recorded with the lift-off phases, the orbit period (:mod:`sawdrift.study.orbits`: a slowly
decaying alternation near a period doubling is not called period 2), its multiplier and the
largest Lyapunov exponent. ``direction="both"`` sweeps up and down (in parallel processes when
workers allow) and marks where the two branches end on different attractors (hysteresis);
``locate=True`` bisects every change between neighbouring values to a relative tolerance.

Outputs in ``out``: ``bifurcation.parquet`` (one row per sample, the code hash in its metadata as
for sweep tables), ``bifurcation.json`` (the summary) and ``journal/`` (one journal per branch: an
interrupted run resumes from it exactly). The figure is drawn from the result by
:func:`sawdrift.report.bifurcation_plot.plot_bifurcation` (``sawdrift bifurcation -o`` writes it
as ``bifurcation.png``, :data:`FIGURE`).
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._version import __version__
from ..contact.binding import bind
from ..contact.registry import get_model
from ..errors import SceneError
from ..scene.schema import Scene, Wave, build_scene, get_dotted
from .axes import _end, field_kind, parse_values
from .bifurcation_tasks import changes, run_branches
from .branch import SAMPLE_COLUMNS, Point
from .provenance import check_resume, code_hash
from .table import META_BASE_SCENE, META_CODE, META_VERSION, table_metadata

#: Names of the outputs in the output folder.
TABLE, SUMMARY, FIGURE, JOURNALS = "bifurcation.parquet", "bifurcation.json", "bifurcation.png", "journal"

#: Scaled distance between two periodic attractors' states above which they are different.
HYSTERESIS_TOL = 1e-3

#: the most Poincare samples per value (a period of the run each; the scene's period cap)
MOST_SAMPLES = 10_000_000

#: Parquet metadata key holding the diagram's spec (field, values, models, samples, direction).
META_SPEC = b"bifurcation"


@dataclass
class BifurcationResult:
    """What :func:`bifurcation` computed.

    Attributes
    ----------
    table
        One row per Poincare sample (columns in :func:`bifurcation`'s docstring).
    summary
        The JSON summary: spec, per-value points, ``bifurcations``, ``hysteresis``.
    out
        The output folder, or None.
    computed
        Values integrated by this call (the others came from the journals).
    seconds
        Wall time of this call.
    """

    table: pd.DataFrame = field(repr=False)
    summary: dict[str, Any] = field(repr=False)
    out: Path | None
    computed: int
    seconds: float

    @property
    def bifurcations(self) -> list[dict[str, Any]]:
        """Every change between neighbouring values (located if ``locate``), by model and value."""
        return self.summary["bifurcations"]

    @property
    def hysteresis(self) -> list[dict[str, Any]]:
        """Intervals where the up and down branches end on different attractors."""
        return self.summary["hysteresis"]

    def to_json(self) -> dict[str, Any]:
        """The summary (JSON-ready)."""
        return self.summary


def _values(values: str | Sequence[Any], field_name: str) -> list[float]:
    items = parse_values(values, field_name) if isinstance(values, str) else list(values)
    kind = field_kind(field_name)
    out = []
    for item in items:
        if isinstance(item, str) and kind is not None:
            # a quantity of a device field ('5 nm'), as the range form takes it, in SI
            item = _end(item, str(values), field_name, kind)[0]
        if isinstance(item, bool) or not isinstance(item, int | float | np.integer | np.floating):
            raise SceneError(f"axis {field_name} = {values!r}: {item!r} is not a number; a "
                             "bifurcation axis takes numbers (a,b,c | START:STOP:N | lin:START:STOP:N)")
        if not math.isfinite(float(item)):
            raise SceneError(f"axis {field_name} = {values!r}: every value must be finite")
        out.append(float(item))
    distinct = sorted(set(out))
    if len(distinct) < 2:
        raise SceneError(f"axis {field_name} = {values!r} must hold at least two different values")
    return distinct


def check_request(scene: Scene | None, field: str, values: str | Sequence[float], *,
                  samples: int = 64, direction: str = "up", tolerance: float = 1e-3,
                  engine: str = "compiled", workers: int | None = None,
                  transient: int | None = None) -> tuple[Scene, list[float]]:
    """The arguments of :func:`bifurcation` checked before anything runs (one-line
    :class:`~sawdrift.errors.SceneError` each): the bound scene and the axis values."""
    scene = bind(scene if scene is not None else Scene())
    if not isinstance(scene.drive, Wave):
        raise SceneError(f"a bifurcation diagram needs a wave drive; the scene has a "
                         f"{scene.drive.kind} drive")
    if (isinstance(samples, bool) or not isinstance(samples, int | np.integer) or samples < 1
            or samples > MOST_SAMPLES):
        # 1e26 reached numpy's allocation as an internal failure, and left a journal behind
        raise SceneError(f"samples = {samples!r} must be an integer from 1 to {MOST_SAMPLES:.0e}"
                         " (Poincare samples per value, a period each)")
    if direction not in ("up", "down", "both"):
        raise SceneError(f"direction = {direction!r} is not allowed; use up, down or both")
    if not 0.0 < float(tolerance) < 1.0:
        raise SceneError(f"tolerance = {tolerance!r} must be in (0, 1) (relative)")
    if engine not in ("compiled", "python"):
        raise SceneError(f"engine = {engine!r} is not allowed; use 'compiled' or 'python'")
    if workers is not None and workers < 1:
        raise SceneError(f"workers = {workers} must be >= 1")
    if transient is not None and transient < 0:
        raise SceneError(f"transient = {transient} must be >= 0 periods")
    _check_field(scene, field)
    return scene, _values(values, field)


def _model_scenes(scene: Scene, models: str | Sequence[str] | None, field_name: str,
                  values: list[float]) -> dict[str, Scene]:
    names = ([m.strip() for m in models.split(",")] if isinstance(models, str)
             else list(models) if models is not None else [scene.model])
    if not names or any(not n for n in names) or len(set(names)) != len(names):
        raise SceneError(f"models = {models!r} must name one or more different models")
    out = {}
    for name in names:
        get_model(name)
        data = scene.model_dump(exclude_none=True)
        if name != scene.model:
            data["model"], data["model_params"] = name, {}
        base = bind(build_scene(data))
        for v in (values[0], values[-1]):
            bind(base.with_updates(**{field_name: v}))  # the field exists and takes both ends
        out[name] = base
    return out


def _check_field(scene: Scene, field_name: str) -> None:
    if field_name in ("model", "") or field_name.startswith("drive.kind"):
        raise SceneError(f"axis {field_name!r} is not a numeric scene field")
    current = get_dotted(scene.model_dump(), field_name)
    if isinstance(current, bool | str | dict | list):
        raise SceneError(f"axis {field_name!r} is not a numeric scene field (it holds "
                         f"{current!r}); a bifurcation axis must be a number such as "
                         "drive.amplitude, particle.m_star or material.mu")


def bifurcation(
    scene: Scene | None,
    field: str,
    values: str | Sequence[float],
    *,
    models: str | Sequence[str] | None = None,
    samples: int = 64,
    direction: str = "up",
    locate: bool = False,
    tolerance: float = 1e-4,
    out: str | Path | None = None,
    workers: int | None = None,
    scheduler: Any = None,
    progress: bool = True,
    force: bool = False,
    engine: str = "compiled",
    transient: int | None = None,
    on_value: Callable[[dict[str, Any]], None] | None = None,
) -> BifurcationResult:
    """A bifurcation diagram of ``scene`` along ``field`` for one or more models.

    Parameters
    ----------
    scene
        The base scene (a wave drive); default ``Scene()``.
    field, values
        The axis: a numeric dotted scene field (``drive.amplitude``, ``particle.m_star``,
        ``material.mu``, ``model_params.restitution``, ...) and its values: a sequence or
        ``a,b,c`` | ``START:STOP:N`` (log-spaced) | ``lin:START:STOP:N``; at least two different
        numbers, swept in increasing order (``up``) or decreasing order (``down``).
    models
        Model names (a list or ``"a,b"``); default the scene's model. Each model is its own
        branch (the scene with that model and its default parameters).
    samples
        K, the Poincare samples recorded per value (>= 1).
    direction
        ``"up"``, ``"down"`` or ``"both"`` (hysteresis: where the two branches disagree).
    locate
        Bisect every change between neighbouring values (of the orbit period, of lift-off, of a
        resting phase) to the relative ``tolerance``.
    out
        Output folder: ``bifurcation.parquet``, ``bifurcation.json`` and the branches' journals;
        a run stopped and started again resumes. Refused when it holds another diagram or one
        of other code, unless ``force``. The figure is drawn apart, by
        :func:`~sawdrift.report.bifurcation_plot.plot_bifurcation`.
    workers, scheduler
        Local processes for the branches and the refinements (default: all cores; 1 serial),
        or a dask.distributed scheduler address / client.
    progress
        Report progress on stderr (:mod:`sawdrift.study.progress`).
    engine
        ``"compiled"`` or ``"python"``.
    transient
        Periods run at each value before its first window (default 100); a value runs on while
        its motion still converges, up to ``numerics.max_periods`` (default: the settle cap).
    on_value
        Called with every newly computed value's record (``{"i", "value", "point", ...}``).

    Returns
    -------
    BifurcationResult
        ``table`` columns: model, direction, index, value, sample, t, a_star, a_rate, v_rel,
        liftoff_phase, liftoffs, period, exact, multiplier, lyapunov, contact_lost,
        contact_fraction, contact, periods, hysteresis, error, field, code_hash, version.
    """
    t0 = time.perf_counter()
    scene, axis = check_request(scene, field, values, samples=samples, direction=direction,
                                tolerance=tolerance, engine=engine, workers=workers,
                                transient=transient)
    workers = workers if workers is not None else (os.cpu_count() or 1)
    bases = _model_scenes(scene, models, field, axis)
    folder = Path(out) if out is not None else None
    if folder is not None:
        _check_table(folder, scene, force)
    directions = ["up", "down"] if direction == "both" else [direction]
    if folder is not None and not force:
        _check_branches(folder, field, axis, samples, [(m, d) for m in bases for d in directions])
    tasks = [{"model": name, "direction": d, "field": field,
              "values": axis if d == "up" else axis[::-1], "samples": int(samples),
              "transient": transient, "scene": base.model_dump_json(), "engine": engine,
              "force": force,
              "journal": str(folder / JOURNALS / f"{name}-{d}.jsonl") if folder else None}
             for name, base in bases.items() for d in directions]
    records, computed = run_branches(tasks, workers, scheduler, progress, on_value)
    points = {(t["model"], t["direction"]): [Point.from_json(r["point"]) for r in rec]
              for t, rec in zip(tasks, records, strict=True)}
    found = changes(tasks, records, points, locate, tolerance, workers, scheduler, progress)
    hyst = _hysteresis(points, list(bases)) if direction == "both" else []
    summary = _summary(field, axis, list(bases), samples, direction, locate, tolerance, points,
                       found, hyst, scene)
    table = _table(points, field, hyst)
    result = BifurcationResult(table, summary, folder, computed, time.perf_counter() - t0)
    summary["seconds"] = round(result.seconds, 3)  # the computation, before the files
    if folder is not None:
        _write(folder, result, scene)
    return result


# -- hysteresis, summary, table ------------------------------------------------------------------


def _attractor_states(p: Point) -> np.ndarray:
    """The p distinct Poincare states of a converged periodic point (scaled to its own range)."""
    rows = p.samples[-max(p.period, 1):, 2:5]
    return rows / np.maximum(np.abs(p.samples[:, 2:5]).max(axis=0), 1.0)


def _disagree(up: Point, down: Point) -> bool:
    """True if two points of one value are on different attractors (see :data:`HYSTERESIS_TOL`)."""
    if up.error is not None or down.error is not None:
        return False
    if up.period != down.period or up.contact != down.contact:
        return True
    if up.period == 0 or not (up.exact and down.exact):
        return False  # two chaotic (or unconverged) motions cannot be told apart this way
    a, b = _attractor_states(up), _attractor_states(down)
    dist = np.abs(a[:, None, :] - b[None, :, :]).max(axis=2).min(axis=1).max()
    return bool(dist > HYSTERESIS_TOL)


def _hysteresis(points: dict[tuple[str, str], list[Point]], models: list[str]) -> list[dict[str, Any]]:
    out = []
    for name in models:
        up = points[(name, "up")]
        down = {p.value: p for p in points[(name, "down")]}
        run: list[float] = []
        for p in [*up, None]:
            if p is not None and _disagree(p, down[p.value]):
                run.append(p.value)
                continue
            if run:
                out.append({"model": name, "from": run[0], "to": run[-1], "values": len(run)})
                run = []
    return out


def _summary(field_name: str, axis: list[float], models: list[str], samples: int, direction: str,
             locate: bool, tolerance: float, points: dict[tuple[str, str], list[Point]],
             found: list[dict[str, Any]], hyst: list[dict[str, Any]], scene: Scene) -> dict[str, Any]:
    return {
        "field": field_name, "values": axis, "models": models, "samples": samples,
        "direction": direction, "locate": locate, "tolerance": tolerance,
        "sawdrift_version": __version__, "code_hash": code_hash(models),
        "points": {name: {d: [p.summary() for p in pts] for (m, d), pts in points.items()
                          if m == name} for name in models},
        "bifurcations": found, "hysteresis": hyst,
        "base_scene": json.loads(scene.model_dump_json()),
    }


def _table(points: dict[tuple[str, str], list[Point]], field_name: str,
           hyst: list[dict[str, Any]]) -> pd.DataFrame:
    frames = []
    for (name, d), pts in points.items():
        spans = [(h["from"], h["to"]) for h in hyst if h["model"] == name]
        hash_ = code_hash([name])
        for idx, p in enumerate(pts):
            f = pd.DataFrame(p.samples, columns=list(SAMPLE_COLUMNS))
            f["sample"] = f["sample"].astype(int)
            f["liftoffs"] = f["liftoffs"].fillna(0).astype(int)
            for key, val in (("model", name), ("direction", d), ("index", idx),
                             ("value", p.value), ("period", p.period), ("exact", p.exact),
                             ("multiplier", p.multiplier), ("lyapunov", p.lyapunov),
                             ("contact_lost", p.contact_lost),
                             ("contact_fraction", p.contact_fraction), ("contact", p.contact),
                             ("periods", p.periods),
                             ("hysteresis", any(a <= p.value <= b for a, b in spans)),
                             ("error", p.error), ("field", field_name), ("code_hash", hash_),
                             ("version", __version__)):
                f[key] = val
            frames.append(f)
    order = ["model", "direction", "index", "value", *SAMPLE_COLUMNS, "period", "exact",
             "multiplier", "lyapunov", "contact_lost", "contact_fraction", "contact", "periods",
             "hysteresis", "error", "field", "code_hash", "version"]
    table = pd.concat(frames, ignore_index=True)[order]
    for col in ("model", "direction", "contact", "error", "field", "code_hash", "version"):
        table[col] = table[col].astype("string")
    return table


# -- files ---------------------------------------------------------------------------------------


def _check_table(folder: Path, scene: Scene, force: bool) -> None:
    """Refuse a folder whose table was computed by other code or from another base scene."""
    if folder.exists() and not folder.is_dir():
        raise SceneError(f"out = {str(folder)!r} exists and is not a folder")
    path = folder / TABLE
    if not path.exists():
        return

    try:
        rows = pd.read_parquet(path, columns=["model", "version", "code_hash"])
    except Exception as exc:  # noqa: BLE001 - a foreign or broken file must not be overwritten
        raise SceneError(f"table {str(path)!r} exists but is not a bifurcation table ({exc})"
                         .splitlines()[0]) from None
    rows = rows.to_dict(orient="records")
    check_resume(path, rows, table_metadata(path)["base_scene"],
                 json.loads(scene.model_dump_json()), force)


def _check_branches(folder: Path, field_name: str, axis: list[float], samples: int,
                    branches: list[tuple[str, str]]) -> None:
    """Refuse a run that would drop branches of the same diagram from the folder's table.

    Parameters
    ----------
    folder
        The output folder.
    field_name, axis, samples
        This run's axis and samples: a table of another axis is another diagram (the journals'
        check names it).
    branches
        This run's (model, direction) branches.

    Raises
    ------
    SceneError
        The table holds a branch of this diagram (a direction or a model) that the run leaves out:
        its rewritten table would lose it.
    """
    import pyarrow.parquet as pq

    path = folder / TABLE
    if not path.exists():
        return
    meta = pq.read_schema(path).metadata or {}
    try:
        spec = json.loads(meta[META_SPEC].decode())
    except (KeyError, ValueError):
        return
    if (spec.get("field"), spec.get("values"), spec.get("samples")) != (field_name, axis, samples):
        return
    held = pd.read_parquet(path, columns=["model", "direction"]).drop_duplicates()
    dropped = sorted({(str(m), str(d)) for m, d in held.itertuples(index=False)} - set(branches))
    if not dropped:
        return
    ways = {d for _, d in dropped} | {d for _, d in branches}
    models = sorted({m for m, _ in dropped} | {m for m, _ in branches})
    way = "both" if len(ways) > 1 else next(iter(ways))
    wider = [f"direction='{way}' (--direction {way})"]
    if len(models) > len({m for m, _ in branches}):
        wider.append(f"models='{','.join(models)}' (--model {','.join(models)})")
    what = ", ".join(f"{m} {d}" for m, d in dropped)
    raise SceneError(
        f"out = {str(folder)!r} already holds this diagram's {what} branch"
        f"{'es' if len(dropped) > 1 else ''}, which this run would drop from its table: give "
        f"{' and '.join(wider)} (values already computed are read back), another output folder, "
        "or force it (--force; force=True in Python) to replace the table")


def _write(folder: Path, result: BifurcationResult, scene: Scene) -> None:
    """Write the table (atomically, with provenance metadata) and the summary."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    folder.mkdir(parents=True, exist_ok=True)
    s = result.summary
    arrow = pa.Table.from_pandas(result.table, preserve_index=False)
    meta = dict(arrow.schema.metadata or {})
    meta[META_VERSION] = s["sawdrift_version"].encode()
    meta[META_CODE] = s["code_hash"].encode()
    meta[META_BASE_SCENE] = json.dumps(s["base_scene"]).encode()
    meta[META_SPEC] = json.dumps({k: s[k] for k in ("field", "values", "models", "samples",
                                                    "direction")}).encode()
    tmp = folder / f".{TABLE}.{os.getpid()}.tmp"
    pq.write_table(arrow.replace_schema_metadata(meta), tmp)
    os.replace(tmp, folder / TABLE)
    (folder / SUMMARY).write_text(json.dumps(s, indent=1) + "\n")
