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

    Markers are coloured by regime; open markers did not settle. The free drift (zero force) is
    marked, and the range the friction can hold, +- mu M g, drawn as dashed lines. Device scenes
    are drawn in mN and m/s. Write a PNG if ``path`` is given.
    """
    data = curve.to_json()
    dev = data.get("device")
    if dev is not None:
        x, y = dev["speed_m_s"], dev["force_mN"]
        scale_f = 1e3 * curve.device["force_n"]  # type: ignore[index]
        scale_v = curve.device["speed_m_s"]  # type: ignore[index]
        labels = ("steady drift speed v (m/s)", "load holding that speed, L = mu <T> (mN)")
    else:
        x, y = data["drift_velocity"], data["force"]
        scale_f = scale_v = 1.0
        labels = ("steady drift velocity v / (a0 f)", "load holding that speed, L = mu <T*> / (M g)")
    fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    pts = [(a, b) for a, b in zip(x, y, strict=True) if a is not None]
    if pts:
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color="0.6", lw=1.0, zorder=1)
    seen: set[str] = set()
    for xi, yi, regime, ok in zip(x, y, curve.regimes, curve.settled, strict=True):
        if xi is None:
            continue
        colour = COLOURS.get(regime, "#000000")
        ax.plot([xi], [yi], "o", ms=6, zorder=2, mec=colour,
                mfc=colour if ok else "white",
                label=None if regime in seen else regime.replace("_", " "))
        seen.add(regime)
    for sign in (-1.0, 1.0):
        ax.axhline(sign * curve.mu * scale_f, color="0.4", ls="--", lw=0.8)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.axvline(0.0, color="k", lw=0.6)
    if math.isfinite(curve.free_drift):
        ax.plot([curve.free_drift * scale_v], [0.0], "*", color="k", ms=12, zorder=3,
                label=f"free drift {curve.free_drift * scale_v:.4g}")
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7.5, loc="lower right")
    ax.set_title((title or "Force-velocity curve (each point a steady state at full inertia)")
                 + f"\ndashed: +- mu M g, the most friction can hold (mu = {curve.mu:g}); "
                 "open markers: not settled", fontsize=8.5)
    if path is not None:
        fig.savefig(path, dpi=130)
    return fig
