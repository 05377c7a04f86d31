"""Scattered points on the log-log plane (an adaptive table): the point nearest to each place
of a fine grid, so that each computed point is drawn as its own region (Voronoi cells)."""

from __future__ import annotations

import numpy as np
import pandas as pd

__all__ = ["nearest", "scattered"]


def padded(logs: np.ndarray) -> tuple[float, float]:
    """The ends of a log axis that hold whole cells: half the median gap beyond the outer points."""
    gaps = np.diff(np.unique(logs))
    half = 0.5 * float(np.median(gaps)) if gaps.size else 0.5
    return float(logs.min() - half), float(logs.max() + half)


#: the part of the grid of their coordinates that points must fill to be drawn as that grid
FILLED = 0.9


def scattered(sub: pd.DataFrame, x: str, y: str) -> bool:
    """Whether a model's points fill less than :data:`FILLED` of the grid of their coordinates
    (an adaptive table, refined once: 39 points of 49 left 10 white cells at a half), drawn as
    each point's region, not as that grid."""
    points = sub[[x, y]].drop_duplicates().shape[0]
    return points < FILLED * sub[x].nunique() * sub[y].nunique()


def nearest(sub: pd.DataFrame, x: str, y: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A fine log grid (400 x 400, half a gap beyond the outer points) and, for each of its
    points ([y, x] flattened), the row of ``sub`` nearest to it in the log-log plane."""
    from scipy.spatial import cKDTree

    lx, ly = np.log10(sub[x].to_numpy(float)), np.log10(sub[y].to_numpy(float))
    gx = np.linspace(*padded(lx), 400)
    gy = np.linspace(*padded(ly), 400)
    mx, my = np.meshgrid(gx, gy)
    _, idx = cKDTree(np.column_stack([lx, ly])).query(np.column_stack([mx.ravel(), my.ravel()]))
    return gx, gy, idx
