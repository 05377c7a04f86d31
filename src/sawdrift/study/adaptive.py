"""Adaptive phase diagrams: refine only where the regime changes, probing every cell first.

The plane (log10 m*, log10 A*) is covered by a base grid of ``base`` x ``base`` points; every
point lies on the uniform grid of (base - 1) 2^levels + 1 points per axis (161 for the defaults 21
and 3). A square cell of that grid is *probed* with a nine-point stencil: its four corners, its
centre (always computed, so that an island inside a cell whose corners agree is seen) and its four
edge midpoints (computed where the edge's two ends disagree; where they agree the midpoint gets
their regime without a run: *inferred*). Every cell of the base grid is probed. A probed cell
whose nine points do not all agree is split into its four quarters (whose corners are those nine
points); a quarter whose corners disagree is probed in turn, its inferred corners computed first
(a thin band crossing an edge whose ends agree would otherwise be guessed away), down to cells of
two fine spacings, whose stencil reaches the fine grid. Cells are probed coarsest first, until
the budget of computed points is spent or no cell disagrees.

Inferred points are checked: a deterministic sample of them (a share ``verify``, chosen by a hash
of the grid position) is computed as well, and a wrong guess replaces the inferred regime, which
makes every cell that has the point in its stencil disagree, so those cells are split, also cells
probed in an earlier round.

What this guarantees: every feature of the diagram that contains a point of the base grid or a
centre of a base cell (a lattice of half the base spacing along the diagonals) is found and its
boundary followed down to the fine grid, as far as the budget goes; a feature that contains no
point of that lattice is found only if a computed edge midpoint or a sampled inferred point falls
in it. On the benchmark plane (mmd, m* 1e-3..1e4, A* 1e-2..10, 21 x 21 base, 161 x 161 fine grid)
the map is 0.43 % wrong with 13.8 % of the points computed (benchmarks/bench_adaptive.py);
corner-only refinement was 0.91 % wrong with 9.8 % and missed every island of 0.07 decade
between base points. The adaptive map at any node of the
fine grid is the regime of the nearest computed or inferred point in the log-log plane
(:func:`regime_map`); :func:`misclassified_area` measures it against a uniform map.

Computed points go through :func:`sawdrift.study.sweep.sweep` (same executors, engines, resumable
table and journal), one call per round: an interrupted adaptive sweep, run again with the same
arguments, recomputes only what is missing. The table holds the computed points only; the
returned frame holds those and the inferred ones (column ``inferred``). For tests of the method,
``regime_of`` replaces the runs by a function of (m*, A*).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..errors import SceneError
from .executor import Executor, resolve_workers
from .progress import progress as make_progress

Key = tuple[int, int]
Cell = tuple[int, int, int]  # lower-left corner (i, j) and size s, in fine-grid spacings


def stencil(cell: Cell) -> tuple[list[Key], Key, list[tuple[Key, Key, Key]]]:
    """A cell's corners, its centre, and its edges as ``(midpoint, end, end)``."""
    i, j, s = cell
    h = s // 2
    corners = [(i, j), (i + s, j), (i, j + s), (i + s, j + s)]
    edges = [((i + h, j), (i, j), (i + s, j)), ((i, j + h), (i, j), (i, j + s)),
             ((i + s, j + h), (i + s, j), (i + s, j + s)),
             ((i + h, j + s), (i, j + s), (i + s, j + s))]
    return corners, (i + h, j + h), edges


def sampled(key: Key, share: float) -> bool:
    """Whether an inferred point is among the verified sample (a fixed hash of its position)."""
    if share <= 0.0:
        return False
    i, j = key
    return ((i * 73856093) ^ (j * 19349663)) % 997 < share * 997


class Refinement:
    """The state of an adaptive diagram: computed and inferred regimes on the fine grid.

    Parameters
    ----------
    fine, step
        Points per axis of the fine grid, and the base grid's spacing in fine spacings.
    evaluate
        Computes the regimes of a list of grid points (one round), ``{key: regime}``.
    budget
        Most points computed.
    verify
        Share of inferred points that are computed to check the inference.
    """

    def __init__(self, fine: int, step: int, evaluate: Callable[[list[Key]], dict[Key, str]],
                 budget: int, verify: float) -> None:
        self.fine, self.step, self.evaluate = fine, step, evaluate
        self.budget, self.verify = budget, verify
        self.computed: dict[Key, str] = {}
        self.inferred: dict[Key, str] = {}
        self.wrong_guesses = 0

    def regime(self, key: Key) -> str | None:
        """The computed regime of a point, else its inferred one (None: unknown)."""
        got = self.computed.get(key)
        return got if got is not None else self.inferred.get(key)

    def agrees(self, cell: Cell) -> bool:
        """Whether the known points of a cell's stencil all have one regime."""
        corners, centre, edges = stencil(cell)
        seen = {self.regime(k) for k in [*corners, centre, *(e[0] for e in edges)]}
        seen.discard(None)
        return len(seen) <= 1

    def _compute(self, keys: Iterable[Key]) -> None:
        todo = sorted({k for k in keys if k not in self.computed})
        if not todo:
            return
        for key, regime in self.evaluate(todo).items():
            guess = self.inferred.pop(key, None)
            if guess is not None and guess != regime:
                self.wrong_guesses += 1
            self.computed[key] = regime

    def run(self) -> None:
        """Compute the base grid, then probe and split cells coarsest first (module docstring)."""
        step, fine = self.step, self.fine
        base = [(i, j) for i in range(0, fine, step) for j in range(0, fine, step)]
        self._compute(base)
        queue = [(i, j, step) for i in range(0, fine - 1, step) for j in range(0, fine - 1, step)]
        leaves: set[Cell] = set()  # probed cells that were not split
        quiet: set[Cell] = set()  # quarters of split cells whose corners agree: not probed
        queue = [c for c in queue if c[2] >= 2]
        while queue and len(self.computed) < self.budget:
            size = max(c[2] for c in queue)
            batch = [c for c in queue if c[2] == size]
            queue = [c for c in queue if c[2] != size]
            # a cell's corners are facts before it is probed: an inferred corner (a midpoint of
            # the split parent) is computed first, or a thin band would be guessed away along
            # every edge it crosses
            confirm: list[Key] = []
            fits = []
            for cell in batch:
                new = [k for k in stencil(cell)[0] if k not in self.computed and k not in confirm]
                if len(self.computed) + len(confirm) + len(new) > self.budget:
                    queue = []
                    break
                confirm += new
                fits.append(cell)
            batch = fits
            self._compute(confirm)
            need: list[Key] = []
            guesses: dict[Key, str] = {}
            taken = []
            for cell in batch:
                corners, centre, edges = stencil(cell)
                new = [] if centre in self.computed or centre in need else [centre]
                for mid, e0, e1 in edges:
                    if mid in self.computed or mid in need or mid in new:
                        continue
                    r0, r1 = self.regime(e0), self.regime(e1)
                    if r0 != r1:
                        new.append(mid)
                    elif mid not in self.inferred and mid not in guesses:
                        guesses[mid] = r0  # type: ignore[assignment]
                        if sampled(mid, self.verify):
                            new.append(mid)
                if len(self.computed) + len(need) + len(new) > self.budget:
                    queue = []  # the budget is spent: no finer cells either
                    break
                need += new
                taken.append(cell)
            for key, regime in guesses.items():
                if key not in self.computed:
                    self.inferred.setdefault(key, regime)
            self._compute(need)
            for cell in taken:
                leaves.add(cell)
            # split every probed cell that disagrees, also one probed earlier whose stencil a
            # wrong guess has just corrected; a quarter is probed when its corners disagree
            for cell in sorted(leaves):
                if not self.agrees(cell):
                    leaves.discard(cell)
                    i, j, s = cell
                    h = s // 2
                    if h >= 2:
                        quiet |= {(i, j, h), (i + h, j, h), (i, j + h, h), (i + h, j + h, h)}
            for cell in sorted(quiet):
                if not self.agrees(cell):
                    quiet.discard(cell)
                    queue.append(cell)
            if not taken:
                break


