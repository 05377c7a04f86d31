"""Figure of a sorting ensemble: purity against time with its band, and a strip chart of positions."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..mixture.sort import SortResult

__all__ = ["plot_sort"]

COLORS = ("#3182bd", "#e6550d")


def plot_sort(result: SortResult, path: str | Path | None = None) -> Figure:
    """Left: the purity of the best interface (mean over the placements, band: mean +- one
    standard deviation) and the Lacey index against time in wave periods (log), device seconds
    on the top axis, the target purity dashed. Right: the first placement's beads, x (mm) against
    time, one line per bead coloured by species (a strip chart: chains are bundles of lines)."""
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12.0, 4.2), layout="constrained")
    t = result.periods[1:]
    for key, color, label in (("purity", "k", "purity"), ("lacey", "0.5", "Lacey index")):
        v = result.measures[key][:, 1:]
        mean, std = v.mean(axis=0), v.std(axis=0, ddof=1) if v.shape[0] > 1 else np.zeros(t.size)
        ax.plot(t, mean, color=color, lw=1.5, label=f"{label} (mean of {v.shape[0]})")
        ax.fill_between(t, mean - std, mean + std, color=color, alpha=0.2, lw=0)
    ax.axhline(result.target, color="tab:red", ls="--", lw=1.0, label=f"target {result.target:g}")
    ax.set_xscale("log")
    ax.set_ylim(-0.1, 1.05)
    ax.set_xlabel("time (wave periods)")
    ax.set_ylabel("segregation of positions")
    ax.legend(fontsize=8, loc="upper left")
    top = ax.secondary_xaxis("top", functions=(lambda p: p / result.frequency,
                                               lambda s: s * result.frequency))
    top.set_xlabel("device time (s)")
    run = result.runs[0]
    for k in (1, 0):  # the small beads on top
        sel = run.kinds == k
        if sel.any():
            bx.plot(t, run.x[1:, sel] * 1e3, color=COLORS[k], lw=0.5, alpha=0.7, zorder=3 - k)
    for k in range(2):
        row = result.species[k]
        bx.plot([], [], color=COLORS[k], label=f"R = {row['radius_m'] * 1e3:.3g} mm, free "
                f"drift ratio {row['free_drift_ratio']:+.3f}")
    bx.set_xscale("log")
    bx.set_xlabel("time (wave periods)")
    bx.set_ylabel("x (mm)")
    bx.set_title(f"placement seed {result.seeds[0]}: every bead", fontsize=9)
    bx.legend(fontsize=8)
    if path is not None:
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig
