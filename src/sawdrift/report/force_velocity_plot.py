"""Figure of a force-velocity curve: the mean friction force against the steady drift speed."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .diagrams import COLOURS  # noqa: E402

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..study.force_velocity import ForceVelocity

__all__ = ["plot_force_velocity"]


def plot_force_velocity(curve: ForceVelocity, path: str | Path | None = None,
                        title: str = "") -> Figure:
    """The load that holds the particle (= its mean friction force) against its steady speed.

    Markers are coloured by regime; open markers did not settle. A speed that is a long-time
    mean (a chaotic or irregular point) carries its standard error as a horizontal error bar.
    The free drift (zero force) is marked, with its error bar, and drawn open where it is zero
    within three errors; the range the friction can hold, +- mu M g, is drawn as dashed lines.
    Device scenes are drawn in mN and m/s. Write a PNG if ``path`` is given.
    """
    data = curve.to_json()
    dev = data.get("device")
    if dev is not None:
        x, y, xerr = dev["speed_m_s"], dev["force_mN"], dev["speed_se_m_s"]
        scale_f = 1e3 * curve.device["force_n"]  # type: ignore[index]
        scale_v = curve.device["speed_m_s"]  # type: ignore[index]
        labels = ("steady drift speed v (m/s)", "load holding that speed, L = mu <T> (mN)")
    else:
        x, y, xerr = data["drift_velocity"], data["force"], data["drift_velocity_se"]
        scale_f = scale_v = 1.0
        labels = ("steady drift velocity v / (a0 f)", "load holding that speed, L = mu <T*> / (M g)")
    fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    pts = [(a, b) for a, b in zip(x, y, strict=True) if a is not None]
    if pts:
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color="0.6", lw=1.0, zorder=1)
    seen: set[str] = set()
    for xi, yi, ei, regime, ok in zip(x, y, xerr, curve.regimes, curve.settled, strict=True):
        if xi is None:
            continue
        colour = COLOURS.get(regime, "#000000")
        if ei is not None:
            ax.errorbar([xi], [yi], xerr=[ei], fmt="none", ecolor=colour, elinewidth=1.0,
                        capsize=3, zorder=2)
        ax.plot([xi], [yi], "o", ms=6, zorder=2, mec=colour,
                mfc=colour if ok else "white",
                label=None if regime in seen else regime.replace("_", " "))
        seen.add(regime)
    for sign in (-1.0, 1.0):
        ax.axhline(sign * curve.friction_bound * scale_f, color="0.4", ls="--", lw=0.8)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.axvline(0.0, color="k", lw=0.6)
    _free_drift(ax, curve, scale_v)
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7.5, loc="lower right")
    ax.set_title((title or "Force-velocity curve (each point a steady state at full inertia)")
                 + f"\ndashed: +- {_bound_text(curve)}, the most friction can hold; "
                 "open markers: not settled\nbars: +- 1 standard error of a long-time mean",
                 fontsize=8.5)
    if path is not None:
        fig.savefig(path, dpi=130)
    return fig


def _free_drift(ax, curve: ForceVelocity, scale: float) -> None:
    """The free drift at zero force: a star with its error bar, open (and said so) where it is
    zero within three standard errors."""
    v = curve.free_drift * scale
    if not math.isfinite(v):
        return
    se = curve.free_drift_se * scale
    label = f"free drift {v:.4g}"
    if math.isfinite(se):
        label += f" +- {se:.2g}"
        ax.errorbar([v], [0.0], xerr=[se], fmt="none", ecolor="k", elinewidth=1.2, capsize=4,
                    zorder=3)
    if not curve.free_drift_resolved:
        label += " (zero within 3 errors)"
    ax.plot([v], [0.0], "*", color="k", ms=12, zorder=4,
            mfc="k" if curve.free_drift_resolved else "white", label=label)


def _bound_text(curve) -> str:
    """The friction bound as the title names it: mu M g, or mu (1 + 2 F*_pull) M g."""
    if curve.friction_bound == curve.mu:
        return f"mu M g (mu = {curve.mu:g})"
    if curve.friction_bound < curve.mu:  # a sphere free to turn: its rolling resistance
        return f"the rolling resistance's {curve.friction_bound:.4g} M g"
    return f"mu (1 + 2 F*_pull) M g = {curve.friction_bound:.4g} M g (adhesion)"
