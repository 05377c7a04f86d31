"""Figures of the LAMMPS engine: a mixture's drift and segregation, and the engine comparison."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..lammps.many import ManyResult

__all__ = ["plot_comparison", "plot_mixture"]

COLORS = ("#3182bd", "#e6550d")


def plot_mixture(result: ManyResult, path: str | Path | None = None, title: str = "") -> Figure:
    """Mean displacement of each species (left) and the segregation index S(t) (right).

    The displacement is in nm against the wave period t* (sawdrift.lammps.many: S = (<dx>_1 -
    <dx>_2) / (|<dx>_1| + |<dx>_2|)); the species' drift ratios are in the legend.
    """
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.0, 4.0), layout="constrained")
    for k, row in enumerate(result.species):
        ratio = row["drift_ratio"]
        label = (f"R = {row['radius_m'] * 1e3:.3g} mm (n = {row['count']}), "
                 f"V/U = {ratio:.3g}" if ratio is not None else f"R = {row['radius_m'] * 1e3:.3g} mm")
        ax.plot(result.times, result.mean_x[:, k] * 1e9, color=COLORS[k % 2], lw=1.4, label=label)
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("t* (wave periods)")
    ax.set_ylabel("mean displacement <dx> (nm)")
    ax.legend(fontsize=8)
    bx.plot(result.times, result.segregation, color="k", lw=1.4)
    bx.set_ylim(-1.05, 1.05)
    bx.axhline(0.0, color="0.6", lw=0.6)
    bx.set_xlabel("t* (wave periods)")
    bx.set_ylabel("segregation index S")
    fig.suptitle(title or f"LAMMPS, {result.count} spheres, {result.steps_per_period} steps/period, "
                 f"{result.processes} process(es), {result.wall_time_s:.3g} s")
    if path is not None:
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig


def plot_comparison(rows: list[dict[str, Any]], path: str | Path | None = None) -> Figure:
    """Drift ratio of LAMMPS against the native engine, scene by scene, with both wall times.

    ``rows`` hold ``name``, ``native``, ``lammps`` (drift ratios), ``native_s`` and ``lammps_s``.
    """
    fig, ax = plt.subplots(figsize=(7.0, 3.8), layout="constrained")
    xs = range(len(rows))
    ax.bar([x - 0.2 for x in xs], [r["native"] for r in rows], 0.4, color=COLORS[0], label="native")
    ax.bar([x + 0.2 for x in xs], [r["lammps"] for r in rows], 0.4, color=COLORS[1], label="LAMMPS")
    ax.set_xticks(list(xs), [f"{r['name']}\n{r['native_s']:.2g} s / {r['lammps_s']:.2g} s"
                             for r in rows], fontsize=7)
    ax.set_ylabel("drift ratio V / (2 pi r A*)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.legend(fontsize=8)
    if path is not None:
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig
