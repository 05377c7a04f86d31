"""Regime diagrams of every model on one grid (paper Fig. 3), drawn side by side.

15 x 15 cells, m* in [1e-3, 1e2], A* in [1e-2, 10], 40 periods, mu = 0.1, nu = 0.3, swept with
:func:`sawdrift.study.sweep`. Every model's sweep must complete with no error cell, and the two
implementations of the same Mindlin law must draw the same diagram: mdr (256 strips, within about
1e-5 of mmd in T*) may differ from mmd only in cells on a boundary of the mmd diagram (a cell with
a 4-neighbour of another regime class), where a small difference in the force can tip the regime.
The statements of the paper are checked by the other cases of this group on the same tables.
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.validation import DIAGRAM_GRID, DIAGRAM_MODELS, MU, NU, Case, CaseResult, regime_table

CASE = Case(
    name="phase_diagrams",
    group="diagrams",
    title="Every model's 15 x 15 regime diagram (m* in [1e-3, 1e2], A* in [1e-2, 10], 40 periods) "
    "is computed without an error cell, and mdr differs from mmd only on mmd's regime boundaries; "
    "value: missing or error cells + mdr/mmd disagreements off a boundary",
    tolerance=0,
    quick=True,
)


def run() -> CaseResult:
    """Sweep (shared with the other diagram cases) and draw all models."""
    n_cells = len(sd.parse_axis(DIAGRAM_GRID["m_star"])) * len(sd.parse_axis(DIAGRAM_GRID["amplitude"]))
    tables, bad, notes = {}, 0, []
    for model in DIAGRAM_MODELS:
        try:
            table = regime_table(model)
        except Exception as exc:  # noqa: BLE001 - a missing model is reported, the others drawn
            bad += n_cells
            notes.append(f"{model}: {type(exc).__name__}: {str(exc).splitlines()[0]}")
            continue
        errors = int((table["regime"] == "error").sum()) + n_cells - len(table)
        bad += errors
        tables[model] = table
        counts = table["regime"].value_counts()
        notes.append(f"{model}: " + ", ".join(f"{counts.get(r, 0)} {r}" for r in sd.REGIMES
                                              if counts.get(r, 0)) + (f", {errors} errors" if errors else ""))
    off_boundary = _disagreements_off_boundary(tables["mmd"], tables["mdr"]) if {
        "mmd", "mdr"} <= set(tables) else n_cells
    notes.append(f"mdr vs mmd: {off_boundary} disagreeing cells off an mmd boundary")
    return CASE.result(bad + off_boundary, message="; ".join(notes),
                       figure=_figure(tables) if tables else None)


def _disagreements_off_boundary(mmd, mdr) -> int:
    """Cells where the regime classes of mdr and mmd differ and no 4-neighbour in mmd differs."""
    from sawdrift.report.diagrams import COLOURS, regime_grid
    from sawdrift.validation import regime_class

    names = list(COLOURS)

    def classes(table, model):
        _, _, codes = regime_grid(table, model)
        return np.vectorize(lambda c: regime_class(names[c]) if c >= 0 else "missing")(codes)

    a, b = classes(mmd, "mmd"), classes(mdr, "mdr")
    pad = np.pad(a, 1, mode="edge")
    boundary = np.zeros(a.shape, dtype=bool)
    for di, dj in ((0, 1), (2, 1), (1, 0), (1, 2)):
        boundary |= pad[di : di + a.shape[0], dj : dj + a.shape[1]] != a
    return int(np.sum((a != b) & ~boundary))


def _edges(v: np.ndarray) -> np.ndarray:
    logs = np.log10(v)
    mids = 0.5 * (logs[1:] + logs[:-1])
    return 10.0 ** np.concatenate([[2 * logs[0] - mids[0]], mids, [2 * logs[-1] - mids[-1]]])


def _figure(tables):
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from sawdrift.report.diagrams import COLOURS, regime_grid

    names = list(COLOURS)
    fig, axes = plt.subplots(2, 3, figsize=(12.0, 7.8), sharex=True, sharey=True, layout="constrained")
    r = sd.rayleigh_ratio(NU)
    gz_stick = 1.0 / math.sqrt(1.0 + (r / MU) ** 2)
    used: set[int] = set()
    for ax, model in zip(axes.flat, DIAGRAM_MODELS, strict=False):
        ax.set_title(model, fontsize=11)
        if model not in tables:
            ax.text(0.5, 0.5, "not available", ha="center", transform=ax.transAxes)
            continue
        amps, masses, codes = regime_grid(tables[model], model)
        used |= {int(c) for c in np.unique(codes) if c >= 0}
        cmap = ListedColormap(["white", *COLOURS.values()])
        ax.pcolormesh(_edges(amps), _edges(masses), codes + 1, cmap=cmap, vmin=0, vmax=len(COLOURS),
                      shading="flat")
        a_line = np.geomspace(1e-2 / 1.3, 10 * 1.3, 50)
        ax.plot(a_line, 1.0 / (4 * math.pi**2 * a_line), "k-", lw=1.0)
        ax.plot(a_line, gz_stick / (4 * math.pi**2 * a_line), "k:", lw=1.0)
        ax.axvline(1.0, color="k", ls="--", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(_edges(amps)[0], _edges(amps)[-1])
        ax.set_ylim(_edges(masses)[0], _edges(masses)[-1])
    for ax in axes[-1]:
        ax.set_xlabel("A*")
    for ax in axes[:, 0]:
        ax.set_ylabel("m*")
    leg = axes.flat[-1]
    leg.axis("off")
    handles = [Patch(color=COLOURS[names[c]], label=names[c]) for c in sorted(used)]
    handles += [
        plt.Line2D([], [], color="k", lw=1.0, label="Gz = 1 (point loses contact above)"),
        plt.Line2D([], [], color="k", ls=":", lw=1.0, label="Gx = mu sqrt(1 - Gz^2) (point sticks below)"),
        plt.Line2D([], [], color="k", ls="--", lw=0.8, label="A* = 1"),
    ]
    leg.legend(handles=handles, loc="center", fontsize=10, frameon=False)
    fig.suptitle(f"Regime diagrams, mu = {MU}, nu = {NU}, {DIAGRAM_GRID['periods']:g} periods", fontsize=12)
    return fig
