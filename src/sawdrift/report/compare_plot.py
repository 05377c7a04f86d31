"""Phase diagrams side by side: models, or models and the values of another swept column.

With one panel per model, one more panel marks the cells where the models disagree. With a
``by`` column (``effects.rotation``, say) the panels form a grid, a row per model and a column
per value, and two kinds of difference are kept apart: at the end of each row, the cells where
that value changes the model's regime; under each column, the cells where the models disagree at
that value. Reads only the table, like :mod:`sawdrift.report.diagrams`.
"""

from __future__ import annotations

from itertools import combinations
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

from ..errors import SceneError  # noqa: E402
from ..study.axes import column_label  # noqa: E402
from .diagrams import (  # noqa: E402
    ERROR_CODE,
    _draw,
    _edges,
    _legend,
    _material_label,
    creep_grid,
    regime_grid,
    unsettled_grid,
)
from .marks import format_device_axes  # noqa: E402
from .selection import (  # noqa: E402
    NO_CELLS,
    _value_text,
    _values_text,
    check_axis,
    one_map,
    pick_rows,
    scene_column,
    select,
    where_label,
)

#: panel size (inches) and the widest figure (inches; at 110 dpi, 1485 pixels)
PANEL_W, PANEL_H, MAX_WIDTH = 4.2, 3.9, 13.5
#: panels per row when only models are compared
MAX_COLUMNS = 3


def variants(table: pd.DataFrame, models: list[str], by: str | None) -> list[tuple[str, str, dict]]:
    """(label, model, fixed columns) of each panel: one per model, or per model and value of ``by``."""
    if by is None:
        return [(m, m, {}) for m in models]
    if by not in table.columns:
        raise SceneError(f"--by {by!r} is not a column of the table (sweep it with --axis)")
    values = sorted(table[by].dropna().unique().tolist())
    for m in models:
        # a model swept at fewer values of by than another has no cells for some panels (an
        # internal failure, exit 3: "single positional indexer is out-of-bounds")
        held = table.loc[table["model"] == m, by]
        missing = [v for v in values if v not in held.dropna().unique().tolist()]
        if missing:
            raise SceneError(f"--by {by}: model {m} has no cells at {by} = "
                             f"{', '.join(map(_value_text, missing))} (its table holds {by} = "
                             f"{_values_text(held)}); compare the values all models have with "
                             f"--where {by}=VALUE")
    return [(f"{m}, {by} = {v}", m, {by: v}) for m in models for v in values]


def _computed(codes: np.ndarray) -> np.ndarray:
    """Cells with a regime: neither missing (-1) nor a run that failed (the 'error' code)."""
    return (codes >= 0) & (codes != ERROR_CODE)


def agreement_from_grids(labels: list[str], codes: list[np.ndarray]) -> pd.DataFrame:
    """Agreement of every pair of panels over the cells both computed (a cell where one of
    them failed is not counted: 14 failed cells of 25 read as 44 % agreement of two models
    that agreed on all 11 others)."""
    rows = []
    for (la, ca), (lb, cb) in combinations(list(zip(labels, codes, strict=True)), 2):
        both = _computed(ca) & _computed(cb)
        same = int(np.sum((ca == cb) & both))
        n = int(both.sum())
        rows.append({"model_a": la, "model_b": lb, "cells": n, "same_regime": same,
                     "agreement": same / n if n else float("nan")})
    return pd.DataFrame(rows)


def agreement_markdown(frame: pd.DataFrame) -> str:
    """The agreement table as GitHub markdown."""
    lines = ["| model A | model B | cells | same regime | agreement |", "|---|---|---:|---:|---:|"]
    for r in frame.itertuples():
        lines.append(f"| {r.model_a} | {r.model_b} | {r.cells} | {r.same_regime} | {r.agreement:.1%} |")
    return "\n".join(lines) + "\n"


def _differ(ax, amps, masses, codes: list[np.ndarray], title: str, x: str, y: str) -> int:
    """Mark the cells where the regimes ``codes`` differ (red; grey where they agree, white where
    one is missing); return how many differ."""
    stack = np.stack(codes)
    every = np.all(_computed(stack), axis=0)
    differ = np.any(stack != stack[0], axis=0) & every
    shown = np.where(every, differ.astype(int), -1)
    ax.pcolormesh(_edges(amps), _edges(masses), shown + 1,
                  cmap=ListedColormap(["white", "#f0f0f0", "#d62728"]), vmin=0, vmax=2,
                  shading="flat")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(column_label(x))
    ax.set_ylabel(column_label(y))
    ax.set_title(f"{title}\n({int(differ.sum())} of {int(every.sum())} cells all computed)",
                 fontsize=10)
    format_device_axes(ax, x, y)
    return int(differ.sum())


