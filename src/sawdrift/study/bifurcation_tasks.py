"""The work of a bifurcation diagram: branch tasks and bisection tasks, with their journals.

A *branch* is one model swept in one direction; it is serial (each value starts from the last
one's state) and runs in one process. Every finished value is appended to the branch's journal
(``DIR/journal/MODEL-DIRECTION.jsonl``) as one JSON line holding its point, its Poincare samples
and the integration's state (:func:`sawdrift.study.branch.save_state`), so a run that is stopped
continues from the last journaled value exactly. The first line is the header: what the branch
computes (scene, axis, values, samples) and the code that computes it
(:func:`sawdrift.study.provenance.code_hash`). A *refinement* bisects one transition between two
neighbouring values of a finished branch; its result is journaled too.

Tasks are plain dicts and the functions here are top-level, so that process pools and dask can
run them.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .._version import __version__
from ..contact.binding import bind
from ..errors import SawdriftError
from ..scene.schema import Scene
from .branch import (
    Budget,
    Point,
    attractor,
    continue_to,
    load_state,
    new_stepper,
    refine,
    save_state,
    transitions,
)
from .executor import Executor
from .progress import counter
from .provenance import TableProvenanceError, code_hash

#: Fractions of a bracket tried in turn when a midpoint's run fails (a step it cannot resolve).
_FRACTIONS = (0.5, 0.45, 0.55, 0.4, 0.6)

#: Values past a bracket that a refinement may move on to (see :func:`~.branch.refine`).
AHEAD = 3

#: Header keys that must match for a journal to be continued (the rest is provenance).
_SPEC_KEYS = ("model", "direction", "field", "values", "samples", "transient", "scene", "engine")


def _scene_at(base: Scene, field: str) -> Callable[[float], Scene]:
    def at(value: float) -> Scene:
        return bind(base.with_updates(**{field: value}))  # bound: its model's checks, defaults

    return at


def header(task: dict[str, Any]) -> dict[str, Any]:
    """The journal header of a branch task: its spec and the code behind it."""
    spec = {key: task[key] for key in _SPEC_KEYS}
    return {"header": spec, "code_hash": code_hash([task["model"]]), "version": __version__}


def read_journal(path: Path | None, task: dict[str, Any], force: bool) -> dict[str, Any]:
    """The branch's journaled values ``{"points": {i: record}, "refined": {key: record}}``.

    Raises
    ------
    TableProvenanceError
        The journal belongs to another spec (axis, values, samples, scene) or to other code,
        unless ``force``: another spec is then started afresh, other code's values are kept.
    """
    out: dict[str, Any] = {"points": {}, "refined": {}}
    if path is None or not path.exists():
        return out
    with path.open(encoding="utf-8", errors="replace") as fh:  # a damaged byte: no JSON
        lines = fh.read().splitlines()
    try:
        head = json.loads(lines[0]) if lines else None
    except json.JSONDecodeError:
        head = None
    mine = header(task)
    if head is None or head.get("header") != mine["header"]:
        if not force:
            theirs = (head or {}).get("header") or {}
            diff = [k for k in _SPEC_KEYS if theirs.get(k) != mine["header"][k]]
            raise TableProvenanceError(
                f"journal {str(path)!r} holds another bifurcation diagram (its "
                f"{', '.join(diff) or 'header'} differ): use another output folder, or "
                "force=True (--force) to start it again")
        path.unlink()
        return out
    if head.get("code_hash") != mine["code_hash"] and not force:
        raise TableProvenanceError(
            f"journal {str(path)!r} was computed by other code (sawdrift {head.get('version')} "
            f"code {head.get('code_hash')}; this is code {mine['code_hash']}): use another output "
            "folder, or force=True (--force) to go on with this code")
    for line in lines[1:]:
        try:
            rec = json.loads(line)
        except json.JSONDecodeError:
            continue  # a line cut by a kill: that value is computed again
        if "i" in rec:
            # a row is the value its index names on this axis, or it is computed again (a row
            # with value NaN went into the table as it was)
            i, values = rec["i"], task["values"]
            value = rec.get("value")
            if (isinstance(i, int) and 0 <= i < len(values) and isinstance(value, (int, float))
                    and float(value) == float(values[i])):
                out["points"][i] = rec
        elif "refined" in rec:
            out["refined"][rec["refined"]] = rec
    return out


def _append(path: Path | None, record: dict[str, Any]) -> None:
    if path is None:
        return
    with path.open("a") as fh:
        fh.write(json.dumps(record) + "\n")
        fh.flush()


def run_branch(task: dict[str, Any], on_value: Callable[[dict[str, Any]], None] | None = None
               ) -> list[dict[str, Any]]:
    """Compute (or resume) one branch; return its value records in branch order.

    ``task`` holds ``model, direction, field, values`` (in branch order), ``samples``,
    ``transient``, ``scene`` (JSON of the model's base scene), ``engine``, ``journal`` (a path or
    None) and ``force``. ``on_value`` is called with each newly computed record.
    """
    path = Path(task["journal"]) if task.get("journal") else None
    done = read_journal(path, task, bool(task.get("force")))["points"]
    if path is not None and not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        _append(path, header(task))
    base = Scene.model_validate_json(task["scene"])
    at = _scene_at(base, task["field"])
    values = [float(v) for v in task["values"]]
    budget = Budget.for_scene(base, int(task["samples"]), task.get("transient"))
    engine = task.get("engine", "compiled")
    hash_ = code_hash([task["model"]])
    first = next((i for i in range(len(values)) if i not in done), len(values))
    stepper = None
    if 0 < first < len(values) and done[first - 1].get("state"):
        stepper = load_state(at(values[first - 1]), done[first - 1]["state"], engine)
    for i in range(first, len(values)):
        value = values[i]
        try:
            scene = at(value)
            if stepper is None:
                stepper = new_stepper(scene, engine)
                wave = scene.drive
                start = max(scene.numerics.periods, getattr(wave, "ramp_periods", 0.0) + 1.0)
                stepper.advance(int(math.ceil(start)) * stepper.k_per)
            else:
                stepper = continue_to(stepper, scene)
            point = attractor(stepper, scene, budget, value)
            state: str | None = save_state(stepper)
        except SawdriftError as exc:
            # the branch cannot go on from a failed integration: the next value starts afresh
            point, state, stepper = Point.failed(value, str(exc)), None, None
        record = {"i": i, "value": value, "point": point.to_json(), "state": state,
                  "code_hash": hash_, "version": __version__}
        _append(path, record)
        done[i] = record
        if on_value is not None:
            on_value(record)
    return [done[i] for i in range(len(values))]


def refine_task(task: dict[str, Any]) -> dict[str, Any]:
    """Bisect one transition of a finished branch (see :func:`sawdrift.study.branch.refine`).

    ``task`` holds ``scene``, ``field``, ``samples``, ``transient``, ``engine``, ``tolerance``,
    ``kind``, ``key``, the two neighbours' records ``prev`` and ``next`` (branch order) and
    ``ahead``, the branch's values after ``next`` the search may move on to.
    Returns ``{"refined": key, "result": {...}}``; a bracket that cannot be run carries
    ``error``.
    """
    base = Scene.model_validate_json(task["scene"])
    at = _scene_at(base, task["field"])
    budget = Budget.for_scene(base, int(task["samples"]), task.get("transient"))
    prev = Point.from_json(task["prev"]["point"])
    nxt = Point.from_json(task["next"]["point"])
    error = None
    for frac in _FRACTIONS:
        try:
            result = refine(at, task["prev"]["state"], prev, nxt, task["kind"], budget,
                            float(task["tolerance"]), task.get("engine", "compiled"), frac,
                            task.get("ahead", ()))
            return {"refined": task["key"], "result": result}
        except SawdriftError as exc:
            error = str(exc).splitlines()[0]
    return {"refined": task["key"], "result": {"error": error}}


# -- running the tasks -------------------------------------------------------------------------


def _executor(tasks: list[dict[str, Any]], fn: Callable[[dict[str, Any]], Any], workers: int,
              scheduler: Any) -> Any:
    """Yield (index, result) of ``fn(task)`` for every task on the study executor; in local
    processes also (None, None) every half second, a tick at which the caller polls the journals."""
    with Executor(workers, scheduler) as executor:
        yield from executor.imap(fn, tasks, tick=0.5)


def _journal_lines(tasks: list[dict[str, Any]]) -> int:
    n = 0
    for t in tasks:
        path = t.get("journal")
        if path and Path(path).exists():
            with open(path) as fh:
                n += max(0, sum(1 for _ in fh) - 1)
    return n


def run_branches(tasks: list[dict[str, Any]], workers: int, scheduler: Any, progress: bool,
                 on_value: Callable[[dict[str, Any]], None] | None) -> tuple[list[Any], int]:
    """Run (or resume) every branch task; return their records and how many values were computed.

    Serially, in local processes (one per branch, progress read from the journals) or on dask.
    ``on_value`` sees every newly computed record.
    """
    total = sum(len(t["values"]) for t in tasks)
    held = [set(read_journal(Path(t["journal"]) if t["journal"] else None, t,
                             bool(t["force"]))["points"]) for t in tasks]
    before = sum(len(h) for h in held)
    bar = counter(total - before, "bifurcation", "value", enabled=progress and before < total)
    results: list[Any] = [None] * len(tasks)
    # the executor's own choice, made here too: serially the bar counts each value as it comes
    serial = Executor(workers, scheduler).backend(len(tasks)) == "serial"

    def tick(record: dict[str, Any]) -> None:
        bar.update(1)
        if on_value is not None:
            on_value(record)

    seen = before
    try:
        if serial:
            for i, t in enumerate(tasks):
                results[i] = run_branch(t, tick)
        else:
            for i, res in _executor(tasks, run_branch, workers, scheduler):
                if i is not None:
                    results[i] = res
                now = _journal_lines(tasks)
                if now > seen:
                    bar.update(now - seen)
                    seen = now
            if on_value is not None:
                for done, rec in zip(held, results, strict=True):
                    for r in rec:
                        if r["i"] not in done:
                            on_value(r)
    finally:
        bar.close()
    computed = total - before
    return results, computed


def changes(tasks: list[dict[str, Any]], records: list[Any],
            points: dict[tuple[str, str], list[Point]], locate: bool, tolerance: float,
            workers: int, scheduler: Any, progress: bool) -> list[dict[str, Any]]:
    """Every change between neighbouring values of each branch; bisected when ``locate``.

    Each entry: model, direction, value, from_period (below the value), to_period (above),
    kind (:func:`~sawdrift.study.branch.transitions`), bracket, located. Refinements already
    journaled are read back; the others run as independent tasks (in parallel where workers
    allow) and are journaled as they finish.
    """
    found: list[dict[str, Any]] = []
    todo: list[dict[str, Any]] = []
    for task, rec in zip(tasks, records, strict=True):
        pts = points[(task["model"], task["direction"])]
        journal = Path(task["journal"]) if task["journal"] else None
        refined = read_journal(journal, task, True)["refined"] if locate else {}
        for i in range(len(pts) - 1):
            below, above = sorted((pts[i], pts[i + 1]), key=lambda p: p.value)
            for kind in transitions(below, above):
                key = f"{i}:{kind}"
                entry = {"model": task["model"], "direction": task["direction"],
                         "value": 0.5 * (below.value + above.value),
                         "from_period": below.period, "to_period": above.period, "kind": kind,
                         "bracket": [below.value, above.value], "located": False}
                found.append(entry)
                if not locate:
                    continue
                if key in refined:
                    entry.update(refined[key]["result"], located="error" not in refined[key]["result"])
                    continue
                todo.append({"scene": task["scene"], "field": task["field"],
                             "samples": task["samples"], "transient": task["transient"],
                             "engine": task["engine"], "tolerance": tolerance, "kind": kind,
                             "key": key, "prev": rec[i], "next": rec[i + 1],
                             "ahead": [r["value"] for r in rec[i + 2:i + 2 + AHEAD]],
                             "journal": task["journal"], "entry": len(found) - 1})
    bar = counter(len(todo), "locate", "bracket", enabled=progress and bool(todo))
    try:
        for j, res in _executor([{k: v for k, v in t.items() if k not in ("journal", "entry")}
                                 for t in todo], refine_task, workers, scheduler):
            if j is None:
                continue
            t = todo[j]
            _append(Path(t["journal"]) if t["journal"] else None, res)
            found[t["entry"]].update(res["result"], located="error" not in res["result"])
            bar.update(1)
    finally:
        bar.close()
    return sorted(found, key=lambda e: (e["model"], e["direction"], e["value"]))
