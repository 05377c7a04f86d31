"""Adaptive phase diagrams: refine only where neighbouring cells disagree in regime.

The plane (log10 A*, log10 m*) is covered by a base grid of ``base`` x ``base`` points. A square
cell between four neighbouring points whose regimes differ straddles a regime boundary; it is
split in four by computing its centre and the midpoints of the edges whose two ends disagree (an
edge whose ends agree gets their regime at its midpoint without a run: *inferred*), down to
``levels`` halvings. Every
point therefore lies on the uniform grid of (base - 1) 2^levels + 1 points per axis (161 for the
defaults 21 and 3), and the adaptive map at any node of that grid is the regime of the nearest
computed point in the log-log plane. Cells are refined coarsest first, until the budget of
computed points is spent or no cell straddles a boundary.

Computed points go through :func:`sawdrift.study.sweep.sweep` (same executors, same resumable
table and journal), round by round: an interrupted adaptive sweep, run again with the same
arguments, recomputes only what is missing.

``misclassified_area`` measures it against a uniform map: the fraction of the uniform grid's
nodes (each the same area of the log-log plane) where the adaptive map's regime differs.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..errors import SceneError


def _key(i: int, j: int) -> tuple[int, int]:
    return int(i), int(j)


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
) -> pd.DataFrame:
    """Compute an adaptive regime diagram of ``model``; return its rows (one per point).

    Parameters
    ----------
    m_range, a_range
        (min, max) of m* and A* (log axes).
    budget
        Largest number of points computed (the base grid counts).
    base, levels
        Points per axis of the base grid, and the number of halvings of a boundary cell.
    """
    from .sweep import sweep

    if base < 2 or levels < 0:
        raise SceneError("adaptive: base must be >= 2 and levels >= 0")
    if budget < base * base:
        raise SceneError(f"--budget = {budget} must be at least the base grid, {base} x {base} = "
                         f"{base * base}")
    fine = (base - 1) * 2**levels + 1
    lm = np.linspace(math.log10(m_range[0]), math.log10(m_range[1]), fine)
    la = np.linspace(math.log10(a_range[0]), math.log10(a_range[1]), fine)
    step = 2**levels
    regimes: dict[tuple[int, int], str] = {}
    inferred: set[tuple[int, int]] = set()
    rows: list[pd.DataFrame] = []

    def compute(keys: Sequence[tuple[int, int]]) -> None:
        keys = [k for k in keys if k not in regimes or k in inferred]
        if not keys:
            return
        pts = [(10.0 ** lm[i], 10.0 ** la[j]) for i, j in keys]
        frame = sweep([model], points=pts, base=scene, table=table, workers=workers,
                      scheduler=scheduler, progress=progress, on_row=on_row)
        lookup = {(round(math.log10(r.m_star), 9), round(math.log10(r.amplitude), 9)): r.regime
                  for r in frame.itertuples()}
        for (i, j) in keys:
            regimes[(i, j)] = lookup[(round(lm[i], 9), round(la[j], 9))]
            inferred.discard((i, j))
        rows.append(frame)

    compute([_key(i, j) for i in range(0, fine, step) for j in range(0, fine, step)])
    cells = [(i, j, step) for i in range(0, fine - 1, step) for j in range(0, fine - 1, step)]
    def computed() -> int:
        return len(regimes) - len(inferred)

    while cells and computed() < budget:
        split = [(i, j, s) for i, j, s in cells if s > 1 and len({
            regimes[(i, j)], regimes[(i + s, j)], regimes[(i, j + s)], regimes[(i + s, j + s)]}) > 1]
        if not split:
            break
        split.sort(key=lambda c: -c[2])  # coarsest first
        new_cells, todo = [], []
        guessed: dict[tuple[int, int], str] = {}
        for i, j, s in split:
            h = s // 2
            edges = [((i + h, j), (i, j), (i + s, j)), ((i, j + h), (i, j), (i, j + s)),
                     ((i + s, j + h), (i + s, j), (i + s, j + s)),
                     ((i + h, j + s), (i, j + s), (i + s, j + s))]
            centre = (i + h, j + h)
            fresh = [] if centre in regimes or centre in todo else [centre]
            for mid, e0, e1 in edges:
                if mid in regimes or mid in todo or mid in guessed or mid in fresh:
                    continue
                if regimes[e0] == regimes[e1]:
                    guessed[mid] = regimes[e0]
                else:
                    fresh.append(mid)
            if computed() + len(todo) + len(fresh) > budget:
                break
            todo += fresh
            new_cells += [(i, j, h), (i + h, j, h), (i, j + h, h), (i + h, j + h, h)]
        if not new_cells:
            break
        for key, regime in guessed.items():
            if key not in regimes and key not in todo:
                regimes[key] = regime
                inferred.add(key)
        compute(todo)
        done = {(i, j, s) for i, j, s in split[: len(new_cells) // 4]}
        cells = [c for c in cells if c not in done] + new_cells
    out = pd.concat(rows, ignore_index=True).drop_duplicates("cell_id").assign(inferred=False)
    guesses = pd.DataFrame({"model": model, "m_star": [10.0 ** lm[i] for i, _ in inferred],
                            "amplitude": [10.0 ** la[j] for _, j in inferred],
                            "regime": [regimes[k] for k in inferred], "inferred": True})
    return pd.concat([out, guesses], ignore_index=True)


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
