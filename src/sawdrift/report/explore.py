"""The explorer page: phase diagrams to hover, click and compare, in one offline HTML file.

``write_explorer(table, out)`` draws, for every model of a sweep table (and every value of any
other swept column), its regime map beside its drift-ratio map, all on linked axes; a hatched
layer marks the cells where the selected models disagree in regime; hovering a cell lists its
metrics, clicking it draws its last periods (x*, a*, N*, T* against t*) from the traces stored
beside the table (:mod:`sawdrift.study.traces`). The page is built with Bokeh, scripts and data
inline (``bokeh.resources.INLINE``): it opens from disk with no server and no network.

Cells: a table on a full grid of its two axes draws each point as the rectangle between the
midpoints to its neighbours (geometric midpoints on log axes, as the phase diagrams do); any
other table (an adaptive one) draws each point's Voronoi cell in the plot plane (log10 of a log
axis, a linear axis scaled to [0, 1]): the region nearest to it, the adaptive map's own rule
(:func:`sawdrift.study.adaptive.regime_map`). A table swept over device fields (``device.*``
columns) is drawn on those physical axes and its tooltips give the drift in m/s, x*' a0 f
(docs/physics.md, "Physical units").
"""

from __future__ import annotations

import base64
import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..errors import SawdriftError, SceneError
from ..result.regimes import CONTACT_LOST, DRIFTING, check_table_regimes
from ..scene.device import Device, normalized
from ..scene.schema import set_dotted
from ..study.axes import column_unit
from ..study.table import TABLE_COLUMNS, table_metadata
from ..study.traces import PACKED_FIELDS, Trace, pack_traces, read_traces, read_traces_file
from .diagrams import COLOURS
from .explore_page import build_document
from .explore_texts import (  # noqa: F401 - the tooltip's texts, also read from here
    chaotic_cells,
    drift_notes,
    error_text,
    heating_cells,
    warning_texts,
)
from .marks import creep_cells
from .selection import one_map, pick_rows

#: Columns a sweep table must have for the page.
REQUIRED = ("cell_id", "model", "regime", "m_star", "amplitude", "drift_ratio")
_LABELS = {"amplitude": "A*", "m_star": "m*"}
_REGIMES = list(COLOURS)


@dataclass(frozen=True)
class Axis:
    """A plotted column: log or linear, its label (with the SI unit of a device field)."""

    column: str
    log: bool
    label: str
    lo: float = 0.0
    hi: float = 1.0

    def plane(self, values: np.ndarray) -> np.ndarray:
        """Coordinates in the plot plane: log10 on a log axis, else scaled to [0, 1]."""
        v = np.asarray(values, dtype=float)
        return np.log10(v) if self.log else (v - self.lo) / ((self.hi - self.lo) or 1.0)

    def data(self, plane: np.ndarray) -> np.ndarray:
        """The inverse of :meth:`plane`."""
        p = np.asarray(plane, dtype=float)
        return 10.0**p if self.log else self.lo + p * ((self.hi - self.lo) or 1.0)


@dataclass
class Panel:
    """One phase diagram: a model (and values of other swept columns), its cells' rows and shapes."""

    label: str
    model: str
    rows: pd.DataFrame
    quads: dict[str, np.ndarray] | None = None
    patches: dict[str, list[np.ndarray]] | None = None
    #: the values of the other swept columns this panel holds fixed (``{column: value}``)
    fixed: dict[str, Any] | None = None