def _layout(n_models: int, values: list | None) -> tuple[int, int]:
    """(rows, columns) of the figure's grid of panels."""
    if values is None:
        n = n_models + 1
        cols = min(MAX_COLUMNS, n)
        return -(-n // cols), cols
    return n_models + (n_models > 1), len(values) + (len(values) > 1)


def _panels(table: pd.DataFrame, models: list[str], by: str | None, x: str,
            y: str) -> list[tuple[str, str, dict]]:
    """:func:`variants`, checked: two panels or more, and none that mixes the values of a swept
    column other than ``by`` (a one-line SceneError naming it and how to pick a value)."""
    if table.empty:
        raise SceneError(NO_CELLS)
    if by is not None and not scene_column(by):
        # --by model ended in an internal failure; an output column would split the panels by
        # the runs' own results
        raise SceneError(f"--by {by!r} is not a swept field: compare draws a panel per model "
                         "already; --by takes a field swept with --axis (e.g. effects.rotation)")
    panels = variants(table, models, by)
    if len(panels) < 2:
        raise SceneError("compare needs at least two panels: two models, or a --by column")
    for column in (x, y):
        check_axis(table, column)
    one_map(table[table["model"].isin(models)], ["model", x, y, *([by] if by else [])],
            by=by is None)
    return panels


def compare_figure(table: pd.DataFrame, models: list[str], by: str | None = None,
                   x: str = "amplitude", y: str = "m_star", where: dict | None = None):
    """The comparison figure (see the module docstring) and its markdown agreement table.

    ``where`` (``{column: value}``) keeps the cells with those values of other swept columns
    (:func:`sawdrift.report.selection.pick_rows`); a table with several values of a swept column
    other than ``by`` needs it: a panel never mixes them.
    """
    table = pick_rows(table, where)
    picked = where_label(table, where)  # (the loops below name each panel's columns ``where``)
    panels = _panels(table, models, by, x, y)
    grids = [regime_grid(table, m, x, y, where) for _, m, where in panels]
    amps, masses = grids[0][0], grids[0][1]
    for (label, _, _), (a2, m2, _) in zip(panels, grids, strict=True):
        if a2.shape != amps.shape or m2.shape != masses.shape or not (
            np.allclose(a2, amps) and np.allclose(m2, masses)
        ):
            raise SceneError(f"{label!r} was swept on a different grid; compare needs shared axes")
    values = None if by is None else sorted(table[by].dropna().unique().tolist())
    nrows, ncols = _layout(len(models), values)
    width = min(PANEL_W * ncols, MAX_WIDTH)
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, PANEL_H * nrows + 0.9), squeeze=False,
                             sharex=True, sharey=True, layout="constrained")
    slots = list(axes.flat)[:len(panels)]
    if values is not None:  # row per model, column per value
        slots = [axes[k // len(values), k % len(values)] for k in range(len(panels))]
    masks = [unsettled_grid(table, m, x, y, where) for _, m, where in panels]
    marks: list = []
    short = by.rsplit(".", 1)[-1] if by else ""
    for ax, (label, model, where), (_, _, codes), mask in zip(slots, panels, grids, masks,
                                                              strict=True):
        title = label if by is None else f"{model}, {short} = {where[by]}"
        marks += _draw(ax, amps, masses, codes, title, x, y, mask,
                       creep_grid(table, model, x, y, where), select(table, model, where))
    codes = [g[2] for g in grids]
    used = set(slots)
    if values is None:
        ax = axes.flat[len(panels)]
        _differ(ax, amps, masses, codes, "cells where the models disagree", x, y)
        used.add(ax)
    else:
        nv = len(values)
        for i, model in enumerate(models):
            if nv > 1:
                _differ(axes[i, nv], amps, masses, codes[i * nv:(i + 1) * nv],
                        f"cells where {short} changes {model}'s regime", x, y)
                used.add(axes[i, nv])
        for j, value in enumerate(values):
            if len(models) > 1:
                _differ(axes[len(models), j], amps, masses, codes[j::nv],
                        f"cells where the models disagree, {short} = {value}", x, y)
                used.add(axes[len(models), j])
    for i, j in np.ndindex(axes.shape):
        if axes[i, j] not in used:
            axes[i, j].set_axis_off()
            if i > 0:  # the panel above keeps the tick labels the shared axis gave this one
                axes[i - 1, j].xaxis.set_tick_params(labelbottom=True)
    _legend(fig, codes, any(m.any() for m in masks), marks)
    head = " vs ".join(models) + (f", {by} = {' / '.join(map(str, values))}" if values else "")
    fig.suptitle(f"{head}{picked}: {_material_label(table)}")
    md = agreement_markdown(agreement_from_grids([p[0] for p in panels], codes))
    return fig, md


def plot_compare(table: pd.DataFrame, models: list[str], path: str | Path, by: str | None = None,
                 x: str = "amplitude", y: str = "m_star",
                 where: dict | None = None) -> tuple[Path, str]:
    """Phase diagrams side by side on shared axes with their differences (module docstring).

    ``by`` names a swept column (e.g. ``effects.rotation``): then every model gets one panel per
    value of it; ``where`` (``{column: value}``) keeps one value of other swept columns. Returns
    the figure path and the markdown agreement table (also written next to the figure as
    ``<name>.md``).
    """
    fig, md = compare_figure(table, models, by, x, y, where)
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    path.with_suffix(".md").write_text(md)
    return path, md
