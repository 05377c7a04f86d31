"""Phase diagrams (paper Fig. 3) and side-by-side model comparison from a sweep table.

Reads only the table (see :mod:`sawdrift.study.sweep`), never the runner.
"""

from __future__ import annotations

from itertools import combinations
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from ..errors import SceneError  # noqa: E402

#: Regime colours, in legend order.
COLOURS = {
    "stick": "#9ecae1",
    "oscillating_slip": "#fdd0a2",
    "drift_with": "#31a354",
    "drift_against": "#e6550d",
    "hopping": "#756bb1",
    "bouncing": "#bcbddc",
    "error": "#000000",
}
_ORDER = list(COLOURS)


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges for log-spaced centres (geometric midpoints, extended at the ends)."""
    v = np.asarray(values, dtype=float)
    if v.size == 1:
        return np.array([v[0] / 1.5, v[0] * 1.5])
    logs = np.log10(v)
    mids = 0.5 * (logs[1:] + logs[:-1])
    first = logs[0] - (mids[0] - logs[0])
    last = logs[-1] + (logs[-1] - mids[-1])
    return 10.0 ** np.concatenate([[first], mids, [last]])


def regime_grid(table: pd.DataFrame, model: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(A* values, m* values, regime codes [m*, A*]) of one model; missing cells are -1."""
    sub = table[table["model"] == model]
    if sub.empty:
        known = ", ".join(sorted(table["model"].dropna().unique()))
        raise SceneError(f"model {model!r} is not in the table; it holds: {known}")
    amps = np.sort(sub["amplitude"].unique())
    masses = np.sort(sub["m_star"].unique())
    codes = np.full((masses.size, amps.size), -1, dtype=int)
    ia = {v: i for i, v in enumerate(amps)}
    im = {v: i for i, v in enumerate(masses)}
    for m, a, regime in zip(sub["m_star"], sub["amplitude"], sub["regime"], strict=True):
        codes[im[m], ia[a]] = _ORDER.index(regime) if regime in COLOURS else _ORDER.index("error")
    return amps, masses, codes


def _draw(ax, amps, masses, codes, title: str) -> None:
    cmap = ListedColormap(["white", *COLOURS.values()])
    ax.pcolormesh(_edges(amps), _edges(masses), codes + 1, cmap=cmap, vmin=0, vmax=len(COLOURS),
                  shading="flat", edgecolors="none")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("A*")
    ax.set_ylabel("m*")
    ax.set_title(title, fontsize=10)


def _legend(fig, codes_list) -> None:
    used = sorted({int(c) for codes in codes_list for c in np.unique(codes) if c >= 0})
    handles = [Patch(color=COLOURS[_ORDER[c]], label=_ORDER[c]) for c in used]
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), frameon=False)


def _material_label(table: pd.DataFrame) -> str:
    mu = ", ".join(f"{v:g}" for v in sorted(table["mu"].dropna().unique()))
    nu = ", ".join(f"{v:g}" for v in sorted(table["nu"].dropna().unique()))
    return f"mu = {mu}, nu = {nu}"


def plot_phase_diagram(table: pd.DataFrame, path: str | Path, model: str | None = None) -> Path:
    """Regimes over (A*, m*) on log axes, one colour per regime (paper Fig. 3)."""
    models = sorted(table["model"].dropna().unique())
    if model is None:
        if len(models) != 1:
            raise SceneError(f"the table holds several models ({', '.join(models)}); choose one with --model")
        model = models[0]
    amps, masses, codes = regime_grid(table, model)
    fig, ax = plt.subplots(figsize=(6.4, 5.6), layout="constrained")
    _draw(ax, amps, masses, codes, f"{model}: {_material_label(table)}")
    _legend(fig, [codes])
    path = Path(path)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def agreement_table(table: pd.DataFrame, models: list[str]) -> pd.DataFrame:
    """Fraction of shared cells where each pair of models finds the same regime."""
    pivot = table.pivot_table(index=["m_star", "amplitude"], columns="model", values="regime",
                              aggfunc="first")
    rows = []
    for a, b in combinations(models, 2):
        both = pivot[[a, b]].dropna()
        same = int((both[a] == both[b]).sum())
        rows.append({"model_a": a, "model_b": b, "cells": len(both), "same_regime": same,
                     "agreement": same / len(both) if len(both) else float("nan")})
    return pd.DataFrame(rows)


def agreement_markdown(frame: pd.DataFrame) -> str:
    """The agreement table as GitHub markdown."""
    lines = ["| model A | model B | cells | same regime | agreement |", "|---|---|---:|---:|---:|"]
    for r in frame.itertuples():
        lines.append(f"| {r.model_a} | {r.model_b} | {r.cells} | {r.same_regime} | {r.agreement:.1%} |")
    return "\n".join(lines) + "\n"


def plot_compare(table: pd.DataFrame, models: list[str], path: str | Path) -> tuple[Path, str]:
    """Side-by-side phase diagrams on shared axes plus a panel of disagreeing cells.

    Returns the figure path and the markdown agreement table (also written next to the figure
    as ``<name>.md``).
    """
    if len(models) < 2:
        raise SceneError("--models must name at least two models to compare")
    grids = [regime_grid(table, m) for m in models]
    amps, masses = grids[0][0], grids[0][1]
    for m, (a2, m2, _) in zip(models, grids, strict=True):
        if a2.shape != amps.shape or m2.shape != masses.shape or not (
            np.allclose(a2, amps) and np.allclose(m2, masses)
        ):
            raise SceneError(f"model {m!r} was swept on a different grid; compare needs shared axes")
    fig, axes = plt.subplots(1, len(models) + 1, figsize=(4.6 * (len(models) + 1), 4.8),
                             sharex=True, sharey=True, layout="constrained")
    for ax, model, (_, _, codes) in zip(axes, models, grids, strict=False):
        _draw(ax, amps, masses, codes, model)
    stack = np.stack([g[2] for g in grids])
    differ = np.any(stack != stack[0], axis=0)
    missing = np.any(stack < 0, axis=0)
    ax = axes[-1]
    disagree = np.where(missing, -1, differ.astype(int))
    ax.pcolormesh(_edges(amps), _edges(masses), disagree + 1,
                  cmap=ListedColormap(["white", "#f0f0f0", "#d62728"]), vmin=0, vmax=2,
                  shading="flat")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("A*")
    ax.set_title(f"cells where they disagree ({int(differ.sum())} of {differ.size})", fontsize=10)
    _legend(fig, [g[2] for g in grids])
    fig.suptitle(f"{' vs '.join(models)}: {_material_label(table)}")
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    md = agreement_markdown(agreement_table(table, models))
    path.with_suffix(".md").write_text(md)
    return path, md
