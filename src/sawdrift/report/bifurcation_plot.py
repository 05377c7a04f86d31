"""The bifurcation diagram figure: Poincare samples, lift-off phases, period and Lyapunov exponent.

One column per model, all on the same axis; rows, top to bottom: the classic diagram (a* at
integer t* against the parameter), the lift-off phases (when the particle loses contact), the
orbit period and the largest Lyapunov exponent. The up branch is drawn in blue, the down branch
in orange; located bifurcations are dotted vertical lines, hysteresis intervals are shaded, a value
whose integration failed is a red cross in the period panel.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from ..study.axes import column_label  # noqa: E402
from .marks import format_device_axes  # noqa: E402

#: colours of the two sweep directions and of the bifurcation kinds
COLOURS = {"up": "#1f77b4", "down": "#ff7f0e"}
KINDS = {"period_doubling": "#d62728", "other": "#7f7f7f", "lift_off": "#2ca02c",
         "contact_regained": "#2ca02c", "sticking_lost": "#9467bd", "sticking_regained": "#9467bd"}


def plot_bifurcation(result: Any, path: str | Path | None = None,
                     summary: dict[str, Any] | None = None, title: str | None = None):
    """Draw a bifurcation diagram (see the module docstring); write a PNG if ``path`` is given.

    Parameters
    ----------
    result
        A :class:`~sawdrift.study.bifurcation.BifurcationResult`, or its table (read back from
        ``bifurcation.parquet``).
    path
        Where to write the PNG.
    summary
        The summary (``bifurcation.json``) when ``result`` is a table: its bifurcations and
        hysteresis intervals are drawn.
    title
        The figure's title (default: the axis and the models).

    Returns
    -------
    matplotlib.figure.Figure
        Closed after writing when ``path`` is given.
    """
    if isinstance(result, pd.DataFrame):
        table, summary = result, summary or {}
    else:
        table, summary = result.table, result.summary
    models = list(dict.fromkeys(table["model"].astype(str)))
    field = str(table["field"].iloc[0]) if len(table) else "value"
    lifts = bool(table["liftoffs"].fillna(0).gt(0).any())
    rows = ["a", "lift", "period", "lyap"] if lifts else ["a", "period", "lyap"]
    heights = {"a": 3.0, "lift": 1.6, "period": 1.2, "lyap": 1.4}
    fig, axes = plt.subplots(len(rows), len(models), figsize=(max(6.4, 4.6 * len(models) + 1.0), 7.5),
                             sharex=True, squeeze=False, layout="constrained",
                             gridspec_kw={"height_ratios": [heights[r] for r in rows]})
    for col, name in enumerate(models):
        sub = table[table["model"].astype(str) == name]
        panel = dict(zip(rows, axes[:, col], strict=True))
        for d in ("up", "down"):
            part = sub[sub["direction"].astype(str) == d]
            if part.empty:
                continue
            _draw_branch(panel, part, d)
        lyap = sub["lyapunov"].to_numpy(dtype=float)
        finite = lyap[np.isfinite(lyap)]
        top = max(0.5, 1.1 * float(finite.max())) if finite.size else 0.5
        panel["lyap"].set_ylim(1.05 * _floor(finite), top)
        _marks(panel, summary, name)
        panel["a"].set_title(name, fontsize=10)
        axes[-1, col].set_xlabel(column_label(field))  # with its unit: device.frequency (Hz)
        if _log_spaced(sub["value"]):  # an axis swept START:STOP:N (m* 0.01:1:5 was crammed)
            axes[-1, col].set_xscale("log")
        format_device_axes(axes[-1, col], field, "")
    axes[0, 0].set_ylabel("a* at integer t*")
    if lifts:
        panel_l = axes[rows.index("lift"), 0]
        panel_l.set_ylabel("lift-off\nphase")
    axes[rows.index("period"), 0].set_ylabel("orbit\nperiod")
    axes[rows.index("lyap"), 0].set_ylabel("Lyapunov\nper period")
    handles = [plt.Line2D([], [], color=COLOURS[d], marker="o", ls="", ms=4, label=f"sweep {d}")
               for d in ("up", "down") if (table["direction"].astype(str) == d).any()]
    # the kinds drawn (:func:`_marks`: located ones at a finite value); without --locate the
    # legend listed lines that no panel drew
    kinds = sorted({b["kind"] for b in summary.get("bifurcations", [])
                    if b.get("located") and math.isfinite(b.get("value", math.nan))})
    handles += [plt.Line2D([], [], color=KINDS.get(k, "k"), ls=":", label=k.replace("_", " "))
                for k in kinds]
    if summary.get("hysteresis"):
        handles.append(plt.Rectangle((0, 0), 1, 1, color="#ffd54f", alpha=0.4, label="hysteresis"))
    fig.legend(handles=handles, loc="outside lower center", fontsize=8,
               ncol=min(len(handles), 3 * len(models)))
    fig.suptitle(title or f"Bifurcation diagram along {field}", fontsize=11)
    if path is not None:
        fig.savefig(Path(path), dpi=120)
        plt.close(fig)
    return fig


def _draw_branch(panel: dict[str, Any], part: pd.DataFrame, direction: str) -> None:
    colour = COLOURS[direction]
    offset = 0.0 if direction == "up" else 0.15  # the down branch's period marks sit a bit higher
    panel["a"].plot(part["value"], part["a_star"], ",", color=colour, alpha=0.7, ms=1)
    panel["a"].plot(part["value"], part["a_star"], "o", color=colour, ms=0.8, alpha=0.5, lw=0)
    if "lift" in panel:
        lp = part[part["liftoff_phase"].notna()]
        panel["lift"].plot(lp["value"], lp["liftoff_phase"], "o", color=colour, ms=0.8, alpha=0.5)
        panel["lift"].set_ylim(0.0, 1.0)
    per = part.groupby("index").first()
    failed = per["error"].notna()
    # a value whose integration failed (its error is in the table) is a cross, not a period 0
    panel["period"].plot(per["value"][failed], np.zeros(int(failed.sum())), "x", color="#d62728",
                         ms=4)
    per = per[~failed]
    panel["period"].plot(per["value"], per["period"] + offset, "o", color=colour, ms=2.5)
    panel["period"].set_ylim(-0.5, max(2.5, float(per["period"].max()) + 0.8))
    lyap = per["lyapunov"].to_numpy(dtype=float)
    finite = lyap[np.isfinite(lyap)]
    floor = _floor(finite)
    ax = panel["lyap"]
    # a marker at every finite exponent: a line alone left a value between two -inf ones (or a
    # branch's only finite one) without a mark
    ax.plot(per["value"], np.where(np.isfinite(lyap), lyap, np.nan), "-", color=colour, lw=0.8,
            marker="o", ms=2.5)
    low = np.isneginf(lyap)  # a superstable orbit: the perturbation was erased
    ax.plot(per["value"][low], np.full(int(low.sum()), floor), "v", color=colour, ms=3)
    ax.axhline(0.0, color="0.5", lw=0.6)


def _log_spaced(values: pd.Series) -> bool:
    """Whether an axis's values (three or more, all > 0) are evenly spaced in their logarithm
    but not in themselves: a log-spaced sweep, drawn on a log axis."""
    v = np.unique(pd.to_numeric(values, errors="coerce").dropna().to_numpy(float))
    if v.size < 3 or not (v > 0.0).all():
        return False
    steps, logs = np.diff(v), np.diff(np.log(v))
    return bool(np.allclose(logs, logs[0], rtol=1e-6) and not np.allclose(steps, steps[0],
                                                                           rtol=1e-6))


def _floor(finite: np.ndarray) -> float:
    """Where -inf exponents are drawn: below every finite one."""
    return min(-1.0, 1.1 * float(finite.min())) if finite.size else -1.0


def _marks(panel: dict[str, Any], summary: dict[str, Any], model: str) -> None:
    for b in summary.get("bifurcations", []):
        if b.get("model") != model or not b.get("located") or not math.isfinite(b.get("value", math.nan)):
            continue
        for ax in panel.values():
            ax.axvline(b["value"], color=KINDS.get(b["kind"], "k"), ls=":", lw=0.9)
    values = np.asarray(sorted(summary.get("values", [])), dtype=float)
    for h in summary.get("hysteresis", []):
        if h.get("model") != model:
            continue
        # the interval's values, widened by half a spacing each side (one value is a band too)
        lo, hi = h["from"], h["to"]
        below, above = values[values < lo], values[values > hi]
        lo -= 0.5 * (lo - below[-1]) if below.size else 0.0
        hi += 0.5 * (above[0] - hi) if above.size else 0.0
        for ax in panel.values():
            ax.axvspan(lo, hi, color="#ffd54f", alpha=0.4, lw=0)
