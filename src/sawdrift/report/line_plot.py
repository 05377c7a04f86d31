"""One-dimensional studies: the drift against the one swept field, as a line plot.

A sweep over one field (a device's speed against its frequency, radius or amplitude; the drift
ratio against A* at one m*) has no plane to colour: :func:`plot_line` draws the value (the speed
in m/s for a device table, else the drift ratio) against the field, one line per model, each
point a marker in its regime's colour (the colours of every regime figure,
:data:`sawdrift.report.diagrams.COLOURS`), an unsettled point open (its drift is still on its
approach). :func:`swept_field` says whether a table is one-dimensional;
:func:`sawdrift.report.diagrams.plot_phase_diagram` draws this plot for such a table.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import EngFormatter, MaxNLocator  # noqa: E402

from ..errors import SceneError  # noqa: E402
from ..study.axes import column_label, column_unit  # noqa: E402
from ..study.table import drift_errors  # noqa: E402

#: regimes without a steady drift speed: a cell of theirs has no value to draw and did not fail
NO_DRIFT = ("runaway", "ejected")
from ..study.export import dimensions  # noqa: E402

#: marker size (points) of a cell
SIZE = 7.0


def swept_field(table: pd.DataFrame) -> str | None:
    """The one swept column of a table (besides the model), or None (none, or several).

    A column a swept device field fixes (m*, A*) does not count (:func:`dimensions`).
    """
    dims = [d for d in dimensions(table) if d != "model"]
    return dims[0] if len(dims) == 1 else None


def value_column(table: pd.DataFrame) -> str:
    """What a line plot shows: the speed in m/s of a device table (even where no cell has one:
    every cell ejected), else the drift ratio."""
    if "drift_speed_m_s" in table.columns:
        return "drift_speed_m_s"
    return "drift_ratio"


def _prefixed(column: str) -> str | None:
    """The SI unit a column's ticks or printed values carry with a prefix (5 MHz, -50 mm/s),
    or None where they are bare numbers (a normalized column, an angle in rad)."""
    unit = column_unit(column)
    return unit if unit and unit != "rad" else None


def axis_label(column: str) -> str:
    """The label of an axis whose ticks are written by :func:`_prefixed`'s rule.

    Ticks that carry a prefixed unit (``8 MHz``, ``-50 mm/s``) make a unit in the label wrong
    (``(Hz)`` over ``8 MHz``): the label is then the bare name (``device.frequency``,
    ``drift speed``); a column whose ticks are bare numbers keeps :func:`column_label`.
    """
    label = column_label(column)
    unit = _prefixed(column)
    suffix = f" ({unit})"
    return label[: -len(suffix)] if unit and label.endswith(suffix) else label


def _unsettled(sub: pd.DataFrame) -> np.ndarray:
    if "settled" not in sub.columns:
        return np.zeros(len(sub), dtype=bool)
    return (sub["settled"].astype("boolean").fillna(True) == False).to_numpy(bool)  # noqa: E712


def _log(values: np.ndarray) -> bool:
    """A log axis for positive values spanning a factor 20 or more."""
    v = values[np.isfinite(values)]
    return bool(v.size and v.min() > 0 and v.max() / v.min() >= 20.0)


def plot_line(table: pd.DataFrame, path: str | Path, model: str | None = None,
              field: str | None = None, value: str | None = None, *,
              colours: dict[str, str]) -> Path:
    """The value (default :func:`value_column`) against the swept ``field``; one line per model.

    Markers take their regime's colour from ``colours`` (the regime figures',
    :data:`sawdrift.report.diagrams.COLOURS`, in legend order, with an ``"error"`` entry); a
    cell whose drift has not settled is drawn open, a cell that failed is left out and counted
    in the title.
    """
    field = field or swept_field(table)
    if field is None or field not in table.columns:
        raise SceneError("a line plot needs a table swept over one field (besides the model)")
    value = value or value_column(table)
    models = [model] if model is not None else sorted(table["model"].dropna().unique())
    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    # the axis first: autoscaling a log axis on a single drawn point warns of a zero width
    categories = _categories(table[field])
    place = {c: float(i) for i, c in enumerate(categories or [])}
    swept = (np.arange(len(categories), dtype=float) if categories is not None
             else table[field].to_numpy(float))
    if _log(swept):
        ax.set_xscale("log")
    _span(ax, swept)
    used: set[str] = set()
    loose = failed = total = none = bars = 0
    for name in models:
        sub = table[table["model"] == name].sort_values(field)
        if sub.empty:
            known = ", ".join(sorted(table["model"].dropna().unique()))
            raise SceneError(f"model {name!r} is not in the table; it holds: {known}")
        x = (sub[field].map(place).to_numpy(float) if categories is not None
             else sub[field].to_numpy(float))
        y = pd.to_numeric(sub[value], errors="coerce").to_numpy(float)
        ok = np.isfinite(x) & np.isfinite(y)
        open_ = _unsettled(sub)
        total += len(sub)
        # a runaway or an ejected particle has no drift speed: not a failure
        gone = sub["regime"].isin(NO_DRIFT).to_numpy() & ~ok
        none += int(gone.sum())
        failed += int((~ok & ~gone).sum())
        loose += int((open_ & ok).sum())
        ax.plot(x[ok], y[ok], "-" if categories is None else "", color="0.55", lw=1.0, zorder=1,
                label=name if len(models) > 1 else None)
        errors = drift_errors(sub, value)
        for xi, yi, regime, is_open, err in zip(x[ok], y[ok], sub["regime"].to_numpy()[ok],
                                                open_[ok], errors[ok], strict=True):
            colour = colours.get(str(regime), colours["error"])
            if np.isfinite(err):  # a long-time mean: its standard error as a bar
                ax.errorbar(xi, yi, yerr=err, color=colour, lw=1.2, capsize=3, zorder=1.5)
                bars += 1
            used.add(str(regime) if str(regime) in colours else "error")
            ax.plot(xi, yi, "o", ms=SIZE, zorder=2, mec=colour if is_open else "k",
                    mfc="white" if is_open else colour, mew=2.0 if is_open else 0.6)
    if categories is not None:  # a word swept (an orbit's sense, a switch): one tick each
        ax.set_xticks(swept, [str(c) for c in categories])
        ax.set_xlim(-0.5, len(categories) - 0.5)
    elif not _log(swept):  # few ticks: a unit on each must not collide with the next
        ax.xaxis.set_major_locator(MaxNLocator(nbins=5))
    # SI ticks with prefixes: 5 MHz, -120 um/s (not 5e6, -0.00012)
    for axis, column in ((ax.xaxis, field), (ax.yaxis, value)):
        if axis is ax.xaxis and categories is not None:
            continue
        unit = _prefixed(column)
        if unit:
            axis.set_major_formatter(EngFormatter(unit=unit, sep=" "))
    ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    # the unit is on every tick (5 MHz, -50 mm/s), so the labels name the quantity only
    ax.set_xlabel(axis_label(field))
    ax.set_ylabel(axis_label(value) if column_unit(value) else _normalized_label(value))
    notes = [f"open: not settled ({loose} of {total})" if loose else "",
             f"{failed} failed (not drawn)" if failed else "",
             f"{none} without a drift (runaway or ejected, not drawn)" if none else "",
             "bars: long-time mean +- its standard error" if bars else ""]
    note = "; ".join(n for n in notes if n)
    title = f"{', '.join(models)}: {_normalized_label(value)} against {field}"
    ax.set_title(f"{title}\n{note}" if note else title, fontsize=10)
    _legend(fig, ax, used, bool(loose), len(models) > 1, colours)
    path = Path(path)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _categories(column: pd.Series) -> list | None:
    """The values of a swept column of words or switches (``device.orbit``,
    ``effects.rotation``), in the table's order, each drawn at its own tick; None for numbers."""
    if pd.api.types.is_numeric_dtype(column) and not pd.api.types.is_bool_dtype(column):
        return None
    return list(dict.fromkeys(column.dropna().tolist()))


