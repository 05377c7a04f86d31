"""Figure of a threshold study: sliding and removal amplitudes against the particle's radius."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..study.threshold import ThresholdStudy

__all__ = ["plot_thresholds"]


def plot_thresholds(study: ThresholdStudy, path: str | Path | None = None) -> Figure:
    """Log-log: the amplitude where sliding starts, where the particle is removed, and the rigid
    removal amplitude (F_pull + m g) / (m (2 pi f)^2), against the swept field (um for a radius),
    with the fitted slopes in the legend (all values, and the smallest third). Write a PNG if
    ``path`` is given."""
    data = study.to_json()
    rows = data["rows"]
    radius = study.field.endswith("radius")
    scale = 1e6 if radius else 1.0
    x = np.array([r["value"] for r in rows]) * scale
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    styles = {"slide_amplitude_m": ("sliding starts", "o-", "#2b8cbe"),
              "removal_amplitude_m": ("removed (ejected)", "s-", "#e34a33"),
              "rigid_removal_m": ("rigid limit (F_pull + m g) / (m w^2)", "--", "k")}
    for column, (label, style, colour) in styles.items():
        y = np.array([r[column] for r in rows], dtype=float) * 1e9
        slope = data["slopes"][column]
        text = f"{label}: slope {slope['all']:.2f} (small: {slope['small']:.2f})"
        ax.loglog(x, y, style, color=colour, label=text, ms=4)
    ax.set_xlabel(f"{study.field.rsplit('.', 1)[-1]} ({'um' if radius else 'SI'})")
    ax.set_ylabel("vertical surface amplitude A (nm)")
    ax.set_title("Sliding and removal of an adhesive particle", fontsize=10)
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
        plt.close(fig)
    return fig