def load_table(table: str | Path | pd.DataFrame) -> tuple[pd.DataFrame, dict[str, Any], str]:
    """The table, its provenance and its name; a one-line SceneError for any bad input."""
    if isinstance(table, pd.DataFrame):
        frame, meta, name = table, {}, "table"
    else:
        path = Path(table)
        name = str(path)
        if not path.exists():
            raise SceneError(f"table {name!r} does not exist")
        if path.is_dir():
            raise SceneError(f"table {name!r} is a directory, not a Parquet file")
        try:
            frame = pd.read_parquet(path)
            meta = table_metadata(path)
        except Exception as exc:  # noqa: BLE001 - any reader failure is the user's file
            text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise SceneError(f"table {name!r} is not a readable Parquet file ({text})") from None
    missing = [c for c in REQUIRED if c not in frame.columns]
    if missing:
        raise SceneError(f"table {name!r} is not a sawdrift sweep table (no {', '.join(missing)} "
                         "column); make one with `sawdrift sweep`")
    if frame.empty:
        raise SceneError(f"table {name!r} holds no cells")
    check_table_regimes(frame["regime"], name, "make one with `sawdrift sweep`")
    return frame, meta, name


#: SI unit of each device field, by its last name (a sweep table stores device fields in SI)
DEVICE_UNITS = {"frequency": "Hz", "amplitude": "m", "radius": "m", "youngs_modulus": "Pa",
                "density": "kg/m^3", "mass": "kg", "gravity": "m/s^2", "preload": "N"}


def _device_unit(column: str) -> str:
    return column_unit(column) or DEVICE_UNITS.get(column.rsplit(".", 1)[-1], "")


def _numeric(frame: pd.DataFrame, column: str) -> bool:
    return pd.api.types.is_numeric_dtype(frame[column]) and not pd.api.types.is_bool_dtype(frame[column])


def choose_axes(frame: pd.DataFrame, x: str | None = None, y: str | None = None) -> tuple[Axis, Axis]:
    """The plotted columns: ``x``/``y`` if given; swept device fields; else A* and m*."""
    device = sorted((c for c in frame.columns if c.startswith("device.") and _numeric(frame, c)
                     and frame[c].nunique() > 1), key=lambda c: (c != "device.amplitude", c))
    if x is None and y is None and device:
        x = device[0]
        if len(device) > 1:
            y = device[1]
        else:  # one device field: the normalized axis it leaves unchanged
            y = next((c for c in ("m_star", "amplitude") if frame[c].nunique() == 1), "m_star")
    x, y = x or "amplitude", y or "m_star"
    axes = []
    for col in (x, y):
        if col not in frame.columns:
            raise SceneError(f"axis {col!r} is not a column of the table")
        if not _numeric(frame, col):
            raise SceneError(f"axis {col!r} is not a numeric column of the table")
        v = frame[col].to_numpy(dtype=float)
        v = v[np.isfinite(v)]
        if v.size == 0:
            raise SceneError(f"axis {col!r} has no finite value in the table")
        log = bool(v.min() > 0 and (col in _LABELS or v.max() / v.min() >= 10.0))
        unit = _device_unit(col) if col.startswith("device.") else ""
        label = _LABELS.get(col, col) + (f" ({unit})" if unit else "")
        axes.append(Axis(col, log, label, float(v.min()), float(v.max())))
    if axes[0].column == axes[1].column:
        raise SceneError(f"x and y are both {x!r}; choose two different columns")
    return axes[0], axes[1]


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges in the plot plane: midpoints, the ends extended by half a gap."""
    if centres.size == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    mids = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - mids[0]], mids, [2 * centres[-1] - mids[-1]]])


def _pad(values: np.ndarray) -> float:
    gaps = np.diff(np.unique(values))
    return 0.5 * float(np.median(gaps)) if gaps.size else 0.5


def voronoi_cells(u: np.ndarray, w: np.ndarray, box: tuple[float, float, float, float]) -> list[np.ndarray]:
    """The Voronoi cell of every point (u, w) inside ``box`` = (u0, u1, w0, w1), as (k, 2) polygons.

    Clipping by reflection: with every point mirrored across the four sides, the sides are
    edges of the diagram, so each original point's region is finite and ends at the box.
    """
    from scipy.spatial import Voronoi

    u0, u1, w0, w1 = box
    pts = np.column_stack([u, w])
    mirrors = [pts, np.column_stack([2 * u0 - u, w]), np.column_stack([2 * u1 - u, w]),
               np.column_stack([u, 2 * w0 - w]), np.column_stack([u, 2 * w1 - w])]
    vor = Voronoi(np.vstack(mirrors))
    cells = []
    for i in range(len(u)):
        region = [v for v in vor.regions[vor.point_region[i]] if v >= 0]
        poly = vor.vertices[region]
        centre = poly.mean(axis=0)
        poly = poly[np.argsort(np.arctan2(poly[:, 1] - centre[1], poly[:, 0] - centre[0]))]
        poly[:, 0] = np.clip(poly[:, 0], u0, u1)
        poly[:, 1] = np.clip(poly[:, 1], w0, w1)
        cells.append(poly)
    return cells


def _speed_scale(rows: pd.DataFrame, meta: dict[str, Any]) -> np.ndarray | None:
    """a0 f (m/s per unit x*') of each row of a device table; None for a normalized table."""
    base = meta.get("base_scene") or {}
    if not isinstance(base.get("device"), dict):
        return None
    columns = [c for c in rows.columns if c.startswith("device.")]
    cache: dict[tuple, float] = {}
    out = np.full(len(rows), np.nan)
    for k, values in enumerate(rows[columns].itertuples(index=False, name=None)):
        if values not in cache:
            data = copy.deepcopy(base)
            for col, value in zip(columns, values, strict=True):
                set_dotted(data, col, value)
            try:
                norm = normalized(Device.model_validate(data["device"]))
                cache[values] = norm["a0_m"] * norm["frequency_hz"]
            except Exception:  # noqa: BLE001 - a cell whose device no longer validates: no m/s
                cache[values] = math.nan
        out[k] = cache[values]
    return out


def make_panels(frame: pd.DataFrame, xa: Axis, ya: Axis) -> list[Panel]:
    """One panel per model and value of every other swept column, with each cell's shape."""
    # the other swept fields (``--axis`` columns are dotted scene paths, as in study.export)
    skip = {*TABLE_COLUMNS, xa.column, ya.column}
    # m* and A* too where neither axis shows them and they vary at one point of the map (--x
    # material.mu --y m_star: a panel per A*, where one map mixed them and the error pointed at
    # a --where explore did not have); a device table's m* and A* follow from its axes
    plane = [c for c in ("m_star", "amplitude")
             if c in frame.columns and c not in (xa.column, ya.column)
             and frame.groupby([xa.column, ya.column])[c].nunique().max() > 1]
    extra = [c for c in [*plane, *(c for c in frame.columns if "." in c and c not in skip)]
             if frame[c].nunique(dropna=True) > 1]
    finite = np.isfinite(frame[xa.column].to_numpy(float)) & np.isfinite(frame[ya.column].to_numpy(float))
    frame = frame[finite]
    if xa.log:
        frame = frame[frame[xa.column] > 0]
    if ya.log:
        frame = frame[frame[ya.column] > 0]
    frame = frame[frame["model"].notna()]
    panels: list[Panel] = []
    for key, rows in frame.groupby(["model", *extra], sort=True, dropna=False):
        key = key if isinstance(key, tuple) else (key,)
        label = ", ".join([str(key[0]), *(f"{c} = {v}" for c, v in zip(extra, key[1:], strict=True))])
        # several cells at one point (another base scene forced into the table): refused as
        # phase-diagram, compare and export do (one panel mixed mu = 0.1 and 0.2 cells)
        one_map(rows, [xa.column, ya.column])
        rows = rows.reset_index(drop=True)
        panels.append(Panel(label, str(key[0]), rows, fixed=dict(zip(extra, key[1:], strict=True))))
    all_u = np.concatenate([xa.plane(p.rows[xa.column]) for p in panels])
    all_w = np.concatenate([ya.plane(p.rows[ya.column]) for p in panels])
    box = (all_u.min() - _pad(all_u), all_u.max() + _pad(all_u), all_w.min() - _pad(all_w),
           all_w.max() + _pad(all_w))
    for panel in panels:
        u, w = xa.plane(panel.rows[xa.column]), ya.plane(panel.rows[ya.column])
        uu, ww = np.unique(u), np.unique(w)
        if len(u) == uu.size * ww.size:  # a full grid: rectangles
            eu, ew = _edges(uu), _edges(ww)
            iu, iw = np.searchsorted(uu, u), np.searchsorted(ww, w)
            panel.quads = {"left": xa.data(eu[iu]), "right": xa.data(eu[iu + 1]),
                           "bottom": ya.data(ew[iw]), "top": ya.data(ew[iw + 1])}
        else:
            cells = voronoi_cells(u, w, box)
            panel.patches = {"xs": [xa.data(c[:, 0]).astype(np.float32) for c in cells],
                             "ys": [ya.data(c[:, 1]).astype(np.float32) for c in cells]}
    return panels


def regime_code(regimes: Any) -> np.ndarray:
    """Index of each regime in the legend order; -1 for an error or an unknown regime."""
    return np.array([_REGIMES.index(r) if isinstance(r, str) and r in COLOURS and r != "error" else -1
                     for r in regimes], dtype=np.int8)


def codes_at(panels: list[Panel], xa: Axis, ya: Axis) -> list[np.ndarray]:
    """For each panel p, a (panels, cells of p) array: panel q's regime code at p's cells.

    q's regime at a point is that of q's nearest cell in the plot plane (identical points on a
    shared grid).
    """
    from scipy.spatial import cKDTree

    planes = [np.column_stack([xa.plane(p.rows[xa.column]), ya.plane(p.rows[ya.column])]) for p in panels]
    codes = [regime_code(p.rows["regime"]) for p in panels]
    trees = [cKDTree(pl) for pl in planes]
    out = []
    for pl in planes:
        out.append(np.stack([codes[q][trees[q].query(pl)[1]] for q in range(len(panels))]))
    return out


def disagreement(codes: np.ndarray, selected: list[int]) -> np.ndarray:
    """1 where the ``selected`` panels' regimes differ at a cell (none of them an error), else 0."""
    if len(selected) < 2:
        return np.zeros(codes.shape[1], dtype=np.float32)
    sub = codes[selected]
    known = np.all(sub >= 0, axis=0)
    return (known & np.any(sub != sub[0], axis=0)).astype(np.float32)


def compare_groups(panels: list[Panel]) -> list[int]:
    """The comparison group of each panel: the models are compared within each value of the
    other swept columns (as ``compare --by`` does), a panel with the panels of its own values;
    a table of one model compares its values with each other (one group)."""
    if len({p.model for p in panels}) < 2:
        return [0] * len(panels)
    keys = [tuple(sorted((p.fixed or {}).items(), key=lambda kv: kv[0])) for p in panels]
    index = {k: i for i, k in enumerate(dict.fromkeys(keys))}
    return [index[k] for k in keys]


def _traces_for(traces: Any, table: Any) -> dict[str, Trace]:
    if isinstance(traces, Mapping):
        return dict(traces)
    try:
        if traces is not None:
            return read_traces_file(traces)
        return {} if isinstance(table, pd.DataFrame) else read_traces(table)
    except SawdriftError as exc:
        raise SceneError(str(exc)) from None


def _cell_columns(panel: Panel, xa: Axis, ya: Axis, scale: np.ndarray | None) -> dict[str, Any]:
    """The data source columns of a panel's cells (numbers as float32, text as strings)."""
    r = panel.rows

    def num(col: str) -> np.ndarray:
        if col not in r.columns:
            return np.full(len(r), np.nan, dtype=np.float32)
        return pd.to_numeric(r[col], errors="coerce").to_numpy(dtype=float).astype(np.float32)

    settled = r["settled"].astype("boolean") if "settled" in r.columns else pd.Series([pd.NA] * len(r))
    blank = np.full(len(r), "")
    creeping = creep_cells(r)
    cols: dict[str, Any] = {
        "xv": r[xa.column].to_numpy(float), "yv": r[ya.column].to_numpy(float),
        "regime": r["regime"].astype(str).to_numpy(), "drift_ratio": num("drift_ratio"),
        "m_star": num("m_star"), "amplitude": num("amplitude"), "drift_velocity": num("drift_velocity"),
        "settled": np.array(["n/a" if pd.isna(s) else ("yes" if s else "no") for s in settled]),
        "settle_periods": num("settle_periods"), "orbit_period": num("orbit_period"),
        "hop_period": num("hop_period"), "lyapunov": num("lyapunov"),
        "lyapunov_text": lyapunov_text(r),
        "creep": np.where(creeping, "yes", np.where(r["regime"].isin(DRIFTING), "no", "n/a")),
        "gross_slip": num("gross_slip_fraction"), "liftoffs": num("liftoffs_per_period"),
        "version": r["version"].astype(str).to_numpy() if "version" in r.columns else blank,
        "error": r["error"].fillna("").astype(str).to_numpy() if "error" in r.columns else blank,
        "cell_id": r["cell_id"].astype(str).to_numpy(),
        "se_text": drift_notes(r),
        "chaos_mark": np.where(chaotic_cells(r), " (chaotic)", ""),
        "warnings": warning_texts(r),
    }
    if scale is not None:
        cols["speed"] = (num("drift_velocity") * scale).astype(np.float32)
    cols.update(panel.quads or panel.patches or {})
    return cols


def lyapunov_text(rows: pd.DataFrame) -> np.ndarray:
    """The tooltip's Lyapunov exponent of each row: its value, or why there is none.

    The exponent is estimated only for a window that lost contact (the chaos test of bouncing,
    :func:`sawdrift.dynamics.window.lyapunov`); a cell that kept contact has none by design.
    """
    nan = pd.Series(np.nan, index=rows.index)
    value = pd.to_numeric(rows["lyapunov"], errors="coerce") if "lyapunov" in rows.columns else nan
    if "contact_lost" in rows.columns:
        kept = (rows["contact_lost"].astype("boolean").fillna(True) == False).to_numpy(bool)  # noqa: E712
    else:
        kept = ~rows["regime"].isin(CONTACT_LOST).to_numpy(bool)
    out = []
    for v, regime, contact in zip(value.to_numpy(float), rows["regime"].astype(str), kept,
                                  strict=True):
        if np.isfinite(v):
            out.append(f"{v:.4g}")
        elif v == -np.inf:
            out.append("-inf (a perfectly inelastic landing erased the perturbation)")
        elif regime == "error":
            out.append("n/a: the cell failed")
        elif contact:
            out.append("not computed: kept contact")
        else:
            out.append("not computed for this run")
    return np.array(out)


@dataclass
class ExplorerData:
    """Everything the page shows: panels, their cells' columns, traces (packed), page facts."""

    panels: list[Panel]
    sources: list[dict[str, Any]]
    marks: list[np.ndarray]
    xa: Axis
    ya: Axis
    info: dict[str, Any]
    blob: str
    samples: int
    fields: list[str]
    limit: float


def explorer_data(table: str | Path | pd.DataFrame,
                  traces: str | Path | Mapping[str, Trace] | None = None, *,
                  x: str | None = None, y: str | None = None, samples: int = 400,
                  where: dict | None = None) -> ExplorerData:
    """The page's data (see :func:`write_explorer` for the arguments)."""
    frame, meta, name = load_table(table)
    cells = set(frame["cell_id"].astype(str))  # the whole table's, before --where picks
    if where:
        frame = pick_rows(frame, where)
    stored = _traces_for(traces, table)
    xa, ya = choose_axes(frame, x, y)
    panels = make_panels(frame, xa, ya)
    if not panels:
        raise SceneError(f"table {name!r} has no cell with finite {xa.column} and {ya.column}")
    codes = codes_at(panels, xa, ya)
    everyone = list(range(len(panels)))
    groups = compare_groups(panels)
    order: list[str] = []
    sources, marks = [], []
    for p, (panel, code) in enumerate(zip(panels, codes, strict=True)):
        cols = _cell_columns(panel, xa, ya, _speed_scale(panel.rows, meta))
        rows = np.full(len(panel.rows), -1, dtype=np.int32)
        for k, cid in enumerate(cols["cell_id"]):
            if cid in stored:
                rows[k] = len(order)
                order.append(cid)
        cols["trace_row"] = rows
        for q in everyone:
            cols[f"c{q}"] = code[q]
        sources.append(cols)
        marks.append(disagreement(code, [q for q in everyone if groups[q] == groups[p]]))
    if (traces is not None and not isinstance(traces, Mapping) and stored
            and cells.isdisjoint(stored)):
        # a traces file of another table: every click said "no trace stored" without a word
        raise SceneError(f"traces {str(traces)!r} hold none of table {name!r}'s cells: give the "
                         "traces file swept with this table (TABLE.traces.parquet beside it)")
    blob, m = pack_traces([stored[c] for c in order], samples) if order else (b"", 0)
    versions = sorted(frame["version"].dropna().astype(str).unique()) if "version" in frame else []
    info = {
        "name": Path(name).name,
        "version": meta.get("sawdrift_version") or ", ".join(versions),
        "has_orbit_period": "orbit_period" in frame.columns,
        "has_errors": bool("error" in frame.columns and frame["error"].notna().any()),
        "device": any("speed" in s for s in sources),
        "stored": len(order), "cells": int(sum(len(p.rows) for p in panels)),
        "has_warnings": "warnings" in frame.columns, "groups": groups,
        "within": sorted(panels[0].fixed or {}) if len(set(groups)) > 1 else [],
    }
    return ExplorerData(panels, sources, marks, xa, ya, info, base64.b64encode(blob).decode("ascii"), m,
                        list(PACKED_FIELDS), _drift_limit(frame))


def write_explorer(table: str | Path | pd.DataFrame, out: str | Path,
                   traces: str | Path | Mapping[str, Trace] | None = None, *,
                   x: str | None = None, y: str | None = None, samples: int = 400,
                   where: dict | None = None) -> Path:
    """Write the explorer page of a sweep table to ``out`` (one self-contained HTML file).

    Parameters
    ----------
    table
        A sweep table (Parquet file written by ``sawdrift sweep``, or its DataFrame).
    out
        The HTML file to write.
    traces
        Traces for the click panel: a traces file, or ``{cell_id: trace}``; default: the side
        file next to the table (``TABLE.traces.parquet``) and its journal, if any. Without
        traces the page says so, and how to store them (``sawdrift sweep ... --traces``).
    x, y
        Columns on the axes; default: the swept device fields of a device table, else A* and m*.
    samples
        Most samples per stored trace carried by the page (8-bit, see
        :func:`sawdrift.study.traces.pack_traces`).
    where
        ``{column: value}``: only the cells with those values (``--where FIELD=VALUE``), as
        phase-diagram and compare take them.

    Raises
    ------
    SceneError
        One line, for a missing or unreadable file or one that is not a sweep table.
    """
    from bokeh.embed import file_html
    from bokeh.resources import INLINE

    data = explorer_data(table, traces, x=x, y=y, samples=samples, where=where)
    doc = build_document(data)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(file_html(doc, INLINE, doc.title), encoding="utf-8")
    return out


def _drift_limit(frame: pd.DataFrame) -> float:
    """The colour scale's end: the largest |drift ratio|, capped at the surface speed (1)."""
    drift = pd.to_numeric(frame["drift_ratio"], errors="coerce").abs()
    peak = float(drift.max()) if drift.notna().any() else 1.0
    return max(min(peak, 1.0), 1e-6)