def _span(ax, swept: np.ndarray) -> None:
    """The x axis spans every swept value, drawn or not (a sweep whose only drift is one point
    would otherwise get a zero-width axis), with a margin of 5 % (a factor 1.12 on a log axis)."""
    v = swept[np.isfinite(swept)]
    if v.size == 0 or v.min() == v.max():
        return
    lo, hi = float(v.min()), float(v.max())
    if ax.get_xscale() == "log":
        ax.set_xlim(lo / 1.12, hi * 1.12)
    else:
        pad = 0.05 * (hi - lo)
        ax.set_xlim(lo - pad, hi + pad)


def _normalized_label(value: str) -> str:
    return {"drift_speed_m_s": "drift speed", "drift_ratio": "drift ratio <x*'> / (2 pi r A*)",
            "drift_velocity": "drift velocity x*' (a0 f)"}.get(value, value)


def _legend(fig, ax, used: set[str], loose: bool, models: bool, colours: dict[str, str]) -> None:
    """The regimes drawn (and the open marker) below the axes, in the regime figures' order."""
    handles = [Line2D([], [], ls="", marker="o", ms=SIZE, mfc=colours[r], mec="k", mew=0.6,
                      label=r) for r in colours if r in used]
    if loose:
        handles.append(Line2D([], [], ls="", marker="o", ms=SIZE, mfc="white", mec="0.3", mew=2.0,
                              label="not settled"))
    if handles:
        fig.legend(handles=handles, loc="outside lower center", ncol=min(len(handles), 4),
                   frameon=False)
    if models:
        ax.legend(loc="best", fontsize=8, frameon=False)


