"""Figures of the work-precision study (``sawdrift bench work-precision``): error against wall time.

Drawing only: the study (``sawdrift.bench``) measures the frame and fits the orders.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

# -- figures -----------------------------------------------------------------------------------------

_MODEL_COLORS = {
    "mmd": "tab:blue",
    "mdr": "tab:orange",
    "jaeger": "tab:green",
    "hertz_mindlin_dem": "tab:red",
    "material_point": "tab:purple",
}
_ORDER_STYLE = {1: (":", "v"), 2: ("-.", "s"), 3: ("-", "o"), 4: ("--", "D"), None: ("-", "P")}
ERROR_FLOOR = 1e-16


def _color(model: str, i: int) -> str:
    import matplotlib.pyplot as plt

    return _MODEL_COLORS.get(model, plt.rcParams["axes.prop_cycle"].by_key()["color"][i % 10])


def _order_or_none(value: Any) -> int | None:
    return None if value is None or pd.isna(value) else int(value)


def _orders(column: pd.Series) -> pd.Series:
    """An order column as plain Python ints and None (object dtype: None stays None)."""
    return pd.Series([_order_or_none(v) for v in column], index=column.index, dtype=object)


def plot_prescribed(frame: pd.DataFrame, path: Path,
                    strip_orders: tuple[float, float] = (float("nan"), float("nan"))) -> Path:
    """Work-precision (error vs wall time) and the mdr strip convergence, prescribed setting.

    ``strip_orders`` is mdr's observed order against the strip count (max and rms error), shown
    in the second panel's title.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sub = frame[frame["setting"] == "prescribed"]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 5.2))
    for i, ((model, ladder), g) in enumerate(sub.groupby(["model", "ladder"], sort=False)):
        g = g.sort_values("wall_s")
        label = f"{model} (strips {int(g['strips'].min())}-{int(g['strips'].max())})" if (
            ladder == "strips") else f"{model}, samples/segment {int(g['samples_per_segment'].min())}-" \
            f"{int(g['samples_per_segment'].max())}"
        ax.loglog(np.maximum(g["error"].astype(float), ERROR_FLOOR), g["wall_s"].astype(float),
                  "-o" if ladder == "strips" else "--s", color=_color(model, i), label=label, ms=4)
    ax.set_xlabel("max |T* - T*_mmd| at the vertices of the random history")
    ax.set_ylabel("wall time of the history (s)")
    ax.set_title("(a) contact law alone: work-precision")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    strips = sub[sub["ladder"] == "strips"].sort_values("strips")
    if not strips.empty:
        s = strips["strips"].astype(float)
        ax2.loglog(s, strips["error"].astype(float), "-o", color=_color("mdr", 1), label="max error")
        ax2.loglog(s, strips["error_rms"].astype(float), "--o", color=_color("mdr", 1), alpha=0.6,
                   label="rms error")
        p_max, p_rms = strip_orders
        ax2.set_title(f"mdr vs strips: observed order {p_max:.2f} (max), {p_rms:.2f} (rms)")
        ax3 = ax2.twinx()
        ax3.loglog(s, strips["ns_per_step"].astype(float), ":^", color="gray", label="ns/step")
        ax3.set_ylabel("ns per sample (gray)")
        mmd = sub[(sub["model"] == "mmd")]
        if not mmd.empty:
            longest = mmd.loc[mmd["steps"].astype(float).idxmax()]
            ax3.axhline(float(longest["ns_per_step"]), color=_color("mmd", 0), ls=":",
                        label="mmd ns/step")
            ax3.legend(loc="upper center", fontsize=8)
        ax2.legend(loc="lower left", fontsize=8)
    ax2.set_xlabel("strips")
    ax2.set_ylabel("|T* - T*_mmd|")
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_wave(frame: pd.DataFrame, path: Path, m_star: float, amplitude: float) -> Path:
    """Work-precision (error vs wall time) and error vs steps per period, wave setting.

    ``m_star`` and ``amplitude`` name the wave scene in the title.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sub = frame[frame["setting"] == "wave"]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(16, 6.4))
    models = list(dict.fromkeys(sub["model"]))
    for i, model in enumerate(models):
        g_model = sub[sub["model"] == model]
        for ladder, g_l in g_model.groupby("ladder", sort=False):
            orders = _orders(g_l["order"]) if ladder == "steps" else pd.Series(
                [None] * len(g_l), index=g_l.index, dtype=object)
            for order in dict.fromkeys(orders):
                g = g_l[orders.map(lambda o, order=order: o == order)]
                g = g[np.isfinite(g["error"].astype(float))].sort_values("wall_s")
                if g.empty:
                    continue
                ls, mk = _order_style(order, ladder)
                if ladder == "strips":
                    label = f"{model} strips {int(g['strips'].min())}-{int(g['strips'].max())}"
                elif order is None:
                    label = f"{model} (event scheme)"
                else:
                    label = f"{model} AB{order}"
                err = np.maximum(g["error"].astype(float), ERROR_FLOOR)
                # mmd on top: mdr (256 strips) lies almost exactly under it
                style = dict(ls=ls, marker=mk, color=_color(model, i), label=label, ms=4,
                             lw=1.8 if model == "mmd" else 1.1, zorder=3 if model == "mmd" else 2)
                ax.loglog(err, g["wall_s"].astype(float), **style)
                if ladder == "steps":
                    ax2.loglog(g["steps_per_period"].astype(float), err, **style)
        dflt = g_model[g_model["is_default"].astype(bool) & (g_model["ladder"] == "steps")]
        for _, r in dflt.iterrows():
            ax.loglog(max(float(r["error"]), ERROR_FLOOR), float(r["wall_s"]), "*", ms=16,
                      mfc="none", mec="k")
            ax2.loglog(float(r["steps_per_period"]), max(float(r["error"]), ERROR_FLOOR), "*",
                       ms=16, mfc="none", mec="k")
    ax.set_xlabel("|drift ratio - reference|")
    ax.set_ylabel("wall time of the run (s)")
    ax.set_title(f"(b) wave scene m* = {m_star:g}, A* = {amplitude:g}: work-precision "
                 "(star: current default)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8, frameon=False)
    for slope in (1, 2, 3):
        xs = np.array([40.0, 320.0])
        ax2.loglog(xs, 1e-6 * (xs / 40.0) ** (-slope), color="0.55", lw=0.9)
        ax2.text(xs[-1] * 1.05, 1e-6 * 8.0 ** (-slope), f"order {slope}", fontsize=7, color="0.35",
                 va="center")
    ax2.set_xlabel("steps per period")
    ax2.set_ylabel("|drift ratio - reference|")
    ax2.set_title("convergence (gray: slopes of order 1, 2, 3; mdr lies under mmd)", fontsize=10)
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout(rect=(0.0, 0.0, 0.86, 1.0))
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _order_style(order: int | None, ladder: str) -> tuple[str, str]:
    if ladder == "strips":
        return "-", "x"
    return _ORDER_STYLE.get(order, ("-", "o"))
