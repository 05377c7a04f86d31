"""Figures: trajectories of single runs (phase diagrams live in :mod:`sawdrift.report.diagrams`)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from ..result.result import Result  # noqa: E402

#: the definition of V printed with every drift ratio
V_DEFINITION = "V = <x*'> / (2 pi r A*): the mean drift over the horizontal surface speed"

#: colours of the two bands of a trajectory figure: the wave's ramp and the measuring window
RAMP_COLOUR, WINDOW_COLOUR = "0.88", "#fff1c1"

#: the four rows of a trajectory figure: column and axis label (two lines: they fit the height)
SERIES = [("x", "x*\n(particle position)"), ("a", "a*\n(normal compression)"),
          ("N_star", "N*\n(normal force)"), ("T_star", "T*\n(friction force)")]


def _bands(axes, result: Result) -> list[Patch]:
    """Shade the wave's ramp and the measuring window on every row; their legend entries."""
    ramp = float(result.ramp_periods)
    end = float(result.periods)
    start = end - float(result.measure_periods)
    handles = []
    for ax in axes:
        if ramp > 0:
            ax.axvspan(0, ramp, color=RAMP_COLOUR, zorder=0)
        if result.measure_periods > 0 and start > 0:
            ax.axvspan(start, end, color=WINDOW_COLOUR, zorder=0)
    if ramp > 0:
        handles.append(Patch(color=RAMP_COLOUR, label=f"wave ramp: the amplitude rises from 0 "
                             f"to A* over {ramp:g} periods"))
    if result.measure_periods > 0 and start > 0:
        handles.append(Patch(color=WINDOW_COLOUR, label=f"measuring window: V and the regime "
                             f"come from its {result.measure_periods} periods"))
    return handles


def unsettled_mark(result: Result) -> str:
    """``", NOT settled"`` for a run whose drift is not the steady one, else ``""``."""
    return ", NOT settled" if result.settled is False else ""


def plot_trajectory(result: Result, path: str | Path) -> Path:
    """Write a PNG of x*, a*, N* and T* against t* for a run made with ``trajectory=True``."""
    if result.trajectory is None:
        raise ValueError("the result has no trajectory; run with trajectory=True")
    tr = result.trajectory
    if result.regime == "prescribed":
        return _plot_prescribed(result, Path(path))
    fig, axes = plt.subplots(4, 1, figsize=(9, 9.4), sharex=True, constrained_layout=True)
    for ax, (col, label) in zip(axes, SERIES, strict=True):
        ax.plot(tr["t"], tr[col], lw=0.8)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    bands = _bands(axes, result)
    if bands:
        fig.legend(handles=bands, loc="outside lower center", ncol=1, frameon=False, fontsize=9)
    axes[-1].set_xlabel("t*  (wave periods)")
    title = (
        f"{result.model}: m* = {result.m_star:g}, A* = {result.amplitude:g}, mu = {result.mu:g}, "
        f"nu = {result.nu:g}  ->  {result.regime}, V = {result.drift_ratio:.3g}"
        f"{unsettled_mark(result)}\n{V_DEFINITION}"
    )
    fig.suptitle(title, fontsize=10)
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_trajectories(results: list[Result], path: str | Path) -> Path:
    """Several runs of one scene (one per model) overlaid: x*, a*, N*, T* against t*.

    Each line is labelled with its model; a run whose drift has not settled says so in the
    legend.
    """
    fig, axes = plt.subplots(4, 1, figsize=(9, 9.4), sharex=True, constrained_layout=True)
    for k, res in enumerate(results):
        if res.trajectory is None:
            raise ValueError("a result has no trajectory; run with trajectory=True")
        tr = res.trajectory
        style = ("-", "--", ":", "-.")[k % 4]  # models that agree stay visible over each other
        for ax, (col, _) in zip(axes, SERIES, strict=True):
            ax.plot(tr["t"], tr[col], lw=0.8 + 0.4 * (k > 0), ls=style, label=res.model)
    for ax, (_, label) in zip(axes, SERIES, strict=True):
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    bands = _bands(axes, results[0])
    axes[0].legend(fontsize=8, loc="best",
                   labels=[f"{r.model}: {r.regime}, V = {r.drift_ratio:.3g}{unsettled_mark(r)}"
                           for r in results])
    if bands:
        fig.legend(handles=bands, loc="outside lower center", ncol=1, frameon=False, fontsize=9)
    axes[-1].set_xlabel("t*  (wave periods)")
    r0 = results[0]
    fig.suptitle(f"{' vs '.join(r.model for r in results)}: m* = {r0.m_star:g}, "
                 f"A* = {r0.amplitude:g}, mu = {r0.mu:g}, nu = {r0.nu:g}\n{V_DEFINITION}",
                 fontsize=10)
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _plot_prescribed(result: Result, path: Path) -> Path:
    """a*, b*, N*, T* against the sample index, and the T*(b*) hysteresis loop."""
    tr = result.trajectory
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), constrained_layout=True)
    for ax, col, label in zip(axes.flat[:3], ("a", "b", "N_star"), ("a*", "b*", "N*"), strict=True):
        ax.plot(tr["t"], tr[col], lw=0.8)
        ax.set_ylabel(label)
        ax.set_xlabel("sample")
        ax.grid(alpha=0.3)
    ax = axes.flat[3]
    ax.plot(tr["b"], tr["T_star"], lw=0.8, label="T*")
    n_max = float(tr["N_star"].max())
    ax.axhline(n_max, lw=0.6, ls="--", color="0.5", label="max N* (Coulomb limit)")
    ax.axhline(-n_max, lw=0.6, ls="--", color="0.5")
    ax.set_xlabel("b*")
    ax.set_ylabel("T*")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    work = result.extra.get("dissipated_work", float("nan"))
    fig.suptitle(f"{result.model}: prescribed history, dissipated work {work:.6g}", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