def line_rows(table: pd.DataFrame, field: str | list[str],
              value: str | None = None) -> list[str]:
    """The points of a table as text: its swept field(s), value, regime (per model). A device
    table swept over several fields is printed so too, in SI units (its regime maps are drawn
    over m* and A*)."""
    fields = [field] if isinstance(field, str) else list(field)
    value = value or value_column(table)
    # the swept values are written with their prefixed unit (5 MHz): the header names the field
    # only; the value column is printed as a bare number in its SI unit, which the header names
    heads = [axis_label(f) for f in fields]
    widths = [max(len(h), 14) for h in heads]
    fmts = [EngFormatter(unit=u, sep=" ") if (u := _prefixed(f)) else None for f in fields]
    lines = [f"{'model':>20} " + " ".join(f"{h:>{w}}" for h, w in zip(heads, widths, strict=True))
             + f" {column_label(value):>18}  regime"]
    ordered = table.sort_values(["model", *fields])
    for data, err in zip(ordered.to_dict(orient="records"), drift_errors(ordered, value),
                         strict=True):
        v = pd.to_numeric(pd.Series([data.get(value)]), errors="coerce").iloc[0]
        shown = f"{v:18.6g}" if np.isfinite(v) else f"{'none':>18}"
        mark = " (not settled)" if data.get("settled") is False or data.get("settled") == 0 else ""
        if np.isfinite(err):  # a long-time mean: drift +- its standard error
            mark = f" (long-time mean +- {err:.2g})"
        where = " ".join(f"{_swept_text(data[f], fmt):>{w}}"
                         for f, fmt, w in zip(fields, fmts, widths, strict=True))
        lines.append(f"{data['model']:>20} {where} {shown}  {data['regime']}{mark}")
    return lines


def _swept_text(value: object, fmt: EngFormatter | None) -> str:
    """A swept value as the table prints it: with its prefixed unit, a number to 6 figures, or a
    word as it is (``device.orbit = retrograde``, ``effects.rotation = True``)."""
    if isinstance(value, bool | str | np.bool_) or value is None:
        return str(value)
    return fmt(value) if fmt is not None else f"{value:.6g}"