def adaptive_sweep(
    model: str,
    m_range: tuple[float, float],
    a_range: tuple[float, float],
    *,
    budget: int,
    base: int = 21,
    levels: int = 3,
    scene: Any = None,
    table: str | Path | None = None,
    workers: int | None = None,
    scheduler: Any = None,
    progress: bool = False,
    on_row: Any = None,
    engine: str = "compiled",
    force: bool = False,
    traces: bool = False,
    verify: float = 0.125,
    regime_of: Callable[[float, float], str] | None = None,
) -> pd.DataFrame:
    """Compute an adaptive regime diagram of ``model``; return its points, computed and inferred.

    Parameters
    ----------
    m_range, a_range
        (low, high) of m* and A* (log axes): two positive numbers, low < high.
    budget
        Largest number of points computed (the base grid counts).
    base, levels
        Points per axis of the base grid, and the number of halvings of a cell.
    scene, table, workers, scheduler, progress, on_row, engine, force
        As for :func:`sawdrift.study.sweep.sweep` (the base scene, the resumable table of the
        computed points, the executor, the engine, and whether to add to a table of other code).
    verify
        Share in [0, 1] of the inferred points computed as a check (module docstring).
    regime_of
        A function (m*, A*) -> regime used instead of running cells (tests of the method); no
        table is written then.

    Returns
    -------
    pandas.DataFrame
        The computed points' table rows (``inferred`` False) and the inferred points (``inferred``
        True, with model, m_star, amplitude and regime only). ``frame.attrs`` has ``computed``
        (the map's computed points), ``computed_now`` (those run by this call; the others were
        in the table), ``inferred`` and ``wrong_guesses`` (sampled inferred points whose run
        disagreed); with a table also those of :func:`table_share`: the table keeps rows it
        held before, also of an earlier run with a larger budget or of another map.
    """
    from .sweep import sweep

    _check_arguments(model, m_range, a_range, budget=budget, base=base, levels=levels,
                     verify=verify)
    fine = (base - 1) * 2**levels + 1
    lm = np.linspace(math.log10(m_range[0]), math.log10(m_range[1]), fine)
    la = np.linspace(math.log10(a_range[0]), math.log10(a_range[1]), fine)
    frames: list[pd.DataFrame] = []
    ran = [0]  # cells run by this call (those already in the table are not)
    # one counter over the whole map, against its budget (each round's own sweep restarted at
    # 0 % and reached 100 % with "ETA 0.0 s" before the next round began)
    bar = (make_progress(budget, "sweep --adaptive (budget)", "cell")
           if progress and regime_of is None else None)

    def counted(row: dict[str, Any]) -> None:
        ran[0] += 1
        if bar is not None:
            bar.update(1)
        if on_row is not None:
            on_row(row)

    def evaluate(keys: list[Key]) -> dict[Key, str]:
        pts = [(10.0 ** lm[i], 10.0 ** la[j]) for i, j in keys]
        if regime_of is not None:
            ran[0] += len(keys)
            return {k: regime_of(m, a) for k, (m, a) in zip(keys, pts, strict=True)}
        frame = sweep([model], points=pts, base=scene, table=table, progress=False,
                      on_row=counted, engine=engine, force=force, traces=traces,
                      executor=executor)
        lookup = {(round(math.log10(r.m_star), 9), round(math.log10(r.amplitude), 9)): r.regime
                  for r in frame.itertuples()}
        frames.append(frame)
        return {(i, j): lookup[(round(lm[i], 9), round(la[j], 9))] for i, j in keys}

    ref = Refinement(fine, 2**levels, evaluate, budget, verify)
    # one executor for every round (the base grid, then a confirm and a probe batch per level):
    # a pool opened per round started its workers (imports, compiled loops) seven times over
    executor = Executor(resolve_workers(workers), scheduler)
    try:
        ref.run()
    finally:
        executor.close()
        if bar is not None:
            bar.close()
    if regime_of is not None:
        out = pd.DataFrame({"model": model, "m_star": [10.0 ** lm[i] for i, _ in ref.computed],
                            "amplitude": [10.0 ** la[j] for _, j in ref.computed],
                            "regime": list(ref.computed.values())})
    else:
        out = pd.concat(frames, ignore_index=True).drop_duplicates("cell_id")
    out = out.assign(inferred=False)
    keys = sorted(ref.inferred)
    guesses = pd.DataFrame({"model": model, "m_star": [10.0 ** lm[i] for i, _ in keys],
                            "amplitude": [10.0 ** la[j] for _, j in keys],
                            "regime": [ref.inferred[k] for k in keys], "inferred": True})
    frame = pd.concat([out, guesses], ignore_index=True) if keys else out.reset_index(drop=True)
    frame.attrs.update(computed=len(out), inferred=len(keys), wrong_guesses=ref.wrong_guesses,
                       computed_now=ran[0])
    if table is not None and regime_of is None:
        frame.attrs.update(table_share(Path(table), model, lm, la, set(out["cell_id"])))
    return frame


def _check_arguments(model: str, m_range: Any, a_range: Any, *, budget: int, base: int,
                     levels: int, verify: float) -> None:
    """Refuse bad arguments of :func:`adaptive_sweep` before anything runs.

    Parameters
    ----------
    model, m_range, a_range, budget, base, levels, verify
        As for :func:`adaptive_sweep`.

    Raises
    ------
    SceneError
        One line naming the argument and what is allowed.
    ModelNotFoundError
        For an unknown model, the message the rest of the API gives.
    """
    from ..contact.registry import get_model

    get_model(model)  # the one-line ModelNotFoundError the rest of the API gives
    _check_range("m_range", m_range)
    _check_range("a_range", a_range)
    # each bound names its own value (levels = -1 quoted the valid base beside it)
    if not 2 <= base <= 401:
        raise SceneError(f"adaptive: base = {base} must be in [2, 401] (points per axis)")
    if not 0 <= levels <= 10:
        raise SceneError(f"adaptive: levels = {levels} must be in [0, 10] (halvings of a cell)")
    if budget > 1_000_000:
        raise SceneError(f"adaptive: budget = {budget} is more than 1000000 cells; split the "
                         "study")
    if budget < base * base:
        raise SceneError(f"adaptive: budget = {budget} must be at least the base grid, {base} x "
                         f"{base} = {base * base}")
    if not 0.0 <= verify <= 1.0:
        raise SceneError(f"adaptive: verify = {verify} must be in [0, 1]")


def _check_range(name: str, bounds: Any) -> None:
    """Refuse a range that is not two finite positive numbers, low < high (a log axis).

    Parameters
    ----------
    name
        The argument's name, said in the error.
    bounds
        The ``(low, high)`` given.

    Raises
    ------
    SceneError
        One line naming the argument and what is allowed.
    """
    try:
        low, high = (float(v) for v in bounds)
    except (TypeError, ValueError):
        low = high = math.nan
    if not (math.isfinite(low) and math.isfinite(high) and 0.0 < low < high):
        raise SceneError(f"adaptive: {name} = {bounds!r} must be two positive numbers (low, high) "
                         "with low < high (a log axis)")


def table_share(table: Path, model: str, lm: np.ndarray, la: np.ndarray,
                cells: set[str]) -> dict[str, int]:
    """What an adaptive map's table holds besides this map's computed points.

    Parameters
    ----------
    table
        The written table.
    model, lm, la
        The map's model and its fine grid's log10 m* and log10 A*.
    cells
        Cell ids of this map's computed points.

    Returns
    -------
    dict
        ``table_cells`` (rows of the table), ``grid_cells`` (rows of this model on this map's fine
        grid but not among its points: an earlier run with a larger budget) and ``other_cells``
        (rows off that grid: another range, base grid, model or a plain grid sweep).
    """
    held = pd.read_parquet(table, columns=["cell_id", "model", "m_star", "amplitude"])
    extra = held[~held["cell_id"].isin(cells)]
    with np.errstate(divide="ignore", invalid="ignore"):
        em = np.round(np.log10(pd.to_numeric(extra["m_star"], errors="coerce").to_numpy(float)), 9)
        ea = np.round(np.log10(pd.to_numeric(extra["amplitude"], errors="coerce").to_numpy(float)), 9)
    on_grid = ((extra["model"] == model).to_numpy() & np.isin(em, np.round(lm, 9))
               & np.isin(ea, np.round(la, 9)))
    grid = int(on_grid.sum())
    return {"table_cells": len(held), "grid_cells": grid, "other_cells": len(extra) - grid}


def regime_map(points: pd.DataFrame, m_values: np.ndarray, a_values: np.ndarray) -> np.ndarray:
    """Regimes on the grid (m_values x a_values): the nearest computed point in log-log space."""
    from scipy.spatial import cKDTree

    xy = np.column_stack([np.log10(points["m_star"]), np.log10(points["amplitude"])])
    tree = cKDTree(xy)
    mm, aa = np.meshgrid(np.log10(m_values), np.log10(a_values), indexing="ij")
    _, idx = tree.query(np.column_stack([mm.ravel(), aa.ravel()]))
    return points["regime"].to_numpy()[idx].reshape(mm.shape)


def misclassified_area(points: pd.DataFrame, uniform: pd.DataFrame) -> float:
    """Fraction of the uniform table's cells where the adaptive map's regime differs."""
    m_values = np.sort(uniform["m_star"].unique())
    a_values = np.sort(uniform["amplitude"].unique())
    adaptive = regime_map(points, m_values, a_values)
    ref = uniform.pivot_table(index="m_star", columns="amplitude", values="regime",
                              aggfunc="first").reindex(index=m_values, columns=a_values).to_numpy()
    return float(np.mean(adaptive != ref))
