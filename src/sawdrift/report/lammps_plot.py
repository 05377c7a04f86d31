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


def plot_mixture(result: ManyResult, path: str | Path | None = None, title: str = "",
                 dilute: list[dict[str, Any]] | None = None) -> Figure:
    """Per-species mean displacement, the segregation index S(t) and the touching pairs.

    Left: each species' mean displacement <dx>_s (nm) against the wave period t*, with its drift
    ratio in the legend and, given ``dilute`` (:func:`sawdrift.lammps.many.dilute_prediction`),
    the single particle's drift as a dashed line of slope V_single (the dilute limit) through the
    measured displacement at the window's start. Middle: S(t) = (<dx>_1 - <dx>_2) / (|<dx>_1| +
    |<dx>_2|) (sawdrift.lammps.many). Right: the number of touching sphere pairs, averaged over
    each period (``compute contact/atom``): zero on a dilute lattice.
    """
    fig, (ax, bx, cx) = plt.subplots(1, 3, figsize=(14.0, 4.0), layout="constrained")
    t0 = result.times[-1] - result.measure_periods
    j0 = int(abs(result.times - t0).argmin())
    for k, row in enumerate(result.species):
        ratio = row["drift_ratio"]
        label = (f"R = {row['radius_m'] * 1e3:.3g} mm (n = {row['count']}): V/U = {ratio:.3g}"
                 if ratio is not None else f"R = {row['radius_m'] * 1e3:.3g} mm")
        label += f", {row.get('contacts_per_sphere', 0.0):.2g} contacts/sphere"
        ax.plot(result.times, result.mean_x[:, k] * 1e9, color=COLORS[k % 2], lw=1.4, label=label)
        if dilute is not None and result.frequency > 0.0 and k < len(dilute):
            single = dilute[k]["single_drift_ratio"]
            # m per wave period: drift ratio x surface speed / f
            per_period = single * result.surface_speed / result.frequency
            tt = result.times[j0:]
            ax.plot(tt, (result.mean_x[j0, k] + per_period * (tt - tt[0])) * 1e9, color=COLORS[k % 2],
                    lw=1.0, ls="--", label=f"single particle (dilute): V/U = {single:.3g}")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("t* (wave periods)")
    ax.set_ylabel("mean displacement <dx> (nm)")
    ax.legend(fontsize=7)
    bx.plot(result.times, result.segregation, color="k", lw=1.4)
    bx.set_ylim(-1.05, 1.05)
    bx.axhline(0.0, color="0.6", lw=0.6)
    bx.set_xlabel("t* (wave periods)")
    bx.set_ylabel("segregation index S")
    if result.contact_times.size:
        cx.step(result.contact_times, result.contact_pairs, where="pre", color="k", lw=1.2)
    cx.set_ylim(bottom=0.0)
    cx.set_xlim(0.0, max(1.0, float(result.times[-1])))
    cx.set_xlabel("t* (wave periods)")
    cx.set_ylabel("touching sphere pairs (mean over each period)")
    fig.suptitle(title or f"LAMMPS, {result.count} spheres ({result.packing}), "
                 f"{result.steps_per_period} steps/period, {result.processes} process(es), "
                 f"{result.wall_time_s:.3g} s")
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
