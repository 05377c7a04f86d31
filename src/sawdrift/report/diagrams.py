"""Phase diagrams (paper Fig. 3) and side-by-side model comparison from a sweep table.

Reads only the table (see :mod:`sawdrift.study.sweep`), never the runner.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from ..errors import SceneError  # noqa: E402
from ..study.axes import column_label  # noqa: E402
from .line_plot import plot_line, swept_field  # noqa: E402
from .marks import (  # noqa: E402
    CREEP_STYLE,
    creep_cells,
    creep_handle,
    draw_resonances,
    format_device_axes,
    mark_creep,
)
from .nearest import nearest, scattered  # noqa: E402
from .selection import (  # noqa: E402
    NO_CELLS,
    check_axis,
    one_map,
    pick_rows,
    select,
    where_label,
)

#: Regime colours, in legend order.
COLOURS = {
    "stick": "#9ecae1",
    "oscillating_slip": "#fdd0a2",
    "drift_with": "#31a354",
    "drift_against": "#e6550d",
    "hopping": "#756bb1",
    "bouncing": "#bcbddc",
    "runaway": "#636363",
    "ejected": "#fec44f",
    "error": "#000000",
}
_ORDER = list(COLOURS)

#: the regime code of a cell whose run failed (its error is in the table)
ERROR_CODE = _ORDER.index("error")


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges for log-spaced centres (geometric midpoints, extended at the ends)."""
    v = np.asarray(values, dtype=float)
    if v.size == 1:
        return np.array([v[0] / 1.5, v[0] * 1.5])
    logs = np.log10(v)
    mids = 0.5 * (logs[1:] + logs[:-1])
    first = logs[0] - (mids[0] - logs[0])
    last = logs[-1] + (logs[-1] - mids[-1])
    return 10.0 ** np.concatenate([[first], mids, [last]])


def regime_grid(table: pd.DataFrame, model: str, x: str = "amplitude", y: str = "m_star",
                where: dict | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(x values, y values, regime codes [y, x]) of one model; missing cells are -1.

    ``x`` and ``y`` are any two swept columns (default A* and m*); ``where`` fixes other columns.
    """
    sub = select(table, model, where)
    for column in (x, y):
        check_axis(sub, column)
    xs = np.sort(sub[x].unique())
    ys = np.sort(sub[y].unique())
    codes = np.full((ys.size, xs.size), -1, dtype=int)
    ix = {v: i for i, v in enumerate(xs)}
    iy = {v: i for i, v in enumerate(ys)}
    for vy, vx, regime in zip(sub[y], sub[x], sub["regime"], strict=True):
        codes[iy[vy], ix[vx]] = _ORDER.index(regime) if regime in COLOURS else _ORDER.index("error")
    return xs, ys, codes


def _cell_mask(sub: pd.DataFrame, flags: np.ndarray, x: str, y: str) -> np.ndarray:
    """``flags`` (one per row of ``sub``) on :func:`regime_grid`'s grid ([y, x]), or-ed per cell."""
    xs = np.sort(sub[x].unique())
    ys = np.sort(sub[y].unique())
    mask = np.zeros((ys.size, xs.size), dtype=bool)
    ix = {v: i for i, v in enumerate(xs)}
    iy = {v: i for i, v in enumerate(ys)}
    for vy, vx, flag in zip(sub[y], sub[x], flags, strict=True):
        mask[iy[vy], ix[vx]] |= bool(flag)
    return mask


def unsettled_grid(table: pd.DataFrame, model: str, x: str = "amplitude", y: str = "m_star",
                   where: dict | None = None) -> np.ndarray:
    """True for each cell of :func:`regime_grid`'s grid whose drift has not settled ([y, x])."""
    sub = select(table, model, where)
    return _cell_mask(sub, unsettled_cells(sub), x, y)


def creep_grid(table: pd.DataFrame, model: str, x: str = "amplitude", y: str = "m_star",
               where: dict | None = None) -> np.ndarray:
    """True for each cell of :func:`regime_grid`'s grid that creeps ([y, x], see
    :func:`sawdrift.report.marks.creep_cells`)."""
    sub = select(table, model, where)
    return _cell_mask(sub, creep_cells(sub), x, y)


#: the hatching of cells whose drift has not settled, in every regime figure and the drift map
HATCH = "////"
#: what the hatching means, in every legend: ``settled`` is false, i.e. the cell's drift did not
#: settle within its cap on a fixed point, a periodic orbit or a motion that beats without
#: repeating (a slow approach, or irregular bouncing whose drift is a long-time mean)
HATCH_LABEL = "not settled: no steady drift found"


def _hatch_unsettled(ax, xs: np.ndarray, ys: np.ndarray, mask: np.ndarray) -> str:
    """Hatch the region where ``mask`` ([y, x] over the points ``xs``, ``ys``) is true.

    The one mechanism of every figure (phase diagram, compare, drift map): a filled contour of
    the mask with no colour and :data:`HATCH`. Returns a title suffix naming how many are
    unsettled ("" when none is).
    """
    if not mask.any():
        return ""
    ax.contourf(xs, ys, mask.astype(float), levels=[0.5, 1.5], colors="none", hatches=[HATCH])
    return f"hatched: not settled ({int(mask.sum())} of {mask.size})"


def _fine(edges: np.ndarray, n: int = 400) -> tuple[np.ndarray, np.ndarray]:
    """Points of a fine log grid over ``edges`` and the index of the cell holding each."""
    fine = np.logspace(np.log10(edges[0]), np.log10(edges[-1]), n)
    return fine, np.clip(np.searchsorted(edges, fine) - 1, 0, edges.size - 2)


def _hatch_cells(ax, amps: np.ndarray, masses: np.ndarray, mask: np.ndarray,
                 cells: int | None = None) -> str:
    """:func:`_hatch_unsettled` for a grid of cells (their centres ``amps``, ``masses``), of
    which ``cells`` were computed (by default all: a merged grid has empty points)."""
    if not mask.any():
        return ""
    fx, ix = _fine(_edges(amps))
    fy, iy = _fine(_edges(masses))
    # the title counts computed cells, not points of the fine grid nor empty ones
    suffix = f"hatched: not settled ({int(mask.sum())} of {mask.size if cells is None else cells})"
    _hatch_unsettled(ax, fx, fy, mask[np.ix_(iy, ix)])
    return suffix


def _draw(ax, amps, masses, codes, title: str, x: str = "amplitude", y: str = "m_star",
          unsettled: np.ndarray | None = None, creep: np.ndarray | None = None,
          rows: pd.DataFrame | None = None) -> list:
    """One regime panel: cells, hatching, creep markers and (from ``rows``) the contact
    resonances. Returns the legend handles of the marks it drew."""
    cmap = ListedColormap(["white", *COLOURS.values()])
    ax.pcolormesh(_edges(amps), _edges(masses), codes + 1, cmap=cmap, vmin=0, vmax=len(COLOURS),
                  shading="flat", edgecolors="none")
    note = (_hatch_cells(ax, amps, masses, unsettled, int((codes >= 0).sum()))
            if unsettled is not None else "")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(column_label(x))
    ax.set_ylabel(column_label(y))
    ax.set_title(wrapped(f"{title}\n{note}" if note else title), fontsize=10)
    handles = mark_creep(ax, amps, masses, creep) if creep is not None else []
    if rows is not None:
        handles += draw_resonances(ax, rows, x, y)
    format_device_axes(ax, x, y)
    return handles


def _legend(fig, codes_list, unsettled: bool = False, marks: list | None = None) -> None:
    """The regimes used (and the hatching, if any cell is unsettled, and the ``marks``' handles:
    creep, resonances, computed points; once each) below the panels.

    As many columns as fit the figure's width: a single row of six regimes is wider than a
    one-panel figure and would be cut at both ends.
    """
    used = sorted({int(c) for codes in codes_list for c in np.unique(codes) if c >= 0})
    handles = [Patch(color=COLOURS[_ORDER[c]], label=_ORDER[c]) for c in used]
    if unsettled:
        handles.append(Patch(facecolor="white", edgecolor="k", hatch=HATCH, label=HATCH_LABEL))
    seen = {h.get_label() for h in handles}
    for handle in marks or []:
        if handle.get_label() not in seen:
            seen.add(handle.get_label())
            handles.append(handle)
    if not handles:
        return
    room = 0.96 * fig.bbox.width
    renderer = fig.canvas.get_renderer()
    for ncol in range(len(handles), 0, -1):  # the most columns that fit (entries differ in width)
        rows = -(-len(handles) // ncol)
        ncol = -(-len(handles) // rows)  # balance the rows
        leg = fig.legend(handles=handles, loc="outside lower center", ncol=ncol, frameon=False)
        if ncol == 1 or leg.get_window_extent(renderer).width <= room:
            return
        leg.remove()


def _material_label(table: pd.DataFrame) -> str:
    """"mu = ..., nu = ..." of the table's cells, of the columns it has (a table without one
    failed as an internal error)."""
    parts = [f"{name} = " + ", ".join(f"{v:g}" for v in sorted(table[name].dropna().unique()))
             for name in ("mu", "nu") if name in table.columns]
    return ", ".join(parts)


def _one_model(table: pd.DataFrame, model: str | None, x: str, y: str) -> str:
    """``model``, or the table's only one; a one-line SceneError where the choice is missing or
    its rows would mix the values of another swept column on one map (:func:`one_map`)."""
    models = sorted(table["model"].dropna().unique())
    if model is None:
        if not models:
            raise SceneError(NO_CELLS)
        if len(models) != 1:
            raise SceneError(f"the table holds several models ({', '.join(models)}); choose one with --model")
        model = models[0]
    rows = select(table, model)
    for column in (x, y):
        check_axis(rows, column)
    one_map(rows, [x, y])
    return model


def plot_phase_diagram(table: pd.DataFrame, path: str | Path, model: str | None = None,
                       x: str = "amplitude", y: str = "m_star", where: dict | None = None) -> Path:
    """Regimes over two swept axes (default A*, m*) on log axes, one colour per regime (Fig. 3).

    A table swept over one field only gets the line plot of :mod:`sawdrift.report.line_plot`.
    ``where`` (``{column: value}``) keeps the cells with those values of other swept columns; a
    table with several values of another swept column needs it (one map never mixes them).
    """
    table = pick_rows(table, where)
    if swept_field(table) is not None:
        return plot_line(table, path, model, colours=COLOURS)
    model = _one_model(table, model, x, y)
    title = f"{model}{where_label(table, where)}: {_material_label(table)}"
    fig, ax = plt.subplots(figsize=(6.4, 5.6), layout="constrained")
    sub = select(table, model)
    if scattered(sub, x, y):
        # an adaptive table on the grid of all its coordinates was mostly empty points (white
        # stripes between the computed ones): each point's region instead, as the drift map's
        codes, unsettled, marks = _nearest_panel(ax, sub, x, y, title)
    else:
        amps, masses, codes = regime_grid(table, model, x, y)
        unsettled = unsettled_grid(table, model, x, y)
        marks = _draw(ax, amps, masses, codes, title, x, y, unsettled,
                      creep_grid(table, model, x, y), sub)
    _legend(fig, [np.unique(codes)], bool(unsettled.any()), marks)
    path = Path(path)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def unsettled_cells(table: pd.DataFrame) -> np.ndarray:
    """True for each row whose drift has not settled (``settled`` false; a missing value is not)."""
    if "settled" not in table.columns:
        return np.zeros(len(table), dtype=bool)
    return (table["settled"].astype("boolean").fillna(True) == False).to_numpy(bool)  # noqa: E712


def plot_drift_map(table: pd.DataFrame, path: str | Path, model: str | None = None,
                   x: str = "amplitude", y: str = "m_star", where: dict | None = None) -> Path:
    """The regime map and, beside it, the drift ratio coloured on a diverging scale.

    Works for uniform and scattered (adaptive) tables alike: each point's cell is the region of
    the log-log plane nearest to it (Voronoi cells, drawn on a fine grid that reaches half a gap
    beyond the outer points, so the outer cells are whole). Regime boundaries (where the regime
    changes between neighbouring points of that grid) are drawn over the drift map. A scattered
    table's computed points are dotted (a full grid's are the cell centres and are not).
    ``where`` picks the values of other swept columns, as in :func:`plot_phase_diagram`.
    """
    from matplotlib.colors import TwoSlopeNorm

    table = pick_rows(table, where)
    model = _one_model(table, model, x, y)
    sub = select(table, model)
    for col in (x, y):
        if sub[col].nunique() < 2:
            raise SceneError(f"the drift map needs at least two values of {col!r}; the table has "
                             f"{sub[col].nunique()} for model {model!r}")
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11.5, 5.0), layout="constrained")
    name = f"{model}{where_label(table, where)}"
    codes, unsettled, marks = _nearest_panel(ax1, sub, x, y, f"{name}: regimes", note=False)
    gx, gy, idx = nearest(sub, x, y)
    drift = sub["drift_ratio"].to_numpy(float)[idx].reshape(gy.size, gx.size)
    # the scale stops at the surface speed (|ratio| = 1): a few chaotic cells far beyond it (long
    # flights after a violent launch) would otherwise wash out every other cell; they saturate
    finite = np.abs(drift[np.isfinite(drift)])
    # no finite drift at all (every cell a runaway): printed "All-NaN slice encountered"
    peak = max(float(finite.max()) if finite.size else 0.0, 1e-6)
    lim = min(peak, 1.0)
    mesh = ax2.pcolormesh(10**gx, 10**gy, drift, cmap="RdBu_r",
                          norm=TwoSlopeNorm(vcenter=0.0, vmin=-lim, vmax=lim), shading="auto")
    ax2.contour(10**gx, 10**gy, codes, levels=np.arange(len(COLOURS)) + 0.5, colors="k",
                linewidths=0.7)
    fig.colorbar(mesh, ax=ax2, label="drift ratio <x*'> / (2 pi r A*)",
                 extend="both" if peak > lim else "neither")
    title2 = f"{name}: drift ratio, regime boundaries"
    # cells whose drift is still on its approach (Result.settled false) are hatched
    mask = unsettled_cells(sub)[idx].reshape(gy.size, gx.size)
    if _hatch_unsettled(ax2, 10**gx, 10**gy, mask):
        title2 += f"; hatched: not settled ({int(unsettled.sum())} of {unsettled.size})"
    _nearest_axes(ax2, sub, x, y, gx, gy, title2)
    _legend(fig, [np.unique(codes)], bool(unsettled.any()), marks)
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def wrapped(title: str, width: int = 60) -> str:
    """``title`` broken into lines of at most ``width`` characters (its own line breaks kept):
    two panels' long titles (a model and two --where values) ran into each other and off the
    figure."""
    import textwrap

    return "\n".join(line for part in title.split("\n")
                     for line in (textwrap.wrap(part, width) or [""]))


def _nearest_panel(ax, sub: pd.DataFrame, x: str, y: str, title: str, note: bool = True
                   ) -> tuple[np.ndarray, np.ndarray, list]:
    """The regime panel of scattered points: each point's region (:func:`~.nearest.nearest`),
    hatched where not settled (said in the title with ``note``), creep marked, computed points
    dotted where they are no full grid. Returns the fine grid's codes, each row's unsettled flag
    and the legend handles."""
    from matplotlib.lines import Line2D

    gx, gy, idx = nearest(sub, x, y)
    codes = np.array([_ORDER.index(r) if r in COLOURS else _ORDER.index("error")
                      for r in sub["regime"]])[idx].reshape(gy.size, gx.size)
    ax.pcolormesh(10**gx, 10**gy, codes + 1, cmap=ListedColormap(["white", *COLOURS.values()]),
                  vmin=0, vmax=len(COLOURS), shading="auto")
    unsettled = unsettled_cells(sub)
    hatched = _hatch_unsettled(ax, 10**gx, 10**gy, unsettled[idx].reshape(gy.size, gx.size))
    if hatched and note:
        title += f"\nhatched: not settled ({int(unsettled.sum())} of {unsettled.size})"
    marks = _nearest_axes(ax, sub, x, y, gx, gy, title)
    lx, ly = np.log10(sub[x].to_numpy(float)), np.log10(sub[y].to_numpy(float))
    creeping = creep_cells(sub)
    if creeping.any():
        ax.scatter(10 ** lx[creeping], 10 ** ly[creeping], **CREEP_STYLE, zorder=5)
        marks.append(creep_handle())
    if sub[[x, y]].drop_duplicates().shape[0] != sub[x].nunique() * sub[y].nunique():
        ax.plot(10**lx, 10**ly, ".", color="k", ms=2, alpha=0.5)
        marks.append(Line2D([], [], ls="none", marker=".", color="k", ms=4, label="computed point"))
    return codes, unsettled, marks


def _nearest_axes(ax, sub: pd.DataFrame, x: str, y: str, gx: np.ndarray, gy: np.ndarray,
                  title: str) -> list:
    """Log axes over the fine grid, labels, title and the contact resonances (their handles)."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(10 ** gx[0], 10 ** gx[-1])
    ax.set_ylim(10 ** gy[0], 10 ** gy[-1])
    ax.set_xlabel(column_label(x))
    ax.set_ylabel(column_label(y))
    ax.set_title(wrapped(title), fontsize=10)
    format_device_axes(ax, x, y)
    return draw_resonances(ax, sub, x, y)
