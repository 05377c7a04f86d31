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
    on the top axis, the target purity dashed. Right, the first placement's beads coloured by
    species: 1-D (``line``), x (mm) against time, one line per bead (a strip chart: chains are
    bundles of lines); 2-D (``plane``), their paths on the plate, y against x (mm), from the
    start (open circles) to twice the time the placement took to reach the target purity, or
    the end (dots)."""
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
    if result.geometry == "plane":
        _paths(bx, result)
    else:
        _strips(bx, result, t)
    for k in range(2):
        row = result.species[k]
        bx.plot([], [], color=COLORS[k], label=f"R = {row['radius_m'] * 1e3:.3g} mm, free "
                f"drift ratio {row['free_drift_ratio']:+.3f}")
    if result.geometry == "plane":  # the paths fill the panel: the legend goes under it
        bx.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    else:
        bx.legend(fontsize=8)
    if path is not None:
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig


def _strips(bx: plt.Axes, result: SortResult, t: np.ndarray) -> None:
    """x of every bead of the first placement against time (1-D)."""
    run = result.runs[0]
    for k in (1, 0):
        sel = run.kinds == k
        if sel.any():
            # the small beads a chain carries sit on the large ones' positions: the large as
            # wide pale bands underneath, the small as thin lines on top, so that both show
            bx.plot(t, run.x[1:, sel] * 1e3, color=COLORS[k], lw=3.0 if k else 0.6,
                    alpha=0.35 if k else 0.9, zorder=3 - k, solid_capstyle="butt")
    bx.set_xscale("log")
    bx.set_xlabel("time (wave periods)")
    # linear over the bed, logarithmic beyond: on a linear axis the 20 mm bed of
    # examples/mixture.toml, where the beads meet, was a flat band under beads 800 mm away
    bed = float(np.abs(run.x[0]).max()) * 1e3
    if bed > 0.0 and np.abs(run.x).max() * 1e3 > 4.0 * bed:
        bx.set_yscale("symlog", linthresh=bed)
        bx.set_ylabel(f"x (mm; linear within +-{bed:.2g}, the bed)")
    else:
        bx.set_ylabel("x (mm)")
    bx.set_title(f"placement seed {result.seeds[0]}: every bead", fontsize=9)


def _paths(bx: plt.Axes, result: SortResult) -> None:
    """Paths of the beads of the first placement on the plate (2-D), up to twice the time to
    the target purity (or the end)."""
    run = result.runs[0]
    hit = result.times_to_target()[0]
    last = run.x.shape[0] - 1
    if np.isfinite(hit):
        last = min(last, int(np.searchsorted(result.periods, 2.0 * hit)))
    y = run.y  # type: ignore[attr-defined]
    for k in (1, 0):
        sel = run.kinds == k
        if sel.any():
            bx.plot(run.x[: last + 1, sel] * 1e3, y[: last + 1, sel] * 1e3, color=COLORS[k],
                    lw=0.5, alpha=0.6, zorder=3 - k)
            bx.scatter(run.x[0, sel] * 1e3, y[0, sel] * 1e3, s=6, facecolors="none",
                       edgecolors=COLORS[k], lw=0.5, zorder=4)
            bx.scatter(run.x[last, sel] * 1e3, y[last, sel] * 1e3, s=6, color=COLORS[k],
                       zorder=4)
    bx.set_xlabel("x along the wave (mm)")
    bx.set_ylabel("y across the wave (mm)")
    bx.set_title(f"placement seed {result.seeds[0]}: paths to {result.periods[last]:.3g} "
                 "periods (open: start, dots: then)", fontsize=9)
